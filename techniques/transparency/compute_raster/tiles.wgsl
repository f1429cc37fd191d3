// plait::compute_raster::tiles — the screen tiles a hair segment lands in,
// for the compute rasterizer's two binning passes: tile_count counts them
// per tile, strand_bin fills the slots tile_scan gave each tile. Both walk
// the same tiles through these functions, so the fill lands exactly where
// the count said it would.
//
// A segment (the line list's vertex pair; the stored index is its first
// vertex: a strand's segment i joins vertices i and i + 1) lands in a tile
// when its screen bounding box grown by one pixel (tile_blend's analytic
// coverage reaches one pixel either side of the line) overlaps the tile,
// the line passes within that pixel of it, and it is not hidden there by
// the opaque scene: not behind the tile's farthest opaque depth
// (tile_depth), and in front of the opaque depth at some pixel of the tile
// that tile_blend would draw it in — so hair hidden behind the head takes
// no slot, is never counted, and the image is the same as without it. The
// `geometry` point's answer is honoured as every hair draw honours it
// (plait::strand_lod): a strand of weight 0 lands nowhere. A quad lands in
// the tiles of its corners' box where its triangles cover a pixel centre in
// front of the opaque depth (quad_visible_in_tile): with `geometry = wisps`
// every segment is one, a quad of a wisp's strip
// (plait::compute_raster::wisp_quad); else a segment wider than a pixel is
// (plait::compute_raster::strand_quad, the quad the hair draws draw for it),
// so it takes a slot in every tile its width reaches.
#define_import_path plait::compute_raster::tiles

#import plait::frame::frame
#import plait::strand_lod::strand_lod_weight
#import plait::hair_point::{HairPoint, camera_segment}
#import plait::compute_raster::triangles::{quad_meets, quad_depth}
#ifdef GEOMETRY_WISPS
#import plait::compute_raster::wisp_quad::{wisp_quad, wisp_quad_first, NO_QUAD}
#else
#import plait::compute_raster::strand_quad::{strand_quad, strand_segment_is_wide}
@group(1) @binding(1) var<storage, read> hair_vertices: array<HairPoint>;
@group(1) @binding(2) var<storage, read> hair_indices: array<u32>;
#endif
@group(1) @binding(3) var<storage, read> tile_far: array<u32>;
@group(1) @binding(7) var opaque_depth: texture_depth_2d;

// A segment on the screen: its ends (screen xy, NDC z, clip w), the tiles
// its grown bounding box covers (inclusive; none when first > last), the
// line's unit normal, its nearest depth, and the vertex a tile stores. A
// quad (`quad`: every segment with `geometry = wisps`, a quad of a wisp's
// strip whose `vertex` is its first wisp vertex; a strand's segment wider
// than a pixel) has its corners in `corner` (screen xy, NDC z, clip w), and
// its a, b and normal are unused.
struct Span {
    a: vec4<f32>,
    b: vec4<f32>,
    first_tile: vec2<i32>,
    last_tile: vec2<i32>,
    normal: vec2<f32>,
    near_z: f32,
    vertex: u32,
    quad: bool,
    corner: array<vec4<f32>, 4>,
}

// Tiles across the screen (the row length of every per-tile buffer).
fn tiles_across(t: i32) -> i32 {
    return (i32(frame.screen_size.x) + t - 1) / t;
}

fn no_tiles(span: Span) -> Span {
    var none = span;
    none.first_tile = vec2<i32>(1);
    none.last_tile = vec2<i32>(0);
    return none;
}

