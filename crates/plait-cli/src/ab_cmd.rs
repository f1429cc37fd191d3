//! `plait ab`: several pipelines on the same scene(s), timed interleaved,
//! compared with a reference pipeline, written as one report directory
//! (`report.html`, `report.json`, PNGs, schedule SVGs).
//!
//! Everything is written into a temporary directory beside `--out` and
//! renamed into place at the end, so a failure or an interrupt never leaves
//! a half-written report (at worst a hidden `.plait-ab-*` directory).

use std::io::IsTerminal as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;
use plait::probe::{ProbeGrid, Probed, probe_visibility, visibility_error};
use plait::session::{Prepared, SceneData, compile_checked, prepare, resolve_pipeline};
use plait_compare::report::{
    Adapter, FileHash, Memory, PassStats, PipelineProvenance, Provenance, Report, ResourceMemory,
    Run, SCHEMA, SceneResult, Sweep, Timing, Variant,
};
use plait_compare::{Stats, heatmap};
use plait_gpu::Gpu;
use plait_graph::{CompileOptions, Schedule};
use sha2::Digest as _;

use crate::pipeline_cmd::SetArgs;
use crate::render_cmd::parse_size;

#[derive(Args)]
pub struct AbArgs {
    /// Pipeline files to compare (the variants).
    #[arg(required = true, value_name = "PIPELINE")]
    pipelines: Vec<PathBuf>,
    /// The pipeline every variant's image is compared with (ground truth);
    /// rendered with the `--set` flags but never swept.
    #[arg(long, value_name = "PIPELINE")]
    reference: PathBuf,
    /// Scene file (repeatable; default: the built-in scene).
    #[arg(long = "scene", value_name = "FILE")]
    scenes: Vec<PathBuf>,
    #[command(flatten)]
    set: SetArgs,
    /// Turn a `--set` key into rows, one per value: `KEY=V1,V2,…`
    /// (e.g. `params.slices=32,64,128`). Applies to the variants, not the reference.
    #[arg(long, value_name = "KEY=V1,V2,...", value_parser = parse_sweep)]
    sweep: Option<SweepArg>,
    /// Timed frames per variant (after one warm-up frame), interleaved A B C A B C ….
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=10000))]
    repeats: u32,
    /// Render size, `WIDTHxHEIGHT`.
    #[arg(long, value_parser = parse_size, default_value = "960x720")]
    size: (u32, u32),
    /// Report directory (replaced if it holds an earlier report).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

#[derive(Clone, Debug)]
pub struct SweepArg {
    key: String,
    values: Vec<String>,
}

/// `--sweep params.slices=32,64,128`.
fn parse_sweep(text: &str) -> Result<SweepArg, String> {
    let (key, values) = text
        .split_once('=')
        .ok_or_else(|| format!("`{text}` is not KEY=V1,V2,… (e.g. params.slices=32,64,128)"))?;
    let key = key.trim();
    if key.is_empty() || key.contains(char::is_whitespace) {
        return Err(format!(
            "`{text}`: the key before `=` must be a --set key such as params.slices"
        ));
    }
    let values: Vec<String> = values.split(',').map(|v| v.trim().to_string()).collect();
    if values.iter().any(String::is_empty) {
        return Err(format!("`{text}`: empty value in the comma-separated list"));
    }
    let mut seen = std::collections::HashSet::new();
    if let Some(dup) = values.iter().find(|v| !seen.insert(v.as_str())) {
        return Err(format!("`{text}`: value `{dup}` is listed twice"));
    }
    Ok(SweepArg {
        key: key.to_string(),
        values,
    })
}

/// One pipeline at one sweep value (or the reference), before any GPU work.
struct VariantPlan {
    id: String,
    label: String,
    pipeline: PathBuf,
    sets: Vec<String>,
    sweep_value: Option<String>,
    is_reference: bool,
}

/// Keep names usable as file names.
fn sanitize(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_' | '@' | '=') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn unique(id: String, taken: &mut Vec<String>) -> String {
    let mut candidate = id.clone();
    let mut n = 2;
    while taken.contains(&candidate) {
        candidate = format!("{id}-{n}");
        n += 1;
    }
    taken.push(candidate.clone());
    candidate
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "pipeline".into())
}

/// Where the report goes: a temporary directory beside `out`, renamed at the end.
struct PendingDir {
    out: PathBuf,
    parent: PathBuf,
    temp: tempfile::TempDir,
}

