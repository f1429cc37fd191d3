//! The renderable strand model and its GPU vertex layout.

use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::hair_file::{HairError, HairFile};

/// An axis-aligned bounding box. An empty box has `min > max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (union identity).
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// A box from two corners.
    pub fn new(min: Vec3, max: Vec3) -> Aabb {
        Aabb { min, max }
    }

    /// The bounds of some points (empty if there are none).
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Aabb {
        points.into_iter().fold(Aabb::EMPTY, |b, p| Aabb {
            min: b.min.min(p),
            max: b.max.max(p),
        })
    }

    /// True if the box contains no point.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// Smallest box containing both.
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Center (zero for an empty box).
    pub fn center(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            (self.min + self.max) * 0.5
        }
    }

    /// Full size along each axis (zero for an empty box).
    pub fn extent(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            self.max - self.min
        }
    }

    /// The 8 corners (meaningless for an empty box).
    pub fn corners(&self) -> [Vec3; 8] {
        let (a, b) = (self.min, self.max);
        [
            Vec3::new(a.x, a.y, a.z),
            Vec3::new(b.x, a.y, a.z),
            Vec3::new(a.x, b.y, a.z),
            Vec3::new(b.x, b.y, a.z),
            Vec3::new(a.x, a.y, b.z),
            Vec3::new(b.x, a.y, b.z),
            Vec3::new(a.x, b.y, b.z),
            Vec3::new(b.x, b.y, b.z),
        ]
    }
}

/// One strand point as uploaded to the GPU (48 bytes, `#[repr(C)]`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct StrandVertex {
    /// Position in model space.
    pub position: [f32; 3],
    /// Strand thickness at this point (model units).
    pub thickness: f32,
    /// Unit tangent: the strand's natural cubic spline's direction at the
    /// point ([`Strands::tangents`]).
    pub tangent: [f32; 3],
    /// Opacity, 1 - transparency.
    pub alpha: f32,
    /// Linear RGB color.
    pub color: [f32; 3],
    /// Index of the strand this point belongs to.
    pub strand_id: u32,
}

/// Renderable strands: points of all strands, strand after strand, with
/// per-point thickness, alpha and color.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Strands {
    /// `offsets[i]..offsets[i+1]` are the points of strand `i`; `offsets[0] == 0`
    /// and the last entry is the point count. Length = strand count + 1.
    pub offsets: Vec<u32>,
    /// All points.
    pub points: Vec<Vec3>,
    /// Per-point thickness.
    pub thickness: Vec<f32>,
    /// Per-point alpha (1 - the format's transparency).
    pub alpha: Vec<f32>,
    /// Per-point color.
    pub color: Vec<Vec3>,
}

impl Strands {
    /// An empty model.
    pub fn new() -> Strands {
        Strands {
            offsets: vec![0],
            ..Strands::default()
        }
    }

    /// Appends a strand whose points share one thickness/alpha/color profile
    /// given per point by the closures' argument `t` in 0..=1 along the strand.
    pub fn push_strand(
        &mut self,
        points: &[Vec3],
        thickness: impl Fn(f32) -> f32,
        alpha: impl Fn(f32) -> f32,
        color: Vec3,
    ) {
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        let n = points.len().max(1) as f32 - 1.0;
        for (i, p) in points.iter().enumerate() {
            let t = if n > 0.0 { i as f32 / n } else { 0.0 };
            self.points.push(*p);
            self.thickness.push(thickness(t));
            self.alpha.push(alpha(t));
            self.color.push(color);
        }
        self.offsets.push(self.points.len() as u32);
    }

