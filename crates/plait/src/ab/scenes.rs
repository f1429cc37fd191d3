//! The scenes of an A/B run: each `--scene` file (or the built-in scene)
//! loaded once, then made into the variants of the scene itself that the
//! run asks for — one per `--hair-color` (every strand recoloured) and one
//! per `--camera-distance` (the camera moved back). Unlike a `--sweep`,
//! which changes only the pipelines, these change what every pipeline and
//! the reference see, so the reference is rendered once per scene variant.

use std::path::PathBuf;

use glam::Vec3;

use super::AbError;
use super::plan::{AbOptions, ScenePlan, SweepSyntaxError, sanitize, stem, unique};
use crate::session::SceneData;

/// `--hair-color NAME=R,G,B`: every strand of every scene recoloured to a
/// linear RGB albedo (each channel in (0, 1]: the path-traced reference maps
/// it to an absorption by Chiang et al. 2016 §4.2, which a 0 channel has
/// none of), the scene named `SCENE@NAME`.
#[derive(Clone, Debug, PartialEq)]
pub struct HairColor {
    pub name: String,
    pub rgb: [f32; 3],
}

impl HairColor {
    /// `blond=0.85,0.65,0.40`: a name usable in a file name, three channels.
    pub fn parse(text: &str) -> Result<Self, SweepSyntaxError> {
        let bad = |message: String| Err(SweepSyntaxError(message));
        let example = "e.g. blond=0.85,0.65,0.40";
        let Some((name, channels)) = text.split_once('=') else {
            return bad(format!("`{text}` is not NAME=R,G,B ({example})"));
        };
        let name = name.trim();
        if name.is_empty()
            || !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        {
            return bad(format!(
                "`{name}`: a colour's name is letters, digits, `_` and `-` (it names the scene's files; {example})"
            ));
        }
        let values: Vec<&str> = channels.split(',').map(str::trim).collect();
        if values.len() != 3 {
            return bad(format!(
                "`{channels}`: a colour is three channels R,G,B ({example})"
            ));
        }
        let mut rgb = [0.0f32; 3];
        for (slot, item) in rgb.iter_mut().zip(&values) {
            let Ok(v) = item.parse::<f32>() else {
                return bad(format!("`{item}` is not a number ({example})"));
            };
            // An albedo above 1 reflects more than it receives; 0 has no
            // absorption in Chiang 2016 §4.2's map (the path tracer's side).
            if !(v > 0.0 && v <= 1.0) {
                return bad(format!(
                    "channel {item} of `{name}` is outside (0, 1]: a hair colour is an albedo (docs/formats.md, \"Light and units\")"
                ));
            }
            *slot = v;
        }
        Ok(HairColor {
            name: name.to_owned(),
            rgb,
        })
    }
}

/// Checks the colours' names are distinct (they name files).
pub(super) fn check_hair_colors(colors: &[HairColor]) -> Result<(), AbError> {
    for (i, c) in colors.iter().enumerate() {
        if colors[..i].iter().any(|d| d.name == c.name) {
            return Err(AbError::HairColorTwice(c.name.clone()));
        }
    }
    Ok(())
}

/// Every scene of the run: each file (or the built-in scene) loaded once,
/// then once per hair colour, each of those once per camera distance.
pub(super) fn load(options: &AbOptions) -> Result<Vec<ScenePlan>, AbError> {
    check_hair_colors(&options.hair_colors)?;
    let paths: Vec<Option<PathBuf>> = if options.scenes.is_empty() {
        vec![None]
    } else {
        options.scenes.iter().cloned().map(Some).collect()
    };
    let mut scenes = Vec::new();
    let mut names = Vec::new();
    for path in paths {
        let data = SceneData::load(path.as_deref()).map_err(|source| AbError::Scene {
            what: match &path {
                Some(p) => format!("--scene {}", p.display()),
                None => "the built-in scene".into(),
            },
            source,
        })?;
        let base = path
            .as_deref()
            .map(stem)
            .unwrap_or_else(|| "default".into());
        for (name, color, data) in recoloured(&base, data, &options.hair_colors) {
            at_distances(
                options,
                Seen {
                    name,
                    path: path.clone(),
                    color,
                    data,
                },
                &mut names,
                &mut scenes,
            );
        }
    }
    Ok(scenes)
}

/// A scene as the camera distances will see it.
struct Seen {
    name: String,
    path: Option<PathBuf>,
    color: Option<HairColor>,
    data: SceneData,
}

/// The scene itself without colours, else one copy per colour with every
/// strand point's colour replaced (opacity kept).
fn recoloured(
    base: &str,
    data: SceneData,
    colors: &[HairColor],
) -> Vec<(String, Option<HairColor>, SceneData)> {
    if colors.is_empty() {
        return vec![(base.to_owned(), None, data)];
    }
    colors
        .iter()
        .map(|c| {
            let mut d = data.clone();
            d.strands.color.fill(Vec3::from(c.rgb));
            (format!("{base}@{}", c.name), Some(c.clone()), d)
        })
        .collect()
}

/// `seen` as it is, or once per camera distance (named `…@dF`).
fn at_distances(
    options: &AbOptions,
    seen: Seen,
    names: &mut Vec<String>,
    scenes: &mut Vec<ScenePlan>,
) {
    let name = unique(sanitize(&seen.name), names);
    if options.camera_distances.is_empty() {
        scenes.push(ScenePlan {
            name,
            path: seen.path,
            distance: None,
            hair_color: seen.color,
            data: seen.data,
        });
        return;
    }
    // The same scene, its camera moved: the reference too sees it from
    // there (unlike a --sweep, which changes only the variants).
    for &factor in &options.camera_distances {
        let mut data = seen.data.clone();
        data.scene.camera = data.scene.camera.dollied(factor as f32);
        scenes.push(ScenePlan {
            name: unique(sanitize(&format!("{name}@d{factor}")), names),
            path: seen.path.clone(),
            distance: Some((name.clone(), factor)),
            hair_color: seen.color.clone(),
            data,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_colour_parses_and_bad_ones_say_why() {
        let c = HairColor::parse("blond=0.85, 0.65,0.40").expect("parses");
        assert_eq!(c.name, "blond");
        assert_eq!(c.rgb, [0.85, 0.65, 0.40]);
        for (text, says) in [
            ("0.85,0.65,0.40", "NAME=R,G,B"),
            ("=0.1,0.1,0.1", "a colour's name"),
            ("a b=0.1,0.1,0.1", "a colour's name"),
            ("x=0.1,0.1", "three channels"),
            ("x=0.1,0.1,y", "`y` is not a number"),
            ("x=0.1,0.1,1.5", "outside (0, 1]"),
            ("x=0.1,0.0,0.5", "outside (0, 1]"),
            ("x=0.1,NaN,0.5", "outside (0, 1]"),
        ] {
            let e = HairColor::parse(text).expect_err(text).to_string();
            assert!(e.contains(says), "{text}: {e}");
        }
    }

    #[test]
    fn a_colour_named_twice_is_refused() {
        let c = |n: &str| HairColor {
            name: n.into(),
            rgb: [0.5; 3],
        };
        assert!(check_hair_colors(&[c("a"), c("b")]).is_ok());
        let e = check_hair_colors(&[c("a"), c("b"), c("a")]).expect_err("twice");
        assert!(e.to_string().contains("--hair-color a:"), "{e}");
    }
}
