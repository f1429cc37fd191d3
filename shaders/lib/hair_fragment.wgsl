// plait::hair_fragment — the shared hair-fragment stage: what every pass that
// shades hair computes before it decides what to do with the fragment. A
// transparency technique's raster passes import it and differ only in how they
// write the result (blend it over, sum it, append it to a list, keep it if it
// is among the nearest k, let its alpha pick MSAA samples).
//
//   @vertex   fn vs_main(v: HairVertex) -> HairVaryings { return hair_vertex(v); }
//   @fragment fn fs_main(in: HairVaryings) -> … { let f = shade_hair(in); … }
//
// The fragment's colour is the key light's reflection (`shading`: Kajiya-Kay
// by default, Halén & Wester 2007 §3.2.1), shadowed by opaque objects
// (Sintorn & Assarsson 2009 §3.5) and by the hair itself (`self_shadow`),
// plus the rest of the environment's light (`lighting`) darkened by per-vertex
// occlusion (`ambient_occlusion`): one provider per choice point, chosen by the
// pass's `uses` (`plait::hair_radiance`). Its alpha is the strand's alpha ×
// the part of the pixel the strand covers (`strand_coverage`).
//
// Where the colour is computed is a choice point too (`shading_space`): per
// fragment (`fragment`, the default), or once per frame at a few points of
// each strand by a compute pass (`strand`, Tafuri 2019's "strand space"),
// whose radiance the fragment interpolates instead of shading.
//
// Group 1 binding 0 is the opaque shadow map (slot `shadow_map`); bindings
// 10–54 belong to the providers; a technique's own slots start at 60.
#define_import_path plait::hair_fragment

#import plait::frame::{frame, view_proj}
#import plait::hair_radiance::hair_radiance
#import plait::ambient_occlusion::occlusion_at
#import plait::shading_space::strand_space_radiance
#import plait::strand_coverage::{strand_coverage, strand_tip_scale, is_quad_vertex, quad_corner, segment_is_wide, quad_place, quad_coverage, QuadPlace}
#import plait::strand_curve::strand_curve_tangent_lerp
#import plait::strand_lod::{strand_lod_place, strand_lod_clip, strand_lod_alpha, strand_lod_vertex, strand_lod_wisps, strand_lod_fraction, strand_lod_texel}

@group(1) @binding(0) var shadow_map: texture_depth_2d;

// A hair vertex as the scene's hair vertex buffer holds it.
struct HairVertex {
    @location(0) position: vec3<f32>,
    @location(1) thickness: f32,
    @location(2) tangent: vec3<f32>,
    @location(3) alpha: f32,
    @location(4) color: vec3<f32>,
    // Which strand it belongs to (the `geometry` point drops or widens it).
    @location(5) strand_id: u32,
    // The next hair vertex (the second vertex buffer, one vertex on): the
    // other end of the segment this vertex starts, for the quad draw of
    // strands wider than a pixel (plait::strand_coverage, "the quad draw").
    @location(6) next_position: vec3<f32>,
    @location(7) next_thickness: f32,
    @location(8) next_tangent: vec3<f32>,
    @location(9) next_alpha: f32,
    @location(10) next_color: vec3<f32>,
    @location(11) next_strand_id: u32,
    // The vertex's index in the hair vertex buffer: per-vertex resources
    // (ambient occlusion) are indexed by it. In the quad draw it is
    // WIDE_FIRST_VERTEX + the corner, and the instance is the hair vertex.
    @builtin(vertex_index) index: u32,
    @builtin(instance_index) instance: u32,
}

