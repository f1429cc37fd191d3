// opacity_shadow_maps: N uniform slices of the texel's hair range [near, far]
// (per-texel range from depth_range), every fragment counted in its slice with
// atomicAdd, all N in one hair draw — the one-pass opacity shadow maps of
// Halén & Wester 2007 §3.3.2, §5.7 (there: 4 targets × 4 channels,
// additive blending). N = the `slices` buffer's u32 words per texel.
#import plait::frame::{view_linear_depth}
#import plait::hair_map::{MapVertex, MapFragment, map_vertex}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> slices: array<atomic<u32>>;

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
    let n = arrayLength(&slices) / (size.x * size.y);
    let slice = min(u32(clamp(rel, 0.0, 1.0) * f32(n)), n - 1u);
    atomicAdd(&slices[(texel.y * size.x + texel.x) * n + slice], 1u);
}
