//! Parsing a `.hair` file image: the header's size claims are checked
//! against the real length before anything is allocated, then the arrays are
//! read and every point is checked to be finite.

use std::path::Path;

use super::{
    FLAG_COLORS, FLAG_POINTS, FLAG_SEGMENTS, FLAG_THICKNESS, FLAG_TRANSPARENCY, HEADER_SIZE,
    HairError, HairFile, HairWarning, INFO_SIZE, KNOWN_FLAGS, SIGNATURE,
};

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

    /// Reads and parses a file; errors name the file.
    pub fn read(path: impl AsRef<Path>) -> Result<(HairFile, Vec<HairWarning>), HairError> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|e| HairError::Read(e).in_file(path))?;
        HairFile::from_bytes(&bytes).map_err(|e| e.in_file(path))
    }
}
