//! Running a [`Plan`]: every variant built once per scene, one warm-up frame
//! each, then interleaved timed repeats (A B C A B C …, so a machine that
//! slows down mid-run slows every variant alike), then images, metrics
//! against the reference, visibility probes, and the report's files.

use std::path::Path;
use std::time::Instant;

use plait_compare::report::{CameraDistance, Report, Run, SCHEMA, SceneResult, Sweep, Visibility};
use plait_compare::{Comparison, heatmap};
use plait_gpu::Gpu;

use super::describe::describe;
use super::measure::Samples;
use super::provenance::provenance;
use super::shard::Shard;
use super::{AbError, Plan, ScenePlan, VariantPlan};
use crate::probe::{ProbeGrid, probe_visibility, visibility_error};
use crate::session::{Prepared, SessionError, prepare_compiled};
use crate::source::PipelineSource;
use plait_graph::Schedule;

/// One finished step of a run, for a progress display.
#[derive(Clone, Copy, Debug)]
pub struct Step<'a> {
    /// Steps finished, this one included (1-based).
    pub done: u64,
    /// [`Plan::step_count`].
    pub total: u64,
    /// What was just done (`small: repeat 1/5 occupancy`).
    pub message: &'a str,
}

/// The progress callback and its count. An error from the callback (its
/// output closed) stops the run.
struct Ticker<'p> {
    done: u64,
    total: u64,
    callback: &'p mut dyn FnMut(Step<'_>) -> std::io::Result<()>,
}

impl Ticker<'_> {
    fn step(&mut self, message: String) -> Result<(), AbError> {
        self.done += 1;
        (self.callback)(Step {
            done: self.done,
            total: self.total,
            message: &message,
        })
        .map_err(AbError::Progress)
    }
}

/// Where the report's files go.
pub(super) struct Files<'d> {
    pub(super) dir: &'d Path,
}

impl Files<'_> {
    pub(super) fn write(&self, name: &str, bytes: &[u8]) -> Result<(), AbError> {
        std::fs::write(self.dir.join(name), bytes).map_err(|source| AbError::Write {
            name: name.to_string(),
            source,
        })
    }

    /// A linear radiance image as OpenEXR (32-bit float).
    fn write_exr(&self, name: &str, img: &image::Rgba32FImage) -> Result<(), AbError> {
        image::DynamicImage::ImageRgba32F(img.clone())
            .save_with_format(self.dir.join(name), image::ImageFormat::OpenExr)
            .map_err(|source| AbError::WriteImage {
                name: name.to_string(),
                source,
            })
    }

    fn write_png(&self, name: &str, img: impl Into<image::DynamicImage>) -> Result<(), AbError> {
        let img: image::DynamicImage = img.into();
        img.save_with_format(self.dir.join(name), image::ImageFormat::Png)
            .map_err(|source| AbError::WriteImage {
                name: name.to_string(),
                source,
            })
    }
}

/// Where `scene` is in the plan.
fn scene_index(plan: &Plan, scene: &ScenePlan) -> usize {
    plan.scenes
        .iter()
        .position(|s| std::ptr::eq(s, scene))
        .unwrap_or(0)
}

fn render_error(what: String) -> impl FnOnce(SessionError) -> AbError {
    move |source| AbError::Render { what, source }
}

