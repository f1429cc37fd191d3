// plait::self_shadow::density_clustering — density clustering (Mertens et al.
// 2004; Halén & Wester 2007 §3.3.2). Per light
// texel: 4 k-means clusters of fragment depth (count n, Σz, Σz², z relative to
// the texel's hair range, fixed point × 2^18; the last stage of the
// density_clustering pass). Each cluster is a histogram bin of density
// n / width centred on its mean, width 2√3·σ (a uniform distribution with the
// cluster's standard deviation σ); the density integrated up to a depth is
// the (piecewise linear) fragment count in front; visibility
// V = exp(-w · ∫d), w = shadow_weight as in occupancy.
#define_import_path plait::self_shadow::density_clustering

#import plait::frame::light_lookup
#import plait::map_share::MAP_SHARE_SCALE

@group(1) @binding(9) var vis_range: texture_2d<f32>;
@group(1) @binding(10) var<storage, read> vis_clusters: array<u32>;

struct VisibilityParams {
    // Opacity added by one hair fragment in front (w of Sintorn & Assarsson 2009 §3.3).
    shadow_weight: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

const DC_K: u32 = 4u;
const DC_SCALE: f32 = 262144.0;

// ∫ density up to linear light depth `depth` at `texel`: fragments in front.
fn cluster_count(texel: vec2<u32>, size: vec2<u32>, depth: f32) -> f32 {
    let range = textureLoad(vis_range, vec2<i32>(texel), 0);
    if (range.y < range.x) {
        return 0.0; // no hair in this texel
    }
    let texels = size.x * size.y;
    let stages = arrayLength(&vis_clusters) / (texels * DC_K * 3u);
    let base = ((stages - 1u) * texels + texel.y * size.x + texel.x) * DC_K * 3u;
    let z = (depth - range.x) / max(range.y - range.x, 1e-9);
    var total = 0.0;
    for (var k = 0u; k < DC_K; k++) {
        // Clusters count strands' shares of the texel (plait::map_share);
        // their depth sums are share-weighted.
        let n = f32(vis_clusters[base + k * 3u]) / MAP_SHARE_SCALE;
        if (n > 0.0) {
            let mean = f32(vis_clusters[base + k * 3u + 1u]) / (DC_SCALE * n);
            let mean_sq = f32(vis_clusters[base + k * 3u + 2u]) / (DC_SCALE * n);
            let sigma = sqrt(max(mean_sq - mean * mean, 0.0));
            let half_width = 1.7320508 * sigma;
            if (half_width < 1e-5) {
                total += select(0.0, n, z > mean);
            } else {
                total += n * clamp((z - (mean - half_width)) / (2.0 * half_width), 0.0, 1.0);
            }
        }
    }
    return total;
}

fn hair_visibility(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 1.0;
    }
    return exp(-visibility_params.shadow_weight * cluster_count(lookup.texel, size, lookup.in_front_below));
}
