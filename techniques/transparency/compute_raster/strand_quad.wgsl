// plait::compute_raster::strand_quad — a hair segment wider than a pixel,
// as the compute rasterizer draws it: the quad the hair draws' quad draw
// draws for it (plait::strand_coverage, "the quad draw"; issue 47) — the
// same corners (quad_place: the strand's width across the view plus half a
// pixel each side, across the tangent on screen), the same two triangles
// (s−, s+, e− and s+, e+, e−), rasterized at pixel centres
// (plait::compute_raster::triangles), its coverage there the same box
// filter of the distance from the centre line (quad_coverage), with that
// distance and the half width interpolated linearly on the screen as the
// quad draw's `across` varying is. Every other segment stays a one-pixel
// line (blend.wgsl, line_coverage).
//
// The near plane: each side edge (s− → e−, s+ → e+) is clipped there
// (plait::hair_point::clip_segment), as the wisps' quads are.
#define_import_path plait::compute_raster::strand_quad

#import plait::hair_point::{HairPoint, clip_segment}
#import plait::strand_coverage::{segment_is_wide, quad_place, quad_coverage}
#import plait::compute_raster::triangles::{quad_weights, quad_perspective}

// A wide segment's quad on the screen: corners s−, s+, e−, e+ (screen xy in
// pixels, NDC z, clip w) after the near-plane clip; per corner its place
// along the segment (`along`: 0, 0, 1, 1 unless clipped), its signed
// distance from the centre line and the strand's half width there, in
// pixels (`across`, `half`: quad_place's). `kept`: drawn at all.
struct StrandQuad {
    corner: array<vec4<f32>, 4>,
    along: vec4<f32>,
    across: vec4<f32>,
    half: vec4<f32>,
    kept: bool,
}

// Whether segment v0 → v1 is drawn as a quad (segment_is_wide: either end
// wider than a pixel, coverage on).
fn strand_segment_is_wide(v0: HairPoint, v1: HairPoint) -> bool {
    return segment_is_wide(v0.position, v0.tangent, v0.thickness, v0.strand, v1.position, v1.tangent, v1.thickness, v1.strand);
}

fn strand_quad(v0: HairPoint, v1: HairPoint) -> StrandQuad {
    var q: StrandQuad;
    q.kept = false;
    let segment = v1.position - v0.position;
    let s_minus = quad_place(v0.position, v0.tangent, v0.thickness, segment, -1.0);
    let s_plus = quad_place(v0.position, v0.tangent, v0.thickness, segment, 1.0);
    let e_minus = quad_place(v1.position, v1.tangent, v1.thickness, segment, -1.0);
    let e_plus = quad_place(v1.position, v1.tangent, v1.thickness, segment, 1.0);
    let left = clip_segment(s_minus.clip, e_minus.clip);
    let right = clip_segment(s_plus.clip, e_plus.clip);
    if (!left.kept || !right.kept) {
        return q;
    }
    q.corner = array<vec4<f32>, 4>(left.a, right.a, left.b, right.b);
    q.along = vec4<f32>(left.t_start, right.t_start, left.t_stop, right.t_stop);
    let l0 = mix(s_minus.across, e_minus.across, left.t_start);
    let r0 = mix(s_plus.across, e_plus.across, right.t_start);
    let l1 = mix(s_minus.across, e_minus.across, left.t_stop);
    let r1 = mix(s_plus.across, e_plus.across, right.t_stop);
    q.across = vec4<f32>(l0.x, r0.x, l1.x, r1.x);
    q.half = vec4<f32>(l0.y, r0.y, l1.y, r1.y);
    q.kept = true;
    return q;
}

// Pixel centre `p` on the quad with corners a b c d, `along`, `across` and
// `half` (StrandQuad's): x = its coverage there (quad_coverage; 0
// outside), y = NDC z, z = the place along the segment, interpolated
// perspective-correctly.
fn strand_quad_hit(p: vec2<f32>, a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, d: vec4<f32>, along: vec4<f32>, across: vec4<f32>, half: vec4<f32>) -> vec3<f32> {
    let q = quad_weights(p, a.xy, b.xy, c.xy, d.xy);
    if (!q.inside) {
        return vec3<f32>(0.0);
    }
    let cover = quad_coverage(vec2<f32>(dot(q.l, across), dot(q.l, half)));
    let z = dot(q.l, vec4<f32>(a.z, b.z, c.z, d.z));
    return vec3<f32>(cover, z, quad_perspective(q.l, vec4<f32>(a.w, b.w, c.w, d.w), along));
}
