// plait::geometry::lod — coverage-preserving strand reduction (Halén &
// Wester 2007 §2.4; Unreal Engine's groom LOD, Auto mode). The formula, its
// assumption and its sources: techniques/geometry/lod/technique.toml.
#define_import_path plait::geometry::lod

#import plait::frame::frame
#import plait::groom_screen::groom_screen_fraction

struct GeometryParams {
    // The groom's height on screen (fraction of the screen height) from
    // which every strand is drawn.
    lod_screen_fraction: f32,
}
@group(1) @binding(45) var<uniform> geometry_params: GeometryParams;

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
