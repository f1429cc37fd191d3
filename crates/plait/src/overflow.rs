//! Bounded buffers that hold everything by default.
//!
//! A technique that appends to a bounded buffer (fragment lists, per-texel
//! depth lists) declares the counter of what it dropped
//! ([`plait_graph::overflow`]); the engine reads every counter after every
//! frame ([`plait_gpu::Overflow`]). The rule the session applies:
//!
//! - a sizing param that still has its technique file's default is only a
//!   starting size: [`prepare_holding`] renders one frame, and when it
//!   dropped anything, raises the param to what the frame needed plus
//!   [`HEADROOM`], rebuilds and renders again; if that still drops, or the
//!   grown buffer does not fit the adapter, the render fails naming the
//!   buffer, the count and the `--set` it would need;
//! - a value the user set (a `--set` flag, or the pipeline file or a file it
//!   extends) is a cap: the render goes on and every frame report says what
//!   was dropped, for the caller to show (`plait render`, `plait ab`).
//!
//! A counter may also count shader invocations that could not finish their
//! work (`incomplete`, [`plait_graph::overflow`]): such a frame fails
//! whoever sized what, since no param restores the missing data.
//!
//! A default whose buffer does not even fit the adapter's storage-binding
//! limit (linked_list's 11 nodes per pixel at 1280x720: 154.7 MiB against
//! 128 MiB) is only a starting size too: [`compile_fitting`] starts it at the
//! largest value that fits, and the sizing frame raises it if the frame needs
//! more. A value the user set is never changed: it fails, naming its flag or
//! line.
//!
//! The sizing frame is thrown away and the pipeline built anew, so the
//! caller's first frame is the renderer's first (histories, `run = "once"`).

use plait_gpu::{FrameReport, Gpu, Overflow};
use plait_graph::{CompileOptions, Errors, ResourceDesc, Schedule};

use crate::session::{Prepared, SceneData, SessionError, build};

/// How much more than a frame asked for a grown buffer holds: the next
/// frame (a moved head, a jittered camera) may ask for a little more.
pub const HEADROOM: f64 = 1.25;

/// Compiles the pipeline again with more `--set` flags than it was
/// compiled with (the grown params).
pub type Recompile<'a> = dyn Fn(&[String]) -> Result<Schedule, Errors> + 'a;

/// Build `schedule` so that every bounded buffer whose size is still its
/// technique's default holds all the first frame appends (see the module
/// docs). `pipeline` is where it came from (its file and library); `recompile` compiles it with
/// extra flags.
pub fn prepare_holding<'g>(
    gpu: &'g Gpu,
    schedule: Schedule,
    recompile: &Recompile<'_>,
    pipeline: &crate::source::PipelineSource,
    scene: &SceneData,
    size: (u32, u32),
) -> Result<Prepared<'g>, SessionError> {
    if !schedule.overflow.iter().any(|c| c.grows) {
        return build(gpu, schedule, pipeline, scene, size);
    }
    let first = sizing_frame(gpu, &schedule, pipeline, scene, size)?;
    check_complete(&first)?;
    let short: Vec<Overflow> = growable_drops(&first).cloned().collect();
    if short.is_empty() {
        return build(gpu, schedule, pipeline, scene, size);
    }
    let grown = grow(gpu, recompile, &short)?;
    let again = sizing_frame(gpu, &grown, pipeline, scene, size)?;
    check_complete(&again)?;
    let still: Vec<Overflow> = growable_drops(&again).cloned().collect();
    if !still.is_empty() {
        return Err(SessionError::Dropped {
            message: "grown to hold what the first frame asked for, the bounded buffers still drop"
                .into(),
            overflow: still,
        });
    }
    build(gpu, grown, pipeline, scene, size)
}

/// Compiles with extra `--set` flags and the given options.
pub type CompileWith<'a> = dyn Fn(&[String], &CompileOptions) -> Result<Schedule, Errors> + 'a;

