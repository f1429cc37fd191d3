// occlusion_cylinders: per-vertex ambient occlusion with every hair vertex a
// transparent cylinder along its strand and the scalp as oriented discs
// (Halén & Wester 2007 §3.3.1, §5.7). Two kernels of one file, picked by a
// define (recorded by crates/plait-passes/src/occlusion_cylinders.rs):
//
// - CYLINDER_BOUNDS: one workgroup writes the hair's bounding box to
//   `hair_box`; the scalp is the opaque triangles whose centroid lies in it
//   (the head under the hair, not the ground);
// - otherwise (the shadow kernel): one thread per receiving hair vertex adds
//   the shadow S of §3.3.1 of one chunk of the casters and of the scalp
//   triangles (`hair_box.chunk`) to its running sum in `vertex_ao`;
// - CYLINDER_VISIBILITY: one thread per vertex turns the sum into the
//   ambient visibility: exp(-S) by default (`combine = "exp"`: the casters as
//   independent occluders, equal to 1 - S while S is small), or the thesis's
//   1 - S clamped to [0, 1] (`combine = "sum"`), which counts overlapping
//   casters twice and reaches 0 wherever a dense groom's casters add up past
//   one.
//
// Why chunks: lavapipe gives each group of 8 invocations one budget of 65,535
// loop iterations, shared by all its loops, and silently ends every loop once
// it is spent. A thread summing every caster of the built-in groom (330,000
// vertices) would stop after the first ~65,000. The pass records the shadow
// kernel once per chunk (at most `chunk_iterations` loop iterations, 16,384
// by default), copying the chunk's bounds into `hair_box` before each
// dispatch. The sums go through `vertex_ao`, one thread per vertex, in the
// order of dispatch: no float atomics, deterministic. The casters are added
// in the order one long loop would add them (the chunking does not change
// their sum); each chunk of scalp triangles adds its sum as one term. A loop that still stops early (a driver with a
// smaller budget) adds 1 to `ao_status[0]`, the `incomplete` word of its
// overflow declaration, and the frame fails instead of showing a wrong AO.
//
// A caster cylinder of radius r (half the strand thickness) and length l (the
// strand segment at the vertex) at distance d along d̄ is seen as a disc of
// the same visible area A = 2r·l·sin(T_c, d̄), radius R² = A/π, solid angle
// 2π(1 - d/√(R² + d²)); over the sphere's 4π, times sin(T_r, d̄) (a caster
// across the receiver shadows it more) and the caster's opacity σ:
//   S = Σ (1 - d/√(R² + d²)) · sin(T_r, d̄) · σ · ½.
// A scalp disc (one per opaque triangle: its area, normal and centroid; the
// thesis uses one per scalp vertex) is opaque (σ = 1) and seen at its
// orientation, A = area·cos; it counts only when it faces the receiver, so a
// closed head is not counted twice, and when the receiver projects onto the
// disc the distance to its plane is used instead (the thesis's fix for roots,
// §5.7).
//
// The sum is O(n²) (the thesis's own limit, §6); `caster_stride` k lets every
// k-th hair vertex cast for k vertices (length k·l), a k-times cheaper
// estimate for large grooms.
#import plait::frame::frame
#ifdef CYLINDER_BOUNDS
#import plait::hair_bounds::{BOUNDS_GROUP, workgroup_bounds}
#endif

struct HairVertex {
    position: vec3<f32>,
    thickness: f32,
    tangent: vec3<f32>,
    alpha: f32,
    color: vec3<f32>,
    strand_id: u32,
}

// The bounding box (written by CYLINDER_BOUNDS) and the current chunk
// (copied in by the pass before each shadow dispatch): hair vertices
// `caster_first, caster_first + stride, … < caster_end` and scalp triangles
// `triangle_first … < triangle_end`.
struct HairBox {
    lo: vec4<f32>,
    hi: vec4<f32>,
    caster_first: u32,
    caster_end: u32,
    triangle_first: u32,
    triangle_end: u32,
}

struct CylinderParams {
    caster_stride: u32,
    // 1: the scalp casts (the scene has opaque geometry).
    scalp_discs: u32,
}

const PI: f32 = 3.141592653589793;
// Floats per opaque vertex (`OpaqueVertex` in crates/plait-gpu/src/geometry.rs):
// position, normal, albedo, head weight.
const OPAQUE_STRIDE: u32 = 10u;

@group(1) @binding(0) var<storage, read> hair_vertices: array<HairVertex>;
@group(1) @binding(1) var<storage, read_write> vertex_ao: array<f32>;
@group(1) @binding(2) var<storage, read_write> hair_box: HairBox;
@group(1) @binding(3) var<uniform> cylinder_params: CylinderParams;
@group(1) @binding(6) var<storage, read_write> ao_status: array<atomic<u32>>;
#ifndef NO_SCALP
@group(1) @binding(4) var<storage, read> opaque_vertices: array<f32>;
@group(1) @binding(5) var<storage, read> opaque_indices: array<u32>;
#endif

