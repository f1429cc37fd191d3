// plait::multiple_scattering::none — nothing added to single scattering.
#define_import_path plait::multiple_scattering::none

fn hair_multiple_scattering(world: vec3<f32>, tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>, hair_visibility: f32) -> vec3<f32> {
    return vec3<f32>(0.0);
}
