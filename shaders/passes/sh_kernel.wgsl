// sh_kernel — the Kajiya-Kay transfer of each irradiance map per SH band.
// Xing et al. 2012 §5 precomputes Σ_j Y_i(l_j) f(t, l_j) dω for every map
// texel; f depends on t only through t · l, so by the Funk–Hecke theorem
// that sum is λ_l Y_i(t) with λ_l = 2π ∫ f(x) P_l(x) dx (Ramamoorthi &
// Hanrahan 2001 §2) — (M + 2) × bands numbers, independent of the
// environment. Midpoint rule in θ, 2048 steps (the specular lobe at p = 60
// is about 0.3 rad wide). One thread per (map, band).
#import plait::frame::frame
#import plait::sh::{kk_diffuse, kk_specular, sh_legendre, PI}

@group(1) @binding(0) var<storage, read_write> kernel: array<f32>;

struct KernelParams {
    intervals: u32,
    bands: u32,
    diffuse_bands: u32,
}
@group(1) @binding(1) var<uniform> kernel_params: KernelParams;

const STEPS: u32 = 2048u;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let bands = kernel_params.bands;
    if (id.x >= arrayLength(&kernel) || id.x >= (kernel_params.intervals + 2u) * bands) {
        return;
    }
    let map = id.x / bands;
    let l = id.x % bands;
    if (map == 0u && l >= kernel_params.diffuse_bands) {
        kernel[id.x] = 0.0;
        return;
    }
    let theta_eye = f32(max(map, 1u) - 1u) * PI / f32(kernel_params.intervals);
    let exponent = frame.hair_shading.z;
    let dt = PI / f32(STEPS);
    var sum = 0.0;
    for (var i = 0u; i < STEPS; i++) {
        let theta = (f32(i) + 0.5) * dt;
        let x = cos(theta);
        var f: f32;
        if (map == 0u) {
            f = kk_diffuse(x);
        } else {
            f = kk_specular(x, theta_eye, exponent);
        }
        sum += f * sh_legendre(l, 0u, x) * sin(theta) * dt;
    }
    kernel[id.x] = 2.0 * PI * sum;
}
