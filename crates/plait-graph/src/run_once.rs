//! `run = "once"`: precompute passes (lookup tables, irradiance maps,
//! per-vertex ambient occlusion) that an executor records on its first frame
//! only. What they write must survive every later frame, so it is kept out of
//! the memory plan's sharing and no every-frame pass may write it too.
//!
//! "Recomputed when its params change" needs nothing here: a changed param or
//! input compiles a new schedule, and a new executor runs its first frame.

use crate::error::{Error, ErrorKind};
use crate::load::Pipeline;
use crate::schedule::{ResolvedResource, ScheduledPass};

/// A resource written by a `run = "once"` pass is written by that pass alone:
/// a second writer would overwrite the kept contents every frame (or clear
/// them, as the first writer of a frame does).
pub(crate) fn check_writers(
    pipeline: &Pipeline,
    passes: &[ScheduledPass],
    errors: &mut Vec<Error>,
) {
    for once in passes.iter().filter(|p| p.run_once) {
        for w in &once.writes {
            let Some(resource) = pipeline.resources.get_index_of(&w.resource_name) else {
                continue;
            };
            for other in passes.iter().filter(|p| p.name != once.name) {
                if let Some(b) = other
                    .writes
                    .iter()
                    .find(|b| pipeline.resources.get_index_of(&b.resource_name) == Some(resource))
                {
                    errors.push(Error::new(
                        b.location.clone(),
                        ErrorKind::Schema(format!(
                            "pass `{}` writes `{}`, which `{}` computes once (`run = \"once\"`) and keeps \
                             across frames; only that pass may write it",
                            other.name, w.resource_name, once.name
                        )),
                    ));
                }
            }
        }
    }
}

/// Mark what `run = "once"` passes write as kept: alive over the whole
/// schedule, so the greedy sharing of the memory plan never hands its
/// allocation to another resource.
pub(crate) fn keep_across_frames(passes: &[ScheduledPass], resources: &mut [ResolvedResource]) {
    let end = passes.len().saturating_sub(1);
    for pass in passes.iter().filter(|p| p.run_once) {
        for w in &pass.writes {
            if let Some(r) = w.resource.and_then(|id| resources.get_mut(id.index())) {
                r.kept = true;
                r.first_use = 0;
                r.last_use = end;
            }
        }
    }
}