struct HairVaryings {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) tangent: vec3<f32>,
    @location(2) color: vec3<f32>,
    // The strand's alpha × its pixel coverage (before the hair colour's alpha).
    @location(3) alpha: f32,
    // Fraction of the environment's light reaching the strand here.
    @location(4) occlusion: f32,
    // Where the fragment lies along its strand, for strand-space shading
    // (plait::strand_lod::strand_lod_place): the strand, for strands the
    // segment's first vertex (the line's provoking vertex; hair segments
    // join vertices i and i + 1) and the vertex index's parity, interpolated
    // — 0 → 1 from an even first vertex, 1 → 0 from an odd one; for wisps
    // the strand's first vertex and the index along it, interpolated.
    @location(5) @interpolate(flat) strand: u32,
    @location(6) @interpolate(flat) segment: u32,
    @location(7) parity: f32,
    // A wisp's strand-texture coordinates (u across, v along, mip level);
    // 0 for strands (plait::strand_lod).
    @location(8) wisp: vec3<f32>,
    // The segment's first vertex and its tangent (the provoking vertex's,
    // flat): with `world` and `tangent` interpolated they give the curve's
    // tangent at the fragment (shading_tangent).
    @location(9) @interpolate(flat) start: vec3<f32>,
    @location(10) @interpolate(flat) start_tangent: vec3<f32>,
    // 0: a line of a segment no wider than a pixel; 1: the line of a wider
    // one, discarded (the quad draw draws it); 2: the quad of a wider one.
    @location(11) @interpolate(flat) mode: u32,
    // In a quad: the distance from the strand's centre line and its half
    // width, in pixels, interpolated in screen space (quad_coverage).
    @location(12) @interpolate(linear) across: vec2<f32>,
}

// A shaded hair fragment: straight (not premultiplied) colour and alpha.
struct HairFragment {
    rgb: vec3<f32>,
    alpha: f32,
}

fn hair_vertex(v: HairVertex) -> HairVaryings {
    if (is_quad_vertex(v.index)) {
        return quad_vertex(v);
    }
    var out = hair_vertex_at(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.index, true);
    // A line's flat varyings are its first vertex's, whose next vertex is the
    // line's other end: the line of a wide segment is dropped.
    let wide = !strand_lod_wisps() && segment_is_wide(v.position, v.tangent, v.thickness, v.strand_id, v.next_position, v.next_tangent, v.next_thickness, v.next_strand_id);
    out.mode = select(0u, 1u, wide);
    return out;
}

// A vertex of the quad draw: the corner of segment (instance, instance + 1)
// it stands for, or a point outside the view (no fragment) when the segment
// is a line.
fn quad_vertex(v: HairVertex) -> HairVaryings {
    let corner = quad_corner(v.index);
    var out: HairVaryings;
    if (corner.end) {
        out = hair_vertex_at(v.next_position, v.next_thickness, v.next_tangent, v.next_alpha, v.next_color, v.next_strand_id, v.instance + 1u, false);
    } else {
        out = hair_vertex_at(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.instance, false);
    }
    let wide = !strand_lod_wisps() && segment_is_wide(v.position, v.tangent, v.thickness, v.strand_id, v.next_position, v.next_tangent, v.next_thickness, v.next_strand_id);
    if (!wide) {
        out.clip = vec4<f32>(2.0, 2.0, 2.0, 1.0);
        out.mode = 1u;
        return out;
    }
    let segment = v.next_position - v.position;
    var q: QuadPlace;
    if (corner.end) {
        q = quad_place(v.next_position, v.next_tangent, v.next_thickness, segment, corner.side);
    } else {
        q = quad_place(v.position, v.tangent, v.thickness, segment, corner.side);
    }
    let p = strand_lod_place(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.instance);
    out.clip = strand_lod_clip(q.clip, p.weight);
    out.across = q.across;
    out.mode = 2u;
    return out;
}

