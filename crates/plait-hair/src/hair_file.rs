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

use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};

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

fn u32_at(b: &[u8], off: usize) -> u32 {
    let mut a = [0u8; 4];
    a.copy_from_slice(&b[off..off + 4]);
    u32::from_le_bytes(a)
}

fn f32_at(b: &[u8], off: usize) -> f32 {
    f32::from_bits(u32_at(b, off))
}

fn read_f32s(b: &[u8], off: usize, n: usize) -> Vec<f32> {
    b[off..off + n * 4]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

fn read_vec3s(b: &[u8], off: usize, n: usize) -> Vec<[f32; 3]> {
    b[off..off + n * 12]
        .chunks_exact(12)
        .map(|c| {
            [
                f32::from_le_bytes([c[0], c[1], c[2], c[3]]),
                f32::from_le_bytes([c[4], c[5], c[6], c[7]]),
                f32::from_le_bytes([c[8], c[9], c[10], c[11]]),
            ]
        })
        .collect()
}

impl HairFile {
    /// Parses a whole file image. Warnings (trailing bytes, unknown flags) are
    /// returned beside the file; everything else that is wrong is an error.
    pub fn from_bytes(bytes: &[u8]) -> Result<(HairFile, Vec<HairWarning>), HairError> {
        let len = bytes.len() as u64;
        if bytes.len() < HEADER_SIZE {
            // Report the signature first if it is visibly wrong.
            if bytes.len() >= 4 && bytes[..4] != SIGNATURE {
                return Err(HairError::BadSignature {
                    found: String::from_utf8_lossy(&bytes[..4]).into_owned(),
                });
            }
            return Err(HairError::ShortHeader { len });
        }
        if bytes[..4] != SIGNATURE {
            return Err(HairError::BadSignature {
                found: String::from_utf8_lossy(&bytes[..4]).into_owned(),
            });
        }
        let hair_count = u32_at(bytes, 4);
        let point_count = u32_at(bytes, 8);
        let flags = u32_at(bytes, 12);
        let default_segments = u32_at(bytes, 16);
        let default_thickness = f32_at(bytes, 20);
        let default_transparency = f32_at(bytes, 24);
        let default_color = [f32_at(bytes, 28), f32_at(bytes, 32), f32_at(bytes, 36)];
        let mut info = [0u8; INFO_SIZE];
        info.copy_from_slice(&bytes[40..HEADER_SIZE]);

        let mut warnings = Vec::new();
        if flags & !KNOWN_FLAGS != 0 {
            warnings.push(HairWarning::UnknownFlags {
                bits: flags & !KNOWN_FLAGS,
            });
        }
        if flags & FLAG_POINTS == 0 {
            return Err(HairError::NoPoints);
        }

        // Size check of every array before any allocation (u64: no overflow).
        let h = u64::from(hair_count);
        let p = u64::from(point_count);
        let layout: [(&'static str, u32, u64); 5] = [
            ("segments", FLAG_SEGMENTS, h * 2),
            ("points", FLAG_POINTS, p * 12),
            ("thickness", FLAG_THICKNESS, p * 4),
            ("transparency", FLAG_TRANSPARENCY, p * 4),
            ("colors", FLAG_COLORS, p * 12),
        ];
        let mut offsets = [0u64; 5];
        let mut offset = HEADER_SIZE as u64;
        for (i, (name, flag, size)) in layout.iter().enumerate() {
            offsets[i] = offset;
            if flags & flag == 0 {
                continue;
            }
            let present = len.saturating_sub(offset);
            if *size > present {
                return Err(HairError::Truncated {
                    array: name,
                    expected: *size,
                    present,
                    offset,
                });
            }
            offset += size;
        }
        if offset < len {
            warnings.push(HairWarning::TrailingBytes {
                count: len - offset,
            });
        }

        // Segment counts must add up to the point count (checked before
        // reading the big arrays).
        let seg_off = offsets[0] as usize;
        let implied: u64 = if flags & FLAG_SEGMENTS != 0 {
            bytes[seg_off..seg_off + hair_count as usize * 2]
                .chunks_exact(2)
                .map(|c| u64::from(u16::from_le_bytes([c[0], c[1]])) + 1)
                .sum()
        } else {
            h * (u64::from(default_segments) + 1)
        };
        if implied != p {
            return Err(HairError::SegmentMismatch {
                implied,
                points: p,
                strands: h,
            });
        }

        let n = point_count as usize;
        let segments = (flags & FLAG_SEGMENTS != 0).then(|| {
            bytes[seg_off..seg_off + hair_count as usize * 2]
                .chunks_exact(2)
                .map(|c| u16::from_le_bytes([c[0], c[1]]))
                .collect::<Vec<u16>>()
        });
        let points = read_vec3s(bytes, offsets[1] as usize, n);
        let thickness =
            (flags & FLAG_THICKNESS != 0).then(|| read_f32s(bytes, offsets[2] as usize, n));
        let transparency =
            (flags & FLAG_TRANSPARENCY != 0).then(|| read_f32s(bytes, offsets[3] as usize, n));
        let colors = (flags & FLAG_COLORS != 0).then(|| read_vec3s(bytes, offsets[4] as usize, n));

        let file = HairFile {
            hair_count,
            segments,
            points,
            thickness,
            transparency,
            colors,
            default_segments,
            default_thickness,
            default_transparency,
            default_color,
            info,
        };
        file.check_finite()?;
        Ok((file, warnings))
    }

    fn check_finite(&self) -> Result<(), HairError> {
        let mut point = 0usize;
        for strand in 0..self.hair_count as usize {
            let count = self.strand_segments(strand) as usize + 1;
            for q in 0..count {
                let idx = point + q;
                if let Some(v) = self.points.get(idx)
                    && !v.iter().all(|c| c.is_finite())
                {
                    return Err(HairError::NonFinite {
                        strand,
                        point: idx,
                        value: *v,
                    });
                }
            }
            point += count;
        }
        Ok(())
    }

    /// Serializes to the exact published layout. The flags are derived from
    /// which optional arrays are `Some`; the points array is always written.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut flags = FLAG_POINTS;
        if self.segments.is_some() {
            flags |= FLAG_SEGMENTS;
        }
        if self.thickness.is_some() {
            flags |= FLAG_THICKNESS;
        }
        if self.transparency.is_some() {
            flags |= FLAG_TRANSPARENCY;
        }
        if self.colors.is_some() {
            flags |= FLAG_COLORS;
        }
        let n = self.points.len();
        let mut out = Vec::with_capacity(HEADER_SIZE + self.hair_count as usize * 2 + n * 32);
        out.extend_from_slice(&SIGNATURE);
        out.extend_from_slice(&self.hair_count.to_le_bytes());
        out.extend_from_slice(&(n as u32).to_le_bytes());
        out.extend_from_slice(&flags.to_le_bytes());
        out.extend_from_slice(&self.default_segments.to_le_bytes());
        out.extend_from_slice(&self.default_thickness.to_le_bytes());
        out.extend_from_slice(&self.default_transparency.to_le_bytes());
        for c in self.default_color {
            out.extend_from_slice(&c.to_le_bytes());
        }
        out.extend_from_slice(&self.info);
        if let Some(segs) = &self.segments {
            for s in segs {
                out.extend_from_slice(&s.to_le_bytes());
            }
        }
        for p in &self.points {
            for c in p {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        for arr in [&self.thickness, &self.transparency].into_iter().flatten() {
            for v in arr {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
        if let Some(colors) = &self.colors {
            for p in colors {
                for c in p {
                    out.extend_from_slice(&c.to_le_bytes());
                }
            }
        }
        out
    }

    /// Reads and parses a file; errors name the file.
    pub fn read(path: impl AsRef<Path>) -> Result<(HairFile, Vec<HairWarning>), HairError> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|e| HairError::Io(e).in_file(path))?;
        HairFile::from_bytes(&bytes).map_err(|e| e.in_file(path))
    }

    /// Writes the file atomically: a temporary file in the same directory is
    /// written, flushed, and renamed over `path`, so readers never see a
    /// half-written file.
    pub fn write(&self, path: impl AsRef<Path>) -> Result<(), HairError> {
        let path = path.as_ref();
        self.write_inner(path).map_err(|e| e.in_file(path))
    }

    fn write_inner(&self, path: &Path) -> Result<(), HairError> {
        let bytes = self.to_bytes();
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = path
            .file_name()
            .ok_or_else(|| HairError::Unrepresentable("output path has no file name".into()))?;
        let mut tmp_name = std::ffi::OsString::from(".");
        tmp_name.push(name);
        tmp_name.push(format!(".{}.tmp", std::process::id()));
        let tmp = dir.join(tmp_name);
        let result = (|| -> std::io::Result<()> {
            let mut f = std::fs::File::create(&tmp)?;
            f.write_all(&bytes)?;
            f.sync_all()?;
            drop(f);
            std::fs::rename(&tmp, path)
        })();
        if let Err(e) = result {
            let _ = std::fs::remove_file(&tmp);
            return Err(HairError::Io(e));
        }
        Ok(())
    }

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

#[cfg(test)]
mod tests {
    use super::*;

    /// An independent writer: builds a file byte by byte from the published
    /// layout, without using `to_bytes`.
    fn independent_file() -> Vec<u8> {
        let mut b: Vec<u8> = Vec::new();
        b.extend_from_slice(b"HAIR");
        b.extend_from_slice(&2u32.to_le_bytes()); // 2 strands
        b.extend_from_slice(&5u32.to_le_bytes()); // 5 points
        b.extend_from_slice(&(1u32 | 2 | 8).to_le_bytes()); // segments, points, transparency
        b.extend_from_slice(&7u32.to_le_bytes()); // default segments (unused: array present)
        b.extend_from_slice(&0.25f32.to_le_bytes()); // default thickness
        b.extend_from_slice(&0.5f32.to_le_bytes()); // default transparency
        for c in [0.1f32, 0.2, 0.3] {
            b.extend_from_slice(&c.to_le_bytes());
        }
        let mut info = [0u8; 88];
        info[..11].copy_from_slice(b"independent");
        b.extend_from_slice(&info);
        assert_eq!(b.len(), 128);
        b.extend_from_slice(&1u16.to_le_bytes()); // strand 0: 1 segment, 2 points
        b.extend_from_slice(&2u16.to_le_bytes()); // strand 1: 2 segments, 3 points
        for i in 0..5 {
            for c in [i as f32, 2.0 * i as f32, -(i as f32)] {
                b.extend_from_slice(&c.to_le_bytes());
            }
        }
        for i in 0..5 {
            b.extend_from_slice(&(i as f32 * 0.1).to_le_bytes());
        }
        b
    }

    #[test]
    fn reads_independent_writer() {
        let bytes = independent_file();
        let (f, w) = HairFile::from_bytes(&bytes).expect("valid file");
        assert!(w.is_empty());
        assert_eq!(f.hair_count, 2);
        assert_eq!(f.points.len(), 5);
        assert_eq!(f.segments.as_deref(), Some(&[1u16, 2][..]));
        assert_eq!(f.points[3], [3.0, 6.0, -3.0]);
        assert_eq!(f.default_segments, 7);
        assert_eq!(f.default_thickness, 0.25);
        assert_eq!(f.default_transparency, 0.5);
        assert_eq!(f.default_color, [0.1, 0.2, 0.3]);
        assert!(f.thickness.is_none() && f.colors.is_none());
        assert_eq!(f.transparency.as_ref().map(|t| t[2]), Some(0.2));
        assert_eq!(f.info_string(), "independent");
        assert_eq!(f.arrays(), vec!["segments", "points", "transparency"]);
        assert_eq!(f.segment_count(), 3);
        // and writing it back is bit-identical
        assert_eq!(f.to_bytes(), bytes);
    }

    fn full_file() -> HairFile {
        let mut f = HairFile {
            hair_count: 3,
            segments: Some(vec![0, 2, 1]),
            points: (0..6)
                .map(|i| [i as f32, -0.5 * i as f32, 1e-7 * i as f32])
                .collect(),
            thickness: Some((0..6).map(|i| 0.01 * i as f32).collect()),
            transparency: Some((0..6).map(|i| 0.1 * i as f32).collect()),
            colors: Some(
                (0..6)
                    .map(|i| [0.1 * i as f32, 0.2, f32::MIN_POSITIVE])
                    .collect(),
            ),
            default_segments: 3,
            default_thickness: 0.5,
            default_transparency: 0.25,
            default_color: [0.4, 0.5, 0.6],
            info: [0; INFO_SIZE],
        };
        f.set_info("plait test");
        f
    }

    #[test]
    fn round_trip_all_arrays_bit_identical() {
        let f = full_file();
        let bytes = f.to_bytes();
        assert_eq!(bytes.len(), 128 + 3 * 2 + 6 * (12 + 4 + 4 + 12));
        let (g, w) = HairFile::from_bytes(&bytes).expect("round trip");
        assert!(w.is_empty());
        assert_eq!(g, f);
        assert_eq!(g.to_bytes(), bytes);
    }

    #[test]
    fn round_trip_defaults_only_and_files() {
        let f = HairFile {
            hair_count: 2,
            default_segments: 2,
            points: (0..6).map(|i| [i as f32; 3]).collect(),
            ..HairFile::default()
        };
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("a.hair");
        f.write(&path).expect("write");
        let bytes = std::fs::read(&path).expect("read back");
        let (g, _) = HairFile::read(&path).expect("read");
        assert_eq!(g, f);
        assert_eq!(g.to_bytes(), bytes);
        // no temp file left behind
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .expect("dir")
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(names.len(), 1);
    }

    fn root(e: &HairError) -> &HairError {
        e.root()
    }

    #[test]
    fn bad_signature() {
        let mut b = independent_file();
        b[0] = b'X';
        let e = HairFile::from_bytes(&b).unwrap_err();
        assert!(matches!(e, HairError::BadSignature { .. }), "{e}");
        assert!(e.to_string().contains("HAIR"));
    }

    #[test]
    fn short_header() {
        let b = &independent_file()[..100];
        assert!(matches!(
            HairFile::from_bytes(b).unwrap_err(),
            HairError::ShortHeader { len: 100 }
        ));
    }

    #[test]
    fn truncated_array_names_array_and_sizes() {
        let b = independent_file();
        let cut = &b[..b.len() - 3];
        let e = HairFile::from_bytes(cut).unwrap_err();
        match &e {
            HairError::Truncated {
                array,
                expected,
                present,
                ..
            } => {
                assert_eq!(*array, "transparency");
                assert_eq!(*expected, 20);
                assert_eq!(*present, 17);
            }
            other => panic!("wrong error {other}"),
        }
        let msg = e.to_string();
        assert!(
            msg.contains("transparency") && msg.contains("20") && msg.contains("17"),
            "{msg}"
        );
    }

    #[test]
    fn huge_claim_fails_fast_without_allocating() {
        let mut b = vec![0u8; 1024];
        b[..4].copy_from_slice(b"HAIR");
        b[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
        b[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
        b[12..16].copy_from_slice(&(FLAG_SEGMENTS | FLAG_POINTS | FLAG_COLORS).to_le_bytes());
        let start = std::time::Instant::now();
        let e = HairFile::from_bytes(&b).unwrap_err();
        assert!(start.elapsed().as_secs_f32() < 0.5);
        match e {
            HairError::Truncated {
                array,
                expected,
                present,
                ..
            } => {
                assert_eq!(array, "segments");
                assert_eq!(expected, u64::from(u32::MAX) * 2);
                assert_eq!(present, 1024 - 128);
            }
            other => panic!("wrong error {other}"),
        }
        // without a segments array the points array is the one reported
        b[12..16].copy_from_slice(&FLAG_POINTS.to_le_bytes());
        match HairFile::from_bytes(&b).unwrap_err() {
            HairError::Truncated {
                array, expected, ..
            } => {
                assert_eq!(array, "points");
                assert_eq!(expected, u64::from(u32::MAX) * 12);
            }
            other => panic!("wrong error {other}"),
        }
    }

    #[test]
    fn segment_mismatch() {
        let mut b = independent_file();
        b[128..130].copy_from_slice(&3u16.to_le_bytes()); // 4 + 3 = 7 != 5
        let e = HairFile::from_bytes(&b).unwrap_err();
        assert!(
            matches!(
                e,
                HairError::SegmentMismatch {
                    implied: 7,
                    points: 5,
                    strands: 2
                }
            ),
            "{e}"
        );
        // default segments path
        let f = HairFile {
            hair_count: 2,
            default_segments: 2,
            points: vec![[0.0; 3]; 5],
            ..HairFile::default()
        };
        let e = HairFile::from_bytes(&f.to_bytes()).unwrap_err();
        assert!(
            matches!(
                e,
                HairError::SegmentMismatch {
                    implied: 6,
                    points: 5,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn non_finite_names_strand() {
        let mut f = full_file();
        f.points[4] = [0.0, f32::NAN, 0.0]; // strand 2 (points 4..6)
        let e = HairFile::from_bytes(&f.to_bytes()).unwrap_err();
        assert!(
            matches!(
                e,
                HairError::NonFinite {
                    strand: 2,
                    point: 4,
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("strand 2"));
        f.points[4] = [0.0, 0.0, 0.0];
        f.points[1] = [f32::INFINITY, 0.0, 0.0];
        let e = HairFile::from_bytes(&f.to_bytes()).unwrap_err();
        assert!(matches!(e, HairError::NonFinite { strand: 1, .. }), "{e}");
    }

    #[test]
    fn no_points_array() {
        let mut b = independent_file();
        b[12..16].copy_from_slice(&1u32.to_le_bytes());
        assert!(matches!(
            HairFile::from_bytes(&b).unwrap_err(),
            HairError::NoPoints
        ));
    }

    #[test]
    fn trailing_garbage_is_a_warning() {
        let mut b = independent_file();
        b.extend_from_slice(b"garbage");
        let (f, w) = HairFile::from_bytes(&b).expect("still readable");
        assert_eq!(f.points.len(), 5);
        assert_eq!(w, vec![HairWarning::TrailingBytes { count: 7 }]);
        assert!(w[0].to_string().contains('7'));
    }

    #[test]
    fn unknown_flags_are_a_warning() {
        let mut b = independent_file();
        b[12..16].copy_from_slice(&(1u32 | 2 | 8 | 64).to_le_bytes());
        let (_, w) = HairFile::from_bytes(&b).expect("readable");
        assert_eq!(w, vec![HairWarning::UnknownFlags { bits: 64 }]);
    }

    #[test]
    fn read_errors_name_the_file() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("bad.hair");
        std::fs::write(&path, b"NOPE and some more bytes").expect("write");
        let e = HairFile::read(&path).unwrap_err();
        assert!(e.to_string().contains("bad.hair"), "{e}");
        assert!(matches!(root(&e), HairError::BadSignature { .. }));
        let missing = dir.path().join("missing.hair");
        let e = HairFile::read(&missing).unwrap_err();
        assert!(e.to_string().contains("missing.hair"), "{e}");
    }
}
