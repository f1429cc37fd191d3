//! Params that only the scene can check, checked before any GPU work.
//!
//! Strand-space shading's `shading_points`: K shading points evenly spread
//! along a strand need K ≤ its points — more would shade between the same
//! two vertices twice, and the contract is one shading point per strand
//! point at most, as Frostbite's. A value the user set (a `--set` flag, or
//! the pipeline file or a file it extends) is an error naming where it was
//! set; the technique's default is only a starting value, fitted to the
//! scene with a note, since the user never chose it.

use plait_graph::{Location, Pipeline, Schedule};

use crate::session::{SceneData, SessionError};
use crate::source::PipelineSource;

/// What fitting changed: `--set`-style flags to compile with after the
/// user's, and a note for each, for the render to print.
#[derive(Clone, Debug, Default)]
pub struct SceneFit {
    pub sets: Vec<String>,
    pub notes: Vec<String>,
}

const PARAM: &str = "shading_points";

/// The params of `schedule` fitted to `scene`, or the error for a value
/// the user set that the scene cannot take.
pub fn fit_to_scene(
    schedule: &Schedule,
    source: &PipelineSource,
    scene: &SceneData,
) -> Result<SceneFit, SessionError> {
    let Some((strand, shortest)) = scene
        .strands
        .ranges()
        .enumerate()
        .map(|(i, r)| (i, r.len()))
        .min_by_key(|&(_, len)| len)
    else {
        return Ok(SceneFit::default());
    };
    let too_many = schedule
        .passes
        .iter()
        .filter(|p| p.type_name == "strand_shading")
        .find_map(|p| {
            let points = p.params.get(PARAM)?.as_i64()?;
            (points > shortest as i64).then_some((p.name.as_str(), points))
        });
    let Some((pass, points)) = too_many else {
        return Ok(SceneFit::default());
    };
    // Only now is it worth reading who set the value: the loaded pipeline
    // keeps each param's location, the schedule does not.
    let pipeline = source.load(&[])?;
    match user_location(&pipeline, PARAM) {
        Some(at) => Err(SessionError::SceneFit(format!(
            "{at}: param `{PARAM}` of pass `{pass}`: {points} shading points per strand, but strand {strand} of the scene has {shortest} points; {PARAM} must be at most {shortest} for this scene"
        ))),
        None => Ok(SceneFit {
            sets: vec![format!("params.{PARAM}={shortest}")],
            notes: vec![format!(
                "{PARAM} = {shortest} (the technique's default {points} is more than strand {strand} of the scene has points; set params.{PARAM} to at most {shortest} to choose)"
            )],
        }),
    }
}

/// Where the user set param `name` (a flag, or the pipeline file or a
/// file it extends), or `None` when it keeps its technique's default.
fn user_location(pipeline: &Pipeline, name: &str) -> Option<Location> {
    let location = &pipeline.params.get(name)?.location;
    let default = match location {
        Location::File { path, .. } => pipeline.techniques.iter().any(|t| t.owns(path)),
        Location::Builtin => true,
        Location::Path { .. } | Location::Flag { .. } => false,
    };
    (!default).then(|| location.clone())
}
