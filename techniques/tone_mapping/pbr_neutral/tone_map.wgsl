// tone_mapping/pbr_neutral: the display transform — Khronos PBR Neutral (see technique.toml).
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

const START_COMPRESSION: f32 = 0.8 - 0.04;
const DESATURATION: f32 = 0.15;

fn tone_map(color: vec3<f32>) -> vec3<f32> {
    let x = min(color.r, min(color.g, color.b));
    let offset = select(0.04, x - 6.25 * x * x, x < 0.08);
    var c = color - offset;
    let peak = max(c.r, max(c.g, c.b));
    if (peak < START_COMPRESSION) {
        return c;
    }
    let d = 1.0 - START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - START_COMPRESSION);
    c = c * (new_peak / peak);
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    return mix(c, vec3<f32>(new_peak), g);
}
