// tone_mapping/clip: the display transform — no tone mapping (see technique.toml).
// The pass: plait::display's exposed radiance through this operator.
#import plait::frame::fullscreen_position
#import plait::display::exposed_radiance

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(tone_map(exposed_radiance(pixel)), 1.0);
}

// Saturated explicitly (the target would clip too): radiance above 1 is white.
fn tone_map(c: vec3<f32>) -> vec3<f32> {
    return saturate(c);
}
