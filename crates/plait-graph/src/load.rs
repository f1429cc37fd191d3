//! Loading pipeline files: TOML with the source location of every value,
//! `extends` chains, `--set key=value` overrides and `${param}` substitution.
//!
//! The steps, in order:
//! 1. parse each file of the `extends` chain into a [`Node`] tree whose every
//!    value carries its `file:line:column`;
//! 2. merge base ← child key by key (tables recursively, everything else
//!    replaced), then apply `--set` flags through the same merge
//!    ([`crate::overrides`]) — technique choices first, then the chosen
//!    techniques' files ([`crate::techniques`]), then every other flag;
//! 3. substitute `${name}` from `[params]`;
//! 4. check the schema (unknown keys, value types) and build a [`Pipeline`].
//!
//! One module per stage: `tree` (the located value tree, parsing, merging,
//! `extends`), [`crate::overrides`] (`--set`), [`crate::techniques`]
//! (`[techniques]`), `params` (`${name}`), `schema` (keys and types).
//!
//! Sizes and integer params may be arithmetic expressions over the screen
//! size, which only [`crate::compile`] knows, so they stay [`Value`]s here.

mod params;
mod schema;
pub(crate) mod tree;

use indexmap::IndexMap;
use std::path::{Path, PathBuf};

use crate::error::{Error, ErrorKind, Errors, Location, Spanned};
use crate::format::Format;
use crate::overrides::apply_override;
use crate::spec::ResourceKind;
use crate::techniques::apply_techniques;
use crate::value::Value;

pub use crate::shader_path::resolve_shader;
pub(crate) use schema::{BUFFER_KEYS, PASS_KEYS, PIPELINE_KEYS, TEXTURE_KEYS, TOP_KEYS};
pub(crate) use tree::{Entry, Node, SourceMap, Table, convert_value, merge, parse_file};

use params::substitute_params;
use schema::build_pipeline;
use tree::load_chain;

/// A loaded pipeline file (after `extends`, `--set` and `${param}`), not yet
/// checked against pass types. Every value keeps the place that set it.
#[derive(Clone, Debug)]
pub struct Pipeline {
    pub name: Spanned<String>,
    pub description: Spanned<String>,
    /// The pipeline file, every file it extends, then the technique files.
    pub files: Vec<PathBuf>,
    /// `[techniques]`: the technique chosen for each choice point.
    pub techniques: Vec<crate::schedule::ChosenTechnique>,
    pub outputs: Vec<Spanned<String>>,
    /// `[params]` with every `${…}` resolved.
    pub params: IndexMap<String, Spanned<Value>>,
    /// `[resources]` in file order (base file's first).
    pub resources: IndexMap<String, ResourceDecl>,
    /// `[passes]` in file order, without those with `enabled = false`.
    pub passes: IndexMap<String, PassDecl>,
    /// Where `outputs` was set (or the `[pipeline]` table), for output errors.
    pub outputs_location: Location,
    /// What loading noticed that is not an error (a param of a technique the
    /// pipeline does not choose); compile passes them on to the schedule.
    pub notes: Vec<String>,
}

impl Pipeline {
    /// Make resource `name` an output besides the pipeline's own (`plait
    /// render --show`), set at `location`: the passes writing it are not
    /// culled and its memory is not shared with one written after it.
    pub fn add_output(&mut self, name: &str, location: Location) {
        if !self.outputs.iter().any(|o| o.value == name) {
            self.outputs.push(Spanned {
                value: name.to_owned(),
                location,
            });
        }
    }
}

/// A `[resources.NAME]` table.
#[derive(Clone, Debug)]
pub struct ResourceDecl {
    pub name: String,
    pub kind: Spanned<ResourceKind>,
    /// Textures only.
    pub format: Option<Spanned<Format>>,
    pub size: SizeDecl,
    /// Textures only; default 1. An integer or an expression string.
    pub layers: Option<Spanned<Value>>,
    /// Textures only; default 1. An integer or an expression string.
    pub samples: Option<Spanned<Value>>,
    /// The `[resources.NAME]` header (or first key) that declared it.
    pub location: Location,
    /// `history = N`: the engine keeps the last N frames' versions, read as
    /// `NAME.previous` (one frame ago) … `NAME.previous.N`.
    pub history: Option<Spanned<u32>>,
    /// `persistent = true`: contents kept between frames, never cleared by
    /// the engine (its location, when set).
    pub persistent: Option<Location>,
    /// Set on the resources the loader adds for a history: `NAME.previous.K`
    /// is `NAME` as it was K frames ago, read-only.
    pub previous_of: Option<PreviousOf>,
    /// Buffers only: `overflow = {…}` makes this buffer the counter of what
    /// another, bounded buffer could not hold ([`crate::overflow`]).
    pub overflow: Option<crate::overflow::OverflowDecl>,
    /// Textures only: `clear = …`, the value it holds before its first
    /// pass in the frame ([`crate::clear`]).
    pub clear: Option<Spanned<crate::clear::ClearValue>>,
}

/// What a `NAME.previous…` resource holds: `resource` as it was `frames_ago`
/// frames before the current one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PreviousOf {
    pub resource: String,
    pub frames_ago: u32,
}

/// `NAME.previous` for one frame ago, `NAME.previous.K` for K ≥ 2.
pub fn previous_name(resource: &str, frames_ago: u32) -> String {
    if frames_ago == 1 {
        format!("{resource}.previous")
    } else {
        format!("{resource}.previous.{frames_ago}")
    }
}

