// sh_project — the environment cube projected on real spherical harmonics
// (Xing et al. 2012 §5, eq. 10): w_i = Σ_j L(l_j) Y_i(l_j) dω_j over every
// cube texel. One thread per float of `coefficients` (vec4 per coefficient:
// rgb, a = 0), each summing all texels: bands² × 3 sums of N terms.
//
// A thread runs 6s² texel laps, each with sh_basis's loops (about 3·l + 5
// for band l): 39,953 loop passes at the defaults (8 bands, s = 16), past
// lavapipe's 65,535 per 8 invocations from 14 bands at s = 16 or s ≥ 21 at
// 8 bands. A thread that ran out counts itself in `status[0]` (the
// `incomplete` word of its overflow declaration) and the frame fails.
#import plait::cube::cube_texel_direction
#import plait::sh::sh_basis
#import plait::loop_budget::loop_budget_spent

@group(1) @binding(0) var environment: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> coefficients: array<f32>;
@group(1) @binding(2) var<storage, read_write> status: array<atomic<u32>>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= arrayLength(&coefficients)) {
        return;
    }
    let coefficient = id.x / 4u;
    let channel = id.x % 4u;
    if (channel == 3u) {
        coefficients[id.x] = 0.0;
        return;
    }
    let env = textureDimensions(environment);
    var sum = 0.0;
    for (var y = 0u; y < env.y; y++) {
        for (var x = 0u; x < env.x; x++) {
            let texel = textureLoad(environment, vec2<u32>(x, y), 0);
            let d = cube_texel_direction(vec2<u32>(x, y), env.y);
            sum += texel[channel] * texel.a * sh_basis(coefficient, d);
        }
    }
    coefficients[id.x] = sum;
    if (loop_budget_spent(env.y)) {
        atomicAdd(&status[0], 1u);
    }
}
