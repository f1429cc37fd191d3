enable wgpu_ray_query;
// plait::strand_rays — the one loop every ray-traced technique walks a ray
// through the strands' acceleration structure with (self_shadow =
// ray_traced, ambient_occlusion = ray_traced, tests/ray_traced_strands.rs).
// The structure holds each segment (crates/plait-gpu/src/strand_structure.rs,
// its `primitive`) either as a box, each candidate box intersected as its
// segment's tapered swept sphere (plait::strand_capsule), or as DOTS, four
// triangles whose reports count the segment once (plait::strand_dots); the
// crossings between `near` and `far` are counted. A candidate of two
// vertices of different strands is no segment. The
// scene's meshes are triangle instances of the same structure, asked for by
// mask (`ray_hits`' mesh_far): a mesh hit is opaque.
//
// Why the structure and the hair's vertices are this module's globals, not
// arguments: naga 30 takes neither a pointer to a `ray_query` ("Ray Query is
// not a local variable") nor a pointer to a storage buffer ("can't be passed
// into functions"); it takes an `acceleration_structure` argument, but then
// the caller's module declares one, and naga_oil, checking an imported
// module that declares one and traces no ray itself, panics in naga's GLSL
// writer (as plait_gpu::shader notes). So every user binds the two at this
// module's bindings, under the self_shadow point's slot names (vis_strands,
// vis_hair: techniques/self_shadow/point.toml), and calls strands_crossed.
#define_import_path plait::strand_rays

#import plait::hair_point::HairPoint
#import plait::strand_capsule::strand_crossing
#import plait::strand_dots::{dots_candidate, dots_plane}

// The strands' acceleration structure (the strand_structure pass's output).
@group(1) @binding(8) var vis_strands: acceleration_structure;
// The hair's vertices as the structure was built from them (hair_vertices).
@group(1) @binding(9) var<storage, read> vis_hair: array<HairPoint>;

// The top-level instances' masks (crates/plait-gpu/src/strand_structure.rs,
// STRAND_MASK and MESH_MASK): the strands' boxes, and the scene's meshes
// (head, ground, [[meshes]]) as triangle instances.
const STRAND_INSTANCES: u32 = 1u;
const MESH_INSTANCES: u32 = 2u;
// The strands' instance's custom data (the meshes' are 1, 2, …): what tells a
// DOTS triangle of a strand from a mesh's triangle.
const STRAND_INSTANCE_DATA: u32 = 0u;

// What one ray meets: the strands it crosses, and whether a mesh stops it.
struct RayHits {
    strands: f32,
    // A mesh between `near` and `mesh_far` (opaque: nothing beyond it
    // counts, and the walk stops there, so `strands` is then partial).
    blocked: bool,
}

// Strands crossed by the ray from `origin` along unit `dir` farther than
// `near` and nearer than `far` (1e30: no end), and whether a mesh lies
// farther than `near` and nearer than `mesh_far` (≤ near: meshes are not
// asked for). The ray query is declared here, in a function and outside
// any loop: one declared in a loop made naga emit a null constant of the
// ray-query type, which Mesa rejects and the device is lost (wgpu PR 9945).
fn ray_hits(origin: vec3<f32>, dir: vec3<f32>, near: f32, far: f32, mesh_far: f32) -> RayHits {
    var rq: ray_query;
    let meshes = mesh_far > near;
    let mask = select(STRAND_INSTANCES, STRAND_INSTANCES | MESH_INSTANCES, meshes);
    rayQueryInitialize(&rq, vis_strands, RayDesc(RAY_FLAG_FORCE_NO_OPAQUE, mask, 0.0, max(far, select(0.0, mesh_far, meshes)), origin, dir));
    var hits = RayHits(0.0, false);
    while (rayQueryProceed(&rq)) {
        let c = rayQueryGetCandidateIntersection(&rq);
        let dots = c.kind == RAY_QUERY_INTERSECTION_TRIANGLE && c.instance_custom_data == STRAND_INSTANCE_DATA;
        if (c.kind == RAY_QUERY_INTERSECTION_TRIANGLE && !dots) {
            if (c.t > near && c.t < mesh_far) {
                hits.blocked = true;
                break;
            }
            continue;
        }
        if (c.kind != RAY_QUERY_INTERSECTION_AABB && !dots) {
            continue;
        }
        // A box is segment i; DOTS triangles 4i … 4i + 3 are.
        let segment = select(c.primitive_index, c.primitive_index / 4u, dots);
        let a = vis_hair[segment];
        let b = vis_hair[segment + 1u];
        if (a.strand != b.strand) {
            continue;
        }
        var t: f32;
        if (dots) {
            t = dots_candidate(origin, dir, a.position, 0.5 * a.thickness, b.position, 0.5 * b.thickness, c.primitive_index % 4u);
            if (t > near && t < far && !dots_owns(origin, dir, segment)) {
                continue;
            }
        } else {
            t = strand_crossing(origin, dir, a.position, 0.5 * a.thickness, b.position, 0.5 * b.thickness);
        }
        if (t > near && t < far) {
            hits.strands += 1.0;
        }
    }
    return hits;
}

