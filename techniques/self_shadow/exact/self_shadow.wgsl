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

#import plait::frame::{light_behind, light_lookup}
#import plait::map_share::{list_depth, list_share}

@group(1) @binding(9) var vis_range: texture_2d<f32>;
@group(1) @binding(10) var<storage, read> vis_lists: array<u32>;
@group(1) @binding(11) var<storage, read> vis_counts: array<u32>;

struct VisibilityParams {
    // Opacity added by one hair fragment in front (w of Sintorn & Assarsson 2009 §3.3).
    shadow_weight: f32,
    // 0: T = exp(-w · Σ share), the convention every provider shares; 1:
    // fibres opaque to light, T = Π (1 - share) — a shadow ray that meets a
    // fibre is blocked, as in a path tracer limited to single scattering
    // (docs/formats.md, "Light and units"); between: the mix of the two.
    shadow_opaque: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

struct InFront {
    // Σ share of the fragments in front (whole-texel fragments count 1).
    count: f32,
    // Π (1 - share) over them: the part of the texel no fibre in front covers.
    open: f32,
}

// Hair fragments at `texel` nearer the light than linear depth `below`.
fn exact_in_front(texel: vec2<u32>, size: vec2<u32>, below: f32) -> InFront {
    let index = texel.y * size.x + texel.x;
    let capacity = arrayLength(&vis_lists) / (size.x * size.y);
    let total = vis_counts[index];
    let stored = min(total, capacity);
    // Each fragment counts its strand's share of the texel (1 for whole
    // texels, coverage off): the depth_lists pass stores it with the depth.
    var out = InFront(0.0, 1.0);
    for (var i = 0u; i < stored; i++) {
        let entry = vis_lists[index * capacity + i];
        if (list_depth(entry) < below) {
            out.count += list_share(entry);
            out.open *= 1.0 - list_share(entry);
        }
    }
    if (stored < total) {
        // The dropped fragments, distributed like the stored ones.
        let scale = f32(total) / f32(stored);
        out.count *= scale;
        out.open = select(pow(out.open, scale), 0.0, out.open <= 0.0);
    }
    return out;
}

fn hair_visibility(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 1.0;
    }
    let front = exact_in_front(lookup.texel, size, lookup.in_front_below);
    let soft = exp(-visibility_params.shadow_weight * front.count);
    return mix(soft, front.open, visibility_params.shadow_opaque);
}

// The strands in front of and behind the point (the self_shadow point's
// optional function), in one pass over the point's list: Σ share of the
// stored fragments nearer the light than `in_front_below` (the count the
// visibility attenuates by) and of those in [past_own, beyond)
// (`plait::frame::light_behind`), both scaled up when the list overflowed,
// as the visibility is.
fn hair_strands_along_light(world: vec3<f32>) -> vec2<f32> {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return vec2<f32>(0.0);
    }
    let behind = light_behind(world);
    let index = lookup.texel.y * size.x + lookup.texel.x;
    let capacity = arrayLength(&vis_lists) / (size.x * size.y);
    let total = vis_counts[index];
    let stored = min(total, capacity);
    var counts = vec2<f32>(0.0);
    for (var i = 0u; i < stored; i++) {
        let entry = vis_lists[index * capacity + i];
        let depth = list_depth(entry);
        let share = list_share(entry);
        counts.x += select(0.0, share, depth < lookup.in_front_below);
        counts.y += select(0.0, share, depth >= behind.x && depth < behind.y);
    }
    if (stored < total) {
        // The dropped fragments, distributed like the stored ones.
        counts *= f32(total) / f32(stored);
    }
    return counts;
}