/// `compile(extra, opts)`; when that fails and a bounded buffer whose size
/// is still its technique's default is larger than `opts` lets a pass bind,
/// the same with that param lowered to the largest value that fits (a
/// starting size the sizing frame raises if the frame needs more; a note
/// says so). Any other failure, or one a user-set size causes, stands.
pub fn compile_fitting(
    compile: &CompileWith<'_>,
    extra: &[String],
    opts: &CompileOptions,
) -> Result<Schedule, Errors> {
    let error = match compile(extra, opts) {
        Ok(schedule) => return Ok(schedule),
        Err(e) => e,
    };
    let unbounded = CompileOptions {
        max_buffer_binding_size: u64::MAX,
        ..opts.clone()
    };
    let Ok(wide) = compile(extra, &unbounded) else {
        return Err(error);
    };
    let (fits, notes) = fitting_values(&wide, opts.max_buffer_binding_size);
    if fits.is_empty() {
        return Err(error);
    }
    let sets: Vec<String> = fits
        .iter()
        .map(|(p, v)| format!("params.{p}={v}"))
        .collect();
    let mut fitted = compile(&[extra, sets.as_slice()].concat(), opts).map_err(|_| error)?;
    // The session chose these values, not the user: they stay growable.
    for c in &mut fitted.overflow {
        if fits.iter().any(|(p, _)| *p == c.param) {
            c.grows = true;
        }
    }
    fitted.notes.extend(notes);
    Ok(fitted)
}

/// For each growable bounded buffer of `schedule` larger than `limit`: its
/// param and the largest value that fits (sizes are linear in it), and a
/// note. Empty when one cannot fit even at 1.
fn fitting_values(schedule: &Schedule, limit: u64) -> (Vec<(String, i64)>, Vec<String>) {
    let mut fits = Vec::new();
    let mut notes = Vec::new();
    for c in schedule.overflow.iter().filter(|c| c.grows && c.value > 0) {
        let Some(ResourceDesc::Buffer { size }) = schedule
            .resources
            .iter()
            .find(|r| r.name == c.of)
            .map(|r| &r.desc)
        else {
            continue;
        };
        if *size <= limit {
            continue;
        }
        let fit = (u128::from(limit) * c.value as u128 / u128::from(*size)) as i64;
        if fit < 1 {
            return (Vec::new(), Vec::new());
        }
        let mib = |b: u64| b as f64 / f64::from(1 << 20);
        notes.push(format!(
            "`{}`: `{}` = {} (its default) makes it {:.1} MiB, more than a pass can bind here ({:.1} MiB); starting from {fit}, raised if a frame needs more",
            c.of,
            c.param,
            c.value,
            mib(*size),
            mib(limit)
        ));
        fits.push((c.param.clone(), fit));
    }
    (fits, notes)
}

/// The checks of the session's frame step ([`crate::frames::Frame`]), which
/// every front end renders through (`plait render`, frames, `ab`, the
/// probes, the viewer), so none forgets one: drops from
/// buffers the user did not size and invocations cut short are an error (a
/// later frame asking for more than the first); drops from a size the user
/// capped are returned, one line each, for the front end to show.
pub fn check_frame(report: &FrameReport) -> Result<Vec<String>, SessionError> {
    check_complete(report)?;
    let short: Vec<Overflow> = growable_drops(report).cloned().collect();
    if short.is_empty() {
        return Ok(dropped_lines(report));
    }
    Err(SessionError::Dropped {
        message: "this frame asked for more than the first, which sized the buffer; set its size with the --set above".into(),
        overflow: short,
    })
}

/// One line per counter of `report` that dropped data, worded as every front
/// end shows a user's cap (for a report that passed [`check_frame`], or a
/// sequence's worst frame per counter, [`crate::frames::median_report`]).
pub fn dropped_lines(report: &FrameReport) -> Vec<String> {
    report
        .dropped()
        .map(|o| {
            format!(
                "dropped: {o} (a size set by --set or the pipeline file is a cap; left unset, it grows to hold everything)"
            )
        })
        .collect()
}

/// A frame whose passes had invocations that could not finish: an error.
fn check_complete(report: &FrameReport) -> Result<(), SessionError> {
    let cut: Vec<Overflow> = report.incomplete().cloned().collect();
    if cut.is_empty() {
        return Ok(());
    }
    Err(SessionError::Dropped {
        message: "the frame lacks what they did not do, and no size restores it; less work \
                  per invocation, or a driver without the limit, avoids it"
            .into(),
        overflow: cut,
    })
}

fn growable_drops(report: &FrameReport) -> impl Iterator<Item = &Overflow> {
    report.dropped().filter(|o| o.grows)
}

/// One frame of `schedule` on a renderer of its own, for its counters.
fn sizing_frame(
    gpu: &Gpu,
    schedule: &Schedule,
    pipeline: &crate::source::PipelineSource,
    scene: &SceneData,
    size: (u32, u32),
) -> Result<FrameReport, SessionError> {
    let probe = build(gpu, schedule.clone(), pipeline, scene, size)?;
    Ok(probe.renderer.render()?)
}

