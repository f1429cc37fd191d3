//! A/B runs (`plait ab`): several pipelines on the same scenes, timed with
//! interleaved repeats and compared with a reference pipeline, as one
//! [`Report`](plait_compare::report::Report) plus the images and schedule
//! pictures it names.
//!
//! - [`plan`]: what will run — each pipeline at every point of the sweeps
//!   (one sweep: a variant per value; two: a grid, every combination), then
//!   the reference — checked, and the scenes loaded, before any GPU work.
//! - [`run()`]: build, warm up, time interleaved repeats, read the images,
//!   compare them with the reference's, probe the self-shadowing; writes its
//!   files into a directory the caller owns (the CLI makes it a temporary
//!   one and renames it into place) and reports progress through a callback.
//! - `measure`: timings and memory in the report's shapes.
//! - `provenance`: hashes of every file the numbers depend on.
//! - [`shard`]: a share of the run (`--shard I/N`) for one machine of
//!   many; [`merge()`] joins the shares into the report one run writes.
//! - [`path_traced`], `cache`, `agx`: a reference rendered by Mitsuba 3
//!   instead of a pipeline, cached, shown through the CPU twin of the
//!   default display transform.

mod agx;
mod cache;
mod describe;
mod measure;
pub mod merge;
pub mod path_traced;
mod plait_reference;
pub mod plan;
mod provenance;
mod references;
mod run;
mod scenes;
pub mod shard;
mod supersample;
mod temporal;

use std::path::PathBuf;

pub use agx::display as display_agx;
pub use cache::default_cache;
pub use merge::{MergeError, merge};
pub use path_traced::{PathTraced, PathTracedError};
pub use plan::{AbOptions, CameraDistances, Plan, ScenePlan, Sequence, SweepSpec, VariantPlan};
pub use provenance::shell_quote;
pub use references::render_references;
pub use run::{Step, run};
pub use scenes::HairColor;
pub use shard::{Shard, ShardSyntaxError, run_shard};
pub use supersample::box_filter;

use crate::session::SessionError;

/// Why an A/B run stopped. Everything a user can get wrong (files, flags,
/// pipelines) is found by [`Plan::new`], before any GPU work.
#[derive(Debug, thiserror::Error)]
pub enum AbError {
    #[error("no pipeline to compare")]
    NoPipelines,
    #[error("pipeline {}: no such file", .0.display())]
    MissingPipeline(PathBuf),
    #[error("--reference {}: no such file", .0.display())]
    MissingReference(PathBuf),
    #[error("--repeats must be at least 1")]
    NoRepeats,
    #[error("--reference-repeats {reference}: must be from 1 to --repeats ({repeats})")]
    ReferenceRepeats { reference: u32, repeats: u32 },
    #[error("--sweep given {0} times; at most two sweeps (a grid of every combination)")]
    TooManySweeps(usize),
    #[error("--sweep {0}: the key is swept twice; give it once with all its values")]
    SweptTwice(String),
    #[error("--hair-color {0}: the name is given twice; each colour names its scenes' files")]
    HairColorTwice(String),
    /// A variant (or the reference) does not load or check; `what` says
    /// which (`--sweep k=v`, `--reference`).
    #[error("pipeline {}{what}", path.display())]
    Pipeline {
        path: PathBuf,
        what: String,
        #[source]
        source: plait_graph::Errors,
    },
    #[error("{what}")]
    Scene {
        what: String,
        #[source]
        source: plait_hair::scene::SceneError,
    },
    /// Building, rendering, reading back or probing a variant on the GPU.
    #[error("{what}")]
    Render {
        what: String,
        #[source]
        source: SessionError,
    },
    /// The reference's bounded buffers dropped data (a size the user
    /// capped): its image is not the truth the variants are measured by.
    #[error(
        "the reference {label} dropped data on scene {scene}, so it is no reference: {dropped}; remove the --set that caps it"
    )]
    ReferenceDropped {
        label: String,
        scene: String,
        dropped: String,
    },
    #[error("{what}")]
    Compare {
        what: String,
        #[source]
        source: plait_compare::CompareError,
    },
    #[error("reading {} to hash it", path.display())]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// Writing a file of the report into the run's directory.
    #[error("writing {name}")]
    Write {
        name: String,
        #[source]
        source: std::io::Error,
    },
    #[error("writing {name}")]
    WriteImage {
        name: String,
        #[source]
        source: image::ImageError,
    },
    #[error("writing report.json")]
    Json(#[source] serde_json::Error),
    /// A path-traced reference (`references/path_traced.toml`): its file,
    /// Mitsuba, the export of a scene, the cache, its noise.
    #[error(transparent)]
    PathTraced(#[from] PathTracedError),
    /// The progress callback failed (e.g. its output was closed).
    #[error("reporting progress")]
    Progress(#[source] std::io::Error),
}
