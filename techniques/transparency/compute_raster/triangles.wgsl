// plait::compute_raster::triangles — a quad of two triangles rasterized at
// pixel centres, as the hardware rasterizer samples them: the wisps' quads
// (plait::compute_raster::wisp_quad) and the quads of strands wider than a
// pixel (plait::compute_raster::strand_quad) both. A quad's corners are
// a, b, c, d (screen xy in pixels, NDC z, clip w), its triangles a b c and
// b d c — the order of the wisp mesh's indices and of the hair draws' quad
// draw (plait::strand_coverage::quad_corner: s−, s+, e− and s+, e+, e−).
#define_import_path plait::compute_raster::triangles

fn cross2(a: vec2<f32>, b: vec2<f32>) -> f32 {
    return a.x * b.y - a.y * b.x;
}

// Pixel centre `p` in triangle a b c (screen xy): x = 1 when inside (edges
// included), yzw its screen barycentrics (for a, b, c); all 0 outside.
fn triangle_weights(p: vec2<f32>, a: vec2<f32>, b: vec2<f32>, c: vec2<f32>) -> vec4<f32> {
    let area = cross2(b - a, c - a);
    if (abs(area) < 1e-12) {
        return vec4<f32>(0.0);
    }
    let la = cross2(b - p, c - p) / area;
    let lb = cross2(c - p, a - p) / area;
    let l = vec3<f32>(la, lb, 1.0 - la - lb);
    if (min(l.x, min(l.y, l.z)) < 0.0) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(1.0, l);
}

// Pixel centre `p` on quad a b c d: its screen barycentrics over the four
// corners (0 at the corner its triangle lacks) — of a b c, else of b d c, so
// a centre on their shared edge is counted once —, and 1 in `inside` when
// it is in one of them.
struct QuadWeights {
    inside: bool,
    l: vec4<f32>,
}

fn quad_weights(p: vec2<f32>, a: vec2<f32>, b: vec2<f32>, c: vec2<f32>, d: vec2<f32>) -> QuadWeights {
    let first = triangle_weights(p, a, b, c);
    if (first.x > 0.0) {
        return QuadWeights(true, vec4<f32>(first.yzw, 0.0));
    }
    let second = triangle_weights(p, b, d, c);
    return QuadWeights(second.x > 0.0, vec4<f32>(0.0, second.y, second.w, second.z));
}

// Attributes `at` of the quad's corners interpolated at weights `l`
// perspective-correctly (the barycentrics over w, renormalized), as the
// rasterizer interpolates a varying; `w` the corners' clip w.
fn quad_perspective(l: vec4<f32>, w: vec4<f32>, at: vec4<f32>) -> f32 {
    let lw = l / w;
    return dot(lw, at) / (lw.x + lw.y + lw.z + lw.w);
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

// Whether quad `c` (corners a b c d) may cover a pixel centre in the box
// lo … hi (screen pixels; the box grown by 1/64 pixel so rounding never
// loses a centre quad_weights would keep).
fn quad_meets(c: array<vec4<f32>, 4>, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    let margin = vec2<f32>(1.0 / 64.0);
    let l = lo - margin;
    let h = hi + margin;
    return triangle_meets(c[0].xy, c[1].xy, c[2].xy, l, h) || triangle_meets(c[1].xy, c[3].xy, c[2].xy, l, h);
}

// Whether quad `c` covers pixel centre `p` (x: 1 inside), and its NDC z
// there (y; NDC z is affine on the screen).
fn quad_depth(p: vec2<f32>, c: array<vec4<f32>, 4>) -> vec2<f32> {
    let q = quad_weights(p, c[0].xy, c[1].xy, c[2].xy, c[3].xy);
    if (!q.inside) {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(1.0, dot(q.l, vec4<f32>(c[0].z, c[1].z, c[2].z, c[3].z)));
}
