// plait::shading_space::fragment — every hair fragment is shaded where it is
// drawn (plait's behaviour before strand space): nothing comes from elsewhere
// (w < 0, a constant, so the hair draws' strand-space branch is compiled
// out), and no tip fading.
#define_import_path plait::shading_space::fragment

fn strand_radiance(strand: u32, segment: u32, along: f32) -> vec4<f32> {
    return vec4<f32>(0.0, 0.0, 0.0, -1.0);
}
