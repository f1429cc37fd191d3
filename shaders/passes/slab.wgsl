// slab: the number of hair fragments per slab of slices per texel
// (Sintorn & Assarsson 2009 §3.1, Fig. 8), counted exactly with atomicAdd
// (the paper's additive float blending would need FLOAT32_BLENDABLE and loses
// precision past 2048 fragments in 16-bit floats). Slabs per texel = the
// `slabs` buffer's u32 words per texel (4 for the paper's 4 slabs of 32 slices).
#import plait::frame::{view_linear_depth}
#import plait::hair_map::{MapVertex, MapFragment, map_vertex}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> slabs: array<atomic<u32>>;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v);
}

@fragment
fn fs_main(in: MapFragment) {
    let size = textureDimensions(range);
    let texel = min(vec2<u32>(in.clip.xy), size - 1u);
    let r = textureLoad(range, vec2<i32>(texel), 0);
    let rel = (view_linear_depth(in.world) - r.x) / max(r.y - r.x, 1e-9);
    let count = arrayLength(&slabs) / (size.x * size.y);
    let slab = min(u32(clamp(rel, 0.0, 1.0) * f32(count)), count - 1u);
    atomicAdd(&slabs[(texel.y * size.x + texel.x) * count + slab], 1u);
}
