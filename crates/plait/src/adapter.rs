//! Whether a pipeline runs on the opened adapter, decided before any GPU
//! resource exists (`plait render`, `view`, `ab`, `check --adapter`), and,
//! when it does not, the techniques that would: tried, never guessed.

use std::path::Path;

use plait_gpu::support::{Problem, check_schedule};
use plait_gpu::{Gpu, GpuError, PassLibrary};
use plait_graph::{Pipeline, Schedule};

use crate::session::{SessionError, check_pipeline, gpu_options};
use crate::source::PipelineSource;

/// Load `pipeline` with `sets` and [`compile_on`] `gpu` with `library`.
pub fn check_on_adapter(
    gpu: &Gpu,
    library: &std::sync::Arc<PassLibrary>,
    pipeline: &Path,
    sets: &[String],
    size: (u32, u32),
) -> Result<Schedule, SessionError> {
    let source = PipelineSource::with_library(pipeline, sets, library.clone());
    compile_on(gpu, &source.load(&[])?, &source, size)
}

/// The one compile of a render: `loaded` (read from `source`) compiled with
/// `gpu`'s capabilities and limits as inputs, so the schedule is final, then
/// checked against what the adapter supports (see [`check_schedule_on`]).
/// A compile that fails only because of the render size names `--size`
/// ([`crate::size_limit`]).
pub fn compile_on(
    gpu: &Gpu,
    loaded: &Pipeline,
    source: &PipelineSource,
    size: (u32, u32),
) -> Result<Schedule, SessionError> {
    // The loaded pipeline as is; with extra flags (a default lowered to
    // fit the adapter), loaded again from its source.
    let compile = |extra: &[String], opts: &plait_graph::CompileOptions| {
        if extra.is_empty() {
            check_pipeline(&source.library, loaded, opts)
        } else {
            source.compile(extra, opts)
        }
    };
    let schedule = match crate::overflow::compile_fitting(&compile, &[], &gpu_options(gpu, size)) {
        Ok(schedule) => schedule,
        Err(errors) => {
            // Resources sized from the screen past the limits: the flag's fault.
            crate::size_limit::explain_on(loaded, source, size, gpu)?;
            return Err(errors.into());
        }
    };
    check_schedule_on(gpu, &schedule, source, size)?;
    Ok(schedule)
}

/// Every problem of `schedule` on `gpu`'s adapter, with `--set
/// techniques.POINT=NAME` flags that make `source` run there when choosing
/// other techniques for the points at fault does.
pub fn check_schedule_on(
    gpu: &Gpu,
    schedule: &Schedule,
    source: &PipelineSource,
    size: (u32, u32),
) -> Result<(), SessionError> {
    let library = &source.library;
    let Err(mut unsupported) = check_schedule(schedule, library, &gpu.support, &gpu.capabilities)
    else {
        return Ok(());
    };
    let trial = Trial {
        gpu,
        library,
        source,
        size,
    };
    unsupported.suggestion = trial.suggest(schedule, &unsupported.problems);
    Err(GpuError::Unsupported(unsupported).into())
}

struct Trial<'a> {
    gpu: &'a Gpu,
    library: &'a PassLibrary,
    source: &'a PipelineSource,
    size: (u32, u32),
}

impl Trial<'_> {
    /// The problems of the pipeline with `extra` sets, `None` if it does not compile.
    fn problems(&self, extra: &[String]) -> Option<(Schedule, Vec<Problem>)> {
        let schedule = self
            .source
            .compile(extra, &gpu_options(self.gpu, self.size))
            .ok()?;
        let problems = match check_schedule(
            &schedule,
            self.library,
            &self.gpu.support,
            &self.gpu.capabilities,
        ) {
            Ok(()) => Vec::new(),
            Err(u) => u.problems,
        };
        Some((schedule, problems))
    }

    /// For each choice point at fault, in order, the first other technique
    /// that clears its problems (on top of those already chosen); the whole
    /// set only if the pipeline then has no problem left. A problem outside
    /// every technique (a pass of the pipeline's own) has no such fix.
    fn suggest(&self, schedule: &Schedule, problems: &[Problem]) -> Option<Vec<String>> {
        let roots = plait_graph::techniques::TechniqueRoots::for_pipeline(&self.source.path);
        let mut points: Vec<String> = Vec::new();
        for p in problems {
            let point = point_of(p, schedule)?;
            if !points.contains(&point) {
                points.push(point);
            }
        }
        let mut chosen: Vec<String> = Vec::new();
        for point in points {
            let current = schedule.techniques.iter().find(|t| t.point == point)?;
            let fix = roots
                .choices(&point)
                .into_iter()
                .filter(|name| *name != current.name)
                .map(|name| format!("techniques.{point}={name}"))
                .find(|set| {
                    let mut extra = chosen.clone();
                    extra.push(set.clone());
                    self.problems(&extra).is_some_and(|(s, left)| {
                        !left
                            .iter()
                            .any(|p| point_of(p, &s).is_none_or(|q| q == point))
                    })
                })?;
            chosen.push(fix);
        }
        let (_, left) = self.problems(&chosen)?;
        left.is_empty().then_some(chosen)
    }
}

/// The choice point whose technique a problem belongs to: its pass's, or for
/// a resource's own problem, that of a pass binding the resource.
fn point_of(p: &Problem, schedule: &Schedule) -> Option<String> {
    let technique = match (&p.technique, &p.pass, &p.resource) {
        (Some(t), _, _) => Some(t.clone()),
        (None, None, Some(resource)) => schedule
            .passes
            .iter()
            .find(|pass| {
                pass.reads.iter().chain(&pass.writes).any(|b| {
                    b.resolved(&schedule.resources)
                        .is_some_and(|r| r.name == *resource)
                })
            })
            .and_then(|pass| pass.technique.clone()),
        _ => None,
    }?;
    technique.split('/').next().map(str::to_owned)
}
