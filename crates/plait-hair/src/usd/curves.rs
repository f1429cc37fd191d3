//! `BasisCurves` data as read from a prim, checked, and turned into
//! polylines: linear curves as they are, cubic curves evaluated at
//! `segments_per_span` points per span. Pure geometry, no USD types, so every
//! rule is tested on its own.
//!
//! The rules are UsdGeomBasisCurves' (the schema's documentation, "Curve
//! types, bases and wraps" and "Primvar interpolation"): a cubic curve of `n`
//! vertices has `(n - 4) / vstep + 1` spans (`vstep` 3 for Bézier, 1 for
//! B-spline and Catmull-Rom); `pinned` adds a phantom vertex at each end so
//! B-spline and Catmull-Rom curves pass through their end points; a
//! `varying` primvar has one value per span end, a `vertex` one per control
//! point (interpolated by the curve's basis), a `uniform` one per curve.

use glam::{DMat4, Vec3};

use crate::strands::Strands;

/// Most output points plait builds from one stage: strand offsets are u32.
pub const MAX_POINTS: u64 = u32::MAX as u64;

/// A cubic basis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Basis {
    /// Bézier: spans of 4 vertices sharing their ends (vstep 3).
    Bezier,
    /// Uniform cubic B-spline (vstep 1): smooth, passes near its vertices.
    Bspline,
    /// Catmull-Rom (vstep 1): passes through its inner vertices.
    CatmullRom,
}

impl Basis {
    /// The USD token.
    pub fn token(self) -> &'static str {
        match self {
            Basis::Bezier => "bezier",
            Basis::Bspline => "bspline",
            Basis::CatmullRom => "catmullRom",
        }
    }

    /// The weights of the span's four vertices at `t` in 0..=1.
    pub fn weights(self, t: f32) -> [f32; 4] {
        let (t2, t3) = (t * t, t * t * t);
        let s = 1.0 - t;
        match self {
            Basis::Bezier => [s * s * s, 3.0 * t * s * s, 3.0 * t2 * s, t3],
            Basis::Bspline => [
                s * s * s / 6.0,
                (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0,
                (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0,
                t3 / 6.0,
            ],
            Basis::CatmullRom => [
                0.5 * (-t3 + 2.0 * t2 - t),
                0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
                0.5 * (-3.0 * t3 + 4.0 * t2 + t),
                0.5 * (t3 - t2),
            ],
        }
    }

    fn vstep(self) -> u64 {
        match self {
            Basis::Bezier => 3,
            Basis::Bspline | Basis::CatmullRom => 1,
        }
    }
}

/// `type` and `basis` together.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurveKind {
    /// Straight segments between the vertices.
    Linear,
    /// Cubic spans of the basis.
    Cubic(Basis),
}

/// `wrap`: plait reads open curves; `periodic` (closed loops) is refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wrap {
    /// Open curves.
    Nonperiodic,
    /// Open curves through their end vertices.
    Pinned,
}

/// A primvar's (or `widths`') `interpolation`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interpolation {
    /// One value for the prim.
    Constant,
    /// One value per curve.
    Uniform,
    /// One value per span end.
    Varying,
    /// One value per control point.
    Vertex,
}

impl Interpolation {
    /// From the USD token (`faceVarying` is `varying` on curves).
    pub fn from_token(token: &str) -> Option<Interpolation> {
        Some(match token {
            "constant" => Interpolation::Constant,
            "uniform" => Interpolation::Uniform,
            "varying" | "faceVarying" => Interpolation::Varying,
            "vertex" => Interpolation::Vertex,
            _ => return None,
        })
    }

    /// The USD token.
    pub fn token(self) -> &'static str {
        match self {
            Interpolation::Constant => "constant",
            Interpolation::Uniform => "uniform",
            Interpolation::Varying => "varying",
            Interpolation::Vertex => "vertex",
        }
    }
}

/// Values with their interpolation.
#[derive(Debug, Clone, PartialEq)]
pub struct Primvar<T> {
    /// The values.
    pub values: Vec<T>,
    /// How they map onto the curves.
    pub interpolation: Interpolation,
}

