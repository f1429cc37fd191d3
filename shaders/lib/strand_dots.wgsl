// plait::strand_dots — a strand segment as DOTS (disjoint orthogonal
// triangle strips: two quads crossed along the segment's axis, NVIDIA's
// representation of hair before linear swept spheres), the other
// representation the strands' acceleration structure takes
// (crates/plait-gpu/src/strand_structure.rs, `primitive = "dots"`). Quad 0
// spans the axis and the unit vector u across it, quad 1 the axis and v
// (u, v and the axis orthonormal); each is a trapezoid of half-width ra at
// vertex a and rb at vertex b (half the strand's width there, as the swept
// sphere's radii), split along its diagonal into two triangles: segment i's
// triangles are primitives 4i … 4i + 3 (quad 0: 4i, 4i + 1; quad 1: 4i + 2,
// 4i + 3). Built by shaders/passes/strand_dots.wgsl from the same functions
// the tracers call, so both see the same quads.
//
// One crossing per segment: a ray through a segment near its axis crosses
// both quads, and one across a quad's diagonal may meet both of its
// triangles, so the structure reports up to four triangles of one segment
// for one crossing of the strand. A reported triangle counts only when it is
// the segment's first triangle (in primitive order) the ray crosses —
// dots_candidate —, so every segment the ray meets counts once, whichever of
// its triangles the traversal reports and in whatever order. (The
// first-triangle test is this file's, the reports the driver's: they can
// disagree only for a ray within rounding of a triangle's edge.) Two
// consecutive segments are separate quads ("disjoint"): a ray oblique to
// the strand near a joint may cross one quad of each, straight strand or
// not. The tracers give such a pass to one segment, as plait::strand_capsule
// does a swept sphere's: plait::strand_rays by the first plane crossed
// (dots_plane, dots_owns), the primary rays by the closest approach
// (techniques/transparency/ray_traced/trace.wgsl, dots_owner).
#define_import_path plait::strand_dots

// Unit vectors across segment direction `e` (not zero): column 0 is u, the
// vector quad 0 spans (quad 1's normal), column 1 is v (quad 0's normal).
// From the direction alone, so the builder and the tracers agree bit for bit.
fn dots_across(e: vec3<f32>) -> mat2x3<f32> {
    let t = normalize(e);
    let helper = select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), abs(t.y) > 0.9);
    let u = normalize(cross(t, helper));
    return mat2x3<f32>(u, cross(t, u));
}

// Corner j (0 … 11) of segment a → b's four triangles, three corners each in
// order: quad q's corners are a ∓ ra·w, b ∓ rb·w (w = u for q = 0, v for
// q = 1); its triangle 2q is (a − ra w, a + ra w, b − rb w), triangle 2q + 1
// (b − rb w, a + ra w, b + rb w): the diagonal from a + ra w to b − rb w.
fn dots_corner(a: vec3<f32>, ra: f32, b: vec3<f32>, rb: f32, j: u32) -> vec3<f32> {
    let across = dots_across(b - a);
    let w = across[(j / 6u) & 1u];
    // (end, side) of each corner of the quad's two triangles: end 0 = a,
    // 1 = b; side −1 or +1 along w.
    var ends = array<u32, 6>(0u, 0u, 1u, 1u, 0u, 1u);
    var sides = array<f32, 6>(-1.0, 1.0, -1.0, -1.0, 1.0, 1.0);
    let k = j % 6u;
    if (ends[k] == 0u) {
        return a + sides[k] * ra * w;
    }
    return b + sides[k] * rb * w;
}

// Ray o + t d (|d| = 1) against quad q (0 or 1) of segment a → b, e = b − a
// (not zero): x = the ray distance of its plane, y = the quad's triangle
// (2q or 2q + 1) the crossing is in; y = −1 when the ray misses the quad or
// runs along its plane (which the structure reports no triangle for either).
fn dots_quad(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, ra: f32, b: vec3<f32>, rb: f32, q: u32) -> vec2<f32> {
    let e = b - a;
    let across = dots_across(e);
    let w = across[q];
    let n = across[1u - q];
    let facing = dot(d, n);
    if (abs(facing) <= 1e-7) {
        return vec2<f32>(-1.0, -1.0);
    }
    let t = dot(a - o, n) / facing;
    let p = o + t * d - a;
    let s = dot(p, e) / dot(e, e);
    let x = dot(p, w);
    if (s < 0.0 || s > 1.0 || abs(x) > mix(ra, rb, s)) {
        return vec2<f32>(-1.0, -1.0);
    }
    // Which side of the diagonal from (s, x) = (0, ra) to (1, −rb).
    let second = x > ra - s * (ra + rb);
    return vec2<f32>(t, f32(2u * q + select(0u, 1u, second)));
}

// Ray o + t d (|d| = 1) against the plane of quad q of segment a → b taken
// past the segment's ends, as a straight strand's neighbours continue it:
// x = the ray distance (−1 when the ray runs along the plane), y = the place
// along the axis (0 at a, 1 at b, any value), z = the crossing's distance
// from the axis in the plane. Which segment of a strand a crossing belongs
// to (plait::strand_rays, dots_owns, which holds z to the half-width of the
// segment the place lies on: past an end, the neighbour's, not this one's).
fn dots_plane(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, b: vec3<f32>, q: u32) -> vec3<f32> {
    let e = b - a;
    let across = dots_across(e);
    let facing = dot(d, across[1u - q]);
    if (abs(facing) <= 1e-7) {
        return vec3<f32>(-1.0, 0.0, 0.0);
    }
    let t = dot(a - o, across[1u - q]) / facing;
    let p = o + t * d - a;
    return vec3<f32>(t, dot(p, e) / dot(e, e), abs(dot(p, across[q])));
}

// The segment's crossing by ray o + t d (|d| = 1): x = its ray distance,
// y = the first of the segment's triangles (0 … 3, in primitive order) the
// ray crosses; x = −1, y = −1 when the ray misses both quads. The ray
// distance is that triangle's quad's: a ray meets a segment's DOTS once,
// where it crosses the first of its quads it crosses in primitive order.
// (No loop: lavapipe's loop budget counts every iteration, plait::loop_budget.)
fn dots_crossing(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, ra: f32, b: vec3<f32>, rb: f32) -> vec2<f32> {
    if (dot(b - a, b - a) <= 0.0) {
        return vec2<f32>(-1.0, -1.0);
    }
    let first = dots_quad(o, d, a, ra, b, rb, 0u);
    if (first.y >= 0.0) {
        return first;
    }
    return dots_quad(o, d, a, ra, b, rb, 1u);
}

// The ray distance of segment a → b's one crossing when reported triangle
// `local` (its primitive index mod 4) is the one that counts it, else −1:
// the segment counts once however many of its triangles are reported.
fn dots_candidate(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, ra: f32, b: vec3<f32>, rb: f32, local: u32) -> f32 {
    let crossing = dots_crossing(o, d, a, ra, b, rb);
    if (crossing.y < 0.0 || u32(crossing.y) != local) {
        return -1.0;
    }
    return crossing.x;
}
