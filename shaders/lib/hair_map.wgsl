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
#ifndef LIGHT_VIEW
#import plait::strand_coverage::{is_quad_vertex, quad_corner, segment_is_wide, quad_place}
#endif

struct MapVertex {
    @location(0) position: vec3<f32>,
    // A wisp vertex's slots all place it (plait::strand_lod_place).
    @location(1) thickness: f32,
    @location(2) tangent: vec3<f32>,
    @location(3) alpha: f32,
    @location(4) color: vec3<f32>,
    // The `geometry` point drops the strands the shaded draws drop.
    @location(5) strand_id: u32,
#ifndef LIGHT_VIEW
    // Camera views: the next hair vertex, for the quad draw of strands wider
    // than a pixel (plait::strand_coverage) — the maps hold the fragments
    // the shaded hair pass draws. Light views draw lines only: a light texel
    // is blocked by the strand's share of it, at most the whole texel.
    @location(6) next_position: vec3<f32>,
    @location(7) next_thickness: f32,
    @location(8) next_tangent: vec3<f32>,
    @location(9) next_alpha: f32,
    @location(10) next_color: vec3<f32>,
    @location(11) next_strand_id: u32,
    @builtin(instance_index) instance: u32,
#endif
    @builtin(vertex_index) index: u32,
}

struct MapFragment {
    @builtin(position) clip: vec4<f32>,
    // Linear depth in the pass's view (`view_linear_depth`).
    @location(0) depth: f32,
    // The strand's width across the light in map coordinates (0..1 over
    // the map); a negative value: it blocks whole texels (see map_share).
    @location(1) width: f32,
    // As plait::hair_fragment's: 1 for the line of a segment the quad draw
    // draws (discarded by map_texel and map_kept), 0 otherwise.
    @location(2) @interpolate(flat) mode: u32,
}


fn map_vertex(v: MapVertex) -> MapFragment {
#ifndef LIGHT_VIEW
    let wide = !strand_lod_wisps() && segment_is_wide(v.position, v.tangent, v.thickness, v.strand_id, v.next_position, v.next_tangent, v.next_thickness, v.next_strand_id);
    if (is_quad_vertex(v.index)) {
        return map_quad_vertex(v, wide);
    }
    var out = map_vertex_at(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.index);
    out.mode = select(0u, 1u, wide);
    return out;
#else
    return map_vertex_at(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.index);
#endif
}

fn map_vertex_at(position: vec3<f32>, thickness: f32, tangent: vec3<f32>, alpha: f32, color: vec3<f32>, strand_id: u32, index: u32) -> MapFragment {
    var out: MapFragment;
    let p = strand_lod_place(position, thickness, tangent, alpha, color, strand_id, index);
    out.clip = strand_lod_clip(view_proj() * vec4<f32>(p.world, 1.0), p.weight);
    out.depth = view_linear_depth(p.world);
    out.width = map_width(position, tangent, thickness);
    out.mode = 0u;
    return out;
}

#ifndef LIGHT_VIEW
// A corner of the quad of segment (instance, instance + 1) in a camera
// view, as plait::hair_fragment's quad_vertex places it; outside the view
// when the segment is a line.
fn map_quad_vertex(v: MapVertex, wide: bool) -> MapFragment {
    let corner = quad_corner(v.index);
    var out: MapFragment;
    if (corner.end) {
        out = map_vertex_at(v.next_position, v.next_thickness, v.next_tangent, v.next_alpha, v.next_color, v.next_strand_id, v.instance + 1u);
    } else {
        out = map_vertex_at(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.instance);
    }
    if (!wide) {
        out.clip = vec4<f32>(2.0, 2.0, 2.0, 1.0);
        return out;
    }
    let segment = v.next_position - v.position;
    let p = strand_lod_place(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.instance);
    if (corner.end) {
        out.clip = strand_lod_clip(quad_place(v.next_position, v.next_tangent, v.next_thickness, segment, corner.side).clip, p.weight);
    } else {
        out.clip = strand_lod_clip(quad_place(v.position, v.tangent, v.thickness, segment, corner.side).clip, p.weight);
    }
    return out;
}
#endif

// False for the line of a segment the quad draw draws: the fragment
// shader discards it (map_texel does).
fn map_kept(in: MapFragment) -> bool {
    return in.mode != 1u;
}

// The strand's width across the light, in light-map coordinates, for light
// views with strand coverage on; −1 (whole texels) for camera views (their
// counts are fragment orders, weighed by the fragments' own alpha where they
// are used), for wisps (a strip's texels are its own) and with coverage off.
fn map_width(world: vec3<f32>, tangent: vec3<f32>, thickness: f32) -> f32 {
#ifdef LIGHT_VIEW
    if (frame.conventions.z < 0.5 || strand_lod_wisps()) {
        return -1.0;
    }
    // Towards the light: a directional light's direction, or a spot's position.
    let to_light = select(frame.light_direction.xyz, normalize(frame.light_position.xyz - world), frame.light_direction.w > 0.5);
    var side = cross(tangent, to_light);
    if (dot(side, side) < 1e-12) {
        side = cross(select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), abs(to_light.y) > 0.9), to_light);
    }
    side = normalize(side);
    let a = frame.light_view_proj * vec4<f32>(world, 1.0);
    let b = frame.light_view_proj * vec4<f32>(world + side * thickness, 1.0);
    if (a.w <= 0.0 || b.w <= 0.0) {
        return -1.0;
    }
    return length((b.xy / b.w - a.xy / a.w) * 0.5);
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
    // The part of the texel the strand covers: its width in texels, at most
    // 1 (1 for camera views, wisps and with strand coverage off). A light
    // texel is blocked by the strand's share of it (issue 47): every map
    // that counts weighs the fragment by it (map_weight).
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
    m.share = select(min(in.width * f32(m.size.x), 1.0), 1.0, in.width < 0.0);
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
