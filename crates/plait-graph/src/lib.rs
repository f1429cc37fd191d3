//! plait's pipeline files, checked and compiled without a GPU.
//!
//! `load` reads a pipeline file (following `extends`, applying `--set`
//! overrides and `${param}` substitution, keeping the source location of every
//! value); `compile` checks it against a [`Registry`] of pass types and builds
//! the petgraph schedule, resource lifetimes and the memory plan; `dot` prints
//! the schedule as Graphviz, `svg` draws it as a picture and `snapshot` as
//! stable text.
//!
//! ```no_run
//! # use plait_graph::*;
//! # fn demo(registry: &Registry) -> Result<(), Errors> {
//! let pipeline = load("pipelines/occupancy.toml".as_ref(), &["params.slices=64".into()])?;
//! let schedule = compile(&pipeline, registry, &CompileOptions::default())?;
//! println!("{}", schedule_text(&schedule));
//! # Ok(()) }
//! ```

pub mod clear;
pub mod compile;
pub mod counters;
pub mod dot;
pub mod error;
pub mod expr;
pub mod format;
mod history;
pub mod load;
mod node_reader;
pub mod overflow;
mod overrides;
pub mod pass_type_file;
pub mod raster_decl;
mod run_once;
pub mod scene_resources;
pub mod schedule;
mod shader_path;
pub mod snapshot;
pub mod spec;
pub mod suggest;
pub mod svg;
pub mod techniques;
pub mod value;

pub use error::{Error, ErrorKind, Errors, Location, Spanned};
pub use format::Format;
pub use schedule::*;
pub use spec::*;
pub use value::Value;

pub use compile::fit::{
    Capabilities as CompileCapabilities, NoShaders, PassCheck, PassChecker, SlotRef, apply_settled,
};
pub use compile::{compile, compile_with};
pub use dot::{to_dot, to_svg};
pub use load::{
    PassDecl, Pipeline, PreviousOf, ResourceDecl, SizeDecl, load, load_str, parse_previous_name,
    previous_name,
};
pub use raster_decl::RasterDecl;
pub use snapshot::schedule_text;
