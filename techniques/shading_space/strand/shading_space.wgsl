// plait::shading_space::strand — the radiance the `strand_shading` pass shaded
// this frame at `shading_points` points evenly spread along each strand
// (Tafuri 2019, "strand space"), interpolated between the two shading points
// either side of the fragment. A strand's points are indexed 0 … n-1 from the
// root; shading point k of K lies at point index k·(n-1)/(K-1) (the middle
// when K = 1), so a fragment at point index p reads s = p·(K-1)/(n-1).
//
// w is always 1, a constant: "shaded elsewhere". plait::hair_fragment (and
// compute_raster) branch on it, and only a w the compiler can decide drops
// the per-fragment path from every hair draw; llvmpipe runs both sides of a
// branch it cannot decide, so a w computed here made strand space cost the
// per-fragment shading plus the interpolation.
//
// `strand_tip` is the strand's tip fading (`tip_scale`, `tip_scale_offset`;
// the tapering of Unity's hair package, com.unity.demoteam.hair,
// HairVertex.hlsl: a strand's width scaled from 1 where the taper begins, at
// fraction tip_scale_offset of its length, linearly to tip_scale at its tip,
// over at least its last segment). A strand thinner than a pixel covers the
// pixel in proportion to its width (plait::strand_coverage), so the scale
// multiplies the coverage of every hair draw's vertex; strand_coverage
// imports it when this provider is chosen. frostbitten-hair-webgpu's "thin
// tip" (the last shading point transparent) is tip_scale = 0 with the taper
// over the last shading interval.
#define_import_path plait::shading_space::strand

struct ShadingSpaceParams {
    // Shading points per strand (K).
    shading_points: u32,
    // The width (coverage) scale at the tip, and the fraction of the
    // strand's length where the taper toward it begins.
    tip_scale: f32,
    tip_scale_offset: f32,
}
@group(1) @binding(50) var<uniform> shading_space_params: ShadingSpaceParams;
// Radiance per shading point, strand after strand: rgb, w = 1 (unused).
@group(1) @binding(51) var<storage, read> shading_radiance: array<vec4<f32>>;

// One drawn strand as the scene's `strand_guides` holds it (48 B): ids.w is
// its first hair vertex, root.w its point count.
struct ShadingStrand {
    ids: vec4<u32>,
    weights: vec4<f32>,
    root: vec4<f32>,
}
@group(1) @binding(52) var<storage, read> shading_strands: array<ShadingStrand>;

// Where hair vertex `segment` of strand `strand`, `along` past it, lies:
// its point index p along the strand, and the strand's last point index.
struct StrandPlace {
    p: f32,
    last: u32,
}

fn strand_place(strand: u32, segment: u32, along: f32) -> StrandPlace {
    let s = shading_strands[strand];
    return StrandPlace(f32(segment - s.ids.w) + along, max(u32(s.root.w), 1u) - 1u);
}

fn strand_radiance(strand: u32, segment: u32, along: f32) -> vec4<f32> {
    let k = shading_space_params.shading_points;
    let place = strand_place(strand, segment, along);
    let p = place.p;
    let last = place.last;
    let at = select(0.0, p * f32(k - 1u) / f32(max(last, 1u)), k > 1u);
    let k0 = min(u32(floor(at)), k - 1u);
    let k1 = min(k0 + 1u, k - 1u);
    let base = strand * k;
    let a = shading_radiance[base + k0];
    let b = shading_radiance[base + k1];
    return vec4<f32>(mix(a.rgb, b.rgb, clamp(at - f32(k0), 0.0, 1.0)), 1.0);
}

// The tip fading at hair vertex `segment` of strand `strand`, `along` past
// it: the scale on the strand's width there (see the header).
fn strand_tip(strand: u32, segment: u32, along: f32) -> f32 {
    let place = strand_place(strand, segment, along);
    return tip_scale(place.p, place.last);
}

// The taper's scale at point index `p` of a strand whose last point is
// `last`: 1 up to tip_scale_offset of its length, then linearly to
// tip_scale at the tip, over at least one segment (as Unity's lower bound on
// the taper interval, so an offset of 1 still fades the last segment).
fn tip_scale(p: f32, last: u32) -> f32 {
    let segments = f32(max(last, 1u));
    let offset = shading_space_params.tip_scale_offset;
    let t = clamp((p / segments - offset) / max(1.0 / segments, 1.0 - offset), 0.0, 1.0);
    return mix(1.0, shading_space_params.tip_scale, t);
}
