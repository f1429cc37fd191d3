//! What `geometry = "lod"` draws, computed on the CPU the way its WGSL does
//! (`techniques/geometry/lod/geometry.wgsl`, in f32): `plait render` names
//! the kept count in a note — strands are left out on purpose, and never
//! silently — and the tests build the same subset to compare against.

use glam::{Mat4, Vec4};
use plait_gpu::frame::FrameUniforms;
use plait_graph::techniques::technique_keys::STRAND_LOD_NOTE;
use plait_graph::{Schedule, Value};

/// The groom's height on screen as a fraction of the screen's height
/// (`groom_screen_fraction`): its bounding sphere projected by the camera.
pub fn groom_screen_fraction(frame: &FrameUniforms) -> f32 {
    let sphere = Vec4::from(frame.hair_sphere);
    let (centre, radius) = (sphere.truncate(), sphere.w);
    let view = Mat4::from_cols_array_2d(&frame.camera_view);
    let view_proj = Mat4::from_cols_array_2d(&frame.camera_view_proj);
    let up = view.row(1).truncate();
    let a = view_proj * centre.extend(1.0);
    let b = view_proj * (centre + up * radius).extend(1.0);
    if a.w <= radius || b.w <= 0.0 {
        return 1e9;
    }
    (b.y / b.w - a.y / a.w).abs()
}

/// The fraction of the strands drawn (`kept_fraction`).
pub fn kept_fraction(frame: &FrameUniforms, lod_screen_fraction: f32) -> f32 {
    let strands = frame.hair_stats[1].max(1.0);
    (groom_screen_fraction(frame) / lod_screen_fraction).clamp(1.0 / strands, 1.0)
}

/// Whether strand `id` is drawn at kept fraction `k` (`strand_weight`:
/// frac(id / φ) in 24 bits below k).
pub fn kept(id: u32, k: f32) -> bool {
    k >= 1.0 || (id.wrapping_mul(0x9E37_79B9) >> 8) < (k * 16_777_216.0) as u32
}

/// "geometry lod: N of M strands drawn …" when a chosen technique asks for
/// the note (`[technique] engine = ["strand_lod_note"]`) and strands are left
/// out at this frame's camera.
pub fn note(schedule: &Schedule, frame: &FrameUniforms) -> Option<String> {
    schedule
        .techniques
        .iter()
        .find(|t| t.engine.iter().any(|e| e == STRAND_LOD_NOTE))?;
    let fraction = match schedule.params.get("lod_screen_fraction")? {
        Value::Float(f) => *f as f32,
        Value::Int(i) => *i as f32,
        _ => return None,
    };
    let k = kept_fraction(frame, fraction);
    if k >= 1.0 {
        return None;
    }
    let total = frame.hair_stats[1] as u32;
    let drawn = (0..total).filter(|&i| kept(i, k)).count();
    Some(format!(
        "geometry lod: {drawn} of {total} strands drawn from the camera, each for {:.2} (the groom spans {:.3} of the screen's height; every strand from lod_screen_fraction = {fraction})",
        1.0 / k,
        groom_screen_fraction(frame)
    ))
}
