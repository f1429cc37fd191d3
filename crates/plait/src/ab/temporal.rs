//! The temporal metric of an A/B run (`--frames N --fps F`): every variant
//! renders the scene's animation frame by frame and its visibility provider
//! is probed at every frame; each is measured against the reference's own
//! frame-to-frame change ([`plait_compare::temporal`]).

use plait_compare::temporal::{Temporal, frame_change, image_flicker, visibility_flicker};
use plait_gpu::Gpu;

use super::{AbError, Plan, ScenePlan, Sequence};
use crate::probe::{ProbeGrid, probe_sequence};
use crate::session::Prepared;
use crate::source::PipelineSource;

/// One [`Temporal`] per variant of `plan` on `scene` (visibility where the
/// variant and the reference both have a provider). `step` hears of each
/// variant finished.
pub(super) fn measure(
    plan: &Plan,
    gpu: &Gpu,
    scene: &ScenePlan,
    prepared: &mut [Prepared<'_>],
    sequence: Sequence,
    step: &mut dyn FnMut(String) -> Result<(), AbError>,
) -> Result<Vec<Option<Temporal>>, AbError> {
    let size = plan.options.size;
    let grid = ProbeGrid::through_hair(&scene.data, (16, 16), 48);
    let mut images = Vec::with_capacity(prepared.len());
    let mut probes = Vec::with_capacity(prepared.len());
    for (v, p) in plan.variants.iter().zip(prepared.iter_mut()) {
        let what = |doing: &str| format!("{doing} {} on scene {} (--frames)", v.label, scene.name);
        let render_error = |doing: &str| {
            let what = what(doing);
            move |source| AbError::Render { what, source }
        };
        let mut frames = Vec::with_capacity(sequence.frames as usize);
        // The reference renders at its supersampled size and is filtered
        // down, as its still image is (`--supersample`).
        let render_size = plan.options.render_size(v.is_reference);
        let k = render_size.0 / size.0.max(1);
        for index in 0..sequence.frames {
            p.render_frame(&scene.data, render_size, index, sequence.fps)
                .map_err(render_error("rendering"))?;
            let image = p.image().map_err(|e| AbError::Render {
                what: what("reading the image of"),
                source: e.into(),
            })?;
            frames.push(if k > 1 {
                super::supersample::box_filter(&image, k)
            } else {
                image
            });
        }
        images.push(frames);
        probes.push(
            probe_sequence(
                gpu,
                &PipelineSource::with_library(&v.pipeline, &v.sets, plan.library.clone()),
                &scene.data,
                size,
                &grid,
                sequence.frames,
                sequence.fps,
            )
            .map_err(render_error("probing"))?,
        );
        step(format!(
            "{}: {} frames of {}",
            scene.name, sequence.frames, v.label
        ))?;
    }
    let reference = plan.reference_index();
    let compare_error = |what: String| {
        move |source| AbError::Compare {
            what: format!("{what} on scene {} (--frames)", scene.name),
            source,
        }
    };
    let mut out = Vec::with_capacity(images.len());
    for (i, v) in plan.variants.iter().enumerate() {
        let flicker = image_flicker(&images[i], &images[reference])
            .map_err(compare_error(format!("the sequence of {}", v.label)))?;
        let change = frame_change(&images[i])
            .map_err(compare_error(format!("the sequence of {}", v.label)))?;
        let visibility = match (&probes[i], &probes[reference]) {
            (Some(variant), Some(exact)) => {
                Some(visibility_flicker(&variant.frames, &exact.frames))
            }
            _ => None,
        };
        out.push(Some(Temporal::new(
            sequence.fps as f64,
            flicker,
            &change,
            visibility,
        )));
    }
    Ok(out)
}
