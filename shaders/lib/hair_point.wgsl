// plait::hair_point — a hair vertex as the `hair_vertices` storage buffer
// holds it (48 B, `plait_hair::StrandVertex`), for the compute passes that
// read the hair directly (strand-space shading, the compute rasterizer), and
// its projection to the screen.
#define_import_path plait::hair_point

#import plait::frame::frame

struct HairPoint {
    position: vec3<f32>,
    thickness: f32,
    tangent: vec3<f32>,
    alpha: f32,
    color: vec3<f32>,
    strand: u32,
}

// Screen position of world point `p` in pixels (y down, pixel centres at
// +0.5), its NDC depth, and its clip w (the camera depth).
fn screen_project(p: vec3<f32>) -> vec4<f32> {
    let c = frame.camera_view_proj * vec4<f32>(p, 1.0);
    let ndc = c.xyz / c.w;
    let xy = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * frame.screen_size.xy;
    return vec4<f32>(xy, ndc.z, c.w);
}
