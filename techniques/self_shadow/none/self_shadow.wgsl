// plait::self_shadow::none — no hair self-shadowing: every point sees the light.
#define_import_path plait::self_shadow::none

fn hair_visibility(world: vec3<f32>) -> f32 {
    return 1.0;
}