/// One `BasisCurves` prim's data, in the prim's own space.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvesData {
    /// `type` and `basis`.
    pub kind: CurveKind,
    /// `wrap`.
    pub wrap: Wrap,
    /// `curveVertexCounts`.
    pub counts: Vec<i32>,
    /// `points`.
    pub points: Vec<Vec3>,
    /// `widths` (diameters).
    pub widths: Option<Primvar<f32>>,
    /// `primvars:displayColor` (linear RGB).
    pub colors: Option<Primvar<Vec3>>,
    /// `primvars:displayOpacity`.
    pub opacity: Option<Primvar<f32>>,
}

/// A problem with one field of a prim: `(field, message)`.
pub type FieldError = (&'static str, String);

/// Spans of a curve of `n` vertices, or why it has none.
fn spans(kind: CurveKind, wrap: Wrap, n: u64) -> Result<u64, String> {
    match (kind, wrap) {
        (CurveKind::Linear, _) => {
            if n < 2 {
                return Err(format!("{n} vertices: a linear curve needs at least 2"));
            }
            Ok(n - 1)
        }
        (CurveKind::Cubic(Basis::Bezier), _) => {
            if n < 4 || !(n - 4).is_multiple_of(3) {
                return Err(format!(
                    "{n} vertices: a Bézier curve needs 4 + 3k (each span shares its end vertex)"
                ));
            }
            Ok((n - 4) / 3 + 1)
        }
        (CurveKind::Cubic(b), Wrap::Nonperiodic) => {
            if n < 4 {
                return Err(format!(
                    "{n} vertices: a {} curve needs at least 4",
                    b.token()
                ));
            }
            Ok((n - 4) / b.vstep() + 1)
        }
        (CurveKind::Cubic(b), Wrap::Pinned) => {
            if n < 2 {
                return Err(format!(
                    "{n} vertices: a pinned {} curve needs at least 2",
                    b.token()
                ));
            }
            Ok(n - 1)
        }
    }
}

impl CurvesData {
    /// Checks every count and array length against the points, in u64, and
    /// every value for NaN and infinity, before anything is built. Returns
    /// the number of output points at `segments_per_span`.
    pub fn check(&self, segments_per_span: u32) -> Result<u64, FieldError> {
        if self.counts.is_empty() {
            return Err((
                "curveVertexCounts",
                "is empty: the prim has no curves".into(),
            ));
        }
        let mut total = 0u64;
        let mut varying = 0u64;
        let mut out = 0u64;
        for (c, &n) in self.counts.iter().enumerate() {
            let n = u64::try_from(n)
                .map_err(|_| ("curveVertexCounts", format!("curve {c} has {n} vertices")))?;
            let spans = spans(self.kind, self.wrap, n)
                .map_err(|m| ("curveVertexCounts", format!("curve {c}: {m}")))?;
            total += n;
            varying += spans + 1;
            out += match self.kind {
                CurveKind::Linear => n,
                CurveKind::Cubic(_) => spans * u64::from(segments_per_span) + 1,
            };
        }
        if total != self.points.len() as u64 {
            return Err((
                "curveVertexCounts",
                format!(
                    "sums to {total} vertices but `points` has {}",
                    self.points.len()
                ),
            ));
        }
        if out > MAX_POINTS {
            return Err((
                "points",
                format!(
                    "the curves evaluate to {out} points (at {segments_per_span} segments per span), more than plait's limit of {MAX_POINTS}"
                ),
            ));
        }
        if let Some((i, p)) = self.points.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(("points", format!("point {i} is not finite: {p}")));
        }
        let curves = self.counts.len() as u64;
        let expect = |interpolation: Interpolation| match interpolation {
            Interpolation::Constant => (1, "one for the prim"),
            Interpolation::Uniform => (curves, "one per curve"),
            Interpolation::Varying => (varying, "one per span end"),
            Interpolation::Vertex => (total, "one per point"),
        };
        let lengths = [
            (
                "widths",
                self.widths
                    .as_ref()
                    .map(|w| (w.values.len(), w.interpolation)),
            ),
            (
                "primvars:displayColor",
                self.colors
                    .as_ref()
                    .map(|w| (w.values.len(), w.interpolation)),
            ),
            (
                "primvars:displayOpacity",
                self.opacity
                    .as_ref()
                    .map(|w| (w.values.len(), w.interpolation)),
            ),
        ];
        for (field, got) in lengths {
            if let Some((len, interpolation)) = got {
                let (need, what) = expect(interpolation);
                if len as u64 != need {
                    return Err((
                        field,
                        format!(
                            "has {len} values, but interpolation `{}` needs {need} ({what})",
                            interpolation.token()
                        ),
                    ));
                }
            }
        }
        if let Some(w) = &self.widths
            && let Some((i, v)) = w
                .values
                .iter()
                .enumerate()
                .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
        {
            return Err((
                "widths",
                format!("value {i} is {v}: widths must be finite and ≥ 0"),
            ));
        }
        if let Some(c) = &self.colors
            && let Some((i, v)) = c.values.iter().enumerate().find(|(_, v)| !v.is_finite())
        {
            return Err((
                "primvars:displayColor",
                format!("value {i} is not finite: {v}"),
            ));
        }
        if let Some(o) = &self.opacity
            && let Some((i, v)) = o.values.iter().enumerate().find(|(_, v)| !v.is_finite())
        {
            return Err((
                "primvars:displayOpacity",
                format!("value {i} is not finite: {v}"),
            ));
        }
        Ok(out)
    }

    /// Appends the curves to `strands`, placed by `to_world` (points) whose
    /// uniform scale also scales the widths; a prim without `widths` gets
    /// `default_width`. Call [`CurvesData::check`] first: it guarantees
    /// every index here is in range.
    ///
    /// Returns how many evaluated widths fell below 0 and were made 0: vertex
    /// widths on a Catmull-Rom (or B-spline, pinned) curve overshoot like the
    /// curve does, and a width cannot be negative.
    pub fn append_to(
        &self,
        strands: &mut Strands,
        to_world: DMat4,
        segments_per_span: u32,
        default_width: f32,
    ) -> usize {
        let mut negative = 0usize;
        let mut width = |w: f32| {
            if w < 0.0 {
                negative += 1;
                0.0
            } else {
                w
            }
        };
        let width_scale = to_world.determinant().abs().cbrt() as f32;
        let place = |p: Vec3| to_world.transform_point3(p.as_dvec3()).as_vec3();
        let mut first = 0usize;
        let mut first_varying = 0usize;
        for (c, &n) in self.counts.iter().enumerate() {
            let n = n as usize;
            let span_count = spans(self.kind, self.wrap, n as u64).unwrap_or(0) as usize;
            let curve = Curve {
                data: self,
                curve: c,
                first,
                n,
                first_varying,
            };
            match self.kind {
                CurveKind::Linear => {
                    for i in 0..n {
                        strands.points.push(place(self.points[first + i]));
                        let (w, col, a) = curve.at_vertex(i, default_width);
                        strands.thickness.push(width(w) * width_scale);
                        strands.color.push(col);
                        strands.alpha.push(a);
                    }
                }
                CurveKind::Cubic(basis) => {
                    let seg = segments_per_span.max(1);
                    for s in 0..span_count {
                        let start = if s == 0 { 0 } else { 1 };
                        for j in start..=seg {
                            let t = j as f32 / seg as f32;
                            let (w, col, a) = curve.cubic(basis, s, t, default_width);
                            strands.points.push(place(curve.cubic_point(basis, s, t)));
                            strands.thickness.push(width(w) * width_scale);
                            strands.color.push(col);
                            strands.alpha.push(a);
                        }
                    }
                }
            }
            strands.offsets.push(strands.points.len() as u32);
            first += n;
            first_varying += span_count + 1;
        }
        negative
    }
}

