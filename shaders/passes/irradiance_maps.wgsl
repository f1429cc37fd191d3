// irradiance_maps — one diffuse and M + 1 specular Kajiya-Kay irradiance
// maps summed directly over every texel of the environment cube (Xing et al.
// 2012 §3, eq. 5 and 8): for the tangent t of each map texel,
//   D(t)      = 1/π² Σ sin θᵢ Lᵢ dωᵢ,
//   S_m(t)    = 1/π² Σ cos^p(π − θᵢ − mπ/M) Lᵢ dωᵢ,
// p the hair material's specular exponent. Atlas 6n wide, (M + 2)·n high:
// map k (0 diffuse, 1 + m specular) in rows k·n … One thread per map texel,
// N = 6·16² texel lights each: the paper's (M + 2)·N² operations.
#import plait::frame::frame
#import plait::cube::cube_texel_direction
#import plait::sh::{kk_diffuse, kk_specular, KK_NORMALIZATION, PI}

@group(1) @binding(0) var environment: texture_2d<f32>;
@group(1) @binding(1) var maps: texture_storage_2d<rgba16float, write>;

struct MapParams {
    intervals: u32,
}
@group(1) @binding(2) var<uniform> map_params: MapParams;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(maps);
    if (id.x >= dims.x || id.y >= dims.y) {
        return;
    }
    let n = dims.x / 6u;
    let map = id.y / n;
    let t = cube_texel_direction(vec2<u32>(id.x, id.y % n), n);
    let theta_eye = f32(max(map, 1u) - 1u) * PI / f32(map_params.intervals);
    let exponent = frame.hair_shading.z;
    let env = textureDimensions(environment);
    let env_n = env.y;
    var sum = vec3<f32>(0.0);
    for (var y = 0u; y < env.y; y++) {
        for (var x = 0u; x < env.x; x++) {
            let texel = textureLoad(environment, vec2<u32>(x, y), 0);
            let c = dot(t, cube_texel_direction(vec2<u32>(x, y), env_n));
            var response: f32;
            if (map == 0u) {
                response = kk_diffuse(c);
            } else {
                response = kk_specular(c, theta_eye, exponent);
            }
            sum += response * texel.rgb * texel.a;
        }
    }
    textureStore(maps, id.xy, vec4<f32>(sum * KK_NORMALIZATION, 1.0));
}
