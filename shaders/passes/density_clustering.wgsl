// density_clustering: k-means (K = 4) of the fragment depths of each light
// texel, one hair draw per iteration (Mertens et al. 2004; summarised in
// Halén & Wester 2007 §3.3.2). The pass defines STAGE per draw: stage 0
// assigns fragments to 4 uniform slices of the texel's hair range; stage s > 0
// assigns each to the nearest mean of stage s - 1. Each stage accumulates, per
// cluster, (count, Σz, Σz²) of z = depth relative to the texel range, fixed
// point × 2^18, with atomicAdd. Layout: [stage][texel][cluster][3] u32.
#import plait::hair_map::{MapVertex, MapFragment, map_vertex, map_texel, map_weight, map_unit}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> clusters: array<atomic<u32>>;

const K: u32 = 4u;
const SCALE: f32 = 262144.0; // 2^18

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v, textureDimensions(range));
}

@fragment
fn fs_main(in: MapFragment) {
    let m = map_texel(in, range);
    let texels = m.size.x * m.size.y;
    let z = clamp(m.rel, 0.0, 1.0);
    let texel_index = m.index;
    var best = min(u32(z * f32(K)), K - 1u);
#if STAGE > 0
    // Nearest mean of the previous stage (empty clusters never win).
    let prev = ((#{STAGE}u - 1u) * texels + texel_index) * K * 3u;
    var best_d = 2.0;
    for (var k = 0u; k < K; k++) {
        let n = atomicLoad(&clusters[prev + k * 3u]);
        if (n > 0u) {
            let mean = f32(atomicLoad(&clusters[prev + k * 3u + 1u])) / (SCALE * f32(n) / map_unit());
            let d = abs(z - mean);
            if (d < best_d) {
                best_d = d;
                best = k;
            }
        }
    }
#endif
    let base = (#{STAGE}u * texels + texel_index) * K * 3u + best * 3u;
    // Weighted by the strand's share of the texel: the count in units of
    // map_unit(), the depth sums by the share (a weighted mean).
    let weight = map_weight(m);
    let share = f32(weight) / map_unit();
    atomicAdd(&clusters[base], weight);
    atomicAdd(&clusters[base + 1u], u32(round(z * share * SCALE)));
    atomicAdd(&clusters[base + 2u], u32(round(z * z * share * SCALE)));
}
