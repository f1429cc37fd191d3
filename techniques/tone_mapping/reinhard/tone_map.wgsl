// tone_mapping/reinhard: the display transform — Reinhard et al. 2002, eq. 3 on luminance (see technique.toml).
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

// L_d = L / (1 + L) (eq. 3) on the Rec. 709 luminance; the colour keeps its
// chromaticity (scaled by L_d / L). Black stays black.
fn tone_map(c: vec3<f32>) -> vec3<f32> {
    let l = dot(max(c, vec3<f32>(0.0)), vec3<f32>(0.2126, 0.7152, 0.0722));
    if (l <= 0.0) {
        return vec3<f32>(0.0);
    }
    return saturate(c * (1.0 / (1.0 + l)));
}
