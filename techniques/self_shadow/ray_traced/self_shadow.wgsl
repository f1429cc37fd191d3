enable wgpu_ray_query;
// plait::self_shadow::ray_traced — self-shadowing by tracing a ray from the
// point toward the key light through the strands' acceleration structure
// (vis_strands, built every frame by the strand_structure pass) and counting
// the strands it crosses: each candidate box is intersected as the tapered
// swept sphere of its segment (plait::strand_capsule). A crossing counts when
// it is farther along the ray than the self-shadow bias ("In front of",
// docs/design.md), so the point's own strand never counts; n is the count
// and visibility = exp(−w · n), w = shadow_weight, the convention of every
// estimator (exact's n is Σ share of the fragments in front: a ray through a
// strand's width counts it once, and over the points a texel covers the
// mean count is that share).
#define_import_path plait::self_shadow::ray_traced

#import plait::frame::frame
#import plait::hair_point::HairPoint
#import plait::strand_capsule::strand_crossing

@group(1) @binding(8) var vis_strands: acceleration_structure;
@group(1) @binding(9) var<storage, read> vis_hair: array<HairPoint>;

struct VisibilityParams {
    // Opacity added by one strand in front (w of Sintorn & Assarsson 2009 §3.3).
    shadow_weight: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

// Strands crossed between `world` and the key light. The ray query is
// declared here, outside any loop: one declared in a loop made naga emit a
// null constant of the ray-query type, which Mesa rejects (wgpu PR 9945).
fn hair_strands_toward_light(world: vec3<f32>) -> f32 {
    let point_light = frame.light_direction.w > 0.5;
    let to_light = select(frame.light_direction.xyz, normalize(frame.light_position.xyz - world), point_light);
    let far = select(1e30, distance(frame.light_position.xyz, world), point_light);
    let bias = frame.conventions.x * (frame.near_far.w - frame.near_far.z);
    var rq: ray_query;
    rayQueryInitialize(&rq, vis_strands, RayDesc(RAY_FLAG_FORCE_NO_OPAQUE, 0xFFu, 0.0, far, world, to_light));
    var n = 0.0;
    while (rayQueryProceed(&rq)) {
        let c = rayQueryGetCandidateIntersection(&rq);
        if (c.kind != RAY_QUERY_INTERSECTION_AABB) {
            continue;
        }
        let a = vis_hair[c.primitive_index];
        let b = vis_hair[c.primitive_index + 1u];
        if (a.strand != b.strand) {
            continue;
        }
        let t = strand_crossing(world, to_light, a.position, 0.5 * a.thickness, b.position, 0.5 * b.thickness);
        if (t > bias && t < far) {
            n += 1.0;
        }
    }
    return n;
}

fn hair_visibility(world: vec3<f32>) -> f32 {
    return exp(-visibility_params.shadow_weight * hair_strands_toward_light(world));
}
