// plait::display — what every tone-mapping technique's pass shares: the
// pipeline's radiance (linear, float; bound by name, slot `radiance`) times
// 2^exposure (the technique's `exposure` param, in stops). The operator
// itself is the technique's own `tone_map`; its rgba8unorm-srgb target
// encodes the result to sRGB.
#define_import_path plait::display

struct DisplayParams {
    exposure: f32,
}

@group(1) @binding(0) var radiance: texture_2d<f32>;
@group(1) @binding(1) var<uniform> display_params: DisplayParams;

// The exposed radiance of the pixel at `pixel` (a fragment's position).
fn exposed_radiance(pixel: vec4<f32>) -> vec3<f32> {
    let c = textureLoad(radiance, vec2<i32>(pixel.xy), 0).rgb;
    return c * exp2(display_params.exposure);
}
