//! AMD TressFX's binary `.tfx` format, versions 3 and 4 (layout in
//! `docs/formats.md`, read from the format's public description in TressFX's
//! `TressFXFileFormat.h`).
//!
//! Both versions are little-endian: a fixed header, then arrays at byte
//! offsets the header gives (0 = absent). Every strand has the same number of
//! vertices. TressFX 4 (160-byte header) stores positions as float4 (w is the
//! simulation's inverse mass); TressFX 3 (296-byte header) as float3.
//!
//! | TressFX 4 offset | type | field |
//! |---:|---|---|
//! | 0 | f32 | version (4.x) |
//! | 4 | u32 | strand count |
//! | 8 | u32 | vertices per strand |
//! | 12 | u32 | offset of positions, float4 per vertex |
//! | 16 | u32 | offset of strand UVs, float2 per strand |
//! | 20 | u32 | offset of vertex UVs, float2 per vertex |
//! | 24 | u32 | offset of strand thickness, f32 per strand |
//! | 28 | u32 | offset of vertex colours, float4 per vertex |
//! | 32 | 32 × u32 | reserved |
//!
//! Reading checks every array the header claims against the real file length
//! in `u64` arithmetic *before* allocating, so a small file claiming billions
//! of strands fails at once with the field named.

use std::fmt;
use std::path::{Path, PathBuf};

mod convert;

/// Header size of TressFX 4 files.
pub const V4_HEADER_SIZE: usize = 160;
/// Header size of TressFX 3 files.
pub const V3_HEADER_SIZE: usize = 296;
/// Vertex counts TressFX itself loads (its simulation runs one strand per
/// part of a 64-thread group); plait reads any count ≥ 2.
pub const TRESSFX_VERTEX_COUNTS: [u32; 5] = [4, 8, 16, 32, 64];

/// Everything that can make a `.tfx` file unreadable or unwritable.
#[derive(Debug, thiserror::Error)]
pub enum TfxError {
    /// Reading or writing failed (the message says it; not a `source()`).
    #[error("{0}")]
    Io(std::io::Error),
    /// The file could not be read at all: `cannot read file: …`, as for
    /// every input file.
    #[error("cannot read file: {0}")]
    Read(std::io::Error),
    /// The file is shorter than the header its version needs.
    #[error("file is {len} bytes, shorter than the {need}-byte TressFX {major} header")]
    ShortHeader {
        /// File length.
        len: u64,
        /// Header size.
        need: usize,
        /// Major version the header is for.
        major: u32,
    },
    /// The version field is not 3.x or 4.x.
    #[error(
        "field `version` is {version}: plait reads TressFX 3.x and 4.x files (is this a .tfx file?)"
    )]
    UnsupportedVersion {
        /// The version float as stored.
        version: f32,
    },
    /// A count in the header is out of range.
    #[error("field `{field}` is {value}: {reason}")]
    BadCount {
        /// Header field name.
        field: &'static str,
        /// Its value.
        value: u64,
        /// Why it cannot be.
        reason: &'static str,
    },
    /// An array offset points into the header.
    #[error("field `{field}` is {offset}, inside the {header}-byte header")]
    OffsetInHeader {
        /// Header field holding the offset.
        field: &'static str,
        /// The offset.
        offset: u64,
        /// Header size.
        header: usize,
    },
    /// The header claims an array that does not fit in the file.
    #[error(
        "truncated {array} array: the header claims {expected} bytes at offset {offset} (field `{field}`), but only {present} bytes are there"
    )]
    Truncated {
        /// The array.
        array: &'static str,
        /// Header field holding its offset.
        field: &'static str,
        /// Bytes the header implies.
        expected: u64,
        /// Bytes present from the offset to the end of the file.
        present: u64,
        /// Where the array starts.
        offset: u64,
    },
    /// A value is NaN or infinite.
    #[error("{array} of strand {strand}, vertex {vertex} is not finite: {value:?}")]
    NonFinite {
        /// The array.
        array: &'static str,
        /// Strand index.
        strand: usize,
        /// Vertex index within the strand (0 for per-strand arrays).
        vertex: usize,
        /// The values.
        value: Vec<f32>,
    },
    /// The data cannot be written as `.tfx`.
    #[error("cannot write .tfx data: {0}")]
    Unrepresentable(String),
    /// Any of the above for a named file (`path: message`; not a `source()`,
    /// so `{:#}` chains print it once).
    #[error("{}: {error}", path.display())]
    InFile {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        error: Box<TfxError>,
    },
}