impl PendingDir {
    fn create(out: &Path) -> Result<Self> {
        if out.exists() && !out.is_dir() {
            bail!("--out {}: exists and is not a directory", out.display());
        }
        if out.is_dir() {
            let empty = std::fs::read_dir(out)
                .map(|mut d| d.next().is_none())
                .unwrap_or(false);
            if !empty && !out.join("report.json").exists() {
                bail!(
                    "--out {}: exists and is not an earlier `plait ab` report (no report.json); refusing to replace it",
                    out.display()
                );
            }
        }
        let parent = match out.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&parent).with_context(|| {
            format!(
                "--out {}: cannot create {}",
                out.display(),
                parent.display()
            )
        })?;
        let temp = tempfile::Builder::new()
            .prefix(".plait-ab-")
            .tempdir_in(&parent)
            .with_context(|| {
                format!(
                    "--out {}: cannot write in {}",
                    out.display(),
                    parent.display()
                )
            })?;
        Ok(PendingDir {
            out: out.to_path_buf(),
            parent,
            temp,
        })
    }

    fn path(&self, name: &str) -> PathBuf {
        self.temp.path().join(name)
    }

    fn write(&self, name: &str, bytes: &[u8]) -> Result<()> {
        std::fs::write(self.path(name), bytes)
            .with_context(|| format!("writing {name} for --out {}", self.out.display()))
    }

    fn write_png(&self, name: &str, img: impl Into<image::DynamicImage>) -> Result<()> {
        let img: image::DynamicImage = img.into();
        img.save_with_format(self.path(name), image::ImageFormat::Png)
            .with_context(|| format!("writing {name} for --out {}", self.out.display()))
    }

    /// Move the finished report into place (replacing an earlier one).
    fn commit(self) -> Result<()> {
        let temp = self.temp.keep();
        crate::output::readable_by_all(&temp, 0o755);
        for entry in std::fs::read_dir(&temp).into_iter().flatten().flatten() {
            crate::output::readable_by_all(&entry.path(), 0o644);
        }
        let mut old = None;
        if self.out.exists() {
            let aside = tempfile::Builder::new()
                .prefix(".plait-ab-old-")
                .tempdir_in(&self.parent)?
                .keep();
            std::fs::remove_dir(&aside).ok();
            std::fs::rename(&self.out, &aside).with_context(|| {
                format!(
                    "--out {}: cannot move the earlier report aside",
                    self.out.display()
                )
            })?;
            old = Some(aside);
        }
        std::fs::rename(&temp, &self.out).with_context(|| {
            format!(
                "--out {}: cannot move the report into place",
                self.out.display()
            )
        })?;
        if let Some(old) = old {
            std::fs::remove_dir_all(old).ok();
        }
        Ok(())
    }
}

/// Progress: a bar on a terminal, plain lines otherwise.
struct Progress {
    bar: Option<indicatif::ProgressBar>,
    total: u64,
    done: u64,
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
        Progress {
            bar,
            total,
            done: 0,
        }
    }

    fn step(&mut self, message: String) -> std::io::Result<()> {
        self.done += 1;
        match &self.bar {
            Some(b) => {
                b.set_message(message);
                b.inc(1);
            }
            None => outln!("[{}/{}] {message}", self.done, self.total)?,
        }
        Ok(())
    }

    fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

