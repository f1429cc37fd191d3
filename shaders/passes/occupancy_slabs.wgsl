// occupancy_slabs: `occupancy.wgsl` and `slice_counts.wgsl` (as `slab`) in
// one fragment shader (Sintorn & Assarsson 2009 §3.1, Fig. 8): the hair is
// drawn once, the texel's range fetched once, and each fragment sets its
// slice's bit and counts itself in its slab.
#import plait::hair_map::{MapVertex, MapFragment, map_vertex, map_texel, words_per_texel}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> bits: array<atomic<u32>>;
@group(1) @binding(2) var<storage, read_write> slabs: array<atomic<u32>>;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v);
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
    atomicAdd(&slabs[m.index * n + slab], 1u);
}