impl From<std::io::Error> for TfxError {
    fn from(e: std::io::Error) -> Self {
        TfxError::Io(e)
    }
}

impl TfxError {
    /// Wraps `self` with the file it came from.
    pub fn in_file(self, path: impl Into<PathBuf>) -> TfxError {
        TfxError::InFile {
            path: path.into(),
            error: Box::new(self),
        }
    }

    /// The error without its file wrapper.
    pub fn root(&self) -> &TfxError {
        match self {
            TfxError::InFile { error, .. } => error.root(),
            other => other,
        }
    }
}

/// Readable but worth telling the user.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TfxWarning {
    /// TressFX itself would refuse this vertex count.
    VertexCountNotTressFx {
        /// The count.
        count: u32,
    },
}

impl fmt::Display for TfxWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TfxWarning::VertexCountNotTressFx { count } => write!(
                f,
                "{count} vertices per strand: plait reads it, TressFX itself loads only 4, 8, 16, 32 or 64"
            ),
        }
    }
}

/// The contents of a `.tfx` file, arrays as stored.
#[derive(Debug, Clone, PartialEq)]
pub struct TfxFile {
    /// The version field (3.x or 4.x when read; 4.0 is written for 3.x).
    pub version: f32,
    /// Vertices per strand (≥ 2), the same for every strand.
    pub vertices_per_strand: u32,
    /// All vertices, strand after strand.
    pub positions: Vec<[f32; 3]>,
    /// TressFX 4's position w (inverse mass: 0 pins a vertex). `None` for
    /// TressFX 3 files; written as 0 for the first two vertices of a strand
    /// and 1 for the others, as TressFX 3 assigns it.
    pub inverse_mass: Option<Vec<f32>>,
    /// Per-strand texture coordinates.
    pub strand_uv: Option<Vec<[f32; 2]>>,
    /// Per-vertex texture coordinates.
    pub vertex_uv: Option<Vec<[f32; 2]>>,
    /// Per-strand thickness.
    pub strand_thickness: Option<Vec<f32>>,
    /// Per-vertex RGBA colour.
    pub vertex_color: Option<Vec<[f32; 4]>>,
    /// TressFX 3 header only: the follow strands the exporter suggested per
    /// guide (TressFX's runtime takes it from its project file instead).
    pub follow_strands_per_guide: u32,
    /// TressFX 3 header only: pin the last two vertices too.
    pub both_ends_immovable: bool,
    /// TressFX 3 only: a u32 per strand marking guides (read, not used).
    pub guide_flags: Option<Vec<u32>>,
}

/// Where one array lives: header field, element size, per strand or vertex.
struct ArraySpec {
    name: &'static str,
    field: &'static str,
    header_offset: usize,
    element_bytes: u64,
    per_vertex: bool,
}

const fn array(
    name: &'static str,
    field: &'static str,
    header_offset: usize,
    element_bytes: u64,
    per_vertex: bool,
) -> ArraySpec {
    ArraySpec {
        name,
        field,
        header_offset,
        element_bytes,
        per_vertex,
    }
}

// Order matches `Arrays` below.
const V4_ARRAYS: [ArraySpec; 5] = [
    array("positions", "offsetVertexPosition", 12, 16, true),
    array("strand UV", "offsetStrandUV", 16, 8, false),
    array("vertex UV", "offsetVertexUV", 20, 8, true),
    array("strand thickness", "offsetStrandThickness", 24, 4, false),
    array("vertex colour", "offsetVertexColor", 28, 16, true),
];

