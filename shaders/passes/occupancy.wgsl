// occupancy: one bit per depth slice per texel, set with atomicOr (wgpu has no
// bitwise-OR blending), Sintorn & Assarsson 2009 §3.1. Slice k of a texel
// covers relative depth [k, k+1) / S within the texel's depth range; S = 32 ×
// the words per texel of the `bits` buffer (128 for 16 bytes per texel).
#import plait::frame::{view_linear_depth}
#import plait::hair_map::{MapVertex, MapFragment, map_vertex}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> bits: array<atomic<u32>>;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v);
}

// No colour output: the depth attachment (opaque depth, test only) rejects
// hair behind opaque geometry (§3.5); the fragment only sets its bit.
@fragment
fn fs_main(in: MapFragment) {
    let size = textureDimensions(range);
    let texel = min(vec2<u32>(in.clip.xy), size - 1u);
    let r = textureLoad(range, vec2<i32>(texel), 0);
    let rel = (view_linear_depth(in.world) - r.x) / max(r.y - r.x, 1e-9);
    let words = arrayLength(&bits) / (size.x * size.y);
    let slices = words * 32u;
    let slice = min(u32(max(rel, 0.0) * f32(slices)), slices - 1u);
    let index = (texel.y * size.x + texel.x) * words + slice / 32u;
    atomicOr(&bits[index], 1u << (slice % 32u));
}