fn sha256_hex(bytes: &[u8]) -> String {
    sha2::Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

fn hash_file(path: &Path) -> Result<FileHash> {
    let bytes =
        std::fs::read(path).with_context(|| format!("reading {} to hash it", path.display()))?;
    Ok(FileHash {
        path: path.display().to_string(),
        sha256: sha256_hex(&bytes),
        bytes: bytes.len() as u64,
    })
}

fn hash_text(name: &str, text: &str) -> FileHash {
    FileHash {
        path: name.to_string(),
        sha256: sha256_hex(text.as_bytes()),
        bytes: text.len() as u64,
    }
}

/// Quote an argument for a POSIX shell when it needs it.
fn shell_quote(arg: &str) -> String {
    if !arg.is_empty()
        && arg
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=:,@+%".contains(c))
    {
        arg.to_string()
    } else {
        format!("'{}'", arg.replace('\'', "'\\''"))
    }
}

fn memory(s: &Schedule) -> Memory {
    Memory {
        peak_bytes: s.memory.peak_bytes,
        unpooled_bytes: s.memory.unpooled_bytes,
        allocations: s.physical.len(),
        resources: s
            .resources
            .iter()
            .enumerate()
            .map(|(id, r)| ResourceMemory {
                name: r.name.clone(),
                desc: r.desc.label(),
                bytes: r.desc.bytes(),
                shares_memory_with: s
                    .shares_memory_with(id)
                    .into_iter()
                    .map(str::to_string)
                    .collect(),
            })
            .collect(),
    }
}

fn pipeline_provenance(path: &Path, s: &Schedule) -> Result<PipelineProvenance> {
    let files = s
        .files
        .iter()
        .map(|f| hash_file(f))
        .collect::<Result<Vec<_>>>()?;
    let mut shader_paths: Vec<&PathBuf> = s
        .passes
        .iter()
        .chain(s.culled.iter().map(|c| &c.pass))
        .filter_map(|p| p.shader.as_ref())
        .collect();
    shader_paths.sort();
    shader_paths.dedup();
    let shaders = shader_paths
        .into_iter()
        .map(|p| hash_file(p))
        .collect::<Result<Vec<_>>>()?;
    Ok(PipelineProvenance {
        path: path.display().to_string(),
        files,
        shaders,
    })
}

/// A library file as the run uses it: the copy on the search path when there
/// is one (`PLAIT_PATH`, the checkout), else the built-in text.
fn as_used(name: &'static str, text: &'static str) -> (String, String) {
    match plait_gpu::shader::library_source(name, text) {
        Ok((path, used)) => (path.display().to_string(), used.into_owned()),
        Err(_) => (name.to_owned(), text.to_owned()),
    }
}

fn builtin_shaders() -> Vec<FileHash> {
    let mut out: Vec<FileHash> = plait_gpu::shader::LIBRARY_MODULES
        .iter()
        .map(|(name, text)| {
            let (path, used) = as_used(name, text);
            hash_text(&path, &used)
        })
        .collect();
    // Several pass types share one WGSL file (hair_shade.wgsl serves six):
    // list each file once, with the pass types that use it.
    let library = plait_passes::library();
    let mut files: Vec<(String, String, Vec<&str>)> = Vec::new();
    for (type_name, t) in &library.types {
        if let Some((name, text)) = t.shader() {
            let (path, used) = as_used(name, text);
            match files.iter_mut().find(|(n, x, _)| *n == path && *x == used) {
                Some((_, _, types)) => types.push(type_name),
                None => files.push((path, used, vec![type_name])),
            }
        }
    }
    for (name, text, types) in files {
        let what = if types.len() == 1 { "type" } else { "types" };
        out.push(hash_text(
            &format!("{name} (pass {what} {})", types.join(", ")),
            &text,
        ));
    }
    out
}

pub fn run(args: AbArgs) -> Result<()> {
    let command: Vec<String> = std::env::args().collect();
    // Everything a user can get wrong fails before the GPU is opened.
    let pending = PendingDir::create(&args.out)?;
    let sets = args.set.sets.clone();

    // Variants: each pipeline × sweep value, then the reference.
    let mut taken = Vec::new();
    let mut plans = Vec::new();
    for given in &args.pipelines {
        let pipeline = resolve_pipeline(Some(given));
        if !pipeline.exists() {
            bail!("pipeline {}: no such file", given.display());
        }
        let base = stem(&pipeline);
        match &args.sweep {
            None => plans.push(VariantPlan {
                id: unique(sanitize(&base), &mut taken),
                label: base.clone(),
                pipeline: pipeline.clone(),
                sets: sets.clone(),
                sweep_value: None,
                is_reference: false,
            }),
            Some(sw) => {
                for v in &sw.values {
                    let mut s = sets.clone();
                    s.push(format!("{}={v}", sw.key));
                    plans.push(VariantPlan {
                        id: unique(sanitize(&format!("{base}@{v}")), &mut taken),
                        label: format!("{base} [{}={v}]", sw.key),
                        pipeline: pipeline.clone(),
                        sets: s,
                        sweep_value: Some(v.clone()),
                        is_reference: false,
                    });
                }
            }
        }
    }
    let reference = resolve_pipeline(Some(&args.reference));
    if !reference.exists() {
        bail!("--reference {}: no such file", args.reference.display());
    }
    plans.push(VariantPlan {
        id: unique("reference".into(), &mut taken),
        label: format!("{} (reference)", stem(&reference)),
        pipeline: reference.clone(),
        sets: sets.clone(),
        sweep_value: None,
        is_reference: true,
    });

    // Compile and check every variant without a GPU.
    let opts = CompileOptions {
        screen: args.size,
        ..CompileOptions::default()
    };
    for p in &plans {
        compile_checked(&p.pipeline, &p.sets, &opts).map_err(|e| {
            let what = match (&p.sweep_value, &args.sweep) {
                (Some(v), Some(sw)) => format!(" (--sweep {}={v})", sw.key),
                _ if p.is_reference => " (--reference)".to_string(),
                _ => String::new(),
            };
            anyhow::anyhow!("{e:#}").context(format!("pipeline {}{what}", p.pipeline.display()))
        })?;
    }

    // Scenes, each loaded once.
    let scene_paths: Vec<Option<PathBuf>> = if args.scenes.is_empty() {
        vec![None]
    } else {
        args.scenes.iter().cloned().map(Some).collect()
    };
    let mut scenes = Vec::new();
    let mut scene_names = Vec::new();
    let mut scene_taken = Vec::new();
    for sp in &scene_paths {
        let data = SceneData::load(sp.as_deref()).with_context(|| match sp {
            Some(p) => format!("--scene {}", p.display()),
            None => "the built-in scene".into(),
        })?;
        let name = sp
            .as_ref()
            .map(|p| stem(p))
            .unwrap_or_else(|| "default".into());
        scene_names.push(unique(sanitize(&name), &mut scene_taken));
        scenes.push(data);
    }

    let gpu = Gpu::new()?;
    let v = plans.len() as u64;
    let mut progress = Progress::new(scenes.len() as u64 * (v * 3 + v * args.repeats as u64 + v));

    let mut variants: Vec<Variant> = Vec::new();
    let mut graphs: Vec<(String, String)> = Vec::new();
    let mut pipelines_prov: Vec<PipelineProvenance> = Vec::new();
    let mut scene_results = Vec::new();

    for (si, (scene, scene_name)) in scenes.iter().zip(&scene_names).enumerate() {
        // Build every variant once for this scene.
        let mut prepared: Vec<Prepared<'_>> = Vec::new();
        for p in &plans {
            let pr = prepare(&gpu, &p.pipeline, &p.sets, scene, args.size)
                .map_err(|e| anyhow::anyhow!("{e:#}"))
                .with_context(|| {
                    format!("pipeline {} on scene {scene_name}", p.pipeline.display())
                })?;
            progress.step(format!("{scene_name}: built {}", p.label))?;
            prepared.push(pr);
        }
        if si == 0 {
            for (p, pr) in plans.iter().zip(&prepared) {
                let s = pr.schedule();
                let svg = plait_graph::to_svg(s);
                let graph_name = format!("graph-{}.svg", p.id);
                pending.write(&graph_name, svg.as_bytes())?;
                graphs.push((p.id.clone(), svg));
                let graph_file = Some(graph_name);
                if !pipelines_prov
                    .iter()
                    .any(|pp| pp.path == p.pipeline.display().to_string())
                {
                    pipelines_prov.push(pipeline_provenance(&p.pipeline, s)?);
                }
                variants.push(Variant {
                    id: p.id.clone(),
                    label: p.label.clone(),
                    pipeline: p.pipeline.display().to_string(),
                    is_reference: p.is_reference,
                    sweep_value: p.sweep_value.clone(),
                    sets: p.sets.clone(),
                    schedule_name: s.name.clone(),
                    memory: memory(s),
                    graph_svg: graph_file,
                });
            }
        }
        // Warm-up (excluded), then interleaved repeats.
        for (p, pr) in plans.iter().zip(&prepared) {
            pr.renderer
                .render()
                .map_err(|e| anyhow::anyhow!("{e:#}"))
                .with_context(|| format!("{} on scene {scene_name} (warm-up)", p.label))?;
            progress.step(format!("{scene_name}: warm-up {}", p.label))?;
        }
        let n = plans.len();
        let mut wall: Vec<Vec<f64>> = vec![Vec::new(); n];
        let mut totals: Vec<Vec<f64>> = vec![Vec::new(); n];
        let mut pass_ms: Vec<Vec<Vec<f64>>> = prepared
            .iter()
            .map(|pr| vec![Vec::new(); pr.schedule().passes.len()])
            .collect();
        for r in 0..args.repeats {
            for (i, (p, pr)) in plans.iter().zip(&prepared).enumerate() {
                let t0 = Instant::now();
                let report = pr
                    .renderer
                    .render()
                    .map_err(|e| anyhow::anyhow!("{e:#}"))
                    .with_context(|| {
                        format!("{} on scene {scene_name} (repeat {})", p.label, r + 1)
                    })?;
                wall[i].push(t0.elapsed().as_secs_f64() * 1e3);
                if let Some(t) = report.total_gpu_ms {
                    totals[i].push(t);
                }
                for (k, pt) in report.passes.iter().enumerate() {
                    if let (Some(ms), Some(list)) = (pt.gpu_ms, pass_ms[i].get_mut(k)) {
                        list.push(ms);
                    }
                }
                progress.step(format!(
                    "{scene_name}: repeat {}/{} {}",
                    r + 1,
                    args.repeats,
                    p.label
                ))?;
            }
        }
        // Images and metrics against the reference.
        let images: Vec<image::RgbaImage> = plans
            .iter()
            .zip(&prepared)
            .map(|(p, pr)| {
                pr.image()
                    .map_err(|e| anyhow::anyhow!("{e:#}"))
                    .with_context(|| {
                        format!("reading the image of {} on scene {scene_name}", p.label)
                    })
            })
            .collect::<Result<_>>()?;
        let ref_index = plans.iter().position(|p| p.is_reference).unwrap_or(n - 1);
        let reference_image = format!("{scene_name}-reference.png");
        pending.write_png(&reference_image, images[ref_index].clone())?;
        let mut comparisons = Vec::new();
        for (p, img) in plans.iter().zip(&images) {
            let c = plait_compare::compare(&images[ref_index], img).with_context(|| {
                format!(
                    "comparing {} with the reference on scene {scene_name}",
                    p.label
                )
            })?;
            progress.step(format!("{scene_name}: compared {}", p.label))?;
            comparisons.push(c);
        }
        // Self-shadowing: every variant's visibility provider probed along the
        // same rays through the hair, against the reference's (Fig. 5).
        let grid = ProbeGrid::through_hair(scene, (16, 16), 48);
        let probe = |p: &VariantPlan| -> Result<Option<Probed>> {
            probe_visibility(&gpu, &p.pipeline, &p.sets, scene, args.size, &grid)
                .map_err(|e| anyhow::anyhow!("{e:#}"))
                .with_context(|| {
                    format!(
                        "probing the self-shadowing of {} on scene {scene_name}",
                        p.label
                    )
                })
        };
        let reference_probe = probe(&plans[ref_index])?;
        let mut visibilities = Vec::new();
        for p in &plans {
            let v = match &reference_probe {
                Some(reference) => {
                    probe(p)?.map(|probed| visibility_error(&grid, reference, &probed))
                }
                None => None,
            };
            progress.step(format!("{scene_name}: probed {}", p.label))?;
            visibilities.push(v);
        }
        // One difference scale per scene, so the heat maps compare.
        let max_diff = comparisons
            .iter()
            .map(|c| c.metrics.max_abs_diff)
            .fold(0.0, f64::max);
        let scale = heatmap::nice_scale(max_diff);
        let mut runs = Vec::new();
        for (i, (p, c)) in plans.iter().zip(comparisons).enumerate() {
            let image = format!("{scene_name}-{}.png", p.id);
            let diff_image = format!("{scene_name}-{}-diff.png", p.id);
            let flip_image = format!("{scene_name}-{}-flip.png", p.id);
            pending.write_png(&image, images[i].clone())?;
            pending.write_png(
                &diff_image,
                heatmap::heatmap(&c.abs_diff, c.width, c.height, scale as f32),
            )?;
            pending.write_png(
                &flip_image,
                heatmap::heatmap(&c.flip_map, c.width, c.height, 1.0),
            )?;
            let schedule = prepared[i].schedule();
            runs.push(Run {
                variant: p.id.clone(),
                image,
                diff_image,
                diff_scale: scale,
                flip_image,
                timing: Timing {
                    total_gpu_ms: Stats::of(&totals[i]),
                    wall_ms: Stats::of(&wall[i]).unwrap_or_default(),
                    passes: schedule
                        .passes
                        .iter()
                        .zip(&pass_ms[i])
                        .map(|(sp, ms)| PassStats {
                            name: sp.name.clone(),
                            type_name: sp.type_name.clone(),
                            gpu_ms: Stats::of(ms),
                        })
                        .collect(),
                },
                metrics: c.metrics,
                visibility: visibilities[i].take(),
            });
        }
        scene_results.push(SceneResult {
            name: scene_name.clone(),
            path: scene_paths[si].as_ref().map(|p| p.display().to_string()),
            reference_image,
            runs,
        });
    }
    progress.finish();

    let scene_hashes = scene_paths
        .iter()
        .flatten()
        .map(|p| hash_file(p))
        .collect::<Result<Vec<_>>>()?;
    let report = Report {
        schema: SCHEMA.into(),
        provenance: Provenance {
            plait_version: env!("CARGO_PKG_VERSION").into(),
            adapter: Adapter {
                name: gpu.adapter_name().to_string(),
                backend: gpu.backend_name(),
                driver: gpu.info.driver.clone(),
                driver_info: gpu.info.driver_info.clone(),
            },
            timestamps: gpu.capabilities.timestamps,
            command_line: command.iter().map(|a| shell_quote(a)).collect::<Vec<_>>().join(" "),
            command,
            working_directory: std::env::current_dir().map(|d| d.display().to_string()).unwrap_or_default(),
            size: [args.size.0, args.size.1],
            repeats: args.repeats,
            warmup_frames: 1,
            order: "interleaved".into(),
            sets,
            reference: reference.display().to_string(),
            metrics: "RMSE and PSNR (peak 1) on 8-bit sRGB RGB values normalized to 0..1; SSIM (Wang et al. 2004) on Rec.601 luma, 11×11 Gaussian window σ=1.5, K1=0.01, K2=0.03; ꟻLIP: LDR-FLIP (nv-flip) at 67 pixels per degree, mean of the error map; visibility |ΔV|: every provider and the reference probed at the same points with the same light-map lookup (the texel the point falls in, no Fig. 9 jitter), hair in front = nearer the light by more than the self-shadow bias".into(),
            pipelines: pipelines_prov,
            builtin_shaders: builtin_shaders(),
            scenes: scene_hashes,
            unix_time: std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_secs()).unwrap_or(0),
        },
        sweep: args.sweep.as_ref().map(|s| Sweep { key: s.key.clone(), values: s.values.clone() }),
        variants,
        scenes: scene_results,
    };
    pending.write(
        "report.json",
        serde_json::to_string_pretty(&report)?.as_bytes(),
    )?;
    pending.write(
        "report.html",
        plait_compare::report::html(&report, &graphs).as_bytes(),
    )?;
    let out = args.out.clone();
    pending.commit()?;
    print_summary(&report)?;
    outln!("wrote {}", out.join("report.html").display())?;
    Ok(())
}

