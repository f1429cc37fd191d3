// plait::lighting::irradiance_maps — environment light from Kajiya-Kay
// irradiance maps (Xing et al. 2012 §3): the diffuse map and the two
// specular maps around θ′ (the angle between the tangent and the eye,
// shifted by the scene's specular shift as the key light's highlight is)
// looked up by the tangent and interpolated linearly, in the units of the
// key light's normalized Kajiya-Kay (docs/formats.md, "Light and units"). The maps come from
// `techniques/lighting/irradiance_maps/technique.toml` (summed directly) or
// `sh_irradiance_maps.toml` (rebuilt from SH, §5): one atlas, diffuse map
// then M + 1 specular maps, M read from its height.
#define_import_path plait::lighting::irradiance_maps

#import plait::frame::frame
#import plait::cube::{cube_atlas_sample, PI}
#import plait::kajiya_kay::kk_environment_specular_units

@group(1) @binding(31) var light_maps: texture_2d<f32>;

fn hair_environment(world: vec3<f32>, tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let dims = textureDimensions(light_maps);
    let intervals = dims.y / (dims.x / 6u) - 2u;
    let t = normalize(tangent);
    let theta_eye = clamp(acos(clamp(dot(t, to_eye), -1.0, 1.0)) + frame.hair_shading.w, 0.0, PI);
    let f = theta_eye / PI * f32(intervals);
    let m0 = min(u32(floor(f)), intervals);
    let m1 = min(m0 + 1u, intervals);
    let a = f - f32(m0);
    let diffuse = cube_atlas_sample(light_maps, 0u, t).rgb;
    let specular = mix(cube_atlas_sample(light_maps, 1u + m0, t).rgb, cube_atlas_sample(light_maps, 1u + m1, t).rgb, a);
    return base * frame.hair_shading.x * diffuse + frame.hair_shading.y * specular * kk_environment_specular_units(frame.hair_shading.z, theta_eye);
}