// After version, numGuideHairStrands, numVerticesPerStrand,
// numFollowHairsPerGuideHair, bothEndsImmovable and 31 reserved u32.
const V3_ARRAYS: [ArraySpec; 6] = [
    array("positions", "verticesOffset", 144, 12, true),
    array(
        "strand thickness",
        "perStrandThicknessOffset",
        148,
        4,
        false,
    ),
    array("strand UV", "perStrandTexCoordOffset", 152, 8, false),
    array("vertex colour", "perVertexColorOffset", 156, 16, true),
    array("guide flags", "guideHairStrandOffset", 160, 4, false),
    array("vertex UV", "perVertexTexCoordOffset", 164, 8, true),
];

fn u32_at(b: &[u8], off: usize) -> u32 {
    u32::from_le_bytes([b[off], b[off + 1], b[off + 2], b[off + 3]])
}

fn f32s<const N: usize>(b: &[u8], off: usize, count: usize, stride: usize) -> Vec<[f32; N]> {
    (0..count)
        .map(|i| {
            let at = off + i * stride;
            std::array::from_fn(|k| f32::from_bits(u32_at(b, at + 4 * k)))
        })
        .collect()
}

impl TfxFile {
    /// Number of strands.
    pub fn strand_count(&self) -> usize {
        self.positions.len() / (self.vertices_per_strand.max(1) as usize)
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// The major version the file was read as (3 or 4).
    pub fn major_version(&self) -> u32 {
        if self.version < 4.0 { 3 } else { 4 }
    }

    /// Names of the optional arrays present.
    pub fn arrays(&self) -> Vec<&'static str> {
        let mut v = vec!["positions"];
        let present = [
            (self.strand_uv.is_some(), "strand UV"),
            (self.vertex_uv.is_some(), "vertex UV"),
            (self.strand_thickness.is_some(), "strand thickness"),
            (self.vertex_color.is_some(), "vertex colour"),
            (self.guide_flags.is_some(), "guide flags"),
        ];
        v.extend(present.iter().filter(|(p, _)| *p).map(|(_, n)| *n));
        v
    }

    /// Bounds of all positions.
    pub fn bounds(&self) -> crate::Aabb {
        crate::Aabb::from_points(self.positions.iter().map(|&p| glam::Vec3::from(p)))
    }

