//! Grooms in USD (`.usda`, `.usdc`, `.usdz`, `.usd`): every `BasisCurves`
//! prim under a chosen prim becomes strands, read through the `openusd`
//! crate (text, binary crate and zip package, with composition: sublayers,
//! references, payloads, variants).
//!
//! - Curves: `linear` as they are; `cubic` with basis `bezier`, `bspline` or
//!   `catmullRom` evaluated to polylines of `segments_per_span` segments per
//!   span; wrap `nonperiodic` or `pinned` (see [`curves`]).
//! - `widths` (diameters) become thickness; `primvars:displayColor` the
//!   colour and `primvars:displayOpacity` the opacity (constant, per curve,
//!   per span end or per vertex).
//! - Every prim's `xformOp`s up to the root, then the stage's
//!   `metersPerUnit` and `upAxis` (USD's fallbacks: centimetres, Y up): the
//!   strands come out in metres, Y up.
//!
//! Writing ([`write`]) gives one linear `BasisCurves` prim with vertex
//! widths, colours and opacities, in metres and Y up.

mod crate_check;
pub mod curves;
pub mod mesh;
mod read;
pub(crate) mod stage;
mod write;

#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};

use crate::strands::Strands;
pub use curves::{Basis, CurveKind, CurvesData, Interpolation, Primvar, Wrap};
pub use stage::StageUnits;
pub use write::{WriteFormat, example_groom_usda, write};

/// Segments per cubic span when a scene or command does not say.
pub const DEFAULT_SEGMENTS_PER_SPAN: u32 = 8;
/// The most segments per span plait evaluates.
pub const MAX_SEGMENTS_PER_SPAN: u32 = 256;

/// Everything that makes a USD groom unreadable; [`UsdError::InFile`] names
/// the file.
#[derive(Debug, thiserror::Error)]
pub enum UsdError {
    /// The file could not be read at all.
    #[error("cannot read file: {0}")]
    Read(std::io::Error),
    /// Not a USD file (or one the reader cannot open): the reader's words.
    #[error("not a readable USD file: {0}")]
    NotUsd(String),
    /// The prim named does not exist.
    #[error("prim `{prim}` is not on the stage{}", hint(.nearest))]
    NoPrim {
        /// The prim asked for.
        prim: String,
        /// The nearest prim path, if one is close.
        nearest: Option<String>,
    },
    /// Nothing to read under the prim.
    #[error("no BasisCurves prim under `{prim}`{}", found_note(.others))]
    NoCurves {
        /// The prim searched.
        prim: String,
        /// Curve prims of types plait does not read, e.g. `NurbsCurves /a`.
        others: Vec<String>,
    },
    /// A field of a prim (or of the stage, prim `/`) is wrong.
    #[error("prim `{prim}`, field `{field}`: {message}")]
    Field {
        /// The prim.
        prim: String,
        /// The attribute or metadata field.
        field: &'static str,
        /// What is wrong.
        message: String,
    },
    /// An option is out of range.
    #[error("{0}")]
    Option(String),
    /// The USD reader (the `openusd` crate) panicked on this file: a bug
    /// in it, reported rather than crashing plait.
    #[error("the USD reader failed on this file ({0}); please report it")]
    ReaderPanic(String),
    /// Any of the above for a named file.
    #[error("{}: {error}", path.display())]
    InFile {
        /// The file.
        path: PathBuf,
        /// The problem.
        error: Box<UsdError>,
    },
}

fn hint(nearest: &Option<String>) -> String {
    nearest
        .as_ref()
        .map(|n| format!(" (did you mean `{n}`?)"))
        .unwrap_or_default()
}

fn found_note(others: &[String]) -> String {
    if others.is_empty() {
        String::new()
    } else {
        format!(
            " (found {}: plait reads BasisCurves only)",
            others.join(", ")
        )
    }
}

