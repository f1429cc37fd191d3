// sh_irradiance_maps — the irradiance maps rebuilt from the environment's SH
// coefficients (Xing et al. 2012 §5, eq. 11): for each map texel's tangent t,
//   I(t) = 1/π² Σ_l λ_l Σ_m w_lm Y_lm(t),
// the diffuse map over `diffuse_bands` bands, the specular maps over all.
// Same atlas as irradiance_maps, so the same run-time lookup reads it.
#import plait::cube::cube_texel_direction
#import plait::sh::{sh_basis, KK_NORMALIZATION}

@group(1) @binding(0) var<storage, read> coefficients: array<vec4<f32>>;
@group(1) @binding(1) var<storage, read> kernel: array<f32>;
@group(1) @binding(2) var maps: texture_storage_2d<rgba16float, write>;

const MAX_BANDS: u32 = 16u;

struct MapParams {
    bands: u32,
    diffuse_bands: u32,
}
@group(1) @binding(3) var<uniform> map_params: MapParams;

// One thread per texel of a face (the first n rows): the basis of its
// tangent is evaluated once and serves all M + 2 maps.
@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(maps);
    let n = dims.x / 6u;
    if (id.x >= dims.x || id.y >= n) {
        return;
    }
    let maps_count = dims.y / n;
    let bands = min(map_params.bands, MAX_BANDS);
    let t = cube_texel_direction(id.xy, n);
    // w_lm · Y_lm(t) summed over m, per band.
    var band_sums: array<vec3<f32>, MAX_BANDS>;
    for (var l = 0u; l < bands; l++) {
        var sum = vec3<f32>(0.0);
        for (var i = l * l; i < (l + 1u) * (l + 1u); i++) {
            sum += coefficients[i].rgb * sh_basis(i, t);
        }
        band_sums[l] = sum;
    }
    for (var map = 0u; map < maps_count; map++) {
        var map_bands = bands;
        if (map == 0u) {
            map_bands = min(map_params.diffuse_bands, bands);
        }
        var sum = vec3<f32>(0.0);
        for (var l = 0u; l < map_bands; l++) {
            sum += kernel[map * map_params.bands + l] * band_sums[l];
        }
        textureStore(maps, vec2<u32>(id.x, map * n + id.y), vec4<f32>(sum * KK_NORMALIZATION, 1.0));
    }
}
