// slice_counts: the number of hair fragments per uniform slice of each texel's
// hair depth range, counted exactly with atomicAdd. One kernel, two papers:
// - `slab` (Sintorn & Assarsson 2009 §3.1, Fig. 8): fragment counts per slab
//   of occupancy slices (4 slabs for the paper's 128 slices);
// - `opacity_shadow_maps` (the one-pass opacity shadow maps of Halén & Wester
//   2007 §3.3.2, §5.7; there 4 targets × 4 channels with additive blending):
//   N slices in one hair draw.
// The paper's additive float blending would need FLOAT32_BLENDABLE and loses
// precision past 2048 fragments in 16-bit floats. Slices per texel = the
// `counts` buffer's u32 words per texel (each pass type binds its own slot,
// `slabs` or `slices`, to `counts`).
#import plait::hair_map::{MapVertex, MapFragment, map_vertex, map_texel, map_weight, words_per_texel}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> counts: array<atomic<u32>>;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v, textureDimensions(range));
}

@fragment
fn fs_main(in: MapFragment) {
    let m = map_texel(in, range);
    let n = words_per_texel(arrayLength(&counts), m);
    let slice = min(u32(clamp(m.rel, 0.0, 1.0) * f32(n)), n - 1u);
    // Weighted by the strand's share of the texel (plait::hair_map::map_weight).
    atomicAdd(&counts[m.index * n + slice], map_weight(m));
}
