//! The groom's TOML table (`[hair.procedural]`): style, counts, head and
//! scalp shape with their defaults, and the range checks that name the
//! offending field before anything is generated.

use serde::Deserialize;

/// Hair style.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Style {
    /// Smooth strands.
    #[default]
    Straight,
    /// Planar sine waves.
    Wavy,
    /// Helical curls.
    Curly,
}

impl std::str::FromStr for Style {
    type Err = String;
    fn from_str(s: &str) -> Result<Style, String> {
        match s {
            "straight" => Ok(Style::Straight),
            "wavy" => Ok(Style::Wavy),
            "curly" => Ok(Style::Curly),
            other => Err(format!(
                "unknown style {other:?} (expected straight, wavy or curly)"
            )),
        }
    }
}

/// The head the hair grows on: an ellipsoid.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeadShape {
    /// Center.
    pub center: [f32; 3],
    /// Semi-axes along x, y, z.
    pub radii: [f32; 3],
}

impl Default for HeadShape {
    fn default() -> Self {
        HeadShape {
            center: [0.0, 0.0, 0.0],
            radii: [0.9, 1.05, 1.0],
        }
    }
}

/// Where on the head hair grows, as angles on the ellipsoid's parameter
/// sphere: the polar angle is measured from the top (+Y), the face is toward +Z.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalpRegion {
    /// Largest polar angle (degrees from +Y) with hair at the back and sides.
    pub max_polar_degrees: f32,
    /// Largest polar angle over the face (the front, +Z side): the hairline.
    pub face_polar_degrees: f32,
    /// Half-width (degrees of azimuth around +Z) of the face region.
    pub face_half_width_degrees: f32,
}

impl Default for ScalpRegion {
    fn default() -> Self {
        ScalpRegion {
            max_polar_degrees: 105.0,
            face_polar_degrees: 50.0,
            face_half_width_degrees: 70.0,
        }
    }
}

/// A procedural groom. Every field has a default, so `[hair.procedural]`
/// may set only what it changes.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GroomSpec {
    /// straight, wavy or curly.
    pub style: Style,
    /// Number of rendered strands (not counting stray strands).
    pub strands: u32,
    /// Segments per strand (points = segments + 1), 1..=65535.
    pub segments: u32,
    /// PRNG seed; same seed, same groom.
    pub seed: u64,
    /// Mean strand length (model units).
    pub length: f32,
    /// Relative length variation: lengths are uniform in `length * (1 ± v)`.
    pub length_variation: f32,
    /// Root thickness (model units).
    pub thickness: f32,
    /// Relative thickness variation per strand.
    pub thickness_variation: f32,
    /// Tip thickness as a fraction of the root thickness.
    pub tip_thickness: f32,
    /// Strand opacity (1 - the format's transparency).
    pub alpha: f32,
    /// Absolute alpha variation per strand (clamped to 0..1).
    pub alpha_variation: f32,
    /// Base linear RGB color.
    pub color: [f32; 3],
    /// Per-strand brightness variation (relative).
    pub color_variation: f32,
    /// The head.
    pub head: HeadShape,
    /// Where hair grows.
    pub scalp: ScalpRegion,
    /// How strongly strands turn downward, per unit length.
    pub gravity: f32,
    /// Wave/curl amplitude (model units); `None` = the style's default.
    pub wave_amplitude: Option<f32>,
    /// Wave/curl period along the strand (model units); `None` = style default.
    pub wave_period: Option<f32>,
    /// Extra strands lifted off the main volume (appended after the others).
    pub stray_strands: u32,
    /// If set, about this many guide strands are grown and the rendered
    /// strands are interpolated from them (Halén & Wester 2007 §2.5).
    pub guides: Option<u32>,
}

impl Default for GroomSpec {
    fn default() -> Self {
        GroomSpec {
            style: Style::Straight,
            strands: 1000,
            segments: 16,
            seed: 1,
            length: 2.0,
            length_variation: 0.15,
            thickness: 0.006,
            thickness_variation: 0.2,
            tip_thickness: 0.4,
            alpha: 0.6,
            alpha_variation: 0.1,
            color: [0.32, 0.2, 0.11],
            color_variation: 0.15,
            head: HeadShape::default(),
            scalp: ScalpRegion::default(),
            gravity: 2.5,
            wave_amplitude: None,
            wave_period: None,
            stray_strands: 0,
            guides: None,
        }
    }
}

impl GroomSpec {
    /// Checks the numbers; the message names the offending field.
    pub fn validate(&self) -> Result<(), String> {
        if self.strands == 0 && self.stray_strands == 0 {
            return Err("strands must be at least 1".into());
        }
        if !(1..=65535).contains(&self.segments) {
            return Err(format!(
                "segments must be in 1..=65535, got {}",
                self.segments
            ));
        }
        let total = (u64::from(self.strands) + u64::from(self.stray_strands))
            * (u64::from(self.segments) + 1);
        // Refused before generating: past this the vertices outgrow memory
        // and any GPU buffer (see `follow::MAX_POINTS`).
        if total > crate::follow::MAX_POINTS {
            return Err(format!(
                "strands × (segments + 1) = {total} points exceeds plait's limit of {}",
                crate::follow::MAX_POINTS
            ));
        }
        let finite_nonneg = [
            ("length", self.length),
            ("length_variation", self.length_variation),
            ("thickness", self.thickness),
            ("thickness_variation", self.thickness_variation),
            ("tip_thickness", self.tip_thickness),
            ("alpha", self.alpha),
            ("alpha_variation", self.alpha_variation),
            ("color_variation", self.color_variation),
            ("gravity", self.gravity),
            ("wave_amplitude", self.wave_amplitude.unwrap_or(0.0)),
        ];
        for (name, v) in finite_nonneg {
            if !v.is_finite() || v < 0.0 {
                return Err(format!("{name} must be a finite number ≥ 0, got {v}"));
            }
        }
        if self.length <= 0.0 {
            return Err("length must be > 0".into());
        }
        if self.alpha > 1.0 {
            return Err(format!("alpha must be in 0..=1, got {}", self.alpha));
        }
        if let Some(p) = self.wave_period
            && !(p.is_finite() && p > 0.0)
        {
            return Err(format!("wave_period must be > 0, got {p}"));
        }
        if self.head.radii.iter().any(|r| !(r.is_finite() && *r > 0.0)) {
            return Err("head.radii must be finite and > 0".into());
        }
        if self
            .head
            .center
            .iter()
            .chain(&self.color)
            .any(|c| !c.is_finite())
        {
            return Err("head.center and color must be finite".into());
        }
        if self.guides == Some(0) {
            return Err("guides must be at least 1 (or absent)".into());
        }
        Ok(())
    }

    pub(super) fn wave(&self) -> (f32, f32) {
        let (a, p) = match self.style {
            Style::Straight => (0.0, 1.0),
            Style::Wavy => (0.06, 0.5),
            Style::Curly => (0.05, 0.15),
        };
        (
            self.wave_amplitude.unwrap_or(a),
            self.wave_period.unwrap_or(p).max(1e-4),
        )
    }
}