fn print_summary(report: &Report) -> std::io::Result<()> {
    for scene in &report.scenes {
        outln!("scene {}:", scene.name)?;
        outln!(
            "{:<36} {:>10} {:>10} {:>9} {:>9} {:>8} {:>8}",
            "variant",
            "frame ms",
            "peak MiB",
            "RMSE",
            "PSNR",
            "SSIM",
            "FLIP"
        )?;
        for run in &scene.runs {
            let Some(v) = report.variant(&run.variant) else {
                continue;
            };
            outln!(
                "{:<36} {:>10} {:>10.2} {:>9.5} {:>9} {:>8.5} {:>8.5}",
                v.label,
                format!("{:.3}", plait_compare::report::cost_ms(&run.timing)),
                v.memory.peak_bytes as f64 / 1048576.0,
                run.metrics.rmse,
                run.metrics
                    .psnr_db
                    .map(|p| format!("{p:.2}"))
                    .unwrap_or_else(|| "inf".into()),
                run.metrics.ssim,
                run.metrics.flip_mean
            )?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_syntax() {
        let s = parse_sweep("params.slices=32, 64,128").unwrap();
        assert_eq!(s.key, "params.slices");
        assert_eq!(s.values, ["32", "64", "128"]);
        assert!(parse_sweep("params.slices").is_err());
        assert!(parse_sweep("=1,2").is_err());
        assert!(parse_sweep("k=1,,2").is_err());
        assert!(parse_sweep("k=1,1").is_err());
    }

    #[test]
    fn names_and_quoting() {
        assert_eq!(sanitize("forward@a b/c"), "forward@a_b_c");
        let mut taken = vec![];
        assert_eq!(unique("a".into(), &mut taken), "a");
        assert_eq!(unique("a".into(), &mut taken), "a-2");
        assert_eq!(shell_quote("--size"), "--size");
        assert_eq!(shell_quote("a b"), "'a b'");
        assert_eq!(shell_quote("it's"), "'it'\\''s'");
    }
}
