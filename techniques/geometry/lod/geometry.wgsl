// plait::geometry::lod — coverage-preserving strand reduction (Halén &
// Wester 2007 §2.4; Unreal Engine's groom LOD, Auto mode). The formula, its
// assumption and its sources: techniques/geometry/lod/technique.toml.
#define_import_path plait::geometry::lod

#import plait::frame::frame

struct GeometryParams {
    // The groom's height on screen (fraction of the screen height) from
    // which every strand is drawn.
    lod_screen_fraction: f32,
}
@group(1) @binding(45) var<uniform> geometry_params: GeometryParams;

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

// The fraction of the groom's strands drawn.
fn kept_fraction() -> f32 {
    let strands = max(frame.hair_stats.y, 1.0);
    let s = groom_screen_fraction();
    return clamp(s / geometry_params.lod_screen_fraction, 1.0 / strands, 1.0);
}

fn strand_weight(strand_id: u32) -> f32 {
#ifdef LIGHT_VIEW
    // The light's frustum is fitted to the hair: it sees the groom whole.
    return 1.0;
#else
    let k = kept_fraction();
    if (k >= 1.0) {
        return 1.0;
    }
    // frac(id / φ) in 24 bits (Fibonacci hashing): a fixed, evenly spread order.
    let rank = (strand_id * 0x9E3779B9u) >> 8u;
    if (rank >= u32(k * 16777216.0)) {
        return 0.0;
    }
    return 1.0 / k;
#endif
}