/// One curve of a prim, for evaluation.
struct Curve<'a> {
    data: &'a CurvesData,
    curve: usize,
    first: usize,
    n: usize,
    first_varying: usize,
}

impl Curve<'_> {
    /// The four vertex indices (within the curve; -1 and n are the pinned
    /// phantoms) of span `s`.
    fn span_vertices(&self, basis: Basis, s: usize) -> [isize; 4] {
        let base = match (basis, self.data.wrap) {
            (Basis::Bezier, _) => 3 * s as isize,
            (_, Wrap::Nonperiodic) => s as isize,
            (_, Wrap::Pinned) => s as isize - 1,
        };
        [base, base + 1, base + 2, base + 3]
    }

    /// A per-vertex value at vertex `i` of the curve, phantoms included:
    /// the reflection `2·v0 − v1` (and its mirror at the tip), which makes
    /// B-spline and Catmull-Rom curves start and end at their end vertices.
    fn vertex<T>(&self, values: &[T], i: isize) -> T
    where
        T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Sub<Output = T>,
    {
        let n = self.n as isize;
        let at = |k: isize| values[self.first + k as usize];
        if i < 0 {
            at(0) * 2.0 - at(1.min(n - 1))
        } else if i >= n {
            at(n - 1) * 2.0 - at((n - 2).max(0))
        } else {
            at(i)
        }
    }

    fn blend<T>(&self, basis: Basis, values: &[T], s: usize, t: f32) -> T
    where
        T: Copy
            + std::ops::Mul<f32, Output = T>
            + std::ops::Sub<Output = T>
            + std::ops::Add<Output = T>,
    {
        let w = basis.weights(t);
        let v = self.span_vertices(basis, s);
        self.vertex(values, v[0]) * w[0]
            + self.vertex(values, v[1]) * w[1]
            + self.vertex(values, v[2]) * w[2]
            + self.vertex(values, v[3]) * w[3]
    }

    fn cubic_point(&self, basis: Basis, s: usize, t: f32) -> Vec3 {
        self.blend(basis, &self.data.points, s, t)
    }

    /// Width, colour and opacity at parameter `t` of span `s`.
    fn cubic(&self, basis: Basis, s: usize, t: f32, default_width: f32) -> (f32, Vec3, f32) {
        let scalar = |p: &Primvar<f32>, default: f32| match p.interpolation {
            Interpolation::Vertex => self.blend(basis, &p.values, s, t),
            _ => self.uniform_or_varying(p, s, t).unwrap_or(default),
        };
        let w = self
            .data
            .widths
            .as_ref()
            .map_or(default_width, |p| scalar(p, default_width));
        let a = self.data.opacity.as_ref().map_or(1.0, |p| scalar(p, 1.0));
        let col = self
            .data
            .colors
            .as_ref()
            .map_or(Vec3::ONE, |p| match p.interpolation {
                Interpolation::Vertex => self.blend(basis, &p.values, s, t),
                _ => self.uniform_or_varying(p, s, t).unwrap_or(Vec3::ONE),
            });
        (w, col, a)
    }

    /// Width, colour and opacity at vertex `i` of a linear curve (where a
    /// span end is a vertex, so varying is vertex).
    fn at_vertex(&self, i: usize, default_width: f32) -> (f32, Vec3, f32) {
        let pick = |interp: Interpolation, len: usize| {
            match interp {
                Interpolation::Constant => 0,
                Interpolation::Uniform => self.curve,
                Interpolation::Varying => self.first_varying + i,
                Interpolation::Vertex => self.first + i,
            }
            .min(len.saturating_sub(1))
        };
        let w = self.data.widths.as_ref().map_or(default_width, |p| {
            p.values[pick(p.interpolation, p.values.len())]
        });
        let col = self.data.colors.as_ref().map_or(Vec3::ONE, |p| {
            p.values[pick(p.interpolation, p.values.len())]
        });
        let a = self
            .data
            .opacity
            .as_ref()
            .map_or(1.0, |p| p.values[pick(p.interpolation, p.values.len())]);
        (w, col, a)
    }

    /// A constant, uniform or varying value at `t` of span `s` (varying
    /// values are linear between the span's ends); `None` for vertex.
    fn uniform_or_varying<T>(&self, p: &Primvar<T>, s: usize, t: f32) -> Option<T>
    where
        T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
    {
        match p.interpolation {
            Interpolation::Constant => Some(p.values[0]),
            Interpolation::Uniform => Some(p.values[self.curve]),
            Interpolation::Varying => {
                let a = p.values[self.first_varying + s];
                let b = p.values[self.first_varying + s + 1];
                Some(a * (1.0 - t) + b * t)
            }
            Interpolation::Vertex => None,
        }
    }
}
