// plait::lighting::ambient — everything but the key light as one constant
// colour (the scene's `ambient`), reflected by the hair's base colour.
#define_import_path plait::lighting::ambient

#import plait::frame::frame

fn hair_environment(world: vec3<f32>, tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    return frame.ambient.rgb * base;
}