    /// Parses a whole file image.
    pub fn from_bytes(bytes: &[u8]) -> Result<(TfxFile, Vec<TfxWarning>), TfxError> {
        let len = bytes.len() as u64;
        if bytes.len() < 4 {
            return Err(TfxError::ShortHeader {
                len,
                need: V4_HEADER_SIZE,
                major: 4,
            });
        }
        let version = f32::from_bits(u32_at(bytes, 0));
        let (major, header, specs): (u32, usize, &[ArraySpec]) = match version {
            v if (3.0..4.0).contains(&v) => (3, V3_HEADER_SIZE, &V3_ARRAYS),
            v if (4.0..5.0).contains(&v) => (4, V4_HEADER_SIZE, &V4_ARRAYS),
            _ => return Err(TfxError::UnsupportedVersion { version }),
        };
        if bytes.len() < header {
            return Err(TfxError::ShortHeader {
                len,
                need: header,
                major,
            });
        }
        let strands = u64::from(u32_at(bytes, 4));
        let per_strand = u64::from(u32_at(bytes, 8));
        let (strands_field, per_field) = if major == 3 {
            ("numGuideHairStrands", "numVerticesPerStrand")
        } else {
            ("numHairStrands", "numVerticesPerStrand")
        };
        if strands == 0 {
            return Err(TfxError::BadCount {
                field: strands_field,
                value: 0,
                reason: "the file holds no strand",
            });
        }
        if per_strand < 2 {
            return Err(TfxError::BadCount {
                field: per_field,
                value: per_strand,
                reason: "a strand needs at least 2 vertices",
            });
        }
        let vertices = strands * per_strand;
        // Where every present array starts, each checked against the file
        // length before anything is allocated.
        let mut offsets = Vec::with_capacity(specs.len());
        for spec in specs {
            let offset = u64::from(u32_at(bytes, spec.header_offset));
            if offset == 0 {
                if spec.name == "positions" {
                    return Err(TfxError::BadCount {
                        field: spec.field,
                        value: 0,
                        reason: "the positions array is required",
                    });
                }
                offsets.push(None);
                continue;
            }
            if offset < header as u64 {
                return Err(TfxError::OffsetInHeader {
                    field: spec.field,
                    offset,
                    header,
                });
            }
            let count = if spec.per_vertex { vertices } else { strands };
            // Saturating: u32 × u32 × 16 can pass 2^64 (found by fuzzing).
            let expected = count.saturating_mul(spec.element_bytes);
            let present = len.saturating_sub(offset);
            if expected > present {
                return Err(TfxError::Truncated {
                    array: spec.name,
                    field: spec.field,
                    expected,
                    present,
                    offset,
                });
            }
            offsets.push(Some(offset as usize));
        }
        // Every count now fits in the file, so usize arithmetic is safe.
        let (s, n) = (strands as usize, vertices as usize);
        let at = |name: &str| {
            specs
                .iter()
                .position(|spec| spec.name == name)
                .and_then(|i| offsets[i])
        };
        let pos_at = at("positions").unwrap_or(header);
        let stride = if major == 4 { 16 } else { 12 };
        let positions: Vec<[f32; 3]> = f32s(bytes, pos_at, n, stride);
        let inverse_mass = (major == 4).then(|| {
            (0..n)
                .map(|i| f32::from_bits(u32_at(bytes, pos_at + i * 16 + 12)))
                .collect()
        });
        let file = TfxFile {
            version,
            vertices_per_strand: per_strand as u32,
            positions,
            inverse_mass,
            strand_uv: at("strand UV").map(|o| f32s(bytes, o, s, 8)),
            vertex_uv: at("vertex UV").map(|o| f32s(bytes, o, n, 8)),
            strand_thickness: at("strand thickness")
                .map(|o| f32s::<1>(bytes, o, s, 4).into_iter().map(|[t]| t).collect()),
            vertex_color: at("vertex colour").map(|o| f32s(bytes, o, n, 16)),
            follow_strands_per_guide: if major == 3 { u32_at(bytes, 12) } else { 0 },
            both_ends_immovable: major == 3 && u32_at(bytes, 16) != 0,
            guide_flags: at("guide flags")
                .map(|o| (0..s).map(|i| u32_at(bytes, o + 4 * i)).collect()),
        };
        file.check_finite()?;
        let mut warnings = Vec::new();
        if !TRESSFX_VERTEX_COUNTS.contains(&file.vertices_per_strand) {
            warnings.push(TfxWarning::VertexCountNotTressFx {
                count: file.vertices_per_strand,
            });
        }
        Ok((file, warnings))
    }

