// plait::visibility::occupancy — self-shadowing from the light-view occupancy
// + slab + depth-range maps (Sintorn & Assarsson 2009 §3.3): opacity = o · w,
// visibility = exp(-opacity), o the order estimate of §3.2. Map lookups are
// jittered by up to half a texel (Fig. 9) against silhouette aliasing.
// The number of slabs is read from the slab buffer's size: one counter per
// texel (occupancy_no_slab.toml) makes every set bit stand for F/S fragments,
// F the texel's total — occupancy bits alone.
#define_import_path plait::visibility::occupancy

#import plait::frame::{frame, light_uv_depth, light_linear_depth}
#import plait::occupancy::{TexelMaps, MAX_WORDS, relative_depth, order_estimate}

@group(1) @binding(9) var vis_range: texture_2d<f32>;
@group(1) @binding(10) var<storage, read> vis_bits: array<u32>;
@group(1) @binding(11) var<storage, read> vis_slabs: array<u32>;

struct VisibilityParams {
    // Opacity added by one hair fragment in front (w of §3.3).
    shadow_weight: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

fn hash2(p: vec3<f32>) -> vec2<f32> {
    let q = vec3<u32>(bitcast<u32>(p.x), bitcast<u32>(p.y), bitcast<u32>(p.z));
    var h = (q.x * 0x9E3779B1u) ^ (q.y * 0x85EBCA77u) ^ (q.z * 0xC2B2AE3Du);
    h = (h ^ (h >> 15u)) * 0x2C1B3C6Du;
    h = (h ^ (h >> 12u)) * 0x297A2D39u;
    h = h ^ (h >> 15u);
    return vec2<f32>(f32(h & 0xFFFFu), f32(h >> 16u)) / 65535.0 - 0.5;
}

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
    let p = light_uv_depth(world);
    if (any(p.xy < vec2<f32>(0.0)) || any(p.xy > vec2<f32>(1.0))) {
        return 1.0;
    }
    let size = textureDimensions(vis_range);
    let jittered = p.xy * vec2<f32>(size) + hash2(world);
    let texel = vec2<u32>(clamp(jittered, vec2<f32>(0.0), vec2<f32>(size) - 1.0));
    var maps = load_light_maps(texel, size);
    let rel = relative_depth(&maps, light_linear_depth(world));
    let order = order_estimate(&maps, rel);
    return exp(-order * visibility_params.shadow_weight);
}
