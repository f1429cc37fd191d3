//! The scene's `[hair]`: where the strands come from (an asset file or a
//! procedural groom), follow strands around them, and where they go in the
//! scene.
//!
//! ```toml
//! [hair]
//! file = "models/mohawk.tfx"   # .hair, .tfx or USD, relative to the scene file
//! prim = "/Groom"              # USD only: read the BasisCurves under this prim
//! segments_per_span = 8        # USD only: polyline segments per cubic span
//! follow_strands = 4           # per guide strand (TressFX files hold guides only)
//! follow_radius = 0.004        # root offset, in the file's units
//! follow_tip_spread = 1.0      # offset × (1 + spread·t) toward the tip
//! [hair.transform]
//! scale = 10.0                 # or [x, y, z]
//! rotate_degrees = [0, 30, 0]  # about X, then Y, then Z
//! translate = [0, -1, 0]
//! ```
//! `hair = { file = "x.hair" }` and `[hair.procedural]` keep working.

use std::path::PathBuf;

use serde::Deserialize;

use crate::follow::FollowStrands;
use crate::groom::GroomSpec;
use crate::transform::Transform;
use crate::usd::{DEFAULT_SEGMENTS_PER_SPAN, UsdOptions};

/// Where the hair comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum HairSource {
    /// A `.hair`, `.tfx` or USD file (relative to the scene file).
    File(PathBuf),
    /// A procedural groom.
    Procedural(GroomSpec),
}

/// The scene's hair: its source, optional follow strands (generated in the
/// source's units), then an optional placement.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(try_from = "HairToml")]
pub struct Hair {
    /// The strands (guides, when `follow` is set).
    pub source: HairSource,
    /// Follow strands around every strand of the source.
    pub follow: Option<FollowStrands>,
    /// Placement in the scene, applied after the follow strands.
    pub transform: Option<Transform>,
    /// What to read from a USD file (`prim`, `segments_per_span`).
    pub usd: UsdOptions,
    /// Where a scene file names `file` (`scene.toml:LINE:COL`), which an
    /// error reading that file names too.
    pub declared_at: Option<String>,
}

impl From<HairSource> for Hair {
    fn from(source: HairSource) -> Hair {
        Hair {
            source,
            follow: None,
            transform: None,
            usd: UsdOptions::default(),
            declared_at: None,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct HairToml {
    file: Option<PathBuf>,
    procedural: Option<GroomSpec>,
    follow_strands: Option<u32>,
    follow_radius: Option<f32>,
    follow_tip_spread: Option<f32>,
    follow_seed: Option<u64>,
    transform: Option<Transform>,
    prim: Option<String>,
    segments_per_span: Option<u32>,
}

impl TryFrom<HairToml> for Hair {
    type Error = String;
    fn try_from(t: HairToml) -> Result<Hair, String> {
        let source = match (t.file, t.procedural) {
            (Some(path), None) => HairSource::File(path),
            (None, Some(spec)) => HairSource::Procedural(spec),
            _ => return Err("hair needs exactly one of `file` or `procedural`".into()),
        };
        let follow = match (t.follow_strands, t.follow_radius) {
            (None | Some(0), None) => {
                if t.follow_tip_spread.is_some() || t.follow_seed.is_some() {
                    return Err(
                        "hair.follow_tip_spread and hair.follow_seed need follow_strands".into(),
                    );
                }
                None
            }
            (Some(count), Some(radius)) => Some(FollowStrands {
                count,
                radius,
                tip_spread: t.follow_tip_spread.unwrap_or(0.0),
                seed: t.follow_seed.unwrap_or(1),
            }),
            (Some(_), None) => {
                return Err(
                    "hair.follow_strands needs follow_radius (the root offset, in the file's units)"
                        .into(),
                );
            }
            (None, Some(_)) => return Err("hair.follow_radius needs follow_strands".into()),
        };
        let is_usd = matches!(&source, HairSource::File(p)
            if crate::asset::Format::from_extension(p) == Some(crate::asset::Format::Usd));
        if !is_usd && (t.prim.is_some() || t.segments_per_span.is_some()) {
            return Err(
                "hair.prim and hair.segments_per_span apply to a USD file (hair.file ending in .usda, .usdc, .usdz or .usd)"
                    .into(),
            );
        }
        Ok(Hair {
            source,
            follow,
            transform: t.transform,
            usd: UsdOptions {
                prim: t.prim,
                segments_per_span: t.segments_per_span.unwrap_or(DEFAULT_SEGMENTS_PER_SPAN),
            },
            // Set by the scene parser, which has the text.
            declared_at: None,
        })
    }
}

impl Hair {
    /// Range checks; messages name the field.
    pub fn validate(&self) -> Result<(), String> {
        if let HairSource::Procedural(g) = &self.source {
            g.validate().map_err(|m| format!("hair.procedural.{m}"))?;
        }
        if let Some(f) = &self.follow {
            f.validate().map_err(|m| format!("hair.{m}"))?;
        }
        if let Some(t) = &self.transform {
            t.validate()?;
        }
        self.usd.validate("hair.prim", "hair.segments_per_span")?;
        Ok(())
    }
}