    /// Positions, thickness and colours must be finite (UVs and inverse
    /// mass are not used by plait, so they are kept as they are).
    fn check_finite(&self) -> Result<(), TfxError> {
        let per = self.vertices_per_strand.max(1) as usize;
        let bad =
            |array: &'static str, index: usize, per: usize, value: &[f32]| TfxError::NonFinite {
                array,
                strand: index / per,
                vertex: index % per,
                value: value.to_vec(),
            };
        if let Some(i) = self.positions.iter().position(|p| !all_finite(p)) {
            return Err(bad("position", i, per, &self.positions[i]));
        }
        if let Some(t) = &self.strand_thickness
            && let Some(i) = t.iter().position(|t| !t.is_finite())
        {
            return Err(bad("thickness", i, 1, &t[i..=i]));
        }
        if let Some(c) = &self.vertex_color
            && let Some(i) = c.iter().position(|c| !all_finite(c))
        {
            return Err(bad("colour", i, per, &c[i]));
        }
        Ok(())
    }

    /// Serializes as TressFX 4 (the version field is kept if it is 4.x, else
    /// 4.0): the header, then positions, strand UVs, vertex UVs, strand
    /// thickness and vertex colours, each present array starting on an
    /// 8-byte boundary as the format asks.
    pub fn to_bytes(&self) -> Result<Vec<u8>, TfxError> {
        let per = self.vertices_per_strand;
        let n = self.positions.len();
        if per < 2 || n == 0 || !n.is_multiple_of(per as usize) {
            return Err(TfxError::Unrepresentable(format!(
                "{n} vertices are not whole strands of {per} (≥ 2) vertices"
            )));
        }
        let s = n / per as usize;
        let lengths_ok = [
            self.inverse_mass.as_ref().is_none_or(|v| v.len() == n),
            self.strand_uv.as_ref().is_none_or(|v| v.len() == s),
            self.vertex_uv.as_ref().is_none_or(|v| v.len() == n),
            self.strand_thickness.as_ref().is_none_or(|v| v.len() == s),
            self.vertex_color.as_ref().is_none_or(|v| v.len() == n),
        ];
        if lengths_ok.contains(&false) {
            return Err(TfxError::Unrepresentable(
                "an optional array's length does not match the strand or vertex count".into(),
            ));
        }
        let sizes = [
            n as u64 * 16,
            self.strand_uv.as_ref().map_or(0, |_| s as u64 * 8),
            self.vertex_uv.as_ref().map_or(0, |_| n as u64 * 8),
            self.strand_thickness.as_ref().map_or(0, |_| s as u64 * 4),
            self.vertex_color.as_ref().map_or(0, |_| n as u64 * 16),
        ];
        let mut offsets = [0u64; 5];
        let mut end = V4_HEADER_SIZE as u64;
        for (offset, size) in offsets.iter_mut().zip(sizes) {
            if size > 0 {
                *offset = end;
                end = (end + size).next_multiple_of(8);
            }
        }
        if end > u64::from(u32::MAX) || s > u32::MAX as usize {
            return Err(TfxError::Unrepresentable(format!(
                "{end} bytes: .tfx offsets are 32-bit"
            )));
        }
        let mut out = Vec::with_capacity(end as usize);
        let version = if (4.0..5.0).contains(&self.version) {
            self.version
        } else {
            4.0
        };
        out.extend_from_slice(&version.to_le_bytes());
        out.extend_from_slice(&(s as u32).to_le_bytes());
        out.extend_from_slice(&per.to_le_bytes());
        for o in offsets {
            out.extend_from_slice(&(o as u32).to_le_bytes());
        }
        out.resize(V4_HEADER_SIZE, 0);
        let pad = |out: &mut Vec<u8>| out.resize(out.len().next_multiple_of(8), 0);
        let put = |out: &mut Vec<u8>, values: &[f32]| {
            for v in values {
                out.extend_from_slice(&v.to_le_bytes());
            }
        };
        for (i, p) in self.positions.iter().enumerate() {
            let w = match &self.inverse_mass {
                Some(m) => m[i],
                None if i % per as usize <= 1 => 0.0,
                None => 1.0,
            };
            put(&mut out, &[p[0], p[1], p[2], w]);
        }
        for uv in self.strand_uv.iter().flatten() {
            put(&mut out, uv);
        }
        pad(&mut out);
        for uv in self.vertex_uv.iter().flatten() {
            put(&mut out, uv);
        }
        pad(&mut out);
        put(&mut out, self.strand_thickness.as_deref().unwrap_or(&[]));
        pad(&mut out);
        for c in self.vertex_color.iter().flatten() {
            put(&mut out, c);
        }
        pad(&mut out);
        debug_assert_eq!(out.len() as u64, end);
        Ok(out)
    }

    /// Reads and parses a file; errors name it.
    pub fn read(path: impl AsRef<Path>) -> Result<(TfxFile, Vec<TfxWarning>), TfxError> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|e| TfxError::Read(e).in_file(path))?;
        TfxFile::from_bytes(&bytes).map_err(|e| e.in_file(path))
    }
}

fn all_finite(v: &[f32]) -> bool {
    v.iter().all(|c| c.is_finite())
}