/// Run `plan` on `gpu`, writing the report's files into `dir` (which must
/// exist): `report.json`, `report.html`, `report.md`, each variant's image
/// (and its linear radiance as .exr, when its pipeline has one), difference
/// and ꟻLIP maps per scene, the reference's images, and each variant's
/// schedule as SVG. `progress` hears of every step.
pub fn run(
    plan: &Plan,
    gpu: &Gpu,
    dir: &Path,
    progress: &mut dyn FnMut(Step<'_>) -> std::io::Result<()>,
) -> Result<Report, AbError> {
    let (report, graphs) = render(plan, gpu, dir, None, progress)?;
    write_report(dir, &report, &graphs)?;
    Ok(report)
}

/// `report.json`, `report.html` and `report.md` of `report` into `dir`;
/// `graphs` are the variants' schedule pictures (id, SVG) for the HTML.
pub(super) fn write_report(
    dir: &Path,
    report: &Report,
    graphs: &[(String, String)],
) -> Result<(), AbError> {
    let files = Files { dir };
    let json = serde_json::to_string_pretty(report).map_err(AbError::Json)?;
    files.write("report.json", json.as_bytes())?;
    files.write(
        "report.html",
        plait_compare::report::html(report, graphs).as_bytes(),
    )?;
    files.write(
        "report.md",
        plait_compare::report::markdown(report).as_bytes(),
    )
}

/// What [`run`] measures, without writing the report itself: every unit of
/// `plan`, or only `shard`'s (its rows, rendered with the references they
/// need; the variants described on the first scene as in a whole run).
pub(super) fn render(
    plan: &Plan,
    gpu: &Gpu,
    dir: &Path,
    shard: Option<Shard>,
    progress: &mut dyn FnMut(Step<'_>) -> std::io::Result<()>,
) -> Result<(Report, Vec<(String, String)>), AbError> {
    let mut ticker = Ticker {
        done: 0,
        total: shard.map_or_else(|| plan.step_count(), |s| s.step_count(plan)),
        callback: progress,
    };
    let files = Files { dir };
    // Every variant and the reference must run on this adapter before any
    // is built; the schedules compiled for it serve every scene.
    let mut schedules = Vec::new();
    for v in plan.gpu_variants() {
        let size = plan.options.render_size(v.is_reference);
        let schedule =
            crate::adapter::check_on_adapter(gpu, &plan.library, &v.pipeline, &v.sets, size)
                .map_err(render_error(format!("pipeline {}", v.label)))?;
        schedules.push(schedule);
    }
    let mut described = None;
    if shard.is_some() {
        // A variant's schedule (its memory) is fitted to the first scene: a
        // shard describes every variant from there, as a whole run does,
        // whichever units it renders.
        let mut silent = |_: Step<'_>| Ok(());
        let mut quiet = Ticker {
            done: 0,
            total: 0,
            callback: &mut silent,
        };
        let prepared = build_all(plan, &schedules, gpu, &plan.scenes[0], &mut quiet)?;
        described = Some(describe(plan, &prepared, &files)?);
    }
    let mut scenes = Vec::new();
    for (index, scene) in plan.scenes.iter().enumerate() {
        let chosen: Vec<usize> = match shard {
            None => (0..plan.variants.len()).collect(),
            Some(s) => s.variants_of(plan, index),
        };
        if chosen.is_empty() {
            continue;
        }
        // The helpers below run every variant of the plan they are given.
        let sub = Plan {
            options: plan.options.clone(),
            reference: plan.reference.clone(),
            variants: chosen.iter().map(|&i| plan.variants[i].clone()).collect(),
            scenes: Vec::new(),
            // Its one scene's path-traced image (sub-plans have no scenes:
            // the helpers' scene index is 0).
            path_traced: plan.path_traced.clone(),
            path_traced_images: plan
                .path_traced_images
                .get(index)
                .cloned()
                .into_iter()
                .collect(),
            library: plan.library.clone(),
        };
        // A path-traced reference (last) has no schedule: it is not built.
        let sub_schedules: Vec<Schedule> = chosen
            .iter()
            .filter_map(|&i| schedules.get(i).cloned())
            .collect();
        let mut prepared = build_all(&sub, &sub_schedules, gpu, scene, &mut ticker)?;
        if described.is_none() {
            // Schedules do not depend on the scene: describe them once.
            described = Some(describe(plan, &prepared, &files)?);
        }
        let mut result = measure_scene(&sub, gpu, scene, &files, &mut prepared, &mut ticker)?;
        if let Some(s) = shard {
            // The reference rendered only as the truth of this shard's
            // units is not a row of it.
            let mut rows = chosen.iter();
            result
                .runs
                .retain(|_| rows.next().is_some_and(|&v| s.owns_unit(plan, index, v)));
            for run in &mut result.runs {
                run.shard = Some(s.index);
            }
        }
        scenes.push(result);
    }
    let (variants, graphs, pipelines) = described.unwrap_or_default();
    let report = Report {
        schema: SCHEMA.into(),
        provenance: provenance(plan, gpu, pipelines, &plan.library)?,
        sweeps: plan
            .options
            .sweeps
            .iter()
            .map(|s| Sweep {
                key: s.key.clone(),
                values: s.values.clone(),
            })
            .collect(),
        camera_distances: plan.options.camera_distances.clone(),
        variants,
        scenes,
        shards: Vec::new(),
    };
    Ok((report, graphs))
}

/// Every variant of `plan` on `scene`, built: timed, read, compared,
/// probed, (with `--frames`) its sequence measured, its files written.
fn measure_scene(
    plan: &Plan,
    gpu: &Gpu,
    scene: &ScenePlan,
    files: &Files<'_>,
    prepared: &mut [Prepared<'_>],
    ticker: &mut Ticker<'_>,
) -> Result<SceneResult, AbError> {
    let samples = time_interleaved(plan, scene, prepared, ticker)?;
    let index = scene_index(plan, scene);
    let images = plan
        .variants
        .iter()
        .zip(prepared.iter())
        .map(|(v, p)| {
            let k = plan.options.render_size(v.is_reference).0 / plan.options.size.0.max(1);
            p.image()
                .map(|image| super::supersample::box_filter(&image, k))
                .map_err(|e| AbError::Render {
                    what: format!("reading the image of {} on scene {}", v.label, scene.name),
                    source: e.into(),
                })
        })
        .chain(
            plan.path_traced_images
                .get(index)
                .map(|r| Ok(r.display.clone())),
        )
        .collect::<Result<Vec<_>, _>>()?;
    let mut linears = read_linears(plan, scene, prepared)?;
    // A path-traced reference: its images join the GPU variants' last.
    if let Some(r) = plan.path_traced_images.get(index) {
        linears.push(Some(r.linear.clone()));
    }
    let comparisons = compare_all(plan, scene, &images, &linears, ticker)?;
    let visibilities = probe_all(plan, gpu, scene, ticker)?;
    let temporals = match plan.options.sequence {
        Some(sequence) => {
            super::temporal::measure(plan, gpu, scene, prepared, sequence, &mut |message| {
                ticker.step(message)
            })?
        }
        None => vec![None; plan.variants.len()],
    };
    scene_result(
        plan,
        scene,
        files,
        prepared,
        &samples,
        (&images, &linears),
        comparisons,
        visibilities,
        temporals,
    )
}

/// Every variant built for `scene`.
fn build_all<'g>(
    plan: &Plan,
    schedules: &[Schedule],
    gpu: &'g Gpu,
    scene: &ScenePlan,
    ticker: &mut Ticker<'_>,
) -> Result<Vec<Prepared<'g>>, AbError> {
    let mut prepared = Vec::new();
    for (v, schedule) in plan.variants.iter().zip(schedules) {
        let size = plan.options.render_size(v.is_reference);
        let source = PipelineSource::with_library(&v.pipeline, &v.sets, plan.library.clone());
        let p = prepare_compiled(gpu, schedule.clone(), &source, &scene.data, size).map_err(
            render_error(format!(
                "pipeline {} on scene {}",
                v.pipeline.display(),
                scene.name
            )),
        )?;
        ticker.step(format!("{}: built {}", scene.name, v.label))?;
        prepared.push(p);
    }
    Ok(prepared)
}

/// One warm-up frame per variant (not timed), then the repeats interleaved.
fn time_interleaved(
    plan: &Plan,
    scene: &ScenePlan,
    prepared: &[Prepared<'_>],
    ticker: &mut Ticker<'_>,
) -> Result<Vec<Samples>, AbError> {
    let mut samples: Vec<Samples> = prepared
        .iter()
        .map(|p| Samples::new(p.schedule()))
        .collect();
    for ((v, p), s) in plan.variants.iter().zip(prepared).zip(&mut samples) {
        let frame = p.render().map_err(render_error(format!(
            "{} on scene {} (warm-up)",
            v.label, scene.name
        )))?;
        s.add_overflow(&frame.report);
        ticker.step(format!("{}: warm-up {}", scene.name, v.label))?;
    }
    // The reference is the truth the others are measured against: one
    // that dropped data (a size capped with --set) measures nothing.
    let reference = plan.reference_index();
    let dropped = samples
        .get(reference)
        .map(Samples::dropped)
        .unwrap_or_default();
    if !dropped.is_empty() {
        return Err(AbError::ReferenceDropped {
            label: plan.variants[reference].label.clone(),
            scene: scene.name.clone(),
            dropped: crate::overflow::list(&dropped),
        });
    }
    let repeats = plan.options.repeats;
    for r in 0..repeats {
        for (i, ((v, p), s)) in plan
            .variants
            .iter()
            .zip(prepared)
            .zip(&mut samples)
            .enumerate()
        {
            if r >= plan.repeats_of(i) {
                continue;
            }
            let start = Instant::now();
            let frame = p.render().map_err(render_error(format!(
                "{} on scene {} (repeat {})",
                v.label,
                scene.name,
                r + 1
            )))?;
            s.add(start.elapsed().as_secs_f64() * 1e3, &frame.report);
            ticker.step(format!(
                "{}: repeat {}/{repeats} {}",
                scene.name,
                r + 1,
                v.label
            ))?;
        }
    }
    Ok(samples)
}

/// Each variant's linear radiance (its pipeline's float `radiance` output,
/// averaged down like its image when supersampled); `None` for a pipeline
/// without one.
fn read_linears(
    plan: &Plan,
    scene: &ScenePlan,
    prepared: &[Prepared<'_>],
) -> Result<Vec<Option<image::Rgba32FImage>>, AbError> {
    plan.variants
        .iter()
        .zip(prepared)
        .map(|(v, p)| {
            let schedule = p.schedule();
            let kept = schedule.resource(crate::linear::RADIANCE).filter(|&id| {
                schedule.outputs.contains(&id)
                    && matches!(schedule.resources[id].desc,
                        plait_graph::ResourceDesc::Texture { format, .. }
                            if crate::linear::is_float_colour(format))
            });
            let Some(_) = kept else { return Ok(None) };
            let k = plan.options.render_size(v.is_reference).0 / plan.options.size.0.max(1);
            p.read_resource(crate::linear::RADIANCE)
                .map(|t| {
                    Some(super::supersample::box_filter_linear(
                        &crate::linear::to_f32_image(&t),
                        k,
                    ))
                })
                .map_err(|e| AbError::Render {
                    what: format!(
                        "reading the radiance of {} on scene {}",
                        v.label, scene.name
                    ),
                    source: e.into(),
                })
        })
        .collect()
}

/// Every variant's image against the reference's: RMSE and the difference
/// map on the linear radiance when both have one, SSIM and ꟻLIP on the
/// displayed images.
fn compare_all(
    plan: &Plan,
    scene: &ScenePlan,
    images: &[image::RgbaImage],
    linears: &[Option<image::Rgba32FImage>],
    ticker: &mut Ticker<'_>,
) -> Result<Vec<Comparison>, AbError> {
    let reference = &images[plan.reference_index()];
    let reference_linear = linears[plan.reference_index()].as_ref();
    let mut comparisons = Vec::new();
    for ((v, img), linear) in plan.variants.iter().zip(images).zip(linears) {
        let both = reference_linear.zip(linear.as_ref());
        let c = plait_compare::compare_linear(reference, img, both).map_err(|source| {
            AbError::Compare {
                what: format!(
                    "comparing {} with the reference on scene {}",
                    v.label, scene.name
                ),
                source,
            }
        })?;
        ticker.step(format!("{}: compared {}", scene.name, v.label))?;
        comparisons.push(c);
    }
    Ok(comparisons)
}

/// Self-shadowing: every variant's visibility provider probed along the
/// same rays through the hair, against the reference's (Sintorn &
/// Assarsson 2009 Fig. 5). `None` for all when the reference has no
/// provider, and for a variant without one.
fn probe_all(
    plan: &Plan,
    gpu: &Gpu,
    scene: &ScenePlan,
    ticker: &mut Ticker<'_>,
) -> Result<Vec<Option<Visibility>>, AbError> {
    if plan.path_traced.is_some() {
        // A path tracer has no visibility provider to probe.
        for v in &plan.variants {
            ticker.step(format!("{}: probed {}", scene.name, v.label))?;
        }
        return Ok(vec![None; plan.variants.len()]);
    }
    let grid = ProbeGrid::through_hair(&scene.data, (16, 16), 48);
    let probe = |v: &VariantPlan| {
        // The run's one library: the probe reads none of its own.
        let source = PipelineSource::with_library(&v.pipeline, &v.sets, plan.library.clone());
        probe_visibility(gpu, &source, &scene.data, plan.options.size, &grid).map_err(render_error(
            format!(
                "probing the self-shadowing of {} on scene {}",
                v.label, scene.name
            ),
        ))
    };
    let reference = probe(&plan.variants[plan.reference_index()])?;
    let mut visibilities = Vec::new();
    for v in &plan.variants {
        let visibility = match &reference {
            Some(reference) => probe(v)?.map(|probed| visibility_error(&grid, reference, &probed)),
            None => None,
        };
        ticker.step(format!("{}: probed {}", scene.name, v.label))?;
        visibilities.push(visibility);
    }
    Ok(visibilities)
}

/// A scene's runs, their images and heat maps written.
#[allow(clippy::too_many_arguments)]
fn scene_result(
    plan: &Plan,
    scene: &ScenePlan,
    files: &Files<'_>,
    prepared: &[Prepared<'_>],
    samples: &[Samples],
    (images, linears): (&[image::RgbaImage], &[Option<image::Rgba32FImage>]),
    comparisons: Vec<Comparison>,
    visibilities: Vec<Option<Visibility>>,
    temporals: Vec<Option<plait_compare::temporal::Temporal>>,
) -> Result<SceneResult, AbError> {
    let reference_image = format!("{}-reference.png", scene.name);
    files.write_png(&reference_image, images[plan.reference_index()].clone())?;
    let reference_linear_image = match &linears[plan.reference_index()] {
        Some(linear) => {
            let name = format!("{}-reference.exr", scene.name);
            files.write_exr(&name, linear)?;
            Some(name)
        }
        None => None,
    };
    // One difference scale per scene, so the heat maps compare.
    let max_diff = comparisons
        .iter()
        .map(|c| c.metrics.max_abs_diff)
        .fold(0.0, f64::max);
    let scale = heatmap::nice_scale(max_diff);
    let mut runs = Vec::new();
    for (i, ((c, visibility), temporal)) in comparisons
        .into_iter()
        .zip(visibilities)
        .zip(temporals)
        .enumerate()
    {
        let v = &plan.variants[i];
        let image = format!("{}-{}.png", scene.name, v.id);
        let diff_image = format!("{}-{}-diff.png", scene.name, v.id);
        let flip_image = format!("{}-{}-flip.png", scene.name, v.id);
        files.write_png(&image, images[i].clone())?;
        let linear_image = match &linears[i] {
            Some(linear) => {
                let name = format!("{}-{}.exr", scene.name, v.id);
                files.write_exr(&name, linear)?;
                Some(name)
            }
            None => None,
        };
        files.write_png(
            &diff_image,
            heatmap::heatmap(&c.abs_diff, c.width, c.height, scale as f32),
        )?;
        files.write_png(
            &flip_image,
            heatmap::heatmap(&c.flip_map, c.width, c.height, 1.0),
        )?;
        runs.push(Run {
            variant: v.id.clone(),
            image,
            linear_image,
            diff_image,
            diff_scale: scale,
            flip_image,
            timing: match (samples.get(i), prepared.get(i)) {
                (Some(s), Some(p)) => s.timing(p.schedule()),
                _ => super::references::timing(plan, scene_index(plan, scene)),
            },
            metrics: c.metrics,
            visibility,
            overflow: samples.get(i).map(Samples::overflow).unwrap_or_default(),
            temporal,
            shard: None,
        });
    }
    Ok(SceneResult {
        name: scene.name.clone(),
        path: scene.path.as_ref().map(|p| p.display().to_string()),
        distance: scene
            .distance
            .as_ref()
            .map(|(name, factor)| CameraDistance {
                scene: name.clone(),
                factor: *factor,
            }),
        hair_color: scene.hair_color.as_ref().map(|c| c.rgb),
        reference_image,
        reference_linear_image,
        runs,
    })
}