// Segment `s` of the line list (of the wisps' quads) with tiles of side `t`.
fn segment_span(s: u32, t: i32) -> Span {
    var span: Span;
    span = no_tiles(span);
#ifdef GEOMETRY_WISPS
    return wisp_span(span, s, t);
#else
    if (2u * s + 1u >= arrayLength(&hair_indices)) {
        return span;
    }
    span.vertex = hair_indices[2u * s];
    let v0 = hair_vertices[span.vertex];
    let v1 = hair_vertices[hair_indices[2u * s + 1u]];
    if (strand_lod_weight(v0.strand) <= 0.0) {
        return span;
    }
    // Clipped at the near plane, as the rasterizer clips a line (a segment
    // reaching behind the eye keeps its part in front).
    let seg = camera_segment(v0.position, v1.position);
    if (!seg.kept) {
        return span;
    }
    span.a = seg.a;
    span.b = seg.b;
    // Wider than a pixel: the quad the hair draws draw for it.
    if (strand_segment_is_wide(v0, v1)) {
        let q = strand_quad(v0, v1);
        if (!q.kept) {
            return span;
        }
        return quad_span(span, q.corner, t);
    }
    span.near_z = min(span.a.z, span.b.z);
    if (span.near_z >= 1.0 || max(span.a.z, span.b.z) < 0.0) {
        return span;
    }
    let size = vec2<i32>(frame.screen_size.xy);
    let lo = max(vec2<i32>(floor(min(span.a.xy, span.b.xy) - 1.0)), vec2<i32>(0));
    let hi = min(vec2<i32>(floor(max(span.a.xy, span.b.xy) + 1.0)), size - vec2<i32>(1));
    if (any(lo > hi)) {
        return span;
    }
    let d = span.b.xy - span.a.xy;
    let len = length(d);
    span.normal = select(vec2<f32>(0.0, 1.0), vec2<f32>(-d.y, d.x) / len, len > 1e-6);
    span.first_tile = lo / t;
    span.last_tile = hi / t;
    return span;
#endif
}

#ifdef GEOMETRY_WISPS
// Quad `s` of the wisps (`none`: a span of no tiles), unless the level of
// detail drops it (quad_span).
fn wisp_span(none: Span, s: u32, t: i32) -> Span {
    var span = none;
    let first = wisp_quad_first(s);
    if (first == NO_QUAD) {
        return span;
    }
    let q = wisp_quad(first);
    if (!q.kept) {
        return span;
    }
    span.vertex = first;
    return quad_span(span, q.corner, t);
}
#endif

// A quad of corners `c` (`none`: the span so far, of no tiles): the tiles its
// corners' bounding box, grown by a pixel, covers — the box of its two
// triangles —, unless it lies wholly before the near plane or beyond the
// far one.
fn quad_span(none: Span, c: array<vec4<f32>, 4>, t: i32) -> Span {
    var span = none;
    span.quad = true;
    span.corner = c;
    span.near_z = min(min(c[0].z, c[1].z), min(c[2].z, c[3].z));
    let far_z = max(max(c[0].z, c[1].z), max(c[2].z, c[3].z));
    if (span.near_z >= 1.0 || far_z < 0.0) {
        return span;
    }
    // Clamped before the conversion: a corner just in front of the near
    // plane can project far off the screen.
    let size = vec2<i32>(frame.screen_size.xy);
    let bound = vec2<f32>(size) + 2.0;
    let box_lo = clamp(min(min(c[0].xy, c[1].xy), min(c[2].xy, c[3].xy)), vec2<f32>(-2.0), bound);
    let box_hi = clamp(max(max(c[0].xy, c[1].xy), max(c[2].xy, c[3].xy)), vec2<f32>(-2.0), bound);
    let lo = max(vec2<i32>(floor(box_lo - 1.0)), vec2<i32>(0));
    let hi = min(vec2<i32>(floor(box_hi + 1.0)), size - vec2<i32>(1));
    if (any(lo > hi)) {
        return span;
    }
    span.first_tile = lo / t;
    span.last_tile = hi / t;
    return span;
}

// Whether the segment lands in tile (tx, ty) (the header's rules).
fn lands_in(span: Span, tx: i32, ty: i32, t: i32) -> bool {
    // Half the tile's diagonal plus the one pixel the coverage reaches.
    let reach = f32(t) * 0.70710678 + 1.5;
    let centre = (vec2<f32>(f32(tx), f32(ty)) + 0.5) * f32(t);
    if (!span.quad && abs(dot(centre - span.a.xy, span.normal)) > reach) {
        return false;
    }
    if (span.near_z >= bitcast<f32>(tile_far[u32(ty * tiles_across(t) + tx)])) {
        return false;
    }
    let size = vec2<i32>(frame.screen_size.xy);
    let tile_lo = vec2<i32>(tx, ty) * t;
    let tile_hi = min(tile_lo + vec2<i32>(t - 1), size - vec2<i32>(1));
    if (span.quad) {
        return quad_visible_in_tile(span.corner, tile_lo, tile_hi);
    }
    return visible_in_tile(span.a, span.b, tile_lo, tile_hi);
}

