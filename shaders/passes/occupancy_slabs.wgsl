// occupancy_slabs: `occupancy.wgsl` and `slice_counts.wgsl` (as `slab`) in
// one fragment shader (Sintorn & Assarsson 2009 §3.1, Fig. 8): the hair is
// drawn once, the texel's range fetched once, and each fragment sets its
// slice's bit and counts itself in its slab.
#import plait::hair_map::{MapVertex, MapFragment, map_vertex, map_texel, map_weight, words_per_texel}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> bits: array<atomic<u32>>;
@group(1) @binding(2) var<storage, read_write> slabs: array<atomic<u32>>;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v, textureDimensions(range));
}

@fragment
fn fs_main(in: MapFragment) {
    let m = map_texel(in, range);
    let words = words_per_texel(arrayLength(&bits), m);
    let slices = words * 32u;
    let slice = min(u32(max(m.rel, 0.0) * f32(slices)), slices - 1u);
    atomicOr(&bits[m.index * words + slice / 32u], 1u << (slice % 32u));
    let n = words_per_texel(arrayLength(&slabs), m);
    let slab = min(u32(clamp(m.rel, 0.0, 1.0) * f32(n)), n - 1u);
    // Weighted by the strand's share of the texel in a light view (the bits
    // say only where hair is: the order between slab ends is interpolated
    // through them, so a slab's weight spreads over its set bits evenly).
    atomicAdd(&slabs[m.index * n + slab], map_weight(m));
}
