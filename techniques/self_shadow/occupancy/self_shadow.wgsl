// plait::self_shadow::occupancy — self-shadowing from the light-view occupancy
// + slab + depth-range maps (Sintorn & Assarsson 2009 §3.3): opacity = o · w,
// visibility = exp(-opacity), o the order estimate of §3.2 at the point's
// "in front of" depth (`plait::frame::light_lookup`, which also applies the
// half-texel jitter of Fig. 9 when the frame asks for it).
// The number of slabs is read from the slab buffer's size: one counter per
// texel (occupancy_no_slab.toml) makes every set bit stand for F/S fragments,
// F the texel's total — occupancy bits alone.
#define_import_path plait::self_shadow::occupancy

#import plait::frame::{light_behind, light_lookup}
#import plait::map_share::MAP_SHARE_SCALE
#import plait::occupancy::{MAX_WORDS, SlabPosition, relative_depth_in, slab_position, word_bits, order_in_slab}

@group(1) @binding(9) var vis_range: texture_2d<f32>;
@group(1) @binding(10) var<storage, read> vis_bits: array<u32>;
@group(1) @binding(11) var<storage, read> vis_slabs: array<u32>;

struct VisibilityParams {
    // Opacity added by one hair fragment in front (w of §3.3).
    shadow_weight: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

// The order estimate of §3.2 (`plait::occupancy::order_estimate`), reading
// only the words it needs: the counts before the point's slab and that slab's
// occupancy words. In front of the texel's hair the order is 0, behind it the
// total; both come out of the same path, selected at the end, because llvmpipe
// runs both sides of a branch (and skipping the branches measured 5% off the
// default frame, README, Performance) — the result is bit-identical.
fn light_order(texel: vec2<u32>, size: vec2<u32>, depth: f32) -> f32 {
    let texels = size.x * size.y;
    let words = min(arrayLength(&vis_bits) / texels, MAX_WORDS);
    let slabs = min(arrayLength(&vis_slabs) / texels, MAX_WORDS);
    let rel = relative_depth_in(textureLoad(vis_range, vec2<i32>(texel), 0).xy, depth);
    let p = position_of(rel, words, slabs);
    let index = texel.y * size.x + texel.x;
    var before = 0.0;
    for (var i = 0u; i < p.slab; i++) {
        before += f32(vis_slabs[index * slabs + i]);
    }
    return order_from(index, words, slabs, p, rel, before);
}

// Where relative depth `rel` falls. Behind the texel's hair the last slab's
// position stands in: the counts before it plus its own are the total,
// exactly (integers in f32).
fn position_of(rel: f32, words: u32, slabs: u32) -> SlabPosition {
    return slab_position(select(max(rel, 0.0), 0.99999994, rel >= 1.0), max(words, 1u), max(slabs, 1u));
}

// The order at `p` (relative depth `rel`) of the texel at `index`, the
// counts before its slab given: its slab's words read, 0 in front of the
// texel's hair, the total behind it.
fn order_from(index: u32, words: u32, slabs: u32, p: SlabPosition, rel: f32, before: f32) -> f32 {
    var set_in_slab = 0u;
    var bits_before = 0u;
    var bits_through = 0u;
    for (var w = p.first / 32u; w * 32u < p.end; w++) {
        let word = vis_bits[index * words + w];
        set_in_slab += word_bits(word, w, p.first, p.end);
        bits_before += word_bits(word, w, p.first, p.slice);
        bits_through += word_bits(word, w, p.first, p.slice + 1u);
    }
    let slab_count = vis_slabs[index * slabs + p.slab];
    let order = select(order_in_slab(p, before, slab_count, set_in_slab, bits_before, bits_through, 0.0), before + f32(slab_count), rel >= 1.0);
    return select(order, 0.0, words == 0u || slabs == 0u || rel <= 0.0);
}

// n and m of `hair_strands_along_light` at one texel, its slab counters read
// once for both (issue 43: three separate order lookups cost the default
// frame with dual scattering more than its budget): the order in front of
// `front`, as `light_order` returns it, and the texel's total less the order
// in front of `past_own` (`plait::frame::light_behind`). The total is the
// order beyond the hair (`light_behind`'s far end, where `light_order`
// returns before + the last slab's count: the same sum in the same order).
fn light_orders(texel: vec2<u32>, size: vec2<u32>, front: f32, past_own: f32) -> vec2<f32> {
    let texels = size.x * size.y;
    let words = min(arrayLength(&vis_bits) / texels, MAX_WORDS);
    let slabs = min(arrayLength(&vis_slabs) / texels, MAX_WORDS);
    let range = textureLoad(vis_range, vec2<i32>(texel), 0).xy;
    let rel_front = relative_depth_in(range, front);
    let rel_own = relative_depth_in(range, past_own);
    let p_front = position_of(rel_front, words, slabs);
    let p_own = position_of(rel_own, words, slabs);
    let index = texel.y * size.x + texel.x;
    // Adding 0.0 leaves a sum unchanged: the prefix sums are light_order's.
    var before_front = 0.0;
    var before_own = 0.0;
    var total = 0.0;
    for (var i = 0u; i < slabs; i++) {
        let count = f32(vis_slabs[index * slabs + i]);
        before_front += select(0.0, count, i < p_front.slab);
        before_own += select(0.0, count, i < p_own.slab);
        total += count;
    }
    let n = order_from(index, words, slabs, p_front, rel_front, before_front);
    let through = order_from(index, words, slabs, p_own, rel_own, before_own);
    return vec2<f32>(n, max(total - through, 0.0));
}

fn hair_visibility(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 1.0;
    }
    // Slabs count strands' shares of the texel (plait::map_share); the bits
    // only place them, so the order is in shares too.
    let order = light_order(lookup.texel, size, lookup.in_front_below) / MAP_SHARE_SCALE;
    return exp(-order * visibility_params.shadow_weight);
}

// The strands in front of and behind the point (the self_shadow point's
// optional function): order estimates, in strands (fragment shares), in the
// point's own texel.
fn hair_strands_along_light(world: vec3<f32>) -> vec2<f32> {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return vec2<f32>(0.0);
    }
    let orders = light_orders(lookup.texel, size, lookup.in_front_below, light_behind(world).x);
    return orders / MAP_SHARE_SCALE;
}
