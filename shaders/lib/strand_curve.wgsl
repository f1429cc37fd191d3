// plait::strand_curve — the tangent hair is shaded about: the derivative of
// the smooth curve through the strand's points, not the straight segment
// plait draws nor its end tangents interpolated linearly.
//
// Each segment p0 → p1 is the cubic Hermite piece whose end derivatives are
// the vertex tangents t0, t1 (unit: the natural cubic spline's directions at
// the points, plait_hair::curve::knot_directions — the curve `plait export
// mitsuba` hands the path tracer) times the chord's length |p1 − p0|. At u
// along it the derivative, over |p1 − p0|, is
//     6u(1 − u) ĉ + (1 − u)(1 − 3u) t0 + u(3u − 2) t1,   ĉ = (p1 − p0)/|p1 − p0|.
// On the wavy groom at 24 segments this is a median 0.3° (at most 1.5°) from
// the spline's tangent, where the linear interpolation was 7.2° (docs/
// formats.md, "Against the path tracer: the shading tangent"). The CPU twin is
// plait_hair::curve::segment_tangent.
#define_import_path plait::strand_curve

// A vector's direction, or 0 for the zero vector (normalize(0) is undefined).
fn curve_unit(v: vec3<f32>) -> vec3<f32> {
    let s = dot(v, v);
    return select(vec3<f32>(0.0), v * inverseSqrt(s), s > 0.0);
}

// The curve's unit tangent at u ∈ [0, 1] along the segment from p0 to p1
// with unit end tangents t0 and t1 (for passes that read both ends).
fn strand_curve_tangent(p0: vec3<f32>, p1: vec3<f32>, t0: vec3<f32>, t1: vec3<f32>, u: f32) -> vec3<f32> {
    let c = curve_unit(p1 - p0);
    if (all(c == vec3<f32>(0.0))) {
        // A segment of length 0 has no piece: its tangents, interpolated.
        return curve_unit(mix(t0, t1, u));
    }
    return curve_unit(6.0 * u * (1.0 - u) * c + (1.0 - u) * (1.0 - 3.0 * u) * t0 + u * (3.0 * u - 2.0) * t1);
}

// The same for a line's fragment, which sees only the provoking vertex's
// values flat (p0, t0) and the others interpolated linearly at u: its point
// on the chord `world` = p0 + u (p1 − p0) and `lerp_t` = (1 − u) t0 + u t1.
// Then u ĉ ∥ world − p0 and u t1 = lerp_t − (1 − u) t0, so the derivative
// above is 6u(1 − u) ĉ + (1 − u)(3 − 6u) t0 + (3u − 2) lerp_t — no division
// by u, exact at both ends.
fn strand_curve_tangent_lerp(world: vec3<f32>, p0: vec3<f32>, t0: vec3<f32>, lerp_t: vec3<f32>, u: f32) -> vec3<f32> {
    let c = curve_unit(world - p0);
    if (all(c == vec3<f32>(0.0))) {
        // At the first vertex (lerp_t = t0 there) or on a segment of length 0.
        return curve_unit(lerp_t);
    }
    return curve_unit(6.0 * u * (1.0 - u) * c + (1.0 - u) * (3.0 - 6.0 * u) * t0 + (3.0 * u - 2.0) * lerp_t);
}
