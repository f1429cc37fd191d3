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
#import plait::strand_dots::dots_candidate

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
        } else {
            t = strand_crossing(origin, dir, a.position, 0.5 * a.thickness, b.position, 0.5 * b.thickness);
        }
        if (t > near && t < far) {
            hits.strands += 1.0;
        }
    }
    return hits;
}

// Strands crossed by the ray from `origin` along unit `dir` farther than
// `near` and nearer than `far`, through the strands only (the meshes'
// instances are masked out).
fn strands_crossed(origin: vec3<f32>, dir: vec3<f32>, near: f32, far: f32) -> f32 {
    return ray_hits(origin, dir, near, far, 0.0).strands;
}
