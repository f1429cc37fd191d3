// plait::self_shadow::occupancy — self-shadowing from the light-view occupancy
// + slab + depth-range maps (Sintorn & Assarsson 2009 §3.3): opacity = o · w,
// visibility = exp(-opacity), o the order estimate of §3.2 at the point's
// "in front of" depth (`plait::frame::light_lookup`, which also applies the
// half-texel jitter of Fig. 9 when the frame asks for it).
// The number of slabs is read from the slab buffer's size: one counter per
// texel (occupancy_no_slab.toml) makes every set bit stand for F/S fragments,
// F the texel's total — occupancy bits alone.
#define_import_path plait::self_shadow::occupancy

#import plait::frame::light_lookup
#import plait::map_share::MAP_SHARE_SCALE
#import plait::occupancy::{MAX_WORDS, relative_depth_in, slab_position, word_bits, order_in_slab}

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
    // Behind the texel's hair the last slab's position stands in: the counts
    // before it plus its own are the total, exactly (integers in f32).
    let behind = rel >= 1.0;
    let p = slab_position(select(max(rel, 0.0), 0.99999994, behind), max(words, 1u), max(slabs, 1u));
    let index = texel.y * size.x + texel.x;
    var before = 0.0;
    for (var i = 0u; i < p.slab; i++) {
        before += f32(vis_slabs[index * slabs + i]);
    }
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
    let order = select(order_in_slab(p, before, slab_count, set_in_slab, bits_before, bits_through, 0.0), before + f32(slab_count), behind);
    return select(order, 0.0, words == 0u || slabs == 0u || rel <= 0.0);
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

// The strand count toward the light (the self_shadow point's optional
// function): the order estimate itself, in strands (fragment shares).
fn hair_strands_toward_light(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 0.0;
    }
    return light_order(lookup.texel, size, lookup.in_front_below) / MAP_SHARE_SCALE;
}
