//! The A/B report: the data of `report.json` and its rendering as one
//! self-contained `report.html` (inline CSS, JS and SVG; images referenced
//! relatively from the report's directory, so it opens from disk offline).
//!
//! # `report.json` (schema `plait-ab/2`)
//! ```text
//! { schema, provenance {…}, sweeps: [ {key, values} ],
//!   variants: [ {id, label, pipeline, is_reference, sweep_values: {key: value, …}, sets, schedule_name,
//!                memory {peak_bytes, unpooled_bytes, allocations, resources: [{name, desc, bytes, shares_memory_with}]},
//!                graph_svg: file name | null} ],
//!   scenes: [ {name, path, reference_image,
//!              runs: [ {variant, image, diff_image, flip_image, diff_scale,
//!                       timing {total_gpu_ms: Stats|null, wall_ms: Stats, passes: [{name, type_name, gpu_ms: Stats|null}]},
//!                       metrics {rmse, psnr_db, ssim, flip_mean, max_abs_diff},
//!                       visibility: Visibility | null,
//!                       overflow: [ {pass, counter, of, dropped, needed, capacity, param, value, value_needed} ]} ] } ] }
//! ```
//!
//! `overflow` lists the variant's bounded buffers that declare an overflow
//! counter (fragment lists, exact depth lists), each at its worst frame of
//! the run: `dropped` items `of` could not hold (0: it held everything).
//! Only a size the user set can drop (the session grows the defaults), and
//! a reference that drops fails the run instead of being reported.
//! `Stats` is `{median, min, max, q1, q3, samples}` in milliseconds.
//!
//! `sweeps` holds the `--sweep`s in order: none, one (a variant per value)
//! or two (a grid: every combination; the HTML tables put the first sweep's
//! values in rows and the second's in columns). A variant's `sweep_values`
//! names its value of each sweep, keys in the order of `sweeps` (empty for
//! the reference and without sweeps). Schema 1 had one `sweep` (or `null`)
//! and a `sweep_value` per variant.
//!
//! With `--camera-distance F1,F2,…` the report also holds
//! `camera_distances: [F1, F2, …]`, and each scene is there once per factor
//! (`small@d2`) with `distance: {scene, factor}`: the same scene, its camera
//! F times as far from its target, the reference rendered from there too.
//! The HTML and Markdown add error (ꟻLIP mean) and frame time against the
//! distance, one series per variant, and a table (`distance_table`).
//!
//! A report merged from shards (`plait ab --shard I/N`, then `plait ab
//! merge`) also holds `shards: [ {index, count, machine, adapter,
//! unix_time} ]` and each run its `shard`: the process (and machine) that
//! rendered and timed it. Rows of different shards were not timed side by
//! side, and the HTML, Markdown and terminal tables say so beside each time.
//!
//! `visibility` is the self-shadowing error (Sintorn & Assarsson 2009
//! Fig. 5): for variants whose pipeline has a visibility provider, curves of
//! visibility against depth along probe rays from the light (the
//! reference's and the variant's) with the mean and max absolute error over
//! the rays through the hair; `null` when the reference has no provider.

mod charts;
mod distance;
mod html;
mod markdown;
#[cfg(test)]
mod tests;

pub use charts::scene_charts;
pub use distance::{distance_charts, distance_markdown};
pub use html::html;
pub use markdown::markdown;

use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

use crate::{Metrics, Stats};

pub const SCHEMA: &str = "plait-ab/2";

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Report {
    pub schema: String,
    pub provenance: Provenance,
    /// The `--sweep`s in order: none, one, or two (a grid).
    pub sweeps: Vec<Sweep>,
    /// `--camera-distance`: the factors every scene was seen from, in order
    /// (left out without it).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub camera_distances: Vec<f64>,
    pub variants: Vec<Variant>,
    pub scenes: Vec<SceneResult>,
    /// `plait ab merge`: the shards the report was joined from, each with
    /// the machine that timed its runs (left out for a run on one machine).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub shards: Vec<ShardInfo>,
}

/// One shard of a merged run: its index, and where its times were measured.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct ShardInfo {
    pub index: usize,
    pub count: usize,
    /// The host name of the machine that ran it.
    pub machine: String,
    pub adapter: Adapter,
    pub unix_time: u64,
}

impl Report {
    /// For a merged report: "shard k on M", the shard a run's times came
    /// from; `None` for a run on one machine.
    pub fn timed_on(&self, run: &Run) -> Option<String> {
        let k = run.shard?;
        let machine = self
            .shards
            .iter()
            .find(|s| s.index == k)
            .map_or("?", |s| s.machine.as_str());
        Some(format!("shard {k} on {machine}"))
    }

