// plait::hair_map — the vertex stage shared by every pass that draws hair into
// a per-texel map (depth range, occupancy, slabs, deep opacity, opacity shadow
// maps, density clusters, depth lists): only the position matters, and the
// fragment gets its linear depth in the pass's view. That depth is an affine
// function of the world position, so interpolating it is exact; it costs one
// interpolant instead of the position's three and no matrix per fragment
// (on a software rasterizer both are per-fragment work).
#define_import_path plait::hair_map

#import plait::frame::{frame, view_proj, view_linear_depth}
#import plait::strand_lod::{strand_lod_place, strand_lod_clip, strand_lod_wisps}
#import plait::map_share::MAP_SHARE_SCALE
#import plait::strand_coverage::{StrandView, camera_strand_view, is_quad_vertex, quad_corner, view_segment_is_wide, view_quad_place, view_band_width, quad_coverage, QuadPlace}

struct MapVertex {
    @location(0) position: vec3<f32>,
    // A wisp vertex's slots all place it (plait::strand_lod_place).
    @location(1) thickness: f32,
    @location(2) tangent: vec3<f32>,
    @location(3) alpha: f32,
    @location(4) color: vec3<f32>,
    // The `geometry` point drops the strands the shaded draws drop.
    @location(5) strand_id: u32,
    // The next hair vertex, for the quad draw of segments wider than a
    // pixel of the view (plait::strand_coverage; the engine adds the quad
    // draw to a hair pass whose vertex stage reads it): in a camera view the
    // maps hold the fragments the shaded hair pass draws; in a light view a
    // strand wider than a texel blocks every texel it covers, each by the
    // quad's box-filtered coverage of it (issue 47).
    @location(6) next_position: vec3<f32>,
    @location(7) next_thickness: f32,
    @location(8) next_tangent: vec3<f32>,
    @location(9) next_alpha: f32,
    @location(10) next_color: vec3<f32>,
    @location(11) next_strand_id: u32,
    @builtin(instance_index) instance: u32,
    @builtin(vertex_index) index: u32,
}

// A hair vertex of a draw of one-texel lines only (no next vertex, so the
// engine adds no quad draw): the depth-only hair maps (shadow_map), whose
// providers take each strand crossed at the groom's mean width
// (plait::light_share), not at its share of the texel.
struct MapLineVertex {
    @location(0) position: vec3<f32>,
    @location(1) thickness: f32,
    @location(2) tangent: vec3<f32>,
    @location(3) alpha: f32,
    @location(4) color: vec3<f32>,
    @location(5) strand_id: u32,
    @builtin(vertex_index) index: u32,
}

struct MapFragment {
    @builtin(position) clip: vec4<f32>,
    // Linear depth in the pass's view (`view_linear_depth`).
    @location(0) depth: f32,
    // A line fragment's share: the band's width across the strand in texels
    // (plait::strand_coverage::view_band_width); a negative value:
    // it blocks whole texels (see map_texel).
    @location(1) width: f32,
    // As plait::hair_fragment's: 1 for the line of a segment the quad draw
    // draws (discarded by map_texel and map_kept), 0 otherwise; in a light
    // view 2 for the quad draw's fragments (their share is `across`'s).
    @location(2) @interpolate(flat) mode: u32,
#ifdef LIGHT_VIEW
    // A quad fragment's (distance from the centre line, half width) in
    // texels (plait::strand_coverage::QuadPlace).
    @location(3) across: vec2<f32>,
#endif
}

// The view the pass draws hair from, `size` its map's texels (the size of
// the per-texel maps it writes: a light map's texels are the light view's
// pixels). Camera views are the screen's (the shaded hair's quads).
fn map_view(size: vec2<u32>) -> StrandView {
#ifdef LIGHT_VIEW
    let s = vec2<f32>(size);
    // Towards the light: a directional light's direction, or a spot's position.
    let eye = select(vec4<f32>(frame.light_direction.xyz, 0.0), vec4<f32>(frame.light_position.xyz, 1.0), frame.light_direction.w > 0.5);
    return StrandView(frame.light_view_proj, vec4<f32>(s, 1.0 / s), eye);
#else
    return camera_strand_view();
#endif
}

