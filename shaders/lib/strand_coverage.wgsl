// plait::strand_coverage — the part of a pixel a strand thinner than a pixel
// covers. Every blending technique weighs the strand's alpha by it (the shared
// hair-fragment stage, plait::hair_fragment, folds it into the fragment's
// alpha, so alpha to coverage turns it into the sample mask too), and so does
// the per-pixel mean alpha of occupancy-order blending (alpha_sum).
#define_import_path plait::strand_coverage

#import plait::frame::frame
// Tip fading is strand space's own (as the wisps' texture is geometry =
// wisps', plait::strand_lod): the shading_space contract answers where the
// colour is shaded with a constant w, so the fading cannot ride on it.
#ifdef SHADING_SPACE_STRAND
#import plait::shading_space::strand::strand_tip
#endif

// A view a strand is drawn from, as the width and quad functions need it:
// the camera for every camera-view draw (`camera_strand_view`), the light
// for the light maps' hair draws (plait::hair_map, issue 47), whose
// "pixels" are the map's texels.
struct StrandView {
    view_proj: mat4x4<f32>,
    // xy: the view's size in pixels (texels); zw: 1 / size.
    size: vec4<f32>,
    // xyz: the eye's position (w = 1: a camera, a spot light) or the unit
    // direction towards it (w = 0: a directional light).
    eye: vec4<f32>,
}

fn camera_strand_view() -> StrandView {
    return StrandView(frame.camera_view_proj, frame.screen_size, vec4<f32>(frame.camera_position.xyz, 1.0));
}

// The strand's width across the view in pixels at `world` along `tangent`
// (`thickness`: world units, its diameter); −1 behind the eye.
fn strand_width_pixels(world: vec3<f32>, tangent: vec3<f32>, thickness: f32) -> f32 {
    return view_width_pixels(camera_strand_view(), world, tangent, thickness);
}

// `strand_width_pixels` from any view.
fn view_width_pixels(view: StrandView, world: vec3<f32>, tangent: vec3<f32>, thickness: f32) -> f32 {
    let side = view_side_pixels(view, world, tangent, thickness);
    return select(length(side.xy), -1.0, side.z < 0.0);
}

// The strand's width across the view as it lands on the view's pixels: xy,
// the image of `thickness` along the side (across the strand and the view
// ray) at `world`; z = −1 behind the eye, else 1. Its length is the width
// where pixels are square; on a light map's texels, which need not be (the
// map's frustum follows the hair's bounds, plait::frame::LightFrustum), the
// image leans towards the strand's own and the band is only as wide as its
// part across the strand (`view_quad_place`, `view_band_width`).
fn view_side_pixels(view: StrandView, world: vec3<f32>, tangent: vec3<f32>, thickness: f32) -> vec3<f32> {
    let to_eye = select(view.eye.xyz, normalize(view.eye.xyz - world), view.eye.w > 0.5);
    // Across the strand and the view ray: the direction its width is seen in.
    var side = cross(tangent, to_eye);
    if (dot(side, side) < 1e-12) {
        side = cross(select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), abs(to_eye.y) > 0.9), to_eye);
    }
    side = normalize(side);
    let a = view.view_proj * vec4<f32>(world, 1.0);
    let b = view.view_proj * vec4<f32>(world + side * thickness, 1.0);
    if (a.w <= 0.0 || b.w <= 0.0) {
        return vec3<f32>(0.0, 0.0, -1.0);
    }
    return vec3<f32>((b.xy / b.w - a.xy / a.w) * 0.5 * view.size.xy, 1.0);
}

// The unit direction on the view's pixels of the strand through `world`
// along `toward` (a world offset along it); +x where it has none.
fn view_pixel_direction(view: StrandView, world: vec3<f32>, toward: vec3<f32>) -> vec2<f32> {
    let a = view_clip_pixels(view, view.view_proj * vec4<f32>(world, 1.0));
    let b = view_clip_pixels(view, view.view_proj * vec4<f32>(world + toward, 1.0));
    let dir = b - a;
    if (dot(dir, dir) < 1e-12) {
        return vec2<f32>(1.0, 0.0);
    }
    return normalize(dir);
}