// Whether segment s + k exists: two vertices of `strand` in vis_hair.
fn strand_segment(s: u32, k: i32, strand: u32) -> bool {
    let i = i32(s) + k;
    return i >= 0 && u32(i) + 1u < arrayLength(&vis_hair) && vis_hair[i].strand == strand && vis_hair[i + 1].strand == strand;
}

// Whether a crossing of one of segment s's quads' planes (dots_plane: x its
// ray distance, y its place along s, z its distance from the axis) lies on
// segment s + k, k = floor(y), of `strand`: the segment exists and the
// crossing is within its half-width where it lies along it. Past s's ends
// that is the neighbour's own width: a tapering strand's neighbour is
// narrower or wider there than s's end, and its quad is crossed, and
// reported, exactly where it is that wide.
fn on_segment(origin: vec3<f32>, dir: vec3<f32>, s: u32, plane: vec3<f32>, strand: u32) -> bool {
    let k = i32(floor(plane.y));
    if (plane.x <= 0.0 || (k != 0 && !strand_segment(s, k, strand))) {
        return false;
    }
    let c = vis_hair[u32(i32(s) + k)];
    let d = vis_hair[u32(i32(s) + k) + 1u];
    let e = d.position - c.position;
    let along = clamp(dot(origin + plane.x * dir - c.position, e) / dot(e, e), 0.0, 1.0);
    return plane.z <= 0.5 * mix(c.thickness, d.thickness, along);
}

// Whether segment `s`, whose DOTS the ray crosses, counts the crossing. A
// ray oblique to a strand near a joint can cross one quad of `s` and the
// other quad of a neighbour — two segments for one pass through a straight
// strand (1.06× the loss of one crossing per ray beside a thick strand at
// 45° to its quads: tests/ray_traced_occlusion.rs). So the pass belongs to
// the segment where the ray first crosses a quad's plane, the planes taken
// along the strand past `s`'s ends (dots_plane; exact for a straight
// strand, whose segments' quads share the planes), among the crossings
// that lie on a segment of the strand (on_segment); `s` counts it only when
// that is `s` — as plait::strand_capsule gives a swept sphere's crossing to
// one segment.
fn dots_owns(origin: vec3<f32>, dir: vec3<f32>, s: u32) -> bool {
    let a = vis_hair[s];
    let b = vis_hair[s + 1u];
    var first = 1e30;
    var owner = 0;
    // Quads 0 and 1, unrolled (no loop: plait::loop_budget).
    let planes = array<vec3<f32>, 2>(dots_plane(origin, dir, a.position, b.position, 0u), dots_plane(origin, dir, a.position, b.position, 1u));
    if (on_segment(origin, dir, s, planes[0], a.strand)) {
        first = planes[0].x;
        owner = i32(floor(planes[0].y));
    }
    if (on_segment(origin, dir, s, planes[1], a.strand) && planes[1].x < first) {
        owner = i32(floor(planes[1].y));
    }
    return owner == 0;
}

// Strands crossed by the ray from `origin` along unit `dir` farther than
// `near` and nearer than `far`, through the strands only (the meshes'
// instances are masked out).
fn strands_crossed(origin: vec3<f32>, dir: vec3<f32>, near: f32, far: f32) -> f32 {
    return ray_hits(origin, dir, near, far, 0.0).strands;
}

// What a path's ray meets first (plait's path tracer,
// shaders/passes/path_trace.wgsl): a strand segment or a mesh triangle.
struct NearestHit {
    // 0: nothing; 1: a strand; 2: a mesh.
    kind: u32,
    // Ray distance of the hit: for a strand the ray's closest approach to
    // the segment's axis (strand_crossing's t).
    t: f32,
    // Strand: the segment's first vertex in vis_hair. Mesh: the triangle
    // in its mesh's stretch of indices.
    primitive: u32,
    // Mesh: the instance's custom index (1 + the mesh's index in the scene's
    // order, crates/plait-gpu/src/strand_structure.rs).
    instance: u32,
    // Mesh: the hit's barycentrics (of vertices 1 and 2).
    barycentrics: vec2<f32>,
    // Mesh: the instance's object-to-world transform (the head's moves).
    object_to_world: mat4x3<f32>,
}