    /// Builds the model from a file, applying the file's defaults for arrays
    /// it lacks. A hand-built inconsistent `HairFile` is clamped (strands past
    /// the last point are dropped), never a panic; files from
    /// [`HairFile::from_bytes`] are always consistent.
    pub fn from_hair_file(file: &HairFile) -> Strands {
        let mut offsets = Vec::with_capacity(file.strand_count() + 1);
        offsets.push(0u32);
        let total = file.points.len() as u64;
        let mut at = 0u64;
        for i in 0..file.strand_count() {
            let next = at + u64::from(file.strand_segments(i)) + 1;
            if next > total {
                break;
            }
            at = next;
            offsets.push(at as u32);
        }
        let n = at as usize;
        let points: Vec<Vec3> = file.points[..n].iter().map(|&p| Vec3::from(p)).collect();
        let per_point = |arr: &Option<Vec<f32>>, default: f32| -> Vec<f32> {
            (0..n)
                .map(|i| {
                    arr.as_ref()
                        .and_then(|a| a.get(i).copied())
                        .unwrap_or(default)
                })
                .collect()
        };
        let thickness = per_point(&file.thickness, file.default_thickness);
        let alpha = per_point(&file.transparency, file.default_transparency)
            .into_iter()
            .map(|t| 1.0 - t)
            .collect();
        let color = (0..n)
            .map(|i| {
                Vec3::from(
                    file.colors
                        .as_ref()
                        .and_then(|c| c.get(i).copied())
                        .unwrap_or(file.default_color),
                )
            })
            .collect();
        Strands {
            offsets,
            points,
            thickness,
            alpha,
            color,
        }
    }

    /// Converts back to a file. Arrays whose values are all equal are stored
    /// as header defaults instead. Fails if a strand has more than 65,535
    /// segments while strands differ in length (the segments array is u16).
    pub fn to_hair_file(&self) -> Result<HairFile, HairError> {
        let n = self.point_count();
        if n > u32::MAX as usize || self.strand_count() > u32::MAX as usize {
            return Err(HairError::Unrepresentable(
                "more than 2^32-1 points or strands".into(),
            ));
        }
        if self.thickness.len() < n || self.alpha.len() < n || self.color.len() < n {
            return Err(HairError::Unrepresentable(
                "per-point arrays shorter than the point array".into(),
            ));
        }
        let segs: Vec<u32> = (0..self.strand_count())
            .map(|i| self.strand_range(i).len().saturating_sub(1) as u32)
            .collect();
        let uniform = segs.windows(2).all(|w| w[0] == w[1]);
        let (segments, default_segments) = if uniform {
            (None, segs.first().copied().unwrap_or(0))
        } else {
            let mut v = Vec::with_capacity(segs.len());
            for (i, &s) in segs.iter().enumerate() {
                let s16 = u16::try_from(s).map_err(|_| {
                    HairError::Unrepresentable(format!(
                        "strand {i} has {s} segments; the .hair segments array holds at most 65535"
                    ))
                })?;
                v.push(s16);
            }
            (Some(v), 0)
        };
        fn uniform_or<T: Copy + PartialEq>(v: &[T], default: T) -> (Option<Vec<T>>, T) {
            match v.first() {
                None => (None, default),
                Some(&first) if v.iter().all(|&x| x == first) => (None, first),
                Some(_) => (Some(v.to_vec()), default),
            }
        }
        let (thickness, default_thickness) = uniform_or(&self.thickness[..n], 1.0);
        let transparency: Vec<f32> = self.alpha.iter().take(n).map(|a| 1.0 - a).collect();
        let (transparency, default_transparency) = uniform_or(&transparency, 0.0);
        let colors: Vec<[f32; 3]> = self.color.iter().take(n).map(|c| c.to_array()).collect();
        let (colors, default_color) = uniform_or(&colors, [1.0, 1.0, 1.0]);
        let mut file = HairFile {
            hair_count: self.strand_count() as u32,
            segments,
            points: self.points.iter().map(|p| p.to_array()).collect(),
            thickness,
            transparency,
            colors,
            default_segments,
            default_thickness,
            default_transparency,
            default_color,
            info: [0; crate::hair_file::INFO_SIZE],
        };
        file.set_info("written by plait");
        Ok(file)
    }

    /// Number of strands.
    pub fn strand_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Number of points.
    pub fn point_count(&self) -> usize {
        self.points.len()
    }

