// plait::shading_space::strand — the radiance the `strand_shading` pass shaded
// this frame at `shading_points` points evenly spread along each strand
// (Tafuri 2019, "strand space"), interpolated between the two shading points
// either side of the fragment. A strand's points are indexed 0 … n-1 from the
// root; shading point k of K lies at point index k·(n-1)/(K-1) (the middle
// when K = 1), so a fragment at point index p reads s = p·(K-1)/(n-1).
#define_import_path plait::shading_space::strand

struct ShadingSpaceParams {
    // Shading points per strand (K).
    shading_points: u32,
}
@group(1) @binding(50) var<uniform> shading_space_params: ShadingSpaceParams;
// Radiance per shading point, strand after strand: rgb, w = 1.
@group(1) @binding(51) var<storage, read> shading_radiance: array<vec4<f32>>;

// One drawn strand as the scene's `strand_guides` holds it (48 B): ids.w is
// its first hair vertex, root.w its point count.
struct ShadingStrand {
    ids: vec4<u32>,
    weights: vec4<f32>,
    root: vec4<f32>,
}
@group(1) @binding(52) var<storage, read> shading_strands: array<ShadingStrand>;

fn strand_radiance(strand: u32, segment: u32, along: f32) -> vec4<f32> {
    let k = shading_space_params.shading_points;
    let s = shading_strands[strand];
    let first = s.ids.w;
    let last = max(u32(s.root.w), 1u) - 1u;
    let p = f32(segment - first) + along;
    let at = select(0.0, p * f32(k - 1u) / f32(max(last, 1u)), k > 1u);
    let k0 = min(u32(floor(at)), k - 1u);
    let k1 = min(k0 + 1u, k - 1u);
    let base = strand * k;
    let a = shading_radiance[base + k0];
    let b = shading_radiance[base + k1];
    return vec4<f32>(mix(a.rgb, b.rgb, clamp(at - f32(k0), 0.0, 1.0)), 1.0);
}
