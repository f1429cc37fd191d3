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
// segment whose tiles are those its two triangles reach
// (plait::compute_raster::triangles, quad_meets),
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
#import plait::compute_raster::triangles::{quad_weights, quad_perspective}

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

// Pixel centre `p` on quad a b c d (corners as WispQuad's, `along` theirs):
// x = 1 when inside one of its triangles (plait::compute_raster::triangles,
// a b c, else b d c, so a centre on their shared edge is counted once), y =
// NDC z there, zw = (u across, along) interpolated perspective-correctly;
// all 0 outside.
fn wisp_quad_hit(p: vec2<f32>, a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, d: vec4<f32>, along: vec4<f32>) -> vec4<f32> {
    let q = quad_weights(p, a.xy, b.xy, c.xy, d.xy);
    if (!q.inside) {
        return vec4<f32>(0.0);
    }
    let w = vec4<f32>(a.w, b.w, c.w, d.w);
    let z = dot(q.l, vec4<f32>(a.z, b.z, c.z, d.z));
    return vec4<f32>(1.0, z, quad_perspective(q.l, w, vec4<f32>(0.0, 1.0, 0.0, 1.0)), quad_perspective(q.l, w, along));
}