// The vertex stage for hair vertex `index`; `line`: as a line's vertex,
// whose alpha is weighed by its coverage — a quad's coverage is per pixel
// instead (quad_coverage in fragment_alpha).
fn hair_vertex_at(position: vec3<f32>, thickness: f32, tangent: vec3<f32>, alpha: f32, color: vec3<f32>, strand_id: u32, index: u32, line: bool) -> HairVaryings {
    var out: HairVaryings;
    // Where the geometry draws the vertex: itself, or a wisp vertex's strip
    // corner, following the hair vertex it stands for.
    let p = strand_lod_place(position, thickness, tangent, alpha, color, strand_id, index);
    out.clip = strand_lod_clip(view_proj() * vec4<f32>(p.world, 1.0), p.weight);
    out.world = p.world;
    out.tangent = p.tangent;
    out.color = p.color;
    // A strand thinner than a pixel covers only part of it: its coverage
    // weighs its alpha in every blending technique (and sets the sample mask
    // of alpha to coverage). A wisp's coverage is its texture's alpha.
    let coverage = select(strand_coverage(position, tangent, thickness), 1.0, strand_lod_wisps() || !line);
    let tip = strand_tip_scale(p.strand, p.segment, strand_lod_fraction(p.segment, p.along));
    out.alpha = strand_lod_alpha(p.alpha * coverage * tip, p.weight);
    out.wisp = p.texture;
    out.occlusion = occlusion_at(strand_lod_vertex(index, strand_id));
    out.strand = p.strand;
    out.segment = p.segment;
    out.parity = p.along;
    out.start = p.world;
    out.start_tangent = p.tangent;
    out.mode = 0u;
    out.across = vec2<f32>(0.0, 1.0);
    return out;
}

fn shade_hair(in: HairVaryings) -> HairFragment {
    // Before the shading: the quad draw draws this line's segment.
    if (in.mode == 1u) {
        discard;
    }
    let texel = strand_lod_texel(in.wisp);
    // Strand space: the radiance a compute pass shaded along the strand this
    // frame, interpolated; w < 0 when the colour is shaded here. w is a
    // constant of the provider, so this branch is compiled out (a computed
    // w kept both paths, and llvmpipe runs both sides of a branch). A wisp
    // fragment reads it where the hair vertex it stands for lies (the strand
    // the wisp follows), scaled by the strand texture's brightness — which
    // the per-fragment path puts into the albedo instead: the two agree on
    // every term linear in the albedo (Kajiya-Kay's diffuse; its specular,
    // untinted by the albedo, the texture dims here and not there).
    let shaded = strand_space_radiance(in.strand, in.segment, segment_fraction(in));
    if (shaded.w >= 0.0) {
        return HairFragment(shaded.rgb * texel.rgb, fragment_alpha(in));
    }
    let rgb = hair_radiance(shadow_map, in.world, shading_tangent(in), in.color * texel.rgb, in.occlusion);
    return HairFragment(rgb, fragment_alpha(in));
}

// How far along its strand past hair vertex `in.segment` the fragment lies
// (within the segment from it, for strands: 0 at its first vertex).
fn segment_fraction(in: HairVaryings) -> f32 {
    return strand_lod_fraction(in.segment, in.parity);
}

// The fragment's alpha alone (coverage × strand alpha × hair colour alpha),
// for passes that need how much the fragment hides but not its colour.
// The line of a segment the quad draw draws (mode 1) is discarded here, so
// every pass that reads a hair fragment's alpha or colour drops it.
fn fragment_alpha(in: HairVaryings) -> f32 {
    if (in.mode == 1u) {
        discard;
    }
    let quad = select(1.0, quad_coverage(in.across), in.mode == 2u);
    return clamp(in.alpha * quad * strand_lod_texel(in.wisp).a * frame.hair_color.a, 0.0, 1.0);
}

// The tangent the fragment is shaded about: the smooth curve's through the
// strand's points at the fragment's place along its segment
// (plait::strand_curve), not the straight segment's. A wisp's strip spans
// its whole strand (no segment): its tangent, interpolated.
fn shading_tangent(in: HairVaryings) -> vec3<f32> {
    if (strand_lod_wisps()) {
        return in.tangent;
    }
    return strand_curve_tangent_lerp(in.world, in.start, in.start_tangent, in.tangent, segment_fraction(in));
}
