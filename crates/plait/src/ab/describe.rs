//! The variants as a report lists them (their schedules, memory, pictures
//! and the files they are read from), taken from their builds on the first
//! scene — by a whole run and by every shard alike.

use plait_compare::report::{PipelineProvenance, Variant};

use super::measure::memory;
use super::provenance::pipeline_provenance;
use super::run::Files;
use super::{AbError, Plan};
use crate::session::Prepared;

/// The variants as the report lists them, their schedule pictures (also
/// written as `graph-<id>.svg`) and the pipelines' provenance, from their
/// builds (every variant of `plan`, in order) on the first scene.
#[allow(clippy::type_complexity)]
pub(super) fn describe(
    plan: &Plan,
    prepared: &[Prepared<'_>],
    files: &Files<'_>,
) -> Result<(Vec<Variant>, Vec<(String, String)>, Vec<PipelineProvenance>), AbError> {
    let mut variants = Vec::new();
    let mut graphs = Vec::new();
    let mut pipelines: Vec<PipelineProvenance> = Vec::new();
    for (v, p) in plan.variants.iter().zip(prepared) {
        let schedule = p.schedule();
        let svg = plait_graph::to_svg(schedule);
        let graph_file = format!("graph-{}.svg", v.id);
        files.write(&graph_file, svg.as_bytes())?;
        graphs.push((v.id.clone(), svg));
        merge_provenance(&mut pipelines, pipeline_provenance(&v.pipeline, schedule)?);
        variants.push(Variant {
            id: v.id.clone(),
            label: v.label.clone(),
            pipeline: v.pipeline.display().to_string(),
            is_reference: v.is_reference,
            sweep_values: v.sweep_values.clone(),
            sets: v.sets.clone(),
            schedule_name: schedule.name.clone(),
            memory: memory(schedule),
            graph_svg: Some(graph_file),
        });
    }
    // A path-traced reference is no schedule: the report names its renderer.
    if let Some(v) = super::references::report_variant(plan) {
        variants.push(v);
        merge_provenance(
            &mut pipelines,
            super::provenance::path_traced_provenance(&plan.reference)?,
        );
    }
    Ok((variants, graphs, pipelines))
}

/// Add a variant's files to the provenance: one entry per pipeline file,
/// holding the files of every sweep point of it (a swept `--set` can name
/// other shaders or technique files than the first point does).
fn merge_provenance(pipelines: &mut Vec<PipelineProvenance>, new: PipelineProvenance) {
    let Some(known) = pipelines.iter_mut().find(|p| p.path == new.path) else {
        pipelines.push(new);
        return;
    };
    for file in new.files {
        if !known.files.contains(&file) {
            known.files.push(file);
        }
    }
    for shader in new.shaders {
        if !known.shaders.contains(&shader) {
            known.shaders.push(shader);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use plait_compare::report::FileHash;

    fn file(path: &str) -> FileHash {
        FileHash {
            path: path.into(),
            sha256: format!("sha-of-{path}"),
            bytes: 1,
        }
    }

    /// Sweep points of one pipeline that use different shaders: every
    /// shader listed, each once, under the one pipeline.
    #[test]
    fn sweep_points_add_their_files_to_their_pipeline() {
        let point = |shader: &str| PipelineProvenance {
            path: "pipelines/occupancy.toml".into(),
            files: vec![file("pipelines/occupancy.toml")],
            shaders: vec![file("shaders/compose_over.wgsl"), file(shader)],
        };
        let mut all = Vec::new();
        merge_provenance(&mut all, point("shaders/a.wgsl"));
        merge_provenance(&mut all, point("shaders/b.wgsl"));
        merge_provenance(&mut all, point("shaders/a.wgsl"));
        assert_eq!(all.len(), 1);
        let shaders: Vec<&str> = all[0].shaders.iter().map(|f| f.path.as_str()).collect();
        assert_eq!(
            shaders,
            [
                "shaders/compose_over.wgsl",
                "shaders/a.wgsl",
                "shaders/b.wgsl"
            ]
        );
        assert_eq!(all[0].files.len(), 1);
    }
}
