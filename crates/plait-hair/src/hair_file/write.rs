//! Serializing a [`HairFile`] to the published layout, and writing it to
//! disk atomically so a reader never sees a half-written file.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::{
    FLAG_COLORS, FLAG_POINTS, FLAG_SEGMENTS, FLAG_THICKNESS, FLAG_TRANSPARENCY, HEADER_SIZE,
    HairError, HairFile, SIGNATURE,
};

impl HairFile {
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
            // Closed (end of block) before the rename. A block, not `drop`:
            // on wasm32 a File has no Drop and clippy refuses `drop(f)`.
            {
                let mut f = std::fs::File::create(&tmp)?;
                f.write_all(&bytes)?;
                f.sync_all()?;
            }
            std::fs::rename(&tmp, path)
        })();
        if let Err(e) = result {
            let _ = std::fs::remove_file(&tmp);
            return Err(HairError::Io(e));
        }
        Ok(())
    }
}
