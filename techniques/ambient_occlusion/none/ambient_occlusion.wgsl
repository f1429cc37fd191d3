// plait::ambient_occlusion::none — no ambient occlusion: every vertex fully open.
#define_import_path plait::ambient_occlusion::none

fn vertex_occlusion(vertex_index: u32) -> f32 {
    return 1.0;
}
