//! What the render thread publishes for the window: the schedule's passes,
//! resources and params, timings, the last good frame, the last error.

use std::path::PathBuf;
use std::sync::Arc;

use glam::Vec3;
use plait_graph::{ResourceDesc, Schedule, Value};
use plait_hair::scene::Camera;

use crate::inspect::{self, Inspected};

/// One pass's row in the timing table.
#[derive(Clone, Debug)]
pub struct PassRow {
    pub name: String,
    pub type_name: String,
    /// Median over the last frames, when the adapter has timestamps.
    pub median_ms: Option<f64>,
    /// Bytes of the resources the pass writes.
    pub writes_bytes: u64,
}

/// One resource in the inspector's list.
#[derive(Clone, Debug)]
pub struct ResourceRow {
    pub name: String,
    pub label: String,
    pub desc: ResourceDesc,
    pub words_per_texel: u32,
}

/// What the window shows; the engine replaces parts of it as it goes.
#[derive(Default)]
pub struct Shared {
    /// Bumped on every change, so the window knows when to re-upload images.
    pub version: u64,
    pub pipeline: PathBuf,
    pub adapter: String,
    /// The pipeline's `[params]` after `--set` and live edits.
    pub params: Vec<(String, Value)>,
    /// Live edits, as the `--set` flags they become.
    pub edits: Vec<String>,
    /// Each choice point of the pipeline: its chosen technique and the choices.
    pub techniques: Vec<TechniqueChoice>,
    pub resources: Vec<ResourceRow>,
    pub output_name: String,
    pub passes: Vec<PassRow>,
    pub culled: Vec<(String, String)>,
    pub frame_median_ms: Option<f64>,
    pub peak_bytes: u64,
    pub notes: Vec<String>,
    /// The last frame's drops from bounded buffers the user capped
    /// (the session's frame step, [`plait::frames::Frame::dropped`]); a
    /// failed check is in `error`.
    pub dropped: Vec<String>,
    /// The last good frame's output.
    pub output: Option<Arc<Inspected>>,
    /// The inspected resource (when not the output).
    pub inspected: Option<Arc<Inspected>>,
    /// Why the inspected resource cannot be shown (e.g. multisampled).
    pub inspect_error: Option<String>,
    /// The last reload's or frame's error, with file:line:column.
    pub error: Option<String>,
    pub status: String,
    /// Frames since the last successful build, and in all.
    pub frames: u64,
    pub total_frames: u64,
    /// Successful rebuilds after the first build.
    pub reloads: u32,
    /// The scene file's camera and light, to reset the controls to.
    pub scene_camera: Option<Camera>,
    pub scene_light: Option<Vec3>,
    pub scene_version: u64,
    /// The screenshot was written (or the engine stopped): the window closes.
    pub finished: bool,
    /// Why the engine stopped, if it failed.
    pub fatal: Option<String>,
}

/// A choice point and what can fill it.
#[derive(Clone, Debug, PartialEq)]
pub struct TechniqueChoice {
    pub point: String,
    pub chosen: String,
    pub choices: Vec<String>,
}

pub(crate) fn describe_schedule(s: &mut Shared, schedule: &Schedule) {
    // The first of `files` is the pipeline file itself.
    let roots = schedule
        .files
        .first()
        .map(|p| plait_graph::techniques::TechniqueRoots::for_pipeline(p))
        .unwrap_or_default();
    s.techniques = schedule
        .techniques
        .iter()
        .map(|t| TechniqueChoice {
            point: t.point.clone(),
            chosen: t.name.clone(),
            choices: roots.choices(&t.point),
        })
        .collect();
    // A point every pipeline has (`geometry`) can be switched here even when
    // the pipeline leaves it to its default.
    for point in roots.implied_points() {
        if s.techniques.iter().any(|t| t.point == point) {
            continue;
        }
        let default = match roots.point_file(&point) {
            Some(Ok(file)) => file.wgsl.map(|w| w.default.value),
            _ => None,
        };
        if let Some(chosen) = default {
            s.techniques.push(TechniqueChoice {
                choices: roots.choices(&point),
                point,
                chosen,
            });
        }
    }
    s.params = schedule
        .params
        .iter()
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect();
    let sizes = texture_sizes(schedule);
    s.resources = schedule
        .resources
        .iter()
        .map(|r| ResourceRow {
            name: r.name.clone(),
            label: r.desc.label(),
            desc: r.desc.clone(),
            words_per_texel: match r.desc {
                ResourceDesc::Buffer { size } => inspect::buffer_layout(size, &sizes).per_texel,
                ResourceDesc::Texture { .. } | ResourceDesc::AccelerationStructure => 0,
            },
        })
        .collect();
    s.passes = schedule
        .passes
        .iter()
        .map(|p| {
            let mut written: Vec<usize> = p.writes.iter().map(|b| b.id().index()).collect();
            written.sort_unstable();
            written.dedup();
            PassRow {
                name: p.name.clone(),
                type_name: p.type_name.clone(),
                median_ms: None,
                writes_bytes: written
                    .iter()
                    .filter_map(|&id| schedule.resources.get(id))
                    .map(|r| r.desc.bytes())
                    .sum(),
            }
        })
        .collect();
    s.culled = schedule
        .culled
        .iter()
        .map(|c| (c.pass.name.clone(), c.reason.clone()))
        .collect();
    s.peak_bytes = schedule.memory.peak_bytes;
    s.frame_median_ms = None;
}

/// Every texture size of the schedule, for laying buffers out.
pub(crate) fn texture_sizes(schedule: &Schedule) -> Vec<(u32, u32)> {
    schedule
        .resources
        .iter()
        .filter_map(|r| match r.desc {
            ResourceDesc::Texture { width, height, .. } => Some((width, height)),
            ResourceDesc::Buffer { .. } | ResourceDesc::AccelerationStructure => None,
        })
        .collect()
}
