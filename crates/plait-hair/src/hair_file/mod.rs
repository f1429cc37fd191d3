//! Cem Yuksel's binary `.hair` format (layout in `docs/formats.md`).
//!
//! Layout, all little-endian:
//!
//! | offset | size | field |
//! |---|---|---|
//! | 0 | 4 | signature `"HAIR"` |
//! | 4 | 4 | hair (strand) count, u32 |
//! | 8 | 4 | point count, u32 |
//! | 12 | 4 | array flags, u32: segments 1, points 2, thickness 4, transparency 8, colors 16 |
//! | 16 | 4 | default segments per strand, u32 (used when there is no segments array) |
//! | 20 | 4 | default thickness, f32 |
//! | 24 | 4 | default transparency, f32 |
//! | 28 | 12 | default color, 3×f32 |
//! | 40 | 88 | info string (NUL padded) |
//!
//! then the arrays that are present, in this order: segments (u16 per strand),
//! points (3×f32 per point), thickness (f32 per point), transparency (f32 per
//! point), colors (3×f32 per point).
//!
//! Reading checks every size claim of the header against the real file length
//! *before* allocating anything, using `u64` arithmetic, so a tiny file that
//! claims billions of strands fails at once.
//!
//! `read` parses and checks a file image, `write` serializes one and writes
//! it atomically; the types and accessors live here.

mod read;
#[cfg(test)]
mod tests;
mod write;

use std::fmt;
use std::path::PathBuf;

/// Size of the fixed header in bytes.
pub const HEADER_SIZE: usize = 128;
/// Size of the info string in bytes.
pub const INFO_SIZE: usize = 88;
/// The 4-byte file signature.
pub const SIGNATURE: [u8; 4] = *b"HAIR";

/// Flag bit: a segments array (u16 per strand) is present.
pub const FLAG_SEGMENTS: u32 = 1;
/// Flag bit: a points array (3×f32 per point) is present.
pub const FLAG_POINTS: u32 = 2;
/// Flag bit: a thickness array (f32 per point) is present.
pub const FLAG_THICKNESS: u32 = 4;
/// Flag bit: a transparency array (f32 per point) is present.
pub const FLAG_TRANSPARENCY: u32 = 8;
/// Flag bit: a colors array (3×f32 per point) is present.
pub const FLAG_COLORS: u32 = 16;
const KNOWN_FLAGS: u32 =
    FLAG_SEGMENTS | FLAG_POINTS | FLAG_THICKNESS | FLAG_TRANSPARENCY | FLAG_COLORS;

/// Everything that can make a `.hair` file unreadable.
#[derive(Debug, thiserror::Error)]
pub enum HairError {
    /// Reading or writing the file failed. (Not a `source()`: the message
    /// already says it, so `{:#}` chains do not repeat it.)
    #[error("{0}")]
    Io(std::io::Error),
    /// The file could not be read at all (missing, unreadable, not a
    /// regular file): `cannot read file: …`, as for every input file.
    #[error("cannot read file: {0}")]
    Read(std::io::Error),
    /// The file is shorter than the 128-byte header.
    #[error("file is {len} bytes, shorter than the 128-byte .hair header")]
    ShortHeader {
        /// File length in bytes.
        len: u64,
    },
    /// The first four bytes are not `"HAIR"`.
    #[error("not a .hair file: signature is {found:?}, expected \"HAIR\"")]
    BadSignature {
        /// The four bytes found (lossy text).
        found: String,
    },
    /// The header claims an array that does not fit in the file.
    #[error(
        "truncated {array} array: the header claims {expected} bytes at offset {offset}, but only {present} bytes are present"
    )]
    Truncated {
        /// Which array ("segments", "points", "thickness", "transparency", "colors").
        array: &'static str,
        /// Bytes the header implies for this array.
        expected: u64,
        /// Bytes the file holds from the array's offset to its end.
        present: u64,
        /// Byte offset where the array starts.
        offset: u64,
    },
    /// Sum over strands of (segments + 1) differs from the point count.
    #[error(
        "segment counts imply {implied} points (sum of segments+1 over {strands} strands) but the header says {points}"
    )]
    SegmentMismatch {
        /// Points implied by the segment counts.
        implied: u64,
        /// Point count in the header.
        points: u64,
        /// Strand count in the header.
        strands: u64,
    },
    /// A point coordinate is NaN or infinite.
    #[error("strand {strand}: point {point} has a non-finite coordinate {value:?}")]
    NonFinite {
        /// Strand index.
        strand: usize,
        /// Global point index.
        point: usize,
        /// The offending point.
        value: [f32; 3],
    },
    /// The points flag is not set.
    #[error("the file has no points array (flag bit 2 is not set)")]
    NoPoints,
    /// The data cannot be represented in the format (writing only).
    #[error("cannot write .hair data: {0}")]
    Unrepresentable(String),
    /// Any of the above, for a named file. The message is
    /// `path: inner message`; `error` is deliberately not a `source()` so
    /// that error chains (`anyhow`'s `{:#}`) do not print it twice.
    #[error("{}: {error}", path.display())]
    InFile {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        error: Box<HairError>,
    },
}

