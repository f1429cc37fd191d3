// plait::compute_raster::wisp_quad — the compute rasterizer's wisps
// (`geometry = wisps`, techniques/geometry/wisps): what the hardware
// rasterizer draws for them, rasterized here.
//
// Every other transparency technique draws the wisp mesh's triangles
// (plait_hair::wisps::WispMesh: per wisp two vertices per spine point, even
// = u 0, odd = u 1; per pair of consecutive spine points a quad of two
// triangles a b c, b d c, its vertices first … first + 3), placed by
// plait::geometry::wisps::wisp_point (the strip facing the view, widened and
// dropped by the wisps' level of detail), one sample at each pixel centre.
// Here a "segment" of the binning and of tile_blend is one such quad: a wide
// segment whose tiles are those its two triangles reach (wisp_quad_meets),
// and whose coverage at a pixel centre is the triangles' — inside one of
// them, with the strand texture's alpha at the (u across, v along, mip
// level) interpolated there as the rasterizer interpolates them
// (perspective-correct), and the depth the triangle has there (NDC z is
// affine on the screen), so the depth test matches the hardware's.
//
// The near plane: each side edge of the quad (a → c, b → d) is clipped
// there as camera_segment clips a strand's segment, and the quad drawn
// between the clipped ends (`along`: each corner's place between the quad's
// spine points), which is the triangles' clipped shape up to where the
// plane crosses their shared diagonal. A quad whose one side lies wholly
// behind the near plane while the other does not (the plane along the
// strip, a sliver of a pixel or so) is not drawn.
#define_import_path plait::compute_raster::wisp_quad

#import plait::hair_point::{HairPoint, camera_segment}
#import plait::geometry::wisps::{WispPoint, wisp_point}

// The wisp mesh as storage (scene bindings, bound by name like
// hair_vertices): its vertices in the hair vertex layout's slots
// (plait_hair::wisps::WispVertex) and its triangle list's indices.
@group(1) @binding(68) var<storage, read> wisp_vertices: array<HairPoint>;
@group(1) @binding(69) var<storage, read> wisp_indices: array<u32>;

const NO_QUAD: u32 = 0xffffffffu;

// One quad of a wisp's strip on the screen: its corners a, b, c, d (wisp
// vertices first … first + 3) as screen xy (pixels), NDC z, clip w, after
// the near-plane clip; `along` each corner's place between the quad's two
// spine points (0, 0, 1, 1 unless clipped). `kept`: drawn at all.
struct WispQuad {
    corner: array<vec4<f32>, 4>,
    along: vec4<f32>,
    kept: bool,
}

// The first wisp vertex of quad `q` (the indices' quad q: a b c, b d c), or
// NO_QUAD past the mesh.
fn wisp_quad_first(q: u32) -> u32 {
    if (6u * q + 5u >= arrayLength(&wisp_indices)) {
        return NO_QUAD;
    }
    return wisp_indices[6u * q];
}

// Wisp vertex `i` this frame, as the hair draws' vertex stage places it.
fn wisp_vertex(i: u32) -> WispPoint {
    let v = wisp_vertices[i];
    return wisp_point(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand, i);
}

// The hair vertex wisp vertex `i` stands for (its per-vertex results, such
// as ambient occlusion, are read there: plait::strand_lod::strand_lod_vertex).
fn wisp_hair_vertex(i: u32) -> u32 {
    return wisp_vertices[i].strand;
}

fn wisp_quad(first: u32) -> WispQuad {
    var q: WispQuad;
    q.kept = false;
    let a = wisp_vertex(first);
    // The wisps' level of detail drops a wisp whole (plait::strand_lod_clip).
    if (a.weight <= 0.0) {
        return q;
    }
    let b = wisp_vertex(first + 1u);
    let c = wisp_vertex(first + 2u);
    let d = wisp_vertex(first + 3u);
    let left = camera_segment(a.corner, c.corner);
    let right = camera_segment(b.corner, d.corner);
    if (!left.kept || !right.kept) {
        return q;
    }
    q.corner = array<vec4<f32>, 4>(left.a, right.a, left.b, right.b);
    q.along = vec4<f32>(left.t_start, right.t_start, left.t_stop, right.t_stop);
    q.kept = true;
    return q;
}