/// The inverse of [`previous_name`]: `("positions", 2)` for
/// `positions.previous.2`; `None` for a name that is not a history's.
pub fn parse_previous_name(name: &str) -> Option<(&str, u32)> {
    if let Some(base) = name.strip_suffix(".previous") {
        return Some((base, 1));
    }
    let (head, k) = name.rsplit_once('.')?;
    let base = head.strip_suffix(".previous")?;
    let k: u32 = k.parse().ok()?;
    (k >= 1).then_some((base, k))
}

/// The `size` of a resource, before the screen size is known.
#[derive(Clone, Debug)]
pub enum SizeDecl {
    /// `"screen"` (divisor 1) or `"screen/N"`.
    Screen { divisor: u32, location: Location },
    /// `[width, height]`, each an integer or an expression string.
    Extent {
        width: Spanned<Value>,
        height: Spanned<Value>,
        location: Location,
    },
    /// A buffer's size in bytes: an integer or an expression string.
    Bytes(Spanned<Value>),
    /// An acceleration structure's: the scene's hair, no key (where its
    /// `kind` is written).
    Scene(Location),
}

impl SizeDecl {
    pub fn location(&self) -> &Location {
        match self {
            SizeDecl::Screen { location, .. } | SizeDecl::Extent { location, .. } => location,
            SizeDecl::Bytes(v) => &v.location,
            SizeDecl::Scene(location) => location,
        }
    }
}

/// A `[passes.NAME]` table.
#[derive(Clone, Debug)]
pub struct PassDecl {
    pub name: String,
    pub type_name: Spanned<String>,
    pub view: Option<Spanned<String>>,
    pub draw: Option<Spanned<String>>,
    /// slot → resource name.
    pub reads: IndexMap<String, Spanned<String>>,
    pub writes: IndexMap<String, Spanned<String>>,
    pub params: IndexMap<String, Spanned<Value>>,
    /// Resolved path (see [`resolve_shader`]); the location is where it was written.
    pub shader: Option<Spanned<PathBuf>>,
    /// `depth`, `blend`, `cull` ([`crate::raster_decl`]).
    pub raster: crate::raster_decl::RasterDecl,
    /// Where `run = "once"` was written: the pass is a precompute that runs
    /// on an executor's first frame only, its outputs kept across frames.
    pub run_once: Option<Location>,
    pub location: Location,
}

/// Loads a pipeline file, following `extends` and applying `--set` flags
/// (`overrides` holds the `key=value` texts).
pub fn load(path: &Path, overrides: &[String]) -> Result<Pipeline, Errors> {
    crate::counters::LOADS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    // The file as a whole: a file that cannot be read has no line 1.
    // `plait_assets` reads built-in copies (`<built-in>/…`) too.
    let text = plait_assets::read_to_string(path).map_err(|e| {
        Error::new(
            Location::Path {
                path: path.to_path_buf(),
            },
            ErrorKind::Io(e.to_string()),
        )
    })?;
    load_str(path, &text, overrides)
}

/// Like [`load`], with the top file's text given (tests, editors). `extends`
/// is still read from disk, relative to `path_for_messages`.
pub fn load_str(
    path_for_messages: &Path,
    text: &str,
    overrides: &[String],
) -> Result<Pipeline, Errors> {
    let mut files = Vec::new();
    let mut chain = Vec::new();
    let mut root = load_chain(path_for_messages, text, &mut chain, &mut files)?;
    let mut errors = Vec::new();
    // Technique choices first, so `--set` can reach the params, resources and
    // passes of the technique it chose.
    let (choices, rest): (Vec<&String>, Vec<&String>) = overrides
        .iter()
        .partition(|f| f.trim_start().starts_with("techniques."));
    let implied = if choices.is_empty() {
        Vec::new()
    } else {
        crate::techniques::TechniqueRoots::for_pipeline(path_for_messages).implied_points()
    };
    for flag in choices {
        apply_override(&mut root, flag, &implied, &mut errors);
    }
    let mut techniques = Vec::new();
    if errors.is_empty() {
        techniques = apply_techniques(&mut root, path_for_messages, &mut files, &mut errors);
    }
    if !errors.is_empty() {
        errors.sort_by(|a, b| location_order(&a.location, &b.location));
        return Err(Errors(errors));
    }
    for flag in rest {
        apply_override(&mut root, flag, &[], &mut errors);
    }
    if !errors.is_empty() {
        crate::techniques::explain_unchosen_sets(&mut errors, &techniques, path_for_messages);
        return Err(Errors(errors));
    }
    let mut notes = Vec::new();
    crate::techniques::check_param_names(
        &root,
        &techniques,
        path_for_messages,
        &mut errors,
        &mut notes,
    );
    crate::techniques::check_param_ranges(&root, &techniques, &mut errors);
    let root = substitute_params(root, &mut errors);
    let mut pipeline = build_pipeline(root, files, path_for_messages, &mut errors);
    pipeline.techniques = techniques;
    pipeline.notes = notes;
    if errors.is_empty() {
        Ok(pipeline)
    } else {
        errors.sort_by(|a, b| location_order(&a.location, &b.location));
        Err(Errors(errors))
    }
}

/// Total order on locations for sorting error lists: files by path then
/// position, then flags, then built-ins.
pub fn location_order(a: &Location, b: &Location) -> std::cmp::Ordering {
    fn key(l: &Location) -> (u8, &Path, u32, u32, &str) {
        match l {
            Location::File { path, line, column } => (0, path.as_path(), *line, *column, ""),
            Location::Path { path } => (0, path.as_path(), 0, 0, ""),
            Location::Flag { flag } => (1, Path::new(""), 0, 0, flag.as_str()),
            Location::Builtin => (2, Path::new(""), 0, 0, ""),
        }
    }
    key(a).cmp(&key(b))
}

fn file_location(path: &Path, line: u32, column: u32) -> Location {
    Location::File {
        path: path.to_path_buf(),
        line,
        column,
    }
}