// A hair vertex of the pass's draw into maps of `size` texels (the line
// draw's, or a corner of the quad draw's).
fn map_vertex(v: MapVertex, size: vec2<u32>) -> MapFragment {
    let view = map_view(size);
    let wide = !strand_lod_wisps() && map_segment_is_wide(view, v);
    if (is_quad_vertex(v.index)) {
        return map_quad_vertex(v, view, wide);
    }
    var out = map_vertex_at(view, v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.index);
    out.mode = select(0u, 1u, wide);
    return out;
}

// Whether the segment starting at `v` is drawn as a quad. A camera view
// asks what the shaded hair asks (plait::strand_coverage::segment_is_wide).
// A light view asks whether its line can hold the band the strand covers:
// a line one texel wide holds a band up to a texel wide across the strand
// (`view_band_width`: on non-square texels not the side's whole image), so
// a segment wider than that at either end is a quad.
fn map_segment_is_wide(view: StrandView, v: MapVertex) -> bool {
#ifdef LIGHT_VIEW
    if (frame.conventions.z < 0.5 || v.strand_id != v.next_strand_id) {
        return false;
    }
    let a = view_band_width(view, v.position, v.tangent, v.thickness);
    let b = view_band_width(view, v.next_position, v.next_tangent, v.next_thickness);
    return a >= 0.0 && b >= 0.0 && max(a, b) > 1.0;
#else
    return view_segment_is_wide(view, v.position, v.tangent, v.thickness, v.strand_id, v.next_position, v.next_tangent, v.next_thickness, v.next_strand_id);
#endif
}

// A vertex of a line-only draw (MapLineVertex): every segment one texel
// wide. Such a draw (depth only) reads no share, so no map size is needed:
// 1 stands in for it.
fn map_line_vertex(v: MapLineVertex) -> MapFragment {
    return map_vertex_at(map_view(vec2<u32>(1u)), v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.index);
}

fn map_vertex_at(view: StrandView, position: vec3<f32>, thickness: f32, tangent: vec3<f32>, alpha: f32, color: vec3<f32>, strand_id: u32, index: u32) -> MapFragment {
    var out: MapFragment;
    let p = strand_lod_place(position, thickness, tangent, alpha, color, strand_id, index);
    out.clip = strand_lod_clip(view_proj() * vec4<f32>(p.world, 1.0), p.weight);
    out.depth = view_linear_depth(p.world);
    out.width = map_width(view, position, tangent, thickness);
    out.mode = 0u;
#ifdef LIGHT_VIEW
    out.across = vec2<f32>(0.0);
#endif
    return out;
}

// A corner of the quad of segment (instance, instance + 1), as
// plait::hair_fragment's quad_vertex places it (the same
// plait::strand_coverage quad, in the pass's view); outside the view when
// the segment is a line.
fn map_quad_vertex(v: MapVertex, view: StrandView, wide: bool) -> MapFragment {
    let corner = quad_corner(v.index);
    var out: MapFragment;
    if (corner.end) {
        out = map_vertex_at(view, v.next_position, v.next_thickness, v.next_tangent, v.next_alpha, v.next_color, v.next_strand_id, v.instance + 1u);
    } else {
        out = map_vertex_at(view, v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.instance);
    }
    if (!wide) {
        out.clip = vec4<f32>(2.0, 2.0, 2.0, 1.0);
        return out;
    }
    let segment = v.next_position - v.position;
    let p = strand_lod_place(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.instance);
    var q: QuadPlace;
    if (corner.end) {
        q = view_quad_place(view, v.next_position, v.next_tangent, v.next_thickness, segment, corner.side);
    } else {
        q = view_quad_place(view, v.position, v.tangent, v.thickness, segment, corner.side);
    }
    out.clip = strand_lod_clip(q.clip, p.weight);
#ifdef LIGHT_VIEW
    out.across = q.across;
    out.mode = 2u;
#endif
    return out;
}

