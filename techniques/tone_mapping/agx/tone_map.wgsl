// tone_mapping/agx: the display transform — Troy Sobotka's AgX as in three.js r160 (see technique.toml).
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

// Column-major like the GLSL it is ported from (mat3 * v).
const SRGB_TO_REC2020 = mat3x3<f32>(
    vec3<f32>(0.6274, 0.0691, 0.0164),
    vec3<f32>(0.3293, 0.9195, 0.0880),
    vec3<f32>(0.0433, 0.0113, 0.8956),
);
const REC2020_TO_SRGB = mat3x3<f32>(
    vec3<f32>(1.6605, -0.1246, -0.0182),
    vec3<f32>(-0.5876, 1.1329, -0.1006),
    vec3<f32>(-0.0728, -0.0083, 1.1187),
);
const AGX_INSET = mat3x3<f32>(
    vec3<f32>(0.856627153315983, 0.137318972929847, 0.11189821299995),
    vec3<f32>(0.0951212405381588, 0.761241990602591, 0.0767994186031903),
    vec3<f32>(0.0482516061458583, 0.101439036467562, 0.811302368396859),
);
const AGX_OUTSET = mat3x3<f32>(
    vec3<f32>(1.1271005818144368, -0.1413297634984383, -0.14132976349843826),
    vec3<f32>(-0.11060664309660323, 1.157823702216272, -0.11060664309660294),
    vec3<f32>(-0.016493938717834573, -0.016493938717834257, 1.2519364065950405),
);
// log2(0.18 · 2^-10) and log2(0.18 · 2^6.5): the encoded range about middle grey.
const AGX_MIN_EV: f32 = -12.47393;
const AGX_MAX_EV: f32 = 4.026069;

// The default contrast sigmoid, a polynomial fit (mean error² 3.7e-6).
fn agx_contrast(x: vec3<f32>) -> vec3<f32> {
    let x2 = x * x;
    let x4 = x2 * x2;
    return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2
        + 0.1191 * x - 0.00232;
}

fn tone_map(c: vec3<f32>) -> vec3<f32> {
    var v = AGX_INSET * (SRGB_TO_REC2020 * c);
    v = log2(max(v, vec3<f32>(1e-10)));
    v = saturate((v - AGX_MIN_EV) / (AGX_MAX_EV - AGX_MIN_EV));
    v = AGX_OUTSET * agx_contrast(v);
    v = pow(max(v, vec3<f32>(0.0)), vec3<f32>(2.2));
    return saturate(REC2020_TO_SRGB * v);
}