    /// Whether the runs of `scene` were timed in more than one process, so
    /// their times are not ratios measured side by side.
    pub fn timed_apart(&self, scene: &SceneResult) -> bool {
        let mut shards = scene.runs.iter().map(|r| r.shard);
        let first = shards.next().flatten();
        shards.any(|s| s != first)
    }

    /// The note above a scene's table whose times came from several shards.
    pub fn timed_apart_note(&self, scene: &SceneResult) -> Option<String> {
        self.timed_apart(scene).then(|| {
            "Times from different shards (machines), each row's shard beside its time: \
             not ratios measured side by side in one run; compare times only \
             between rows of the same shard."
                .to_string()
        })
    }
}

/// Where the numbers came from.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Provenance {
    pub plait_version: String,
    pub adapter: Adapter,
    /// Whether per-pass GPU times come from timestamp queries.
    pub timestamps: bool,
    /// `argv`, exactly, and as one shell-quoted line.
    pub command: Vec<String>,
    pub command_line: String,
    pub working_directory: String,
    pub size: [u32; 2],
    pub repeats: u32,
    /// The reference's timed frames when fewer than `repeats`
    /// (`--reference-repeats`: a slow reference timed once).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_repeats: Option<u32>,
    /// Frames rendered per variant before timing (excluded).
    pub warmup_frames: u32,
    /// `interleaved`: repeat r renders every variant once, in order, before repeat r+1.
    pub order: String,
    pub sets: Vec<String>,
    pub reference: String,
    pub metrics: String,
    pub pipelines: Vec<PipelineProvenance>,
    /// Shader modules compiled into the binary (the `plait::` import library and pass types' own WGSL).
    pub builtin_shaders: Vec<FileHash>,
    pub scenes: Vec<FileHash>,
    pub unix_time: u64,
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct Adapter {
    pub name: String,
    pub backend: String,
    pub driver: String,
    pub driver_info: String,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PipelineProvenance {
    pub path: String,
    /// The pipeline file and every file it extends.
    pub files: Vec<FileHash>,
    /// WGSL files named by its passes.
    pub shaders: Vec<FileHash>,
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct FileHash {
    pub path: String,
    pub sha256: String,
    pub bytes: u64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Sweep {
    pub key: String,
    pub values: Vec<String>,
}

/// One pipeline (at one point of the sweeps), or the reference.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Variant {
    pub id: String,
    pub label: String,
    pub pipeline: String,
    pub is_reference: bool,
    /// This variant's value of each sweep, by key, in the order of
    /// [`Report::sweeps`]; empty for the reference and without sweeps.
    pub sweep_values: IndexMap<String, String>,
    /// Every `--set` applied (the sweeps' last).
    pub sets: Vec<String>,
    pub schedule_name: String,
    pub memory: Memory,
    /// File name of the schedule's picture (also inlined in the HTML).
    pub graph_svg: Option<String>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Memory {
    /// Bytes of all allocations, with sharing.
    pub peak_bytes: u64,
    /// Bytes if no resource shared an allocation.
    pub unpooled_bytes: u64,
    pub allocations: usize,
    pub resources: Vec<ResourceMemory>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ResourceMemory {
    pub name: String,
    pub desc: String,
    pub bytes: u64,
    pub shares_memory_with: Vec<String>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SceneResult {
    pub name: String,
    /// `null` for the built-in default scene.
    pub path: Option<String>,
    /// With `--camera-distance`: which scene, and how far back its camera
    /// was (every variant and the reference seen from there).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distance: Option<CameraDistance>,
    /// With `--hair-color`: the linear RGB albedo every strand was given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hair_color: Option<[f32; 3]>,
    pub reference_image: String,
    /// The reference's linear radiance (OpenEXR), when its pipeline has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference_linear_image: Option<String>,
    pub runs: Vec<Run>,
}

impl SceneResult {
    /// What the scene's RMSE and difference maps compare (the runs share it).
    pub fn error_space(&self) -> crate::ErrorSpace {
        self.runs
            .first()
            .map(|r| r.metrics.error_space)
            .unwrap_or_default()
    }

    /// The sentence a report prints under the scene's table.
    pub fn metrics_note(&self) -> String {
        format!(
            "RMSE, PSNR and the difference maps compare {}; SSIM and ꟻLIP compare the displayed images (after exposure and tone mapping).",
            match self.error_space() {
                crate::ErrorSpace::LinearRadiance => "linear radiance (the .exr beside each image)",
                crate::ErrorSpace::Displayed =>
                    "the displayed sRGB values (a pipeline without a float radiance target)",
            }
        )
    }
}

/// A scene seen from a camera moved along its view ray.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CameraDistance {
    /// The scene's name without the distance (`small` for `small@d2`).
    pub scene: String,
    /// Distance to the camera's target, × the scene's (1 = as the scene has it).
    pub factor: f64,
}

/// One variant on one scene.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Run {
    pub variant: String,
    pub image: String,
    /// The variant's linear radiance (OpenEXR), when its pipeline has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub linear_image: Option<String>,
    /// |RGB difference| heat map (in `metrics.error_space`), 0 → `diff_scale`.
    pub diff_image: String,
    pub diff_scale: f64,
    /// ꟻLIP error map, 0 → 1.
    pub flip_image: String,
    pub timing: Timing,
    pub metrics: Metrics,
    pub visibility: Option<Visibility>,
    /// Every overflow counter of the variant at its worst frame.
    pub overflow: Vec<Overflow>,
    /// Flicker over the animated sequence (`plait ab --frames`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub temporal: Option<crate::temporal::Temporal>,
    /// `plait ab merge`: the shard whose process rendered and timed this run
    /// (see [`Report::shards`]); left out for a run on one machine.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shard: Option<usize>,
}

/// What one bounded buffer of a variant could not hold, at the run's worst
/// frame (`plait_gpu::Overflow` in the report's shape).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Overflow {
    /// The pass appending to the buffer.
    pub pass: String,
    /// The counter buffer.
    pub counter: String,
    /// The bounded buffer.
    pub of: String,
    /// Items dropped (0: it held everything).
    pub dropped: u64,
    /// The capacity that would have held them all (when `dropped > 0`).
    pub needed: u64,
    /// Items the buffer holds.
    pub capacity: u64,
    /// The param sizing the buffer, its value, and the value that holds `needed`.
    pub param: String,
    pub value: i64,
    pub value_needed: u64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Timing {
    /// First timestamp to last, over the repeats; `null` without timestamp queries.
    pub total_gpu_ms: Option<Stats>,
    /// `Renderer::render` on the CPU clock (submit + wait), over the repeats.
    pub wall_ms: Stats,
    pub passes: Vec<PassStats>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PassStats {
    pub name: String,
    pub type_name: String,
    pub gpu_ms: Option<Stats>,
}

/// Self-shadowing error of one variant: its visibility provider probed along
/// rays from the light through the hair, against the reference's.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Visibility {
    /// The variant's provider (`occupancy`, `deep_opacity`, …).
    pub provider: String,
    /// The reference's provider (`exact` for `reference.toml`).
    pub reference_provider: String,
    /// Probe rays along which the reference sees hair; the errors are over their samples.
    pub rays_through_hair: usize,
    /// The rays through the most hair.
    pub curves: Vec<VisibilityCurve>,
    pub mean_abs_error: f64,
    pub max_abs_error: f64,
}

/// Visibility against light depth along one ray from the light.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct VisibilityCurve {
    /// Where the ray crosses the light map (0..1, y down).
    pub light_uv: [f32; 2],
    /// Light NDC depth of each sample, spanning the hair.
    pub depth: Vec<f64>,
    /// The reference's visibility.
    pub exact: Vec<f64>,
    /// The variant's visibility.
    pub approx: Vec<f64>,
}

impl Report {
    pub fn variant(&self, id: &str) -> Option<&Variant> {
        self.variants.iter().find(|v| v.id == id)
    }
}

/// The cost used on plots: median total GPU ms, else median wall ms.
pub fn cost_ms(t: &Timing) -> f64 {
    t.total_gpu_ms
        .as_ref()
        .map(|s| s.median)
        .unwrap_or(t.wall_ms.median)
}

impl Variant {
    /// The sweep values, comma-separated (`64` or `64, exact`); `None` without.
    pub fn sweep_label(&self) -> Option<String> {
        (!self.sweep_values.is_empty()).then(|| {
            self.sweep_values
                .values()
                .map(String::as_str)
                .collect::<Vec<_>>()
                .join(", ")
        })
    }

    /// The pipeline's file stem (`forward` for `pipelines/forward.toml`).
    pub fn pipeline_stem(&self) -> String {
        std::path::Path::new(&self.pipeline)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| self.pipeline.clone())
    }
}