// The strand's width across its own direction on the view's pixels
// (texels): the side's image across the strand's image at `world` — the
// band's width, what a line fragment holds of it. A line is drawn as a
// rectangle one pixel wide across it (lavapipe draws Vulkan's non-strict
// lines so: at 27° to the rows 1.13 fragments per column, 1 / cos 27° =
// 1.12), so its fragments cover its length × 1 and each holds the band's
// width. An adapter drawing parallelograms instead (one fragment per
// column, which Vulkan also allows and wgpu does not choose) would need
// the width over the direction's larger component. −1 behind the eye.
fn view_band_width(view: StrandView, world: vec3<f32>, tangent: vec3<f32>, thickness: f32) -> f32 {
    let side = view_side_pixels(view, world, tangent, thickness);
    if (side.z < 0.0) {
        return -1.0;
    }
    let dir = view_pixel_direction(view, world, tangent * max(thickness, 1e-6));
    return abs(side.x * dir.y - side.y * dir.x);
}

// The fraction of a pixel's width a strand of `thickness` (world units, its
// diameter) at `world` along `tangent` covers when it is drawn as a line:
// its width across the view in pixels, at most 1 — lines are one pixel wide,
// so a thin strand must weigh by its true width (as AMD TressFX and vkhr do
// for their lines and strips). A segment wider than a pixel is not drawn as
// a line where the pass has the quad draw (`segment_is_wide`), so the 1 here
// only holds for passes without it. frame.conventions.z = 0 turns coverage
// off (coverage 1).
fn strand_coverage(world: vec3<f32>, tangent: vec3<f32>, thickness: f32) -> f32 {
    if (frame.conventions.z < 0.5) {
        return 1.0;
    }
    let width = strand_width_pixels(world, tangent, thickness);
    // Behind the eye the line is clipped anyway; 1 as before.
    return select(min(width, 1.0), 1.0, width < 0.0);
}

// ---- Strands wider than a pixel: the quad draw (issue 47) ----
//
// A hair pass whose vertex stage is plait::hair_fragment's draws the hair
// twice: the indexed line list (every vertex i with the next one, i + 1, in
// its second vertex buffer) and a non-indexed triangle draw of 6 vertices per
// hair vertex i, instanced, both buffers stepped per instance, whose vertex
// indices start at WIDE_FIRST_VERTEX. A segment (i, i + 1) of one strand is
// "wide" when either end is wider than a pixel across the view: the line draw
// drops it (its fragments are discarded by the flat flag of the line's first
// vertex) and the quad draw draws it as a screen-aligned quad of its width
// plus half a pixel on each side; every other segment is a line as before and
// a degenerate quad. Vertex indices of the line draw are hair vertex indices,
// far below WIDE_FIRST_VERTEX.
const WIDE_FIRST_VERTEX: u32 = 1073741824u;

// A quad-draw vertex's place in its segment's quad: two triangles
// (s−, s+, e−) and (s+, e+, e−), each starting at a start corner so the flat
// varyings are the segment's first vertex's, as for its line.
struct QuadCorner {
    end: bool,
    side: f32,
}

fn quad_corner(vertex_index: u32) -> QuadCorner {
    let c = vertex_index - WIDE_FIRST_VERTEX;
    let end = c == 2u || c == 4u || c == 5u;
    let plus = c == 1u || c == 3u || c == 4u;
    return QuadCorner(end, select(-1.0, 1.0, plus));
}

fn is_quad_vertex(vertex_index: u32) -> bool {
    return vertex_index >= WIDE_FIRST_VERTEX;
}

// Whether the segment from hair vertex a to b (strands `strand_a`,
// `strand_b`) is drawn as a quad: coverage on, one strand, and either end
// wider than a pixel.
fn segment_is_wide(a: vec3<f32>, tangent_a: vec3<f32>, thickness_a: f32, strand_a: u32, b: vec3<f32>, tangent_b: vec3<f32>, thickness_b: f32, strand_b: u32) -> bool {
    return view_segment_is_wide(camera_strand_view(), a, tangent_a, thickness_a, strand_a, b, tangent_b, thickness_b, strand_b);
}

// `segment_is_wide` from any view: wider than one of its pixels (texels).
fn view_segment_is_wide(view: StrandView, a: vec3<f32>, tangent_a: vec3<f32>, thickness_a: f32, strand_a: u32, b: vec3<f32>, tangent_b: vec3<f32>, thickness_b: f32, strand_b: u32) -> bool {
    if (frame.conventions.z < 0.5 || strand_a != strand_b) {
        return false;
    }
    let wa = view_width_pixels(view, a, tangent_a, thickness_a);
    let wb = view_width_pixels(view, b, tangent_b, thickness_b);
    return wa >= 0.0 && wb >= 0.0 && max(wa, wb) > 1.0;
}

// A quad corner placed: clip position, and (distance from the centre line,
// half width) in pixels, for the fragment's box-filtered coverage.
struct QuadPlace {
    clip: vec4<f32>,
    across: vec2<f32>,
}

