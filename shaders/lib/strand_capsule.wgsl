// plait::strand_capsule — a ray against one strand segment as a tapered
// swept sphere (the tapered capsules issue 48 describes for RTX Hair: a sphere swept from one
// vertex to the next, its radius going linearly from the strand's
// half-width at one end to that at the other). Used on each candidate box
// of the strands' acceleration structure by plait::strand_rays, the one ray
// loop of the ray-traced techniques (crates/plait-gpu/src/strand_structure.rs
// builds one box per segment).
//
// A ray crosses a strand once where it passes within the strand's radius of
// its axis. Consecutive segments of a strand share a vertex, so a ray
// through the joint passes through both segments' capsules: counting each
// capsule would count that crossing twice. The crossing therefore belongs
// to the segment whose own half-open stretch of the axis, [0, 1), holds the
// ray's point of closest approach — the swept sphere's body, without the
// end caps that overlap the next segment's.
#define_import_path plait::strand_capsule

// Ray distance of the crossing of ray `o + t d` (|d| = 1) with segment
// a → b of radii ra → rb, or -1 when the ray misses it or runs (nearly)
// along it.
fn strand_crossing(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, ra: f32, b: vec3<f32>, rb: f32) -> f32 {
    let e = b - a;
    let w = o - a;
    let ee = dot(e, e);
    let de = dot(d, e);
    let denom = ee - de * de;
    // Parallel (sin² of the angle below 1e-8): no single crossing.
    if (ee <= 0.0 || denom <= 1e-8 * ee) {
        return -1.0;
    }
    let dw = dot(d, w);
    let ew = dot(e, w);
    let t = (de * ew - ee * dw) / denom;
    let s = (ew - de * dw) / denom;
    if (s < 0.0 || s >= 1.0) {
        return -1.0;
    }
    let gap = length(w + t * d - s * e);
    if (gap > mix(ra, rb, s)) {
        return -1.0;
    }
    return t;
}

// The ray's closest approach to segment a → b: x = its ray distance t,
// y = the place s along the segment, in the segment's own half-open [0, 1)
// as strand_crossing takes it, z = the distance between the two (the ray to
// the axis); x = −1 when the approach is outside the segment or the ray
// runs (nearly) along it. What strand_crossing tests against the radius,
// for a caller that weighs a hit by how near the axis the ray passes
// (transparency = ray_traced: the part of a pixel the strand covers).
fn strand_approach(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    let e = b - a;
    let w = o - a;
    let ee = dot(e, e);
    let de = dot(d, e);
    let denom = ee - de * de;
    if (ee <= 0.0 || denom <= 1e-8 * ee) {
        return vec3<f32>(-1.0, 0.0, 0.0);
    }
    let dw = dot(d, w);
    let ew = dot(e, w);
    let t = (de * ew - ee * dw) / denom;
    let s = (ew - de * dw) / denom;
    if (s < 0.0 || s >= 1.0) {
        return vec3<f32>(-1.0, 0.0, 0.0);
    }
    return vec3<f32>(t, s, length(w + t * d - s * e));
}
