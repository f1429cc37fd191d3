// marschner_tables — the lookup tables of the Marschner model (Halén & Wester
// 2007 §5.8, after Nguyen & Donnelly 2005): the longitudinal M and the
// azimuthal N precomputed once, so the shading pass reads two texels instead
// of solving for light paths per fragment.
//
// - `m_table` at (sin θi, sin θr), both −1 … 1: M_R, M_TT, M_TRT and, in
//   alpha, cos θd ("a function of θi, θr", §5.8), so the shader needs no
//   inverse trigonometry.
// - `n_table` at (cos φ, cos θd), −1 … 1 and 0 … 1: N_TT and N_TRT with no
//   absorption (N_TRT's caustics clamped), and their path lengths per unit
//   σa (plait::marschner::Transmitted), so the lookup applies any hair
//   colour's absorption per channel, exp(−σa · length): exact for TT (one
//   root), the roots' weighted mean length for TRT. N_R needs no table: the
//   lookup evaluates it exactly (plait::marschner::reflection, square roots
//   only).
// Texel centres sit on both ends of each axis (plait::marschner::
// table_coordinate), so a table is exact at its texels. One fragment per
// texel of both tables (colour targets 0 and 1, `table_size`² each). The
// model is plait::marschner, the same WGSL the per-fragment reference
// evaluates.
#import plait::frame::fullscreen_position
#import plait::marschner::{model, longitudinal, azimuthal, cos_theta_d, table_value}

struct Params {
    table_size: i32,
    shift_r: f32,
    shift_tt: f32,
    shift_trt: f32,
    width_r: f32,
    width_tt: f32,
    width_trt: f32,
    ior: f32,
    absorption: f32,
    caustic_limit: f32,
}
@group(1) @binding(0) var<uniform> params: Params;

struct Tables {
    @location(0) m_table: vec4<f32>,
    @location(1) n_table: vec4<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> Tables {
    let size = u32(max(params.table_size, 2));
    let texel = vec2<u32>(pixel.xy);
    let m = model(
        vec3<f32>(params.shift_r, params.shift_tt, params.shift_trt),
        vec3<f32>(params.width_r, params.width_tt, params.width_trt),
        params.ior,
        params.absorption,
        params.caustic_limit,
    );
    let sin_i = table_value(texel.x, -1.0, 1.0, size);
    let sin_r = table_value(texel.y, -1.0, 1.0, size);
    let cos_phi = table_value(texel.x, -1.0, 1.0, size);
    let cos_td = table_value(texel.y, 0.0, 1.0, size);
    var out: Tables;
    out.m_table = vec4<f32>(longitudinal(m, sin_i, sin_r), cos_theta_d(sin_i, sin_r));
    let n = azimuthal(m, cos_phi, cos_td, vec3<f32>(0.0));
    out.n_table = vec4<f32>(n.clear, n.length);
    return out;
}