fn clip_pixels(clip: vec4<f32>) -> vec2<f32> {
    return view_clip_pixels(camera_strand_view(), clip);
}

fn view_clip_pixels(view: StrandView, clip: vec4<f32>) -> vec2<f32> {
    return clip.xy / clip.w * 0.5 * view.size.xy;
}

// The corner on `side` (±1) of the quad at hair vertex `world` (tangent,
// thickness) of the segment running `segment` (end − start, world units).
// Across is perpendicular to the strand's tangent on screen, so two
// segments meeting at a vertex share its corners (no gap, no overlap); the
// segment's own direction where the tangent is nearly across it.
fn quad_place(world: vec3<f32>, tangent: vec3<f32>, thickness: f32, segment: vec3<f32>, side: f32) -> QuadPlace {
    return view_quad_place(camera_strand_view(), world, tangent, thickness, segment, side);
}

// `quad_place` in any view (a light map's texels for its pixels).
fn view_quad_place(view: StrandView, world: vec3<f32>, tangent: vec3<f32>, thickness: f32, segment: vec3<f32>, side: f32) -> QuadPlace {
    var clip = view.view_proj * vec4<f32>(world, 1.0);
    let side_pixels = view_side_pixels(view, world, tangent, thickness);
    let length_ = length(segment);
    let along = dot(tangent, segment);
    var ahead_world = world + segment;
    if (abs(along) > 0.1 * length_) {
        ahead_world = world + tangent * (sign(along) * length_);
    }
    var ahead = view.view_proj * vec4<f32>(ahead_world, 1.0);
    if (clip.w <= 0.0) {
        return QuadPlace(vec4<f32>(2.0, 2.0, 2.0, 1.0), vec2<f32>(0.0));
    }
    // A segment running past the eye: the point ahead lies behind it, where
    // its projection flips. Any point of the same line in front of the eye
    // gives the same direction on screen: take the one halfway to the eye
    // plane (w linear along the line).
    if (ahead.w <= 0.0) {
        let t = 0.5 * clip.w / (clip.w - ahead.w);
        ahead = view.view_proj * vec4<f32>(world + (ahead_world - world) * t, 1.0);
    }
    var dir = view_clip_pixels(view, ahead) - view_clip_pixels(view, clip);
    if (dot(dir, dir) < 1e-12) {
        dir = vec2<f32>(1.0, 0.0);
    }
    let normal = normalize(vec2<f32>(-dir.y, dir.x));
    // The band's width across the quad's own direction: the side's image
    // along the normal (its whole length on square pixels; on non-square
    // light texels the image leans along the strand, view_side_pixels).
    let half = 0.5 * select(abs(dot(side_pixels.xy, normal)), 0.0, side_pixels.z < 0.0);
    // Half a pixel beyond the edge: every pixel centre the box-filtered
    // edge reaches is inside the quad. A pass param quad_edges = "band"
    // (QUAD_EDGES_BAND) draws the band itself, unfiltered: under MSAA whose
    // samples the strand's alpha picks (alpha_to_coverage) the samples it
    // covers are its edges' antialiasing, and `opaque`, which ignores alpha,
    // draws the strand's width solid rather than its width + 1.
#ifdef QUAD_EDGES_BAND
    let reach = side * half;
#else
    let reach = side * (half + 0.5);
#endif
    clip = vec4<f32>(clip.xy + normal * reach * 2.0 * view.size.zw * clip.w, clip.zw);
    return QuadPlace(clip, vec2<f32>(reach, half));
}

// The part of a pixel a band of half width `across.y` covers at distance
// `across.x` (pixels) from its centre line: the pixel taken as a box one
// pixel wide across the band, so over a row of pixels the parts sum to the
// band's width.
fn quad_coverage(across: vec2<f32>) -> f32 {
#ifdef QUAD_EDGES_BAND
    return 1.0;
#endif
    let d = abs(across.x);
    return clamp(min(d + 0.5, across.y) - max(d - 0.5, -across.y), 0.0, 1.0);
}

// The strand's tip fading at a place along it (strand `strand`, hair vertex
// `segment`, `along` past it): the scale on its width, hence on its
// coverage — strand space's `tip_scale` there, 1 for every other
// shading_space. Every hair draw scales its vertices' coverage by it — the
// shaded draws, the mean alpha (alpha_sum) and the compute rasterizer — so a
// faded tip hides what it shows.
fn strand_tip_scale(strand: u32, segment: u32, along: f32) -> f32 {
#ifdef SHADING_SPACE_STRAND
    return strand_tip(strand, segment, along);
#else
    return 1.0;
#endif
}
