//! Strands to and from `.tfx`: one vertex count per file, so strands of
//! other lengths are resampled by arc length.

use glam::Vec3;

use super::{TfxError, TfxFile};
use crate::strands::Strands;

/// Builds renderable strands from a `.tfx` file: per-strand thickness (1 when
/// absent), vertex colour RGB as colour and its A as opacity (white and
/// opaque when absent). UVs and inverse mass are not rendered.
impl From<&TfxFile> for Strands {
    fn from(file: &TfxFile) -> Strands {
        let per = file.vertices_per_strand.max(1) as usize;
        let n = file.strand_count() * per;
        let mut strands = Strands::new();
        strands.points = file.positions[..n].iter().map(|&p| Vec3::from(p)).collect();
        strands.thickness = (0..n)
            .map(|i| file.strand_thickness.as_ref().map_or(1.0, |t| t[i / per]))
            .collect();
        let color = |i: usize| file.vertex_color.as_ref().map_or([1.0; 4], |c| c[i]);
        strands.color = (0..n).map(|i| Vec3::from_slice(&color(i)[..3])).collect();
        strands.alpha = (0..n).map(|i| color(i)[3]).collect();
        strands.offsets = (0..=n / per).map(|k| (k * per) as u32).collect();
        strands
    }
}

impl TfxFile {
    /// A TressFX 4 file from strands. Every strand gets `vertices_per_strand`
    /// vertices (default: the most any strand has); strands with another
    /// count are resampled by arc length. Thickness is kept per strand (the
    /// root's); colour and opacity per vertex. Arrays that would hold only
    /// the reader's defaults (thickness 1, opaque white) are left out.
    pub fn from_strands(
        strands: &Strands,
        vertices_per_strand: Option<u32>,
    ) -> Result<TfxFile, TfxError> {
        let per = vertices_per_strand
            .unwrap_or_else(|| strands.ranges().map(|r| r.len()).max().unwrap_or(0).max(2) as u32);
        if per < 2 {
            return Err(TfxError::Unrepresentable(format!(
                "{per} vertices per strand: a strand needs at least 2"
            )));
        }
        if strands.strand_count() == 0 {
            return Err(TfxError::Unrepresentable("there is no strand".into()));
        }
        let total = strands.strand_count() as u64 * u64::from(per);
        if total * 16 > u64::from(u32::MAX) {
            return Err(TfxError::Unrepresentable(format!(
                "{} strands × {per} vertices do not fit in a file with 32-bit offsets",
                strands.strand_count()
            )));
        }
        let mut positions = Vec::with_capacity(total as usize);
        let mut colors = Vec::with_capacity(total as usize);
        let mut thickness = Vec::with_capacity(strands.strand_count());
        for r in strands.ranges() {
            let at = |v: &[f32], i: usize| v.get(i).copied().unwrap_or(1.0);
            thickness.push(at(&strands.thickness, r.start));
            for (i, t) in resample(&strands.points[r.clone()], per as usize) {
                let i = r.start + i;
                let j = (i + 1).min(r.end.saturating_sub(1));
                positions.push(strands.points[i].lerp(strands.points[j], t).to_array());
                let c = strands.color.get(i).copied().unwrap_or(Vec3::ONE);
                let c2 = strands.color.get(j).copied().unwrap_or(Vec3::ONE);
                let a = at(&strands.alpha, i) + (at(&strands.alpha, j) - at(&strands.alpha, i)) * t;
                colors.push(c.lerp(c2, t).extend(a).to_array());
            }
        }
        Ok(TfxFile {
            version: 4.0,
            vertices_per_strand: per,
            positions,
            inverse_mass: None,
            strand_uv: None,
            vertex_uv: None,
            strand_thickness: thickness.iter().any(|&t| t != 1.0).then_some(thickness),
            vertex_color: colors.iter().any(|&c| c != [1.0; 4]).then_some(colors),
            follow_strands_per_guide: 0,
            both_ends_immovable: false,
            guide_flags: None,
        })
    }
}

/// Where `count` vertices spaced evenly by arc length fall on a polyline:
/// for each, the index of the segment's first point and the fraction along
/// it. A polyline that already has `count` points maps onto itself exactly.
fn resample(points: &[Vec3], count: usize) -> Vec<(usize, f32)> {
    if points.len() == count {
        return (0..count).map(|i| (i, 0.0)).collect();
    }
    let lengths: Vec<f32> = points.windows(2).map(|w| w[0].distance(w[1])).collect();
    let total: f32 = lengths.iter().sum();
    if points.len() < 2 || total <= 0.0 || !total.is_finite() {
        return vec![(0, 0.0); count];
    }
    let mut out = Vec::with_capacity(count);
    let (mut segment, mut start) = (0usize, 0.0f32);
    for k in 0..count {
        let target = total * k as f32 / (count - 1) as f32;
        while segment + 1 < lengths.len() && start + lengths[segment] < target {
            start += lengths[segment];
            segment += 1;
        }
        let t = if lengths[segment] > 0.0 {
            ((target - start) / lengths[segment]).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push((segment, t));
    }
    out
}
