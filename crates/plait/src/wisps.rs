//! `geometry = "wisps"` at load (Halén & Wester, "Real-Time Hair Simulation
//! and Visualization for Games", M.Sc. thesis, Lund University, 2007,
//! §2.2–2.4): the wisps' triangle strips are built on the CPU from the
//! scene's strands and guides ([`plait_hair::wisps`]) and every hair draw
//! draws them instead of the strands' lines. What was built is named in a
//! note: wisps stand for strands on purpose, never silently.

use plait_graph::{Schedule, Value};
use plait_hair::wisps::{WispGuides, WispMesh, build_wisps};

use crate::session::SceneData;

/// Whether the schedule draws hair as wisps.
pub fn chosen(schedule: &Schedule) -> bool {
    schedule
        .techniques
        .iter()
        .any(|t| t.point == "geometry" && t.name == "wisps")
}

/// The wisps of `scene` as the schedule's params ask (`wisp_count`, range
/// checked at load with the param), and the note naming them; `None` when
/// the schedule does not draw wisps.
pub fn build(schedule: &Schedule, scene: &SceneData) -> Option<(WispMesh, String)> {
    if !chosen(schedule) {
        return None;
    }
    let count = match schedule.params.get("wisp_count") {
        Some(Value::Int(n)) => (*n).max(0) as usize,
        _ => plait_passes::geometry::WISP_COUNT_DEFAULT as usize,
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
