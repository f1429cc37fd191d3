// plait::hair_radiance — the radiance a hair point sends towards the eye:
// the key light's irradiance times its reflection per unit irradiance
// (`shading`), shadowed by opaque objects (Sintorn & Assarsson 2009 §3.5)
// and by the hair itself (`self_shadow`), plus the light scattered by more
// than one strand (`multiple_scattering`), plus the rest
// of the environment's light (`lighting`) darkened by the point's ambient
// occlusion. One function, so the per-fragment path (`plait::hair_fragment`)
// and the strand-space compute pass (`techniques/shading_space/strand/`)
// cannot shade differently.
//
// The opaque shadow map is an argument: the caller binds it (group 1 binding
// 0, slot `shadow_map`), so a pass that imports the hair stage without
// shading (ShortCut's depth pass) binds no shadow map.
#define_import_path plait::hair_radiance

#import plait::frame::{frame, to_light, light_irradiance}
#import plait::shading::shade_direct
#import plait::lighting::shade_environment
#import plait::shadow::opaque_shadow
#import plait::self_shadow::self_shadow
#import plait::multiple_scattering::multiple_scattering

// `tangent` need not be unit length; `color` is the strand's colour (the
// frame's hair colour multiplies it); `occlusion` the fraction of the
// environment's light reaching the point.
fn hair_radiance(shadow_map: texture_depth_2d, world: vec3<f32>, tangent_in: vec3<f32>, color: vec3<f32>, occlusion: f32) -> vec3<f32> {
    let tangent = normalize(tangent_in);
    let l = to_light(world);
    let e = normalize(frame.camera_position.xyz - world);
    let hair_visibility = self_shadow(world);
    let opaque = opaque_shadow(shadow_map, world, 0.002);
    let visibility = hair_visibility * opaque;
    let base = color * frame.hair_color.rgb;
    let direct = shade_direct(tangent, l, e, base);
    // Light scattered by more than one strand (`multiple_scattering`; zero
    // with `none`, so single scattering's images are unchanged), shadowed
    // by opaque objects; the hair's own shadowing is the method's.
    let multiple = multiple_scattering(world, tangent, l, e, base, hair_visibility) * opaque;
    let environment = shade_environment(world, tangent, e, base) * occlusion;
    return light_irradiance(world) * direct * visibility + light_irradiance(world) * multiple + environment;
}
