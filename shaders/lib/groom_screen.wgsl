// plait::groom_screen — how big the groom is on screen this frame, from the
// frame's uniforms alone (every vertex computes the same number, so no pass
// or buffer is needed). The level of detail of `geometry = "lod"` (fewer
// strands) and of `geometry = "wisps"` (fewer, wider wisps) both follow it
// (Halén & Wester 2007 §2.4). Its CPU twin: plait::strand_lod::groom_screen_fraction.
#define_import_path plait::groom_screen

#import plait::frame::frame

// The groom's height on screen as a fraction of the screen height: its
// bounding sphere's diameter projected at its centre's depth. Large (every
// strand) when the eye is within the sphere's radius of its centre's depth.
fn groom_screen_fraction() -> f32 {
    let centre = frame.hair_sphere.xyz;
    let radius = frame.hair_sphere.w;
    // The camera's up axis in the world: row 1 of the view's rotation.
    let up = vec3<f32>(frame.camera_view[0].y, frame.camera_view[1].y, frame.camera_view[2].y);
    let a = frame.camera_view_proj * vec4<f32>(centre, 1.0);
    let b = frame.camera_view_proj * vec4<f32>(centre + up * radius, 1.0);
    if (a.w <= radius || b.w <= 0.0) {
        return 1e9;
    }
    // NDC spans 2 over the screen's height, the diameter 2 × this.
    return abs(b.y / b.w - a.y / a.w);
}
