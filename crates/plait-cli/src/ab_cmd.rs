//! `plait ab`: several pipelines on the same scene(s), timed interleaved,
//! compared with a reference pipeline, written as one report directory
//! (`report.html`, `report.json`, PNGs, schedule SVGs). The run itself is
//! `plait::ab`; this is its flags, its output directory and its printing.
//!
//! `--shard I/N` (or a Slurm array task / Kubernetes Indexed Job index from
//! the environment) writes one shard's share instead; `plait ab merge`
//! joins the shards' directories into the report (`plait::ab::shard`,
//! `plait::ab::merge`).
//!
//! Everything is written into a temporary directory beside `--out` and
//! renamed into place at the end, so a failure or an interrupt never leaves
//! a half-written report; an interrupt removes the temporary directory.

use std::io::IsTerminal as _;
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use plait::ab::{AbError, AbOptions, CameraDistances, Plan, Shard, Step, SweepSpec};
use plait_compare::report::Report;
use plait_gpu::Gpu;

use crate::args::{SetArgs, parse_scene, parse_size};
use crate::table::{Align, Table};

#[derive(Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct AbArgs {
    #[command(subcommand)]
    merge: Option<AbCommand>,
    /// Pipeline files to compare (the variants).
    #[arg(required = true, value_name = "PIPELINE")]
    pipelines: Vec<PathBuf>,
    /// The pipeline every variant's image is compared with (ground truth);
    /// rendered with the `--set` flags but never swept. Or a path-traced
    /// reference (`references/path_traced.toml`): rendered by Mitsuba 3.
    #[arg(long, value_name = "PIPELINE", required = true)]
    reference: Option<PathBuf>,
    /// Where path-traced references are cached (default:
    /// `$CARGO_TARGET_DIR/plait-references`, or `target/plait-references`).
    #[arg(long, value_name = "DIR")]
    cache: Option<PathBuf>,
    /// Scene file (repeatable; default: the built-in scene).
    #[arg(long = "scene", value_name = "FILE", value_parser = parse_scene)]
    scenes: Vec<PathBuf>,
    #[command(flatten)]
    set: SetArgs,
    /// Turn a `--set` key into rows, one per value: `KEY=V1,V2,…`
    /// (e.g. `params.slices=32,64,128`, `techniques.self_shadow=occupancy,exact`).
    /// Given twice, every combination (a grid: the first key's values in
    /// rows, the second's in columns). Applies to the variants, not the reference.
    #[arg(long, value_name = "KEY=V1,V2,...", value_parser = SweepSpec::parse)]
    sweep: Vec<SweepSpec>,
    /// Render every scene (variants and reference alike) with its camera
    /// moved back along its view ray to each of these factors of its
    /// distance to the target (`1,2,4,8`; each > 0, at most 100): error
    /// and frame time against distance.
    #[arg(long, value_name = "F1,F2,...", value_parser = CameraDistances::parse)]
    camera_distance: Option<CameraDistances>,
    /// Render every scene (variants and reference alike) once per colour,
    /// every strand recoloured to it: `NAME=R,G,B`, a linear albedo, each
    /// channel in (0, 1] (repeatable; e.g. `--hair-color
    /// blond=0.85,0.65,0.40 --hair-color black=0.02,0.02,0.02`). The scene is
    /// named `SCENE@NAME`; a path-traced reference maps the colour to an
    /// absorption (Chiang et al. 2016 §4.2).
    #[arg(long, value_name = "NAME=R,G,B", value_parser = plait::ab::HairColor::parse)]
    hair_color: Vec<plait::ab::HairColor>,
    /// Timed frames per variant (after one warm-up frame), interleaved A B C A B C ….
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=10000))]
    repeats: u32,
    /// Time the reference on only the first N repeats (1 to --repeats): a
    /// reference far slower than the variants (supersampled depth peeling)
    /// need not be timed as often; its image is one frame either way.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=10000))]
    reference_repeats: Option<u32>,
    /// Render size, `WIDTHxHEIGHT`.
    #[arg(long, value_parser = parse_size, default_value = "960x720")]
    size: (u32, u32),
    /// Also render frames 0..N of each scene's animation per variant and
    /// report their flicker against the reference's own frame-to-frame
    /// change (image and visibility), with a plot over time.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(2..=10000))]
    frames: Option<u32>,
    /// Frames per second of --frames (frame i is at time i / fps).
    #[arg(long, value_parser = crate::sequence::parse_fps, default_value = "30", requires = "frames")]
    fps: f32,
    /// Render the reference N × N times larger and filter it down to
    /// `--size` (a box filter in linear colour): the ground truth of
    /// anti-aliasing, e.g. strand coverage against `--supersample 4`.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=8))]
    supersample: u32,
    /// Render only shard I of N (0 ≤ I < N) of the run's rows (scene ×
    /// variant, round-robin in the plan's order) with the references they
    /// need, into a partial directory for `plait ab merge`. Without it, a
    /// Slurm array task (SLURM_ARRAY_TASK_ID) or a Kubernetes Indexed Job
    /// (JOB_COMPLETION_INDEX) is a shard of its own.
    #[arg(long, value_name = "I/N", value_parser = Shard::parse)]
    shard: Option<Shard>,
    /// The number of shards of a Kubernetes Indexed Job (its completions),
    /// which the pod is not told; or set PLAIT_SHARD_COUNT.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    shard_count: Option<u32>,
    /// Report directory (replaced if it holds an earlier report).
    #[arg(long, value_name = "DIR", required = true)]
    out: Option<PathBuf>,
}