#ifdef CYLINDER_BOUNDS
@compute @workgroup_size(256)
fn main(@builtin(local_invocation_index) t: u32) {
    let n = arrayLength(&hair_vertices);
    var a = vec3<f32>(3.0e38);
    var z = vec3<f32>(-3.0e38);
    for (var i = t; i < n; i += BOUNDS_GROUP) {
        let p = hair_vertices[i].position;
        a = min(a, p);
        z = max(z, p);
    }
    let box = workgroup_bounds(t, a, z);
    if (t == 0u) {
        hair_box.lo = vec4<f32>(box.lo, 0.0);
        hair_box.hi = vec4<f32>(box.hi, 0.0);
    }
}
#else
// Length of strand `j` at its vertex: its segment to the next vertex of the
// strand, or from the previous one at the tip.
fn segment_length(j: u32, n: u32) -> f32 {
    let v = hair_vertices[j];
    if (j + 1u < n && hair_vertices[j + 1u].strand_id == v.strand_id) {
        return distance(hair_vertices[j + 1u].position, v.position);
    }
    if (j > 0u && hair_vertices[j - 1u].strand_id == v.strand_id) {
        return distance(hair_vertices[j - 1u].position, v.position);
    }
    return 0.0;
}

// The solid angle of a disc of radius² `r2` at distance `d`, over 4π.
fn disc_fraction(r2: f32, d: f32) -> f32 {
    return 0.5 * (1.0 - d / sqrt(r2 + d * d));
}

#ifndef NO_SCALP
fn opaque_position(k: u32) -> vec3<f32> {
    let at = opaque_indices[k] * OPAQUE_STRIDE;
    return vec3<f32>(opaque_vertices[at], opaque_vertices[at + 1u], opaque_vertices[at + 2u]);
}

// Shadow of the scalp discs of this chunk's triangles on a receiver at `p`
// with tangent `tr`; `complete` is false when the loop was cut short.
struct ScalpSum {
    shadow: f32,
    complete: bool,
}

fn scalp_shadow(p: vec3<f32>, tr: vec3<f32>) -> ScalpSum {
    let lo = hair_box.lo.xyz;
    let hi = hair_box.hi.xyz;
    var shadow = 0.0;
    let end = min(hair_box.triangle_end, arrayLength(&opaque_indices) / 3u);
    var t = hair_box.triangle_first;
    for (; t < end; t++) {
        let a = opaque_position(3u * t);
        let b = opaque_position(3u * t + 1u);
        let c = opaque_position(3u * t + 2u);
        let m = (a + b + c) / 3.0;
        if (any(m < lo) || any(m > hi)) {
            continue;
        }
        let cr = cross(b - a, c - a);
        let twice_area = length(cr);
        if (twice_area <= 0.0) {
            continue;
        }
        let normal = cr / twice_area;
        let area = 0.5 * twice_area;
        let to_disc = m - p;
        let d = length(to_disc);
        if (d <= 0.0) {
            continue;
        }
        let dir = to_disc / d;
        // Facing the receiver: its normal points back along d̄.
        let facing = -dot(normal, dir);
        if (facing <= 0.0) {
            continue;
        }
        let sin_r = length(cross(tr, dir));
        let height = facing * d;
        let lateral2 = max(d * d - height * height, 0.0);
        if (lateral2 <= area / PI) {
            // Over the disc: the whole disc at the distance to its plane.
            shadow += disc_fraction(area / PI, height) * sin_r;
        } else {
            shadow += disc_fraction(area * facing / PI, d) * sin_r;
        }
    }
    return ScalpSum(shadow, t >= end);
}
#endif

#ifdef CYLINDER_VISIBILITY
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&hair_vertices) || i >= arrayLength(&vertex_ao)) {
        return;
    }
    let shadow = vertex_ao[i];
#ifdef COMBINE_SUM
    vertex_ao[i] = clamp(1.0 - shadow, 0.0, 1.0);
#else
    vertex_ao[i] = exp(-shadow);
#endif
}
#else
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = arrayLength(&hair_vertices);
    let i = id.x;
    if (i >= n || i >= arrayLength(&vertex_ao)) {
        return;
    }
    let receiver = hair_vertices[i];
    let p = receiver.position;
    let tr = normalize(receiver.tangent);
    let stride = max(cylinder_params.caster_stride, 1u);
    let opacity = clamp(frame.hair_color.a, 0.0, 1.0);
    // The sum so far (zeroed before the first chunk): the casters are added
    // in the order one loop over all of them would add them.
    var shadow = vertex_ao[i];
    let end = min(hair_box.caster_end, n);
    var j = hair_box.caster_first;
    for (; j < end; j += stride) {
        if (j == i) {
            continue;
        }
        let caster = hair_vertices[j];
        let to_caster = caster.position - p;
        let d2 = dot(to_caster, to_caster);
        if (d2 <= 1e-12) {
            continue;
        }
        let d = sqrt(d2);
        let dir = to_caster / d;
        let length_k = segment_length(j, n) * f32(stride);
        let sin_c = length(cross(normalize(caster.tangent), dir));
        // R² = 2r·l·sin(T_c, d̄)/π with r = thickness / 2.
        let r2 = caster.thickness * length_k * sin_c / PI;
        let sin_r = length(cross(tr, dir));
        let sigma = clamp(caster.alpha * opacity, 0.0, 1.0);
        shadow += disc_fraction(r2, d) * sin_r * sigma;
    }
    var complete = j >= end;
#ifndef NO_SCALP
    if (cylinder_params.scalp_discs != 0u) {
        let scalp = scalp_shadow(p, tr);
        shadow += scalp.shadow;
        complete = complete && scalp.complete;
    }
#endif
    vertex_ao[i] = shadow;
    if (!complete) {
        atomicAdd(&ao_status[0], 1u);
    }
}
#endif
#endif