/// The pipeline compiled again with every short buffer's param raised: to
/// what the frame needed plus [`HEADROOM`], or, when that does not fit the
/// adapter, to exactly what it needed.
fn grow(
    gpu: &Gpu,
    recompile: &Recompile<'_>,
    short: &[Overflow],
) -> Result<Schedule, SessionError> {
    let compile = |factor: f64| {
        let extra: Vec<String> = short
            .iter()
            .map(|o| format!("params.{}={}", o.param, grown_value(o, factor)))
            .collect();
        recompile(&extra)
    };
    let schedule = compile(HEADROOM).or_else(|_| compile(1.0));
    let mut schedule = schedule.map_err(|errors| SessionError::Dropped {
        message: format!(
            "the adapter cannot hold that (it binds at most {} bytes as storage): {}",
            gpu.capabilities.max_storage_buffer_binding_size,
            errors
                .0
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; ")
        ),
        overflow: short.to_vec(),
    })?;
    // The session chose these values, not the user: they stay growable, so
    // a later frame that needs more fails instead of dropping quietly.
    for c in &mut schedule.overflow {
        if short.iter().any(|o| o.param == c.param) {
            c.grows = true;
        }
    }
    Ok(schedule)
}

/// The param value that holds `factor` × what `o` needed, and more than it has.
fn grown_value(o: &Overflow, factor: f64) -> u64 {
    let needed = (o.needed as f64 * factor).ceil() as u64;
    needed.div_ceil(o.per).max(o.value.max(0) as u64 + 1)
}

/// `a; b` of several counters' messages.
pub(crate) fn list(overflow: &[Overflow]) -> String {
    overflow
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("; ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn counter(dropped: u64, grows: bool) -> Overflow {
        Overflow {
            pass: "hair_lists".into(),
            counter: "list_counter".into(),
            of: "list_nodes".into(),
            dropped,
            needed: 451_556,
            capacity: 11 * 25_600,
            param: "nodes_per_pixel".into(),
            value: 11,
            per: 25_600,
            value_needed: 18,
            incomplete: 0,
            last_pass: "hair_lists".into(),
            grows,
        }
    }

    fn frame(overflow: Vec<Overflow>) -> FrameReport {
        FrameReport {
            passes: Vec::new(),
            total_gpu_ms: None,
            overflow,
        }
    }

    /// A frame that drops from a buffer the session sized fails, naming the
    /// count and the flag; the user's cap only reports.
    #[test]
    fn only_drops_from_sizes_nobody_chose_fail_a_frame() {
        assert_eq!(
            check_frame(&frame(vec![counter(0, true)])).ok(),
            Some(Vec::new())
        );
        let capped = check_frame(&frame(vec![counter(5, false)])).expect("a cap reports");
        assert_eq!(capped.len(), 1);
        assert!(capped[0].starts_with("dropped: "), "{capped:?}");
        assert!(capped[0].contains("dropped 5"), "{capped:?}");
        let e = check_frame(&frame(vec![counter(5, true)]))
            .expect_err("a grown buffer that drops")
            .to_string();
        assert!(e.contains("dropped 5"), "{e}");
        assert!(e.contains("--set params.nodes_per_pixel=18"), "{e}");
    }

    /// Invocations that could not finish fail the frame, even where the
    /// user chose the sizes, and the message says why.
    #[test]
    fn incomplete_invocations_fail_a_frame() {
        let mut o = counter(0, false);
        o.incomplete = 3;
        let e = check_frame(&frame(vec![o]))
            .expect_err("an incomplete pass")
            .to_string();
        assert!(
            e.contains("3 shader invocations of pass `hair_lists`"),
            "{e}"
        );
        assert!(e.contains("65,535"), "{e}");
    }

    #[test]
    fn grown_sizes_hold_what_was_needed_with_headroom() {
        let o = counter(1, true);
        // 451556 × 1.25 = 564445 nodes over 25600 pixels: 22.05 → 23.
        assert_eq!(grown_value(&o, HEADROOM), 23);
        assert_eq!(grown_value(&o, 1.0), 18);
        // Never below one more than it had.
        let barely = Overflow {
            needed: 11 * 25_600 + 1,
            ..o
        };
        assert_eq!(grown_value(&barely, 1.0), 12);
    }
}
