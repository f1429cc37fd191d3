// occupancy: one bit per depth slice per texel, set with atomicOr (wgpu has no
// bitwise-OR blending), Sintorn & Assarsson 2009 §3.1. Slice k of a texel
// covers relative depth [k, k+1) / S within the texel's depth range; S = 32 ×
// the words per texel of the `bits` buffer (128 for 16 bytes per texel).
#import plait::hair_map::{MapVertex, MapFragment, map_vertex, map_texel, words_per_texel}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> bits: array<atomic<u32>>;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v, textureDimensions(range));
}

// No colour output: the depth attachment (opaque depth, test only) rejects
// hair behind opaque geometry (§3.5); the fragment only sets its bit.
@fragment
fn fs_main(in: MapFragment) {
    let m = map_texel(in, range);
    let words = words_per_texel(arrayLength(&bits), m);
    let slices = words * 32u;
    let slice = min(u32(max(m.rel, 0.0) * f32(slices)), slices - 1u);
    atomicOr(&bits[m.index * words + slice / 32u], 1u << (slice % 32u));
}
