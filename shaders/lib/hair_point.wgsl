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
    return project_clip(frame.camera_view_proj * vec4<f32>(p, 1.0));
}

// A hair segment from world point p0 to p1 as the camera sees it: clipped
// to the near plane (clip z ≥ 0, where the rasterizer clips a line), its
// ends projected as screen_project does (`a`, `b`), at parameters t_start ≤ t_stop
// of the segment from p0 to p1 (clip space is linear in it). `kept` is
// false when the whole segment lies on the eye's side of the near plane.
struct CameraSegment {
    a: vec4<f32>,
    b: vec4<f32>,
    t_start: f32,
    t_stop: f32,
    kept: bool,
}

// screen_project of a clip-space point.
fn project_clip(c: vec4<f32>) -> vec4<f32> {
    let ndc = c.xyz / c.w;
    let xy = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * frame.screen_size.xy;
    return vec4<f32>(xy, ndc.z, c.w);
}

fn camera_segment(p0: vec3<f32>, p1: vec3<f32>) -> CameraSegment {
    return clip_segment(frame.camera_view_proj * vec4<f32>(p0, 1.0), frame.camera_view_proj * vec4<f32>(p1, 1.0));
}

// camera_segment of the segment between two clip-space points (a quad's
// side edge: the compute rasterizer clips a wide strand's quad, as the
// wisps', side edge by side edge).
fn clip_segment(c0: vec4<f32>, c1: vec4<f32>) -> CameraSegment {
    var seg: CameraSegment;
    seg.t_start = 0.0;
    seg.t_stop = 1.0;
    seg.kept = c0.z >= 0.0 || c1.z >= 0.0;
    var e0 = c0;
    var e1 = c1;
    if (c0.z < 0.0 && seg.kept) {
        seg.t_start = c0.z / (c0.z - c1.z);
        e0 = mix(c0, c1, seg.t_start);
    } else if (c1.z < 0.0 && seg.kept) {
        seg.t_stop = c0.z / (c0.z - c1.z);
        e1 = mix(c0, c1, seg.t_stop);
    }
    seg.a = project_clip(e0);
    seg.b = project_clip(e1);
    return seg;
}
