// plait::visibility::occupancy — self-shadowing from the light-view occupancy
// + slab + depth-range maps (Sintorn & Assarsson 2009 §3.3): opacity = o · w,
// visibility = exp(-opacity), o the order estimate of §3.2 at the point's
// "in front of" depth (`plait::frame::light_lookup`, which also applies the
// half-texel jitter of Fig. 9 when the frame asks for it).
// The number of slabs is read from the slab buffer's size: one counter per
// texel (occupancy_no_slab.toml) makes every set bit stand for F/S fragments,
// F the texel's total — occupancy bits alone.
#define_import_path plait::visibility::occupancy

#import plait::frame::light_lookup
#import plait::occupancy::{TexelMaps, MAX_WORDS, relative_depth, order_estimate}

@group(1) @binding(9) var vis_range: texture_2d<f32>;
@group(1) @binding(10) var<storage, read> vis_bits: array<u32>;
@group(1) @binding(11) var<storage, read> vis_slabs: array<u32>;

struct VisibilityParams {
    // Opacity added by one hair fragment in front (w of §3.3).
    shadow_weight: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

fn load_light_maps(texel: vec2<u32>, size: vec2<u32>) -> TexelMaps {
    var maps: TexelMaps;
    let texels = size.x * size.y;
    let words = min(arrayLength(&vis_bits) / texels, MAX_WORDS);
    let slabs = min(arrayLength(&vis_slabs) / texels, MAX_WORDS);
    maps.words = words;
    maps.slabs = slabs;
    let range = textureLoad(vis_range, vec2<i32>(texel), 0);
    maps.near = range.x;
    maps.far = range.y;
    let index = texel.y * size.x + texel.x;
    for (var i = 0u; i < words; i++) {
        maps.bits[i] = vis_bits[index * words + i];
    }
    for (var i = 0u; i < slabs; i++) {
        maps.counts[i] = vis_slabs[index * slabs + i];
    }
    return maps;
}

fn hair_visibility(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 1.0;
    }
    var maps = load_light_maps(lookup.texel, size);
    let order = order_estimate(&maps, relative_depth(&maps, lookup.in_front_below));
    return exp(-order * visibility_params.shadow_weight);
}
