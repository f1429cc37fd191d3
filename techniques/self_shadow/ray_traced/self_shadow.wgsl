enable wgpu_ray_query;
// plait::self_shadow::ray_traced — self-shadowing by tracing a ray from the
// point toward the key light through the strands' acceleration structure
// (vis_strands, built every frame by the strand_structure pass) and counting
// the strands it crosses: each candidate box is intersected as the tapered
// swept sphere of its segment (plait::strand_capsule, walked by plait::strand_rays). A crossing counts when
// it is farther along the ray than the self-shadow bias ("In front of",
// docs/design.md), so the point's own strand never counts; n is the count
// and visibility = exp(−w · n), w = shadow_weight, the convention of every
// estimator (exact's n is Σ share of the fragments in front: a ray through a
// strand's width counts it once, and over the points a texel covers the
// mean count is that share). With `shadow_rays` > 1 the rays' origins are
// jittered over a disc of one pixel's area across the light (the pixel's
// footprint at the point's depth), so a strand edge's hard shadow is averaged
// over the pixel instead of sampled at its centre. The scene's meshes (head,
// ground) are in the structure too: with `shadow_meshes` = 1 a ray that
// meets one beyond the bias carries no light (visibility 0), so the head
// shadows the hair per pixel; the strand count
// (hair_strands_along_light) is the strands' alone.
#define_import_path plait::self_shadow::ray_traced

#import plait::frame::frame
#import plait::strand_rays::{ray_hits, strands_crossed}

// The strands' structure and vertices (vis_strands at binding 8, vis_hair
// at 9) are plait::strand_rays' globals.

struct VisibilityParams {
    // Opacity added by one strand in front (w of Sintorn & Assarsson 2009 §3.3).
    shadow_weight: f32,
    // Rays per shading point (1–64, checked at load): 1 traces the point's
    // own ray; more jitter the origin over the pixel's footprint.
    shadow_rays: u32,
    // 1: a mesh between the point and the light blocks the ray; 0: the
    // strands alone, as exact's lists (the head is the opaque shadow map's).
    shadow_meshes: u32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

const GOLDEN_ANGLE: f32 = 2.39996322972865;
const TAU: f32 = 6.28318530717959;

// The side of one pixel at `world`'s depth in the camera's view (world
// units): `world` and the point one pixel above it on screen, unprojected.
fn pixel_footprint(world: vec3<f32>) -> f32 {
    let clip = frame.camera_view_proj * vec4<f32>(world, 1.0);
    let ndc = clip.xyz / clip.w;
    let up = ndc + vec3<f32>(0.0, 2.0 * frame.screen_size.w, 0.0);
    let a = frame.camera_inv_view_proj * vec4<f32>(ndc, 1.0);
    let b = frame.camera_inv_view_proj * vec4<f32>(up, 1.0);
    return distance(a.xyz / a.w, b.xyz / b.w);
}

// A 32-bit integer hash (PCG's output permutation): the per-point rotation
// of the ray pattern, from the point's position bits.
fn hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct Rays {
    origin: vec3<f32>,
    to_light: vec3<f32>,
    far: f32,
    bias: f32,
    // Two unit vectors perpendicular to to_light, spanning the jitter disc.
    u: vec3<f32>,
    v: vec3<f32>,
    // The disc's radius: that of a disc of one pixel's area (side / √π).
    radius: f32,
    // The pattern's rotation about to_light (radians), per point.
    turn: f32,
}

fn rays_from(world: vec3<f32>) -> Rays {
    var r: Rays;
    let point_light = frame.light_direction.w > 0.5;
    r.origin = world;
    r.to_light = select(frame.light_direction.xyz, normalize(frame.light_position.xyz - world), point_light);
    r.far = select(1e30, distance(frame.light_position.xyz, world), point_light);
    r.bias = frame.conventions.x * (frame.near_far.w - frame.near_far.z);
    let helper = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(r.to_light.x) > 0.9);
    r.u = normalize(cross(r.to_light, helper));
    r.v = cross(r.to_light, r.u);
    r.radius = pixel_footprint(world) * 0.5641895835;
    let bits = bitcast<vec3<u32>>(world);
    r.turn = TAU * f32(hash(bits.x ^ hash(bits.y ^ hash(bits.z))) >> 8u) / 16777216.0;
    return r;
}

// Origin of ray i of `count`: the point itself for one ray; else point i of
// a Vogel spiral (radius ∝ √((i + ½) / count), golden-angle turns) over the
// disc, rotated per point, so the rays cover the footprint evenly and
// neighbouring points do not share the pattern's aliasing. The origin moves
// across the light only: the light's direction, hence a hard shadow's mean
// over the footprint, stays.
fn ray_origin(r: Rays, i: u32, count: u32) -> vec3<f32> {
    if (count <= 1u) {
        return r.origin;
    }
    let rho = r.radius * sqrt((f32(i) + 0.5) / f32(count));
    let phi = r.turn + GOLDEN_ANGLE * f32(i);
    return r.origin + rho * (cos(phi) * r.u + sin(phi) * r.v);
}

// Strands crossed between `world` and the key light, the mean over the
// point's rays. A crossing counts beyond the bias ("in front of").
fn strands_toward(world: vec3<f32>) -> f32 {
    let r = rays_from(world);
    let count = max(visibility_params.shadow_rays, 1u);
    var n = 0.0;
    for (var i = 0u; i < count; i++) {
        n += strands_crossed(ray_origin(r, i, count), r.to_light, r.bias, r.far);
    }
    return n / f32(count);
}

// The mean of the rays' transmittances exp(−w · n_i): the light reaching
// the pixel's footprint, not the light through its mean count.
fn hair_visibility(world: vec3<f32>) -> f32 {
    let r = rays_from(world);
    let count = max(visibility_params.shadow_rays, 1u);
    let mesh_far = select(0.0, r.far, visibility_params.shadow_meshes != 0u);
    var sum = 0.0;
    for (var i = 0u; i < count; i++) {
        let hits = ray_hits(ray_origin(r, i, count), r.to_light, r.bias, r.far, mesh_far);
        sum += select(exp(-visibility_params.shadow_weight * hits.strands), 0.0, hits.blocked);
    }
    return sum / f32(count);
}

// The strands in front of and behind the point (the self_shadow point's
// optional function): the rays' mean count from the point, and from beyond the hair
// less from just past the point's own strand (two biases behind it), along the
// light's ray — `plait::frame::light_behind`'s span, as a count toward the
// light from both ends.
fn hair_strands_along_light(world: vec3<f32>) -> vec2<f32> {
    let bias = frame.conventions.x * (frame.near_far.w - frame.near_far.z);
    let away = -rays_from(world).to_light;
    let through = strands_toward(world + away * (2.0 * bias));
    let beyond = strands_toward(world + away * (2.0 * frame.hair_sphere.w + 2.0 * bias));
    return vec2<f32>(strands_toward(world), max(beyond - through, 0.0));
}