impl From<std::io::Error> for HairError {
    fn from(e: std::io::Error) -> Self {
        HairError::Io(e)
    }
}

impl HairError {
    /// Wraps `self` with the file it came from.
    pub fn in_file(self, path: impl Into<PathBuf>) -> HairError {
        HairError::InFile {
            path: path.into(),
            error: Box::new(self),
        }
    }

    /// The error without its file wrapper.
    pub fn root(&self) -> &HairError {
        match self {
            HairError::InFile { error, .. } => error.root(),
            other => other,
        }
    }
}

/// Things in a readable file that are suspicious but not fatal.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum HairWarning {
    /// Bytes after the last array.
    TrailingBytes {
        /// How many.
        count: u64,
    },
    /// Flag bits beyond the five defined ones (ignored, not written back).
    UnknownFlags {
        /// The unknown bits.
        bits: u32,
    },
}

impl fmt::Display for HairWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HairWarning::TrailingBytes { count } => {
                write!(
                    f,
                    "{count} trailing bytes after the last array were ignored"
                )
            }
            HairWarning::UnknownFlags { bits } => {
                write!(f, "unknown array flag bits {bits:#x} were ignored")
            }
        }
    }
}

/// The contents of a `.hair` file, arrays kept exactly as stored.
#[derive(Debug, Clone, PartialEq)]
pub struct HairFile {
    /// Number of strands (header field).
    pub hair_count: u32,
    /// Segments per strand, if the file has a segments array.
    pub segments: Option<Vec<u16>>,
    /// All points of all strands, strand after strand.
    pub points: Vec<[f32; 3]>,
    /// Per-point thickness, if present.
    pub thickness: Option<Vec<f32>>,
    /// Per-point transparency (0 = opaque, 1 = invisible), if present.
    pub transparency: Option<Vec<f32>>,
    /// Per-point color, if present.
    pub colors: Option<Vec<[f32; 3]>>,
    /// Segments per strand when there is no segments array.
    pub default_segments: u32,
    /// Thickness when there is no thickness array.
    pub default_thickness: f32,
    /// Transparency when there is no transparency array.
    pub default_transparency: f32,
    /// Color when there is no colors array.
    pub default_color: [f32; 3],
    /// The 88-byte info string, NUL padded.
    pub info: [u8; INFO_SIZE],
}

impl Default for HairFile {
    fn default() -> Self {
        HairFile {
            hair_count: 0,
            segments: None,
            points: Vec::new(),
            thickness: None,
            transparency: None,
            colors: None,
            default_segments: 0,
            default_thickness: 1.0,
            default_transparency: 0.0,
            default_color: [1.0, 1.0, 1.0],
            info: [0; INFO_SIZE],
        }
    }
}

impl HairFile {
    /// Number of strands.
    pub fn strand_count(&self) -> usize {
        self.hair_count as usize
    }

    /// Number of points.
    pub fn point_count(&self) -> usize {
        self.points.len()
    }

    /// Segments of strand `i` (from the array, or the default).
    pub fn strand_segments(&self, i: usize) -> u32 {
        match &self.segments {
            Some(s) => s.get(i).map_or(0, |&v| u32::from(v)),
            None => self.default_segments,
        }
    }

    /// Total number of line segments over all strands.
    pub fn segment_count(&self) -> u64 {
        (0..self.strand_count())
            .map(|i| u64::from(self.strand_segments(i)))
            .sum()
    }

    /// Names of the arrays present, in file order.
    pub fn arrays(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        if self.segments.is_some() {
            v.push("segments");
        }
        v.push("points");
        if self.thickness.is_some() {
            v.push("thickness");
        }
        if self.transparency.is_some() {
            v.push("transparency");
        }
        if self.colors.is_some() {
            v.push("colors");
        }
        v
    }

    /// The info string up to its first NUL, lossily decoded.
    pub fn info_string(&self) -> String {
        let end = self.info.iter().position(|&b| b == 0).unwrap_or(INFO_SIZE);
        String::from_utf8_lossy(&self.info[..end]).into_owned()
    }

    /// Sets the info string (truncated to 88 bytes, NUL padded).
    pub fn set_info(&mut self, text: &str) {
        self.info = [0; INFO_SIZE];
        let b = text.as_bytes();
        let n = b.len().min(INFO_SIZE);
        self.info[..n].copy_from_slice(&b[..n]);
    }

    /// Axis-aligned bounds of all points.
    pub fn bounds(&self) -> crate::Aabb {
        crate::Aabb::from_points(self.points.iter().map(|&p| glam::Vec3::from(p)))
    }
}