fn cross2(a: vec2<f32>, b: vec2<f32>) -> f32 {
    return a.x * b.y - a.y * b.x;
}

// Pixel centre `p` in triangle a b c (screen xy, NDC z, clip w), whose
// corners carry (u, along) `ua`, `ub`, `uc`: x = 1 when inside (edges
// included), y = NDC z there, zw = (u, along) interpolated perspective-
// correctly (the screen barycentrics over w, renormalized); all 0 outside.
fn triangle_hit(p: vec2<f32>, a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, ua: vec2<f32>, ub: vec2<f32>, uc: vec2<f32>) -> vec4<f32> {
    let area = cross2(b.xy - a.xy, c.xy - a.xy);
    if (abs(area) < 1e-12) {
        return vec4<f32>(0.0);
    }
    let la = cross2(b.xy - p, c.xy - p) / area;
    let lb = cross2(c.xy - p, a.xy - p) / area;
    let l = vec3<f32>(la, lb, 1.0 - la - lb);
    if (min(l.x, min(l.y, l.z)) < 0.0) {
        return vec4<f32>(0.0);
    }
    let w = l / vec3<f32>(a.w, b.w, c.w);
    let attributes = (w.x * ua + w.y * ub + w.z * uc) / (w.x + w.y + w.z);
    return vec4<f32>(1.0, dot(l, vec3<f32>(a.z, b.z, c.z)), attributes);
}

// Pixel centre `p` on quad a b c d (corners as WispQuad's, `along` theirs):
// triangle_hit of a b c, else of b d c (so a centre on their shared edge is
// counted once).
fn wisp_quad_hit(p: vec2<f32>, a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, d: vec4<f32>, along: vec4<f32>) -> vec4<f32> {
    let first = triangle_hit(p, a, b, c, vec2<f32>(0.0, along.x), vec2<f32>(1.0, along.y), vec2<f32>(0.0, along.z));
    if (first.x > 0.0) {
        return first;
    }
    return triangle_hit(p, b, d, c, vec2<f32>(1.0, along.y), vec2<f32>(1.0, along.w), vec2<f32>(0.0, along.z));
}

// Whether the edge from e0 to e1 of a triangle of signed area sign `s` has
// some point of the box lo … hi on its inner side.
fn edge_reaches(e0: vec2<f32>, e1: vec2<f32>, s: f32, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    let d = e1 - e0;
    // cross2(d, p − e0) · s grows along g: the box's corner farthest along it.
    let g = vec2<f32>(-d.y, d.x) * s;
    let corner = select(lo, hi, g > vec2<f32>(0.0));
    return dot(g, corner - e0) >= 0.0;
}

// Whether triangle a b c (screen xy) may hold a point of the box lo … hi:
// the boxes overlap and no edge has the whole box outside (a separating
// axis test, conservative only at the box's corners).
fn triangle_meets(a: vec2<f32>, b: vec2<f32>, c: vec2<f32>, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    if (any(max(max(a, b), c) < lo) || any(min(min(a, b), c) > hi)) {
        return false;
    }
    let area = cross2(b - a, c - a);
    if (abs(area) < 1e-12) {
        return false;
    }
    let s = sign(area);
    return edge_reaches(a, b, s, lo, hi) && edge_reaches(b, c, s, lo, hi) && edge_reaches(c, a, s, lo, hi);
}

// Whether quad `q` may cover a pixel centre in the box lo … hi (screen
// pixels; the box grown by 1/64 pixel so rounding never loses a centre
// wisp_quad_hit would keep).
fn wisp_quad_meets(q: WispQuad, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    let margin = vec2<f32>(1.0 / 64.0);
    let l = lo - margin;
    let h = hi + margin;
    let c = q.corner;
    return triangle_meets(c[0].xy, c[1].xy, c[2].xy, l, h) || triangle_meets(c[1].xy, c[3].xy, c[2].xy, l, h);
}