// False for the line of a segment the quad draw draws: the fragment
// shader discards it (map_texel does).
fn map_kept(in: MapFragment) -> bool {
    return in.mode != 1u;
}

// A line fragment's share of its texel, for light views with strand
// coverage on: the band's width across the strand in texels
// (`view_band_width`; at most 1: wider segments are quads), so over the
// line's fragments (its length × 1 texel) the shares sum to the strand's
// width × length, on non-square texels too; −1 (whole texels) for camera views (their counts
// are fragment orders, weighed by the fragments' own alpha where they are
// used), for wisps (a strip's texels are its own) and with coverage off.
fn map_width(view: StrandView, world: vec3<f32>, tangent: vec3<f32>, thickness: f32) -> f32 {
#ifdef LIGHT_VIEW
    if (frame.conventions.z < 0.5 || strand_lod_wisps()) {
        return -1.0;
    }
    return view_band_width(view, world, tangent, thickness);
#else
    return -1.0;
#endif
}

// Where a map fragment lands: its texel of a per-texel map as big as the
// texel's hair depth-range texture `range` (near in red, far in green), its
// index in per-texel buffers, and its depth in the pass's view relative to
// that texel's hair — 0 at the nearest, 1 at the farthest.
struct MapTexel {
    size: vec2<u32>,
    texel: vec2<u32>,
    // texel.y * size.x + texel.x
    index: u32,
    near: f32,
    far: f32,
    // linear depth in the pass's view (`view_linear_depth`)
    depth: f32,
    rel: f32,
    // The part of the texel the strand covers (1 for camera views, wisps
    // and with strand coverage off): a line's width in texels (at most 1),
    // a quad fragment's box-filtered coverage of its texel. A light texel is
    // blocked by the strand's share of it (issue 47): every map that counts
    // weighs the fragment by it (map_weight).
    share: f32,
}

fn map_texel(in: MapFragment, range: texture_2d<f32>) -> MapTexel {
    if (!map_kept(in)) {
        discard;
    }
    var m: MapTexel;
    m.size = textureDimensions(range);
    m.texel = min(vec2<u32>(in.clip.xy), m.size - 1u);
    m.index = m.texel.y * m.size.x + m.texel.x;
    let r = textureLoad(range, vec2<i32>(m.texel), 0);
    m.near = r.x;
    m.far = r.y;
    m.depth = in.depth;
    m.rel = (m.depth - r.x) / max(r.y - r.x, 1e-9);
    m.share = select(min(in.width, 1.0), 1.0, in.width < 0.0);
#ifdef LIGHT_VIEW
    if (in.mode == 2u) {
        m.share = quad_coverage(in.across);
        // The quad reaches half a texel past the strand's edge so that the
        // box filter sees every texel it touches; a centre beyond it is
        // not covered at all.
        if (m.share <= 0.0) {
            discard;
        }
    }
#endif
    return m;
}

// What the fragment adds to a map's count: in a light view its share of the
// texel in units of 1 / MAP_SHARE_SCALE (at least one unit: a strand
// thinner than 1/4096 texel still counts, a little too much, never
// nothing), which the self-shadow providers divide out; in a camera view 1,
// a fragment count (occupancy order's slabs).
// One whole-texel fragment in map_weight's units.
fn map_unit() -> f32 {
#ifdef LIGHT_VIEW
    return MAP_SHARE_SCALE;
#else
    return 1.0;
#endif
}

fn map_weight(m: MapTexel) -> u32 {
#ifdef LIGHT_VIEW
    return max(u32(round(m.share * MAP_SHARE_SCALE)), 1u);
#else
    return 1u;
#endif
}

// u32 words per texel of a per-texel buffer of `words_total` words.
fn words_per_texel(words_total: u32, m: MapTexel) -> u32 {
    return words_total / (m.size.x * m.size.y);
}
