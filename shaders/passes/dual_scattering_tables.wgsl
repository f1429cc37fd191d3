// The dual-scattering tables (shaders/passes/dual_scattering_tables.toml):
// one texel per (sin θi, σ_a), the Chiang fibre's scattered energy
// integrated over θo and φ by the midpoint rule (THETA_STEPS × PHI_STEPS
// points, each the mean over the strand's width at WIDTH_STEPS points), split
// into the forward (φ > π/2) and backward half, with the energy-weighted
// mean and variance of θh in each (plait::dual_scattering has the layout).
#import plait::frame::fullscreen_position
#import plait::chiang::{Fibre, fibre, chiang_at}
#import plait::dual_scattering::absorption_at

struct Params {
    sin_steps: i32,
    absorption_steps: i32,
    beta_m: f32,
    beta_n: f32,
    tilt: f32,
    eta: f32,
}
@group(1) @binding(0) var<uniform> params: Params;

struct Tables {
    @location(0) table_a: vec4<f32>,
    @location(1) table_b: vec4<f32>,
}

const PI: f32 = 3.14159265358979;
// 32 × 24 × 32 points: the tables are drawn once; their sums against 2×
// the points differ by < 1 % (tests/dual_scattering.rs).
const THETA_STEPS: i32 = 32;
const PHI_STEPS: i32 = 24;
const WIDTH_STEPS: i32 = 32;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

// Energy, energy·θh and energy·θh² of each half: (forward, backward) × 3.
struct Sums {
    forward: vec3<f32>,
    backward: vec3<f32>,
}

fn integrate(f: Fibre, sin_i: f32) -> Sums {
    let theta_i = asin(sin_i);
    let d_theta = PI / f32(THETA_STEPS);
    let d_phi = PI / f32(PHI_STEPS);
    var s = Sums(vec3<f32>(0.0), vec3<f32>(0.0));
    for (var j = 0; j < THETA_STEPS; j++) {
        let theta_o = -0.5 * PI + (f32(j) + 0.5) * d_theta;
        let theta_h = 0.5 * (theta_i + theta_o);
        let weight = cos(theta_o) * d_theta * d_phi * 2.0; // φ and −φ
        for (var i = 0; i < PHI_STEPS; i++) {
            let phi = (f32(i) + 0.5) * d_phi;
            let e = weight * chiang_at(f, sin_i, sin(theta_o), phi, vec4<f32>(1.0), WIDTH_STEPS).x;
            let m = vec3<f32>(e, e * theta_h, e * theta_h * theta_h);
            if (phi > 0.5 * PI) {
                s.forward += m;
            } else {
                s.backward += m;
            }
        }
    }
    return s;
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> Tables {
    let size = vec2<f32>(f32(max(params.sin_steps, 2)), f32(max(params.absorption_steps, 2)));
    let uv = pixel.xy / size;
    let sin_i = -1.0 + 2.0 * uv.x;
    // Row j holds σ_a/(1 + σ_a) = j/N (plait::dual_scattering).
    let sigma = absorption_at((pixel.y - 0.5) / size.y);
    var f = fibre(params.beta_m, params.beta_n, params.tilt, params.eta, vec3<f32>(1.0));
    f.sigma_a = vec3<f32>(sigma);
    let s = integrate(f, sin_i);
    let mean_f = s.forward.y / max(s.forward.x, 1e-30);
    let mean_b = s.backward.y / max(s.backward.x, 1e-30);
    var out: Tables;
    out.table_a = vec4<f32>(s.forward.x, s.backward.x, mean_f, mean_b);
    out.table_b = vec4<f32>(
        s.forward.z / max(s.forward.x, 1e-30) - mean_f * mean_f,
        s.backward.z / max(s.backward.x, 1e-30) - mean_b * mean_b,
        0.0,
        0.0,
    );
    return out;
}
