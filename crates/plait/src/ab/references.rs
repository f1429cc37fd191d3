//! Rendering the path-traced reference of a run (`renderer` Mitsuba or
//! plait) before its GPU work, and how the report shows it: its row, its
//! "frame time".

use std::path::Path;

use super::Plan;
use super::path_traced::{display_exposure, sets_not_followed};

/// Render (or find in `cache`) the path-traced reference of every scene of
/// `plan`, before the run's GPU work (`renderer = "plait"`: on a device of
/// its own, never cached); `progress` hears a line per reference. Does
/// nothing for a pipeline reference.
pub fn render_references(
    plan: &mut Plan,
    cache: &Path,
    progress: &mut dyn FnMut(&str) -> std::io::Result<()>,
) -> Result<(), super::AbError> {
    let Some(spec) = plan.path_traced.clone() else {
        return Ok(());
    };
    let exposure = display_exposure(&plan.options.sets)?;
    let ignored = sets_not_followed(&plan.options.sets);
    if !ignored.is_empty() {
        progress(&format!(
            "note: the path-traced reference does not follow --set {} (it renders the scene and its fibre; it follows params.exposure and params.chiang_*)",
            ignored.join(", --set ")
        ))
        .map_err(super::AbError::Progress)?;
    }
    let size = plan.options.render_size(true);
    let k = plan.options.supersample.max(1);
    // plait's own path tracer renders on a device of its own, closed
    // before the run opens the one the variants share.
    let gpu = match spec.renderer.as_str() {
        "plait" => Some(plait_gpu::Gpu::new().map_err(|e| super::AbError::Render {
            what: "opening the GPU for the path-traced reference (renderer \"plait\")".into(),
            source: e.into(),
        })?),
        _ => None,
    };
    let mut rendered = Vec::new();
    for scene in &plan.scenes {
        let r = match &gpu {
            Some(gpu) => {
                progress(&format!(
                    "{}: path-traced reference: plait's path tracer, 2 × {} spp",
                    scene.name, spec.spp
                ))
                .map_err(super::AbError::Progress)?;
                super::plait_reference::reference(&spec, scene, (size, k), gpu)?
            }
            None => super::cache::reference(&spec, scene, (size, k), cache, progress)?,
        };
        let linear = r.mean;
        let display = super::agx::display(&linear, exposure);
        rendered.push(Rendered {
            linear,
            display,
            noise_rmse: r.noise_rmse,
            seconds: r.seconds,
        });
    }
    let notes: Vec<String> = plan
        .scenes
        .iter()
        .zip(&rendered)
        .map(|(s, r)| format!("noise RMSE {:.4} on {}", r.noise_rmse, s.name))
        .collect();
    let index = plan.reference_index();
    plan.variants[index].label = format!(
        "{} (reference: {}, {})",
        stem(&spec.file),
        spec.describe(),
        notes.join(", ")
    );
    plan.path_traced_images = rendered;
    Ok(())
}

/// One scene's path-traced reference, at the run's `--size`.
#[derive(Clone, Debug)]
pub struct Rendered {
    pub linear: image::Rgba32FImage,
    /// Through the default display (AgX at the run's exposure).
    pub display: image::RgbaImage,
    /// Estimated RMSE of `linear` against the converged image.
    pub noise_rmse: f64,
    /// The renderer's wall time for both seeds (Mitsuba's as recorded when
    /// first rendered; plait's including building its pipeline).
    pub seconds: f64,
}

/// The report's entry for a path-traced reference: no schedule, no GPU
/// memory; its "schedule" names the renderer.
pub(super) fn report_variant(plan: &Plan) -> Option<plait_compare::report::Variant> {
    let spec = plan.path_traced.as_ref()?;
    let v = &plan.variants[plan.reference_index()];
    Some(plait_compare::report::Variant {
        id: v.id.clone(),
        label: v.label.clone(),
        pipeline: spec.file.display().to_string(),
        is_reference: true,
        sweep_values: v.sweep_values.clone(),
        sets: v.sets.clone(),
        schedule_name: match spec.renderer.as_str() {
            "plait" => format!("plait {}", super::plait_reference::pipeline().display()),
            _ => format!("mitsuba {}", super::cache::mitsuba_version()),
        },
        memory: plait_compare::report::Memory {
            peak_bytes: 0,
            unpooled_bytes: 0,
            allocations: 0,
            resources: Vec::new(),
        },
        graph_svg: None,
    })
}

/// A path-traced reference's "frame time": its renderer's wall time for the
/// scene's reference (both seeds, when it was rendered; Mitsuba's cached
/// runs report the time of the run that rendered it), in ms, one sample.
pub(super) fn timing(plan: &Plan, scene: usize) -> plait_compare::report::Timing {
    let ms = plan
        .path_traced_images
        .get(scene)
        .map_or(0.0, |r| r.seconds * 1e3);
    plait_compare::report::Timing {
        total_gpu_ms: None,
        wall_ms: plait_compare::Stats {
            median: ms,
            min: ms,
            max: ms,
            q1: ms,
            q3: ms,
            samples: vec![ms],
        },
        passes: Vec::new(),
    }
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "path_traced".into())
}