const NO_HIT: NearestHit = NearestHit(0u, -1.0, 0u, 0u, vec2<f32>(0.0), mat4x3<f32>());

// The strand of segment `skip` (0xffffffff: none, and then none is).
fn skipped_strand(skip: u32) -> u32 {
    if (skip == 0xffffffffu) {
        return 0xffffffffu;
    }
    return vis_hair[skip].strand;
}

// Ray distance of box candidate `i` for a path's rays (nearest_hit,
// ray_blocked): its segment's swept sphere crossed (strand_crossing), or −1
// for a pair of two strands' vertices and for segment `skip` of
// `skip_strand` and its neighbours. The one test both walks share: their
// ray-query loops cannot be one function (naga takes no pointer to a
// ray_query, above).
fn box_crossing(origin: vec3<f32>, dir: vec3<f32>, i: u32, skip: u32, skip_strand: u32) -> f32 {
    let a = vis_hair[i];
    let b = vis_hair[i + 1u];
    if (a.strand != b.strand || (a.strand == skip_strand && i + 1u >= skip && i <= skip + 1u)) {
        return -1.0;
    }
    return strand_crossing(origin, dir, a.position, 0.5 * a.thickness, b.position, 0.5 * b.thickness);
}

// The nearest strand or mesh along the ray from `origin` along unit `dir`
// farther than `near` and nearer than `far`, skipping segment `skip` and its
// neighbours along the same strand (the segment a path leaves from: a ray
// starting on its axis would meet it again at once); skip = 0xffffffff
// skips none. Each nearer hit is committed, so traversal drops boxes past it.
fn nearest_hit(origin: vec3<f32>, dir: vec3<f32>, near: f32, far: f32, skip: u32) -> NearestHit {
    var rq: ray_query;
    rayQueryInitialize(&rq, vis_strands, RayDesc(RAY_FLAG_FORCE_NO_OPAQUE, STRAND_INSTANCES | MESH_INSTANCES, near, far, origin, dir));
    var best = NO_HIT;
    var nearest = far;
    let skip_strand = skipped_strand(skip);
    while (rayQueryProceed(&rq)) {
        let c = rayQueryGetCandidateIntersection(&rq);
        if (c.kind == RAY_QUERY_INTERSECTION_TRIANGLE) {
            if (c.t > near && c.t < nearest) {
                nearest = c.t;
                best = NearestHit(2u, c.t, c.primitive_index, c.instance_custom_data, c.barycentrics, c.object_to_world);
                rayQueryConfirmIntersection(&rq);
            }
            continue;
        }
        if (c.kind != RAY_QUERY_INTERSECTION_AABB) {
            continue;
        }
        let i = c.primitive_index;
        let t = box_crossing(origin, dir, i, skip, skip_strand);
        if (t > near && t < nearest) {
            nearest = t;
            best = NearestHit(1u, t, i, 0u, vec2<f32>(0.0), mat4x3<f32>());
            rayQueryGenerateIntersection(&rq, t);
        }
    }
    return best;
}

// Whether anything — a strand (opaque, as Mitsuba's fibres are to shadow
// rays) or a mesh — lies along the ray from `origin` along unit `dir`
// farther than `near` and nearer than `far`, skipping segment `skip` and
// its neighbours as nearest_hit does. Stops at the first blocker.
fn ray_blocked(origin: vec3<f32>, dir: vec3<f32>, near: f32, far: f32, skip: u32) -> bool {
    var rq: ray_query;
    rayQueryInitialize(&rq, vis_strands, RayDesc(RAY_FLAG_FORCE_NO_OPAQUE, STRAND_INSTANCES | MESH_INSTANCES, near, far, origin, dir));
    let skip_strand = skipped_strand(skip);
    var blocked = false;
    while (rayQueryProceed(&rq)) {
        let c = rayQueryGetCandidateIntersection(&rq);
        if (c.kind == RAY_QUERY_INTERSECTION_TRIANGLE) {
            if (c.t > near && c.t < far) {
                blocked = true;
                break;
            }
            continue;
        }
        if (c.kind != RAY_QUERY_INTERSECTION_AABB) {
            continue;
        }
        let t = box_crossing(origin, dir, c.primitive_index, skip, skip_strand);
        if (t > near && t < far) {
            blocked = true;
            break;
        }
    }
    return blocked;
}