#[derive(clap::Subcommand)]
enum AbCommand {
    /// Join the directories of `plait ab --shard` runs (every shard of one
    /// plan, each once) into one report.
    Merge(MergeArgs),
}

#[derive(Args)]
struct MergeArgs {
    /// The shards' output directories.
    #[arg(required = true, value_name = "DIR")]
    shards: Vec<PathBuf>,
    /// Report directory (replaced if it holds an earlier report).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Progress: a bar on a terminal, plain lines otherwise.
struct Progress {
    bar: Option<indicatif::ProgressBar>,
}

impl Progress {
    fn new(total: u64) -> Self {
        let bar = std::io::stdout().is_terminal().then(|| {
            let b = indicatif::ProgressBar::new(total);
            if let Ok(style) = indicatif::ProgressStyle::with_template(
                "{bar:40.cyan/blue} {pos}/{len} {elapsed_precise} {msg}",
            ) {
                b.set_style(style);
            }
            b
        });
        Progress { bar }
    }

    fn show(&self, step: Step<'_>) -> std::io::Result<()> {
        match &self.bar {
            Some(b) => {
                b.set_message(step.message.to_string());
                b.set_position(step.done);
            }
            None => outln!("[{}/{}] {}", step.done, step.total, step.message)?,
        }
        Ok(())
    }

    fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

/// `plait ab merge`: the shards joined into one report directory.
fn merge(args: MergeArgs) -> Result<()> {
    let pending = crate::output::PendingDir::create(&args.out, "report.json", "`plait ab` report")?;
    let report = plait::ab::merge(&args.shards, pending.dir())?;
    pending.commit()?;
    print_summary(&report)?;
    outln!("wrote {}", args.out.join("report.html").display())?;
    Ok(())
}

/// `--shard`, else the batch system's index from the environment.
fn shard_of(args: &AbArgs) -> Result<Option<Shard>> {
    if args.shard.is_some() {
        return Ok(args.shard);
    }
    let count = args.shard_count.map(|n| n as usize);
    Shard::from_env(&|name| std::env::var(name).ok(), count)
        .map_err(|e| anyhow::anyhow!("--shard (from the environment): {e}"))
}

pub fn run(args: AbArgs) -> Result<()> {
    if let Some(AbCommand::Merge(merge_args)) = args.merge {
        return merge(merge_args);
    }
    // Required by clap unless `merge` is given.
    let (Some(reference), Some(out)) = (args.reference.clone(), args.out.clone()) else {
        anyhow::bail!("--reference and --out are required");
    };
    let shard = shard_of(&args)?;
    // Everything a user can get wrong fails before the GPU is opened.
    let pending = crate::output::PendingDir::create(&out, "report.json", "`plait ab` report")?;
    // A --size past WebGPU's limits (what the plan checks against) names the
    // flag, not a resource of some technique file.
    let reference_size = (
        args.size.0 * args.supersample.max(1),
        args.size.1 * args.supersample.max(1),
    );
    for (pipeline, size) in args
        .pipelines
        .iter()
        .map(|p| (p, args.size))
        .chain([(&reference, reference_size)])
    {
        let path = plait::session::resolve_pipeline(Some(pipeline));
        if plait::ab::path_traced::is_path_traced(&path) {
            continue;
        }
        plait::size_limit::check_default_limits(&path, &args.set.sets, size)?;
    }
    let plan = Plan::new(AbOptions {
        pipelines: args.pipelines,
        reference,
        scenes: args.scenes,
        sets: args.set.sets,
        sweeps: args.sweep,
        repeats: args.repeats,
        reference_repeats: args.reference_repeats,
        size: args.size,
        supersample: args.supersample,
        command: std::env::args().collect(),
        sequence: args.frames.map(|frames| plait::ab::Sequence {
            frames,
            fps: args.fps,
        }),
        camera_distances: args.camera_distance.map_or_else(Vec::new, |d| d.0),
        hair_colors: args.hair_color,
    })?;
    let mut plan = plan;
    // A path-traced reference is rendered (or found in the cache) before
    // the GPU is opened: Mitsuba missing or failing stops the run here.
    let cache = args.cache.unwrap_or_else(plait::ab::default_cache);
    plait::ab::render_references(&mut plan, &cache, &mut |line| outln!("{line}"))?;
    let gpu = Gpu::new()?;
    // A --size past the adapter's limits names the flag, not a resource of
    // some technique file (as `plait render` does).
    for v in plan.gpu_variants() {
        let size = plan.options.render_size(v.is_reference);
        plait::size_limit::check(&v.pipeline, &v.sets, size, &gpu).map_err(|e| {
            let e = anyhow::Error::from(e);
            if v.is_reference && plan.options.supersample > 1 {
                e.context(format!(
                    "the reference renders at --size × --supersample {}",
                    plan.options.supersample
                ))
            } else {
                e
            }
        })?;
    }
    let progress = Progress::new(shard.map_or_else(|| plan.step_count(), |s| s.step_count(&plan)));
    let mut show = |step: Step<'_>| progress.show(step);
    let report = match shard {
        None => plait::ab::run(&plan, &gpu, pending.dir(), &mut show),
        Some(s) => plait::ab::run_shard(&plan, s, &gpu, pending.dir(), &mut show).map(|(r, _)| r),
    }
    .map_err(|e| match e {
        // A file of the report: name the directory the user gave.
        AbError::Write { .. } | AbError::WriteImage { .. } | AbError::Json(_) => {
            anyhow::Error::new(e).context(format!("--out {}", out.display()))
        }
        e => e.into(),
    })?;
    progress.finish();
    pending.commit()?;
    print_summary(&report)?;
    match shard {
        None => outln!("wrote {}", out.join("report.html").display())?,
        Some(s) => outln!(
            "wrote shard {}/{} to {} (join the shards with `plait ab merge`)",
            s.index,
            s.count,
            out.display()
        )?,
    }
    Ok(())
}

/// One table per scene, the columns of the HTML report's summary that fit a
/// terminal: time, memory, the self-shadowing error |ΔV| where the variants
/// were probed against another provider, and the image metrics.
fn print_summary(report: &Report) -> std::io::Result<()> {
    for scene in &report.scenes {
        outln!("scene {}:", scene.name)?;
        let apart = report.timed_apart(scene);
        if let Some(note) = report.timed_apart_note(scene) {
            outln!("{note}")?;
        }
        // A provider probed against itself says nothing (as in report.md).
        let probed = scene.runs.iter().any(|r| {
            r.visibility
                .as_ref()
                .is_some_and(|v| v.provider != v.reference_provider)
        });
        let mut columns = vec![
            ("variant", Align::Left),
            ("frame ms", Align::Right),
            ("peak MiB", Align::Right),
        ];
        if probed {
            columns.push(("mean / max |ΔV|", Align::Right));
        }
        columns.extend([
            ("RMSE", Align::Right),
            ("PSNR", Align::Right),
            ("SSIM", Align::Right),
            ("FLIP", Align::Right),
        ]);
        let mut table = Table::new(&columns);
        for run in &scene.runs {
            let Some(v) = report.variant(&run.variant) else {
                continue;
            };
            let m = &run.metrics;
            let mut ms = format!("{:.3}", plait_compare::report::cost_ms(&run.timing));
            if let Some(on) = report.timed_on(run).filter(|_| apart) {
                ms = format!("{ms} ({on})");
            }
            let mut cells = vec![
                v.label.clone(),
                ms,
                format!("{:.2}", v.memory.peak_bytes as f64 / 1048576.0),
            ];
            if probed {
                cells.push(run.visibility.as_ref().map_or(String::new(), |d| {
                    format!("{:.4} / {:.2}", d.mean_abs_error, d.max_abs_error)
                }));
            }
            cells.extend([
                format!("{:.5}", m.rmse),
                m.psnr_db
                    .map(|p| format!("{p:.2}"))
                    .unwrap_or_else(|| "inf".into()),
                format!("{:.5}", m.ssim),
                format!("{:.5}", m.flip_mean),
            ]);
            table.row(cells);
        }
        for line in table.lines() {
            outln!("{line}")?;
        }
        outln!("{}", scene.metrics_note())?;
    }
    Ok(())
}
