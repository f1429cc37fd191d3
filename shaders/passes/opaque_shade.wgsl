// opaque_shade: the head and the ground, Lambert-lit, shadowed by the opaque
// shadow map and by the hair through the visibility provider
// (Sintorn & Assarsson 2009 §3.5: hair shadows on opaque objects come from the
// same light maps the hair uses for itself).
//
// Units (docs/formats.md, "Light and units"): `light_irradiance` is the
// irradiance E on a surface facing the light and `ambient` the radiance L_a
// of a uniform environment, so a Lambertian surface of albedo ρ reflects the
// radiance ρ/π·E·cos θ + ρ·L_a (the BRDF ρ/π integrated against a uniform
// L_a over the hemisphere's projected solid angle π gives ρ·L_a).
#import plait::frame::{frame, view_proj, to_light, light_irradiance, opaque_world, opaque_world_normal}
#import plait::shadow::opaque_shadow
#import plait::self_shadow::self_shadow

const PI: f32 = 3.14159265358979;

@group(1) @binding(0) var shadow_map: texture_depth_2d;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
    // 1 for the head, which moves with the scene's animation.
    @location(3) head: f32,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    let world = opaque_world(v.position, v.head);
    out.clip = view_proj() * vec4<f32>(world, 1.0);
    out.world = world;
    out.normal = opaque_world_normal(v.normal, v.head);
    out.albedo = v.albedo;
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let n = normalize(in.normal);
    let l = to_light(in.world);
    let lambert = max(dot(n, l), 0.0);
    // Slope-scaled bias against acne on surfaces grazing the light.
    let bias = 0.001 + 0.004 * (1.0 - lambert);
    let visibility = opaque_shadow(shadow_map, in.world, bias) * self_shadow(in.world);
    let rgb = in.albedo * (light_irradiance(in.world) * (lambert * visibility / PI) + frame.ambient.rgb);
    return vec4<f32>(rgb, 1.0);
}
