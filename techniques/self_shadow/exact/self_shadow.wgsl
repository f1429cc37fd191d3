// plait::self_shadow::exact — exact self-shadowing, the ground truth: the
// number n of hair fragments in front of a point from the light
// (Sintorn & Assarsson 2009 §3, Fig. 5; the occupancy order o estimates it),
// counted in the point's light texel over the depth lists of the depth_lists
// pass. Visibility = exp(-w · n), w = shadow_weight. "In front of" is the
// convention every provider shares (`plait::frame::light_lookup`): nearer the
// light by more than the self-shadow bias, so a point never counts itself. Where a list
// overflowed, the dropped fragments are assumed distributed like the stored
// ones (the pass's `overflow` buffer says whether that happened).
#define_import_path plait::self_shadow::exact

#import plait::frame::light_lookup
#import plait::map_share::{list_depth, list_share}

@group(1) @binding(9) var vis_range: texture_2d<f32>;
@group(1) @binding(10) var<storage, read> vis_lists: array<u32>;
@group(1) @binding(11) var<storage, read> vis_counts: array<u32>;

struct VisibilityParams {
    // Opacity added by one hair fragment in front (w of Sintorn & Assarsson 2009 §3.3).
    shadow_weight: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

// Hair fragments at `texel` nearer the light than linear depth `below`.
fn exact_count(texel: vec2<u32>, size: vec2<u32>, below: f32) -> f32 {
    let index = texel.y * size.x + texel.x;
    let capacity = arrayLength(&vis_lists) / (size.x * size.y);
    let total = vis_counts[index];
    let stored = min(total, capacity);
    // Each fragment counts its strand's share of the texel (1 for whole
    // texels, coverage off): the depth_lists pass stores it with the depth.
    var n = 0.0;
    for (var i = 0u; i < stored; i++) {
        let entry = vis_lists[index * capacity + i];
        if (list_depth(entry) < below) {
            n += list_share(entry);
        }
    }
    if (stored == 0u) {
        return 0.0;
    }
    return n * f32(total) / f32(stored);
}

fn hair_visibility(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 1.0;
    }
    return exp(-visibility_params.shadow_weight * exact_count(lookup.texel, size, lookup.in_front_below));
}