// Whether segment a → b (screen xy, NDC z) is in front of the opaque depth
// at some pixel of the tile from `lo` to `hi` (inclusive) that tile_blend
// draws it in: pixel centres whose major-axis coordinate falls in [0, 1)
// of the segment and whose distance across the line is under one pixel
// (blend.wgsl, line_coverage).
fn visible_in_tile(a: vec4<f32>, b: vec4<f32>, lo: vec2<i32>, hi: vec2<i32>) -> bool {
    let d = b.xy - a.xy;
    let x_major = abs(d.x) >= abs(d.y);
    // Swizzled so that .x is the major axis.
    let a2 = select(a.yx, a.xy, x_major);
    let d2 = select(d.yx, d, x_major);
    let lo2 = select(lo.yx, lo, x_major);
    let hi2 = select(hi.yx, hi, x_major);
    if (abs(d2.x) < 1e-6) {
        return false;
    }
    let cos_theta = abs(d2.x) / length(d2);
    let first = max(lo2.x, i32(floor(min(a2.x, a2.x + d2.x) - 0.5)));
    let last = min(hi2.x, i32(floor(max(a2.x, a2.x + d2.x) + 0.5)));
    for (var i = first; i <= last; i++) {
        let t = (f32(i) + 0.5 - a2.x) / d2.x;
        if (t < 0.0 || t >= 1.0) {
            continue;
        }
        let minor = a2.y + t * d2.y;
        let z = mix(a.z, b.z, t);
        if (z < 0.0) {
            continue;
        }
        let from_j = max(lo2.y, i32(floor(minor - 1.5)));
        let to_j = min(hi2.y, i32(floor(minor + 1.5)));
        for (var j = from_j; j <= to_j; j++) {
            if (abs(f32(j) + 0.5 - minor) * cos_theta >= 1.0) {
                continue;
            }
            let pixel = select(vec2<i32>(j, i), vec2<i32>(i, j), x_major);
            if (z < textureLoad(opaque_depth, pixel, 0)) {
                return true;
            }
        }
    }
    return false;
}

// Whether the quad of corners `c` covers a pixel centre of the tile from
// `lo` to `hi` (inclusive) in front of the opaque depth there: the pixels
// tile_blend draws it in (the same triangles), as visible_in_tile asks of a
// line. A quick rejection first: its triangles miss the tile.
fn quad_visible_in_tile(c: array<vec4<f32>, 4>, lo: vec2<i32>, hi: vec2<i32>) -> bool {
    if (!quad_meets(c, vec2<f32>(lo) + 0.5, vec2<f32>(hi) + 0.5)) {
        return false;
    }
    // The pixels of the tile whose centres lie in the corners' box (clamped
    // to the tile before the conversion).
    let box_lo = min(min(c[0].xy, c[1].xy), min(c[2].xy, c[3].xy));
    let box_hi = max(max(c[0].xy, c[1].xy), max(c[2].xy, c[3].xy));
    let first = vec2<i32>(max(ceil(box_lo - 0.5), vec2<f32>(lo)));
    let last = vec2<i32>(min(floor(box_hi - 0.5), vec2<f32>(hi)));
    for (var y = first.y; y <= last.y; y++) {
        for (var x = first.x; x <= last.x; x++) {
            let hit = quad_depth(vec2<f32>(f32(x), f32(y)) + 0.5, c);
            if (hit.x > 0.0 && hit.y >= 0.0 && hit.y < textureLoad(opaque_depth, vec2<i32>(x, y), 0)) {
                return true;
            }
        }
    }
    return false;
}
