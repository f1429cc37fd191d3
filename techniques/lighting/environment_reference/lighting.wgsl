// plait::lighting::environment_reference — environment light by brute force
// (Xing et al. 2012 Fig. 3a, 3c): every texel of the environment cube is a
// directional light, summed per fragment with the same Kajiya-Kay responses
// the irradiance maps store (eq. 5 and 7, normalized by 1/π²), at the
// fragment's own tangent and θ′, in the maps' units (plait::kajiya_kay::kk_environment_specular_units).
// The ground truth of the maps; its cost is
// one loop over the 6·16² texels per fragment.
#define_import_path plait::lighting::environment_reference

#import plait::frame::frame
#import plait::cube::{cube_texel_direction, PI}
#import plait::sh::{kk_diffuse, kk_specular, KK_NORMALIZATION}
#import plait::kajiya_kay::kk_environment_specular_units

@group(1) @binding(32) var light_environment: texture_2d<f32>;

fn hair_environment(world: vec3<f32>, tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let t = normalize(tangent);
    let theta_eye = clamp(acos(clamp(dot(t, to_eye), -1.0, 1.0)) + frame.hair_shading.w, 0.0, PI);
    let exponent = frame.hair_shading.z;
    let dims = textureDimensions(light_environment);
    var diffuse = vec3<f32>(0.0);
    var specular = vec3<f32>(0.0);
    for (var y = 0u; y < dims.y; y++) {
        for (var x = 0u; x < dims.x; x++) {
            let texel = textureLoad(light_environment, vec2<u32>(x, y), 0);
            let c = dot(t, cube_texel_direction(vec2<u32>(x, y), dims.y));
            let light = texel.rgb * texel.a;
            diffuse += kk_diffuse(c) * light;
            specular += kk_specular(c, theta_eye, exponent) * light;
        }
    }
    return (base * frame.hair_shading.x * diffuse + frame.hair_shading.y * specular * kk_environment_specular_units(exponent, theta_eye)) * KK_NORMALIZATION;
}
