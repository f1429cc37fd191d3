// tone_mapping/clip: the display transform — no tone mapping (see technique.toml).
// The radiance (linear, float) times 2^exposure, mapped by the operator;
// the rgba8unorm-srgb target encodes the result to sRGB. Bindings by name.
#import plait::frame::fullscreen_position

struct DisplayParams {
    exposure: f32,
}

@group(1) @binding(0) var radiance: texture_2d<f32>;
@group(1) @binding(1) var<uniform> display_params: DisplayParams;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let c = textureLoad(radiance, vec2<i32>(pixel.xy), 0).rgb;
    return vec4<f32>(tone_map(c * exp2(display_params.exposure)), 1.0);
}

// Saturated explicitly (the target would clip too): radiance above 1 is white.
fn tone_map(c: vec3<f32>) -> vec3<f32> {
    return saturate(c);
}