impl UsdError {
    /// This error, naming `path`.
    pub fn in_file(self, path: &Path) -> UsdError {
        match self {
            e @ UsdError::InFile { .. } => e,
            e => UsdError::InFile {
                path: path.to_path_buf(),
                error: Box::new(e),
            },
        }
    }
}

/// What to read from a stage.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UsdOptions {
    /// The prim whose `BasisCurves` descendants (itself included) are read;
    /// `None` reads the whole stage.
    pub prim: Option<String>,
    /// Segments per span of a cubic curve (1..=256).
    pub segments_per_span: u32,
}

impl Default for UsdOptions {
    fn default() -> UsdOptions {
        UsdOptions {
            prim: None,
            segments_per_span: DEFAULT_SEGMENTS_PER_SPAN,
        }
    }
}

impl UsdOptions {
    /// Range checks; messages name the option as `field`.
    pub fn validate(&self, prim_field: &str, segments_field: &str) -> Result<(), String> {
        if !(1..=MAX_SEGMENTS_PER_SPAN).contains(&self.segments_per_span) {
            return Err(format!(
                "{segments_field} must be in 1..={MAX_SEGMENTS_PER_SPAN}, got {}",
                self.segments_per_span
            ));
        }
        if let Some(p) = &self.prim
            && !p.starts_with('/')
        {
            return Err(format!(
                "{prim_field} must be an absolute prim path such as \"/Groom\", got {p:?}"
            ));
        }
        Ok(())
    }
}

/// One `BasisCurves` prim as read.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvesPrim {
    /// Its path.
    pub path: String,
    /// `type` and `basis`.
    pub kind: CurveKind,
    /// `wrap`.
    pub wrap: Wrap,
    /// Curves in it.
    pub curves: usize,
    /// Control points in it.
    pub points: usize,
    /// `widths`' interpolation, if authored.
    pub widths: Option<Interpolation>,
    /// `primvars:displayColor`'s interpolation, if authored.
    pub colors: Option<Interpolation>,
    /// `primvars:displayOpacity`'s interpolation, if authored.
    pub opacity: Option<Interpolation>,
}

/// A groom read from a USD stage.
#[derive(Debug, Clone, PartialEq)]
pub struct UsdGroom {
    /// The strands, in metres, Y up.
    pub strands: Strands,
    /// The prims they came from.
    pub prims: Vec<CurvesPrim>,
    /// The stage's units.
    pub units: StageUnits,
    /// The container: `usda`, `usdc` or `usdz`.
    pub container: &'static str,
    /// The options read with.
    pub options: UsdOptions,
}

impl UsdGroom {
    /// True if no prim has `widths` (the scene then gives the default look).
    pub fn lacks_widths(&self) -> bool {
        self.prims.iter().all(|p| p.widths.is_none())
    }

    /// True if no prim has `primvars:displayColor`.
    pub fn lacks_colors(&self) -> bool {
        self.prims.iter().all(|p| p.colors.is_none())
    }

    /// Reads `bytes` as the USD file `path` (named in errors; its extension
    /// picks the format). `on_disk`: layers it names resolve beside it.
    /// Warnings come back as text.
    pub fn from_bytes(
        path: &Path,
        bytes: Vec<u8>,
        options: &UsdOptions,
        on_disk: bool,
    ) -> Result<(UsdGroom, Vec<String>), UsdError> {
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            read::read(path, bytes, options, on_disk)
        }));
        let result = result.unwrap_or_else(|panic| {
            let what = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(UsdError::ReaderPanic(what))
        });
        result.map_err(|e| e.in_file(path))
    }
}

/// The container a file's bytes are.
pub fn container(bytes: &[u8]) -> &'static str {
    if bytes.starts_with(b"PXR-USDC") {
        "usdc"
    } else if bytes.starts_with(b"PK\x03\x04") {
        "usdz"
    } else {
        "usda"
    }
}

#[cfg(test)]
mod mesh_tests;
