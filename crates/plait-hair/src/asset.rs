//! Hair asset files of any format, told apart by their content: Cem
//! Yuksel's `.hair` starts with `"HAIR"`; a USD file is read as USD when its
//! name ends in `.usd`, `.usda`, `.usdc` or `.usdz` (the reader then tells
//! text, crate and package apart by content); a TressFX `.tfx` has no
//! signature, so a file is read as `.tfx` when its name ends in `.tfx` or its
//! first four bytes are a TressFX version (3.x or 4.x as an f32).

use std::path::{Path, PathBuf};

use crate::hair_file::{self, HairError, HairFile};
use crate::strands::Strands;
use crate::tfx::{TfxError, TfxFile};
use crate::usd::{UsdError, UsdGroom, UsdOptions};

/// A hair asset format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Cem Yuksel's `.hair`.
    Hair,
    /// AMD TressFX's `.tfx`.
    Tfx,
    /// USD `BasisCurves` (`.usd`, `.usda`, `.usdc`, `.usdz`).
    Usd,
}

impl Format {
    /// The format a path's extension names, if any.
    pub fn from_extension(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "hair" => Some(Format::Hair),
            "tfx" => Some(Format::Tfx),
            "usd" | "usda" | "usdc" | "usdz" => Some(Format::Usd),
            _ => None,
        }
    }

    /// The format of a file's bytes (see the module docs), or `None`.
    pub fn detect(path: &Path, bytes: &[u8]) -> Option<Format> {
        if bytes.starts_with(&hair_file::SIGNATURE) {
            return Some(Format::Hair);
        }
        if let Some(format) = Format::from_extension(path) {
            return Some(format);
        }
        let version = bytes
            .get(..4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))?;
        (3.0..5.0).contains(&version).then_some(Format::Tfx)
    }
}

/// Reading an asset failed; the message names the file.
#[derive(Debug, thiserror::Error)]
pub enum AssetError {
    /// A `.hair` problem.
    #[error(transparent)]
    Hair(#[from] HairError),
    /// A `.tfx` problem.
    #[error(transparent)]
    Tfx(#[from] TfxError),
    /// A USD problem.
    #[error(transparent)]
    Usd(#[from] UsdError),
    /// Neither format.
    #[error(
        "{}: not a hair asset: a .hair file starts with \"HAIR\", a .tfx file with a TressFX version (3.x or 4.x); name a TressFX file *.tfx and a USD file *.usda, *.usdc, *.usdz or *.usd",
        path.display()
    )]
    Unknown {
        /// The file.
        path: PathBuf,
    },
}

/// A parsed asset, as stored.
#[derive(Debug, Clone, PartialEq)]
pub enum Asset {
    /// A `.hair` file.
    Hair(HairFile),
    /// A `.tfx` file.
    Tfx(TfxFile),
    /// A USD stage's `BasisCurves`, evaluated.
    Usd(UsdGroom),
}

impl Asset {
    /// Parses `bytes` (named `path` in messages and for format detection);
    /// warnings come back as text.
    pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<(Asset, Vec<String>), AssetError> {
        Asset::from_bytes_with(path, bytes, &UsdOptions::default())
    }

    /// [`Asset::from_bytes`] with what to read from a USD stage (ignored for
    /// other formats). Layers a USD file names are not read: there is no
    /// file to find them beside.
    pub fn from_bytes_with(
        path: &Path,
        bytes: &[u8],
        usd: &UsdOptions,
    ) -> Result<(Asset, Vec<String>), AssetError> {
        Asset::parse(path, bytes.to_vec(), usd, false)
    }

    fn parse(
        path: &Path,
        bytes: Vec<u8>,
        usd: &UsdOptions,
        on_disk: bool,
    ) -> Result<(Asset, Vec<String>), AssetError> {
        match Format::detect(path, &bytes) {
            Some(Format::Usd) => {
                let (groom, warnings) = UsdGroom::from_bytes(path, bytes, usd, on_disk)?;
                Ok((Asset::Usd(groom), warnings))
            }
            Some(Format::Hair) => {
                let (file, warnings) = HairFile::from_bytes(&bytes).map_err(|e| e.in_file(path))?;
                Ok((Asset::Hair(file), texts(&warnings)))
            }
            Some(Format::Tfx) => {
                let (file, warnings) = TfxFile::from_bytes(&bytes).map_err(|e| e.in_file(path))?;
                Ok((Asset::Tfx(file), texts(&warnings)))
            }
            None => Err(AssetError::Unknown {
                path: path.to_path_buf(),
            }),
        }
    }

    /// Reads a file of any format (a USD stage whole, at the default
    /// segments per span).
    pub fn read(path: impl AsRef<Path>) -> Result<(Asset, Vec<String>), AssetError> {
        Asset::read_with(path, &UsdOptions::default())
    }

    /// [`Asset::read`] with what to read from a USD stage (ignored for other
    /// formats); layers a USD file names resolve beside it.
    pub fn read_with(
        path: impl AsRef<Path>,
        usd: &UsdOptions,
    ) -> Result<(Asset, Vec<String>), AssetError> {
        let path = path.as_ref();
        // A device or pipe (/dev/zero, a FIFO) would be read forever.
        let meta = std::fs::metadata(path).map_err(|e| HairError::Read(e).in_file(path))?;
        if !meta.is_file() {
            let e = std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a regular file");
            return Err(HairError::Read(e).in_file(path).into());
        }
        let bytes = std::fs::read(path).map_err(|e| HairError::Read(e).in_file(path))?;
        Asset::parse(path, bytes, usd, true)
    }

    /// The renderable strands.
    pub fn strands(&self) -> Strands {
        match self {
            Asset::Hair(file) => Strands::from_hair_file(file),
            Asset::Tfx(file) => Strands::from(file),
            Asset::Usd(groom) => groom.strands.clone(),
        }
    }
}

fn texts<T: std::fmt::Display>(warnings: &[T]) -> Vec<String> {
    warnings.iter().map(ToString::to_string).collect()
}
