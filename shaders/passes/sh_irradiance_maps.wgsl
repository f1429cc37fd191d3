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

struct MapParams {
    bands: u32,
    diffuse_bands: u32,
}
@group(1) @binding(3) var<uniform> map_params: MapParams;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(maps);
    if (id.x >= dims.x || id.y >= dims.y) {
        return;
    }
    let n = dims.x / 6u;
    let map = id.y / n;
    let t = cube_texel_direction(vec2<u32>(id.x, id.y % n), n);
    var bands = map_params.bands;
    if (map == 0u) {
        bands = min(map_params.diffuse_bands, bands);
    }
    var sum = vec3<f32>(0.0);
    for (var l = 0u; l < bands; l++) {
        let lambda = kernel[map * map_params.bands + l];
        for (var i = l * l; i < (l + 1u) * (l + 1u); i++) {
            sum += lambda * coefficients[i].rgb * sh_basis(i, t);
        }
    }
    textureStore(maps, id.xy, vec4<f32>(sum * KK_NORMALIZATION, 1.0));
}