    /// Number of line segments (points minus one per non-empty strand).
    pub fn segment_count(&self) -> usize {
        (0..self.strand_count())
            .map(|i| self.strand_range(i).len().saturating_sub(1))
            .sum()
    }

    /// The point index range of strand `i` (empty if out of range).
    pub fn strand_range(&self, i: usize) -> Range<usize> {
        match (self.offsets.get(i), self.offsets.get(i + 1)) {
            (Some(&a), Some(&b)) if a <= b => a as usize..(b as usize).min(self.points.len()),
            _ => 0..0,
        }
    }

    /// Point index ranges of all strands.
    pub fn ranges(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        (0..self.strand_count()).map(|i| self.strand_range(i))
    }

    /// The points of strand `i`.
    pub fn strand(&self, i: usize) -> &[Vec3] {
        &self.points[self.strand_range(i)]
    }

    /// Bounds of all points.
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(self.points.iter().copied())
    }

    /// Unit tangents per point: the directions of the natural cubic spline
    /// through each strand's points at them ([`crate::curve::knot_directions`],
    /// the curve the Mitsuba export draws), which the shaders bend between
    /// as that curve does (`shaders/lib/strand_curve.wgsl`); a degenerate
    /// strand gets +Y.
    pub fn tangents(&self) -> Vec<Vec3> {
        let mut out = vec![Vec3::Y; self.points.len()];
        for r in self.ranges() {
            let t = crate::curve::knot_directions(&self.points[r.clone()]);
            out[r].copy_from_slice(&t);
        }
        out
    }

    /// Unit tangents per point as central differences of the points
    /// (one-sided at a strand's ends; +Y where degenerate): what the
    /// simulation's per-point GPU interpolation writes for moved points
    /// (`shaders/passes/sim_interpolate.wgsl`), which cannot solve
    /// [`Strands::tangents`]'s per-strand system.
    pub fn central_tangents(&self) -> Vec<Vec3> {
        let mut out = vec![Vec3::Y; self.points.len()];
        for r in self.ranges() {
            let pts = &self.points[r.clone()];
            let mut last = Vec3::Y;
            for (k, slot) in out[r].iter_mut().enumerate() {
                let a = pts[k.saturating_sub(1)];
                let b = pts[(k + 1).min(pts.len() - 1)];
                let t = (b - a).normalize_or_zero();
                if t != Vec3::ZERO {
                    last = t;
                }
                *slot = last;
            }
        }
        out
    }

    /// One [`StrandVertex`] per point, and line-list indices (2 per segment).
    pub fn line_list(&self) -> (Vec<StrandVertex>, Vec<u32>) {
        let tangents = self.tangents();
        let mut vertices = Vec::with_capacity(self.points.len());
        let mut indices = Vec::with_capacity(self.segment_count() * 2);
        for (id, r) in self.ranges().enumerate() {
            for i in r.clone() {
                vertices.push(StrandVertex {
                    position: self.points[i].to_array(),
                    thickness: self.thickness.get(i).copied().unwrap_or(1.0),
                    tangent: tangents[i].to_array(),
                    alpha: self.alpha.get(i).copied().unwrap_or(1.0),
                    color: self.color.get(i).copied().unwrap_or(Vec3::ONE).to_array(),
                    strand_id: id as u32,
                });
            }
            for i in r.start..r.end.saturating_sub(1) {
                indices.push(i as u32);
                indices.push(i as u32 + 1);
            }
        }
        (vertices, indices)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_strands() -> Strands {
        let mut s = Strands::new();
        s.push_strand(
            &[Vec3::ZERO, Vec3::X, Vec3::new(2.0, 1.0, 0.0)],
            |t| 1.0 - t * 0.5,
            |_| 0.8,
            Vec3::new(0.5, 0.4, 0.3),
        );
        s.push_strand(
            &[Vec3::Y, Vec3::new(0.0, 3.0, 0.0)],
            |_| 0.1,
            |t| 1.0 - t,
            Vec3::ONE,
        );
        s
    }

    #[test]
    fn vertex_layout_is_48_bytes() {
        assert_eq!(std::mem::size_of::<StrandVertex>(), 48);
        assert_eq!(std::mem::offset_of!(StrandVertex, tangent), 16);
        assert_eq!(std::mem::offset_of!(StrandVertex, color), 32);
        assert_eq!(std::mem::offset_of!(StrandVertex, strand_id), 44);
    }

    #[test]
    fn counts_bounds_and_line_list() {
        let s = two_strands();
        assert_eq!(s.strand_count(), 2);
        assert_eq!(s.point_count(), 5);
        assert_eq!(s.segment_count(), 3);
        let b = s.bounds();
        assert_eq!(b.min, Vec3::ZERO);
        assert_eq!(b.max, Vec3::new(2.0, 3.0, 0.0));
        assert_eq!(b.center(), Vec3::new(1.0, 1.5, 0.0));
        assert_eq!(b.extent(), Vec3::new(2.0, 3.0, 0.0));
        let (v, i) = s.line_list();
        assert_eq!(v.len(), 5);
        assert_eq!(i, vec![0, 1, 1, 2, 3, 4]);
        assert_eq!(v[3].strand_id, 1);
        let t1 = Vec3::from(v[1].tangent) - Vec3::new(2.0, 1.0, 0.0).normalize();
        assert!(t1.length() < 1e-6, "{:?}", v[1].tangent);
        // The natural spline's end: D0 = (1, -0.25, 0) (2 D0 + D1 = 3 (p1 - p0)).
        let t0 = Vec3::from(v[0].tangent) - Vec3::new(1.0, -0.25, 0.0).normalize();
        assert!(t0.length() < 1e-6, "{:?}", v[0].tangent);
        assert_eq!(v[4].tangent, [0.0, 1.0, 0.0]);
        for x in &v {
            let t = Vec3::from(x.tangent);
            assert!((t.length() - 1.0).abs() < 1e-5);
        }
        let bytes: &[u8] = bytemuck::cast_slice(&v);
        assert_eq!(bytes.len(), 5 * 48);
    }

    #[test]
    fn aabb_union_and_empty() {
        let a = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let b = Aabb::new(Vec3::splat(-1.0), Vec3::splat(0.5));
        let u = a.union(&b);
        assert_eq!(u, Aabb::new(Vec3::splat(-1.0), Vec3::ONE));
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.union(&a), a);
        assert_eq!(Aabb::EMPTY.center(), Vec3::ZERO);
    }

    #[test]
    fn hair_file_round_trip_through_strands() {
        let s = two_strands();
        let f = s.to_hair_file().expect("representable");
        assert!(f.segments.is_some(), "strands differ in length");
        assert!(f.colors.is_some());
        let (g, _) = HairFile::from_bytes(&f.to_bytes()).expect("parse");
        let t = Strands::from_hair_file(&g);
        assert_eq!(t.offsets, s.offsets);
        assert_eq!(t.points, s.points);
        assert_eq!(t.thickness, s.thickness);
        assert_eq!(t.color, s.color);
        for (a, b) in t.alpha.iter().zip(&s.alpha) {
            assert!((a - b).abs() < 1e-6);
        }
    }

    #[test]
    fn defaults_apply_and_alpha_is_one_minus_transparency() {
        let f = HairFile {
            hair_count: 2,
            default_segments: 1,
            points: vec![[0.0; 3], [1.0; 3], [2.0; 3], [3.0; 3]],
            default_thickness: 0.3,
            default_transparency: 0.25,
            default_color: [0.1, 0.2, 0.3],
            ..HairFile::default()
        };
        let s = Strands::from_hair_file(&f);
        assert_eq!(s.offsets, vec![0, 2, 4]);
        assert!(s.thickness.iter().all(|&t| t == 0.3));
        assert!(s.alpha.iter().all(|&a| a == 0.75));
        assert!(s.color.iter().all(|&c| c == Vec3::new(0.1, 0.2, 0.3)));
        // inconsistent hand-built file: clamped, no panic
        let bad = HairFile { hair_count: 5, ..f };
        assert_eq!(Strands::from_hair_file(&bad).strand_count(), 2);
    }
}
