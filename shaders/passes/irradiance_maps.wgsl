// irradiance_maps — one diffuse and M + 1 specular Kajiya-Kay irradiance
// maps summed directly over every texel of the environment cube (Xing et al.
// 2012 §3, eq. 5 and 8): for the tangent t of each map texel,
//   D(t)      = 1/π² Σ sin θᵢ Lᵢ dωᵢ,
//   S_m(t)    = 1/π² Σ cos^p(π − θᵢ − mπ/M) Lᵢ dωᵢ,
// p the hair material's specular exponent. Atlas 6n wide, (M + 2)·n high:
// map k (0 diffuse, 1 + m specular) in rows k·n …: the paper's
// (M + 2)·N² operations, N = 6·16² texel lights.
//
// A thread runs 6s²·(M + 3) loop passes (s = environment_size): 16,924 at the
// defaults, past lavapipe's 65,535 per 8 invocations for s ≥ 18 at M = 32 or
// s ≥ 32 at M = 8. A thread that ran out counts itself in `status[0]` (the
// `incomplete` word of its overflow declaration) and the frame fails.
#import plait::frame::frame
#import plait::cube::cube_texel_direction
#import plait::sh::{kk_diffuse, KK_NORMALIZATION, PI}
#import plait::loop_budget::loop_budget_spent

@group(1) @binding(0) var environment: texture_2d<f32>;
@group(1) @binding(1) var maps: texture_storage_2d<rgba16float, write>;

struct MapParams {
    intervals: u32,
}
@group(1) @binding(2) var<uniform> map_params: MapParams;
@group(1) @binding(3) var<storage, read_write> status: array<atomic<u32>>;

// Specular maps a thread can hold (`intervals` ≤ 32 in the pass type).
const MAX_MAPS: u32 = 33u;

// One thread per texel of a face (the first n rows): it sums the
// environment once for the diffuse and every specular map of its tangent,
// sharing each light's direction and angle, and writes all M + 2 maps.
@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(maps);
    let n = dims.x / 6u;
    if (id.x >= dims.x || id.y >= n) {
        return;
    }
    let intervals = min(map_params.intervals, MAX_MAPS - 1u);
    let t = cube_texel_direction(id.xy, n);
    let exponent = frame.hair_shading.z;
    let env = textureDimensions(environment);
    var diffuse = vec3<f32>(0.0);
    var specular: array<vec3<f32>, MAX_MAPS>;
    for (var y = 0u; y < env.y; y++) {
        for (var x = 0u; x < env.x; x++) {
            let texel = textureLoad(environment, vec2<u32>(x, y), 0);
            let light = texel.rgb * texel.a;
            let c = clamp(dot(t, cube_texel_direction(vec2<u32>(x, y), env.y)), -1.0, 1.0);
            diffuse += kk_diffuse(c) * light;
            let theta = acos(c);
            for (var m = 0u; m <= intervals; m++) {
                let theta_eye = f32(m) * PI / f32(intervals);
                specular[m] += pow(max(0.0, cos(PI - theta - theta_eye)), exponent) * light;
            }
        }
    }
    textureStore(maps, id.xy, vec4<f32>(diffuse * KK_NORMALIZATION, 1.0));
    for (var m = 0u; m <= intervals; m++) {
        textureStore(maps, vec2<u32>(id.x, (1u + m) * n + id.y), vec4<f32>(specular[m] * KK_NORMALIZATION, 1.0));
    }
    if (loop_budget_spent(env.y)) {
        atomicAdd(&status[0], 1u);
    }
}
