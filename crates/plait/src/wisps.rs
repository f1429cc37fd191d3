//! A technique asking for the wisp mesh (`engine = ["wisp_mesh"]`, the
//! geometry technique `wisps`) at load (Halén & Wester, "Real-Time Hair Simulation
//! and Visualization for Games", M.Sc. thesis, Lund University, 2007,
//! §2.2–2.4): the wisps' triangle strips are built on the CPU from the
//! scene's strands and guides ([`plait_hair::wisps`]) and every hair draw
//! draws them instead of the strands' lines. What was built is named in a
//! note: wisps stand for strands on purpose, never silently.

use plait_gpu::PassLibrary;
use plait_graph::techniques::technique_keys::WISP_MESH;
use plait_graph::{Schedule, Value};
use plait_hair::wisps::{WispGuides, WispMesh, build_wisps};

use crate::session::SceneData;

/// Whether the schedule draws hair as wisps: a chosen technique asks the
/// engine for the wisp mesh (`[technique] engine = ["wisp_mesh"]`).
pub fn chosen(schedule: &Schedule) -> bool {
    schedule
        .techniques
        .iter()
        .any(|t| t.engine.iter().any(|e| e == WISP_MESH))
}

/// The wisps of `scene` as the schedule's params ask (`wisp_count`, range
/// checked at load with the param; the geometry point's default in
/// `library` when the pipeline leaves it), and the note naming them; `None`
/// when the schedule does not draw wisps.
pub fn build(
    schedule: &Schedule,
    library: &PassLibrary,
    scene: &SceneData,
) -> Option<(WispMesh, String)> {
    if !chosen(schedule) {
        return None;
    }
    let count = match schedule.params.get("wisp_count") {
        Some(Value::Int(n)) => (*n).max(0) as usize,
        _ => match plait_passes::points::default(library, "geometry", "wisp_count") {
            Some(Value::Int(n)) => n.max(0) as usize,
            _ => 0,
        },
    };
    let (mesh, followed) = build_wisps(&scene.strands, &scene.guides, count);
    let what = match followed {
        WispGuides::Guides => format!(
            "each along its nearest of the groom's {} guide strands",
            scene.guides.strands.strand_count()
        ),
        WispGuides::Strands => {
            "the groom has no guide strands: each follows the strand rooted at its centre".into()
        }
    };
    let short = if mesh.wisp_count < count {
        format!(
            " (wisp_count = {count} asked; the groom's {} strand roots hold no more apart)",
            scene.strands.strand_count()
        )
    } else {
        String::new()
    };
    let note = format!(
        "geometry wisps: {} wisps{short} for {} strands, centres at least {:.4} apart (relaxation dart throwing), {what}",
        mesh.wisp_count,
        scene.strands.strand_count(),
        mesh.radius,
    );
    Some((mesh, note))
}

/// How many of `count` wisps the wisps' level of detail draws at `frame`'s
/// camera for `wisp_lod_screen_fraction` = `fraction`, computed in f32 the
/// way `wisp_lod` in `techniques/geometry/wisps/geometry.wgsl` does: the
/// first ceil(k · count) of the acceptance order, k = the groom's screen
/// fraction / `fraction` in [1 / count, 1]; every wisp when `fraction` is 0.
/// Each drawn wisp is count / kept times as wide.
pub fn kept_wisps(frame: &plait_gpu::frame::FrameUniforms, fraction: f32, count: usize) -> usize {
    let n = count.max(1) as f32;
    if fraction <= 0.0 {
        return count;
    }
    let k = (crate::strand_lod::groom_screen_fraction(frame) / fraction).clamp(1.0 / n, 1.0);
    if k >= 1.0 {
        return count;
    }
    ((k * n).ceil().clamp(1.0, n) as usize).min(count)
}

/// The schedule's `wisp_lod_screen_fraction` (its point's default in
/// `library` when the pipeline leaves it), read once when the wisps are
/// built, not per frame.
pub fn lod_fraction(schedule: &Schedule, library: &PassLibrary) -> f32 {
    match schedule.params.get("wisp_lod_screen_fraction") {
        Some(Value::Float(f)) => *f as f32,
        Some(Value::Int(i)) => *i as f32,
        _ => match plait_passes::points::default(library, "geometry", "wisp_lod_screen_fraction") {
            Some(Value::Float(f)) => f as f32,
            _ => 0.0,
        },
    }
}

/// "geometry wisps: m of n wisps drawn …" when their level of detail
/// (`fraction`, [`lod_fraction`]) leaves some of the `count` built out at
/// this frame's camera: wisps are left out on purpose, never silently.
pub fn lod_note(
    frame: &plait_gpu::frame::FrameUniforms,
    fraction: f32,
    count: usize,
) -> Option<String> {
    let kept = kept_wisps(frame, fraction, count);
    if kept >= count {
        return None;
    }
    Some(format!(
        "geometry wisps: {kept} of {count} wisps drawn from the camera, each {:.2}× as wide (the groom spans {:.3} of the screen's height; every wisp from wisp_lod_screen_fraction = {fraction})",
        count as f32 / kept as f32,
        crate::strand_lod::groom_screen_fraction(frame)
    ))
}
