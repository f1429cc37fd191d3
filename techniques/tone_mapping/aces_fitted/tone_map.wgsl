// tone_mapping/aces_fitted: the display transform — Stephen Hill's ACES RRT+ODT fit (see technique.toml).
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

// Rows of Hill's matrices (ACES.hlsl applies them as mul(M, v)).
// sRGB => XYZ => D65_2_D60 => AP1 => RRT_SAT
fn aces_input(v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        dot(vec3<f32>(0.59719, 0.35458, 0.04823), v),
        dot(vec3<f32>(0.07600, 0.90834, 0.01566), v),
        dot(vec3<f32>(0.02840, 0.13383, 0.83777), v),
    );
}

// ODT_SAT => XYZ => D60_2_D65 => sRGB
fn aces_output(v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        dot(vec3<f32>(1.60475, -0.53108, -0.07367), v),
        dot(vec3<f32>(-0.10208, 1.10813, -0.00605), v),
        dot(vec3<f32>(-0.00327, -0.07276, 1.07602), v),
    );
}

// The rational fit of the RRT followed by the sRGB ODT.
fn rrt_and_odt_fit(v: vec3<f32>) -> vec3<f32> {
    let a = v * (v + 0.0245786) - 0.000090537;
    let b = v * (0.983729 * v + 0.4329510) + 0.238081;
    return a / b;
}

fn tone_map(c: vec3<f32>) -> vec3<f32> {
    return saturate(aces_output(rrt_and_odt_fit(aces_input(c))));
}
