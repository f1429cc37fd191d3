//! A path-traced reference for `plait ab`: a file a user reads and edits
//! (`references/path_traced.toml`) naming the renderer (Mitsuba 3), its
//! samples, depth and seeds, the noise it must stay under, and the fibre
//! parameters of Mitsuba's `hair` BSDF. [`PathTraced::load`] reads it;
//! [`render_references`] renders it for every scene of a plan (through the
//! cache, `super::cache`), before any GPU work; `run` then compares the
//! variants with those images as with a reference pipeline's.

use std::ops::Range;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use crate::mitsuba::{ExportError, Fibre};

/// Why a path-traced reference could not be read or rendered.
#[derive(Debug, thiserror::Error)]
pub enum PathTracedError {
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A bad key or value, at its place in the file.
    #[error("{}:{line}:{col}: {message}", path.display())]
    Syntax {
        path: PathBuf,
        line: usize,
        col: usize,
        message: String,
    },
    /// `install` is the command that installs it: the checkout's script, or
    /// outside a checkout the built-in copy plait wrote out.
    #[error(
        "Mitsuba is not installed ({tried}): run `{install}` (or `eval \"$({install})\"` to set PLAIT_MITSUBA_PYTHON)"
    )]
    NoMitsuba { tried: String, install: String },
    #[error("scene {scene}: {source}")]
    Export {
        scene: String,
        #[source]
        source: ExportError,
    },
    #[error(
        "Mitsuba failed on scene {scene}, seed {seed} (exported to {}; re-run it with scripts/mitsuba/render.py DIR OUT.exr --seed {seed}): {why}",
        dir.display()
    )]
    Mitsuba {
        scene: String,
        dir: PathBuf,
        seed: u32,
        why: String,
    },
    #[error("the path-traced reference of scene {scene} has {count} NaN or Inf values ({})", path.display())]
    NotFinite {
        scene: String,
        path: PathBuf,
        count: usize,
    },
    #[error(
        "the path-traced reference of scene {scene} is too noisy: RMSE {noise:.6} between its two seeds' mean and the truth (estimated), above max_noise_rmse = {bound} in {}: raise spp",
        file.display()
    )]
    TooNoisy {
        scene: String,
        noise: f64,
        bound: f64,
        file: PathBuf,
    },
    #[error("{}: {source}", path.display())]
    Cache {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{}: {source}", path.display())]
    Image {
        path: PathBuf,
        source: image::ImageError,
    },
    /// A `--set params.chiang_…` the path tracer's fibre cannot take.
    #[error("--set {set}: {message}")]
    FibreSet { set: String, message: String },
    /// A `--set` the reference cannot follow (its display is AgX).
    #[error("--set {0}: a path-traced reference is shown through tone_mapping = agx only")]
    Display(String),
    #[error(
        "--frames: a path-traced reference renders one still per scene, not an animation; drop --frames or use a pipeline reference"
    )]
    Frames,
}

/// `references/path_traced.toml`, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct PathTraced {
    pub file: PathBuf,
    /// "mitsuba" (Mitsuba 3, run by `scripts/mitsuba/render.py`, cached) or
    /// "plait" (plait's own GPU path tracer, `pipelines/physical/path_traced.toml`).
    pub renderer: String,
    /// Samples per pixel of each seed's image.
    pub spp: u32,
    /// Mitsuba's `max_depth` (2: single scattering; -1: unbounded).
    pub max_depth: i32,
    /// Two distinct seeds: the reference is their images' mean, their
    /// difference its noise estimate.
    pub seeds: [u32; 2],
    /// The run fails when the estimated RMSE of the reference (linear
    /// radiance) exceeds this.
    pub max_noise_rmse: f64,
    pub fibre: Fibre,
    /// The standard fibre of the run's library ([`Fibre::standard`]): the
    /// one `fibre` starts from, and the report names `fibre` only when it
    /// differs.
    pub standard_fibre: Fibre,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileToml {
    path_traced: Section,
    fibre: Option<FibreToml>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Section {
    renderer: Spanned<String>,
    spp: Spanned<u32>,
    max_depth: Spanned<i32>,
    seeds: Spanned<Vec<u32>>,
    max_noise_rmse: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FibreToml {
    longitudinal_roughness: Option<Spanned<f32>>,
    azimuthal_roughness: Option<Spanned<f32>>,
    scale_tilt_degrees: Option<Spanned<f32>>,
    eta: Option<Spanned<f32>>,
}

/// Whether `path` is a path-traced reference (a TOML file with a top-level
/// `[path_traced]` table) rather than a pipeline.
pub fn is_path_traced(path: &Path) -> bool {
    plait_assets::read_to_string(path)
        .ok()
        .and_then(|text| text.parse::<toml::Table>().ok())
        .is_some_and(|t| t.contains_key("path_traced"))
}

impl PathTraced {
    /// Read and check `path`: every bad key or value at file:line:col. Its
    /// `[fibre]` table is over `library`'s standard fibre.
    pub fn load(path: &Path, library: &plait_gpu::PassLibrary) -> Result<Self, PathTracedError> {
        // `plait_assets` reads a built-in copy (`<built-in>/references/…`) too.
        let text = plait_assets::read_to_string(path).map_err(|source| PathTracedError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let at = |span: Option<Range<usize>>, message: String| {
            let (line, col) = line_col(&text, span.map_or(0, |s| s.start));
            PathTracedError::Syntax {
                path: path.to_path_buf(),
                line,
                col,
                message,
            }
        };
        let file: FileToml =
            toml::from_str(&text).map_err(|e| at(e.span(), e.message().trim().to_string()))?;
        let s = file.path_traced;
        let renderer = s.renderer.get_ref().as_str();
        if !RENDERERS.contains(&renderer) {
            let nearest = plait_graph::suggest::nearest(renderer, RENDERERS.iter().copied())
                .map(|n| format!(" (did you mean \"{n}\"?)"))
                .unwrap_or_default();
            return Err(at(
                Some(s.renderer.span()),
                format!("renderer `{renderer}`: one of \"mitsuba\", \"plait\"{nearest}"),
            ));
        }
        if *s.spp.get_ref() == 0 {
            return Err(at(Some(s.spp.span()), "spp must be at least 1".into()));
        }
        let depth = *s.max_depth.get_ref();
        if depth < 1 && depth != -1 {
            return Err(at(
                Some(s.max_depth.span()),
                "max_depth must be at least 1 (2: single scattering), or -1: unbounded".into(),
            ));
        }
        if renderer == "plait" {
            super::plait_reference::check(&s.spp, &s.max_depth, &s.seeds, &at)?;
        }
        let seeds: [u32; 2] = match s.seeds.get_ref().as_slice() {
            &[a, b] if a != b => [a, b],
            _ => {
                return Err(at(
                    Some(s.seeds.span()),
                    "seeds must be two different numbers (their images' difference is the noise estimate)".into(),
                ));
            }
        };
        let bound = *s.max_noise_rmse.get_ref();
        if !(bound.is_finite() && bound > 0.0) {
            return Err(at(
                Some(s.max_noise_rmse.span()),
                "max_noise_rmse must be a finite number above 0".into(),
            ));
        }
        Ok(PathTraced {
            file: path.to_path_buf(),
            renderer: s.renderer.into_inner(),
            spp: *s.spp.get_ref(),
            max_depth: depth,
            seeds,
            max_noise_rmse: bound,
            fibre: fibre(file.fibre, Fibre::standard(library), &at)?,
            standard_fibre: Fibre::standard(library),
        })
    }

    /// How the report names it: renderer, version, samples, depth, and
    /// the fibre when it is not the standard one.
    pub fn describe(&self) -> String {
        let f = &self.fibre;
        let fibre = if *f == self.standard_fibre {
            String::new()
        } else {
            format!(
                ", fibre β_m {} β_n {} α {}° η {}",
                f.longitudinal_roughness, f.azimuthal_roughness, f.scale_tilt_degrees, f.eta
            )
        };
        let renderer = match self.renderer.as_str() {
            "plait" => "plait's GPU path tracer, Chiang fibre".to_string(),
            _ => format!("Mitsuba {} hair BSDF", super::cache::mitsuba_version()),
        };
        format!(
            "path-traced, {renderer}, {} × {} spp, max_depth {}{fibre}",
            self.seeds.len(),
            self.spp,
            self.max_depth
        )
    }
}

/// The renderers a path-traced reference names.
const RENDERERS: [&str; 2] = ["mitsuba", "plait"];

type Check = fn(f32) -> bool;

/// The fibre's values: each one's `[fibre]` key, the `--set` that sets it
/// too (the `chiang` technique's param of the same quantity, so one flag
/// describes the fibre to the variants and to the path tracer), its check
/// and what it must be.
const FIBRE_FIELDS: [(&str, &str, Check, &str); 4] = [
    (
        "longitudinal_roughness",
        "params.chiang_beta_m",
        |x| x > 0.0 && x <= 1.0,
        "in (0, 1]",
    ),
    (
        "azimuthal_roughness",
        "params.chiang_beta_n",
        |x| x > 0.0 && x <= 1.0,
        "in (0, 1]",
    ),
    (
        "scale_tilt_degrees",
        "params.chiang_tilt",
        |x| x.abs() <= 45.0,
        "within ±45",
    ),
    (
        "eta",
        "params.chiang_eta",
        |x| x > 1.0 && x < 4.0,
        "in (1, 4)",
    ),
];

fn fibre_field(fibre: &mut Fibre, i: usize) -> &mut f32 {
    match i {
        0 => &mut fibre.longitudinal_roughness,
        1 => &mut fibre.azimuthal_roughness,
        2 => &mut fibre.scale_tilt_degrees,
        _ => &mut fibre.eta,
    }
}

/// The `[fibre]` table over `standard`; each value finite and within its
/// field's bounds.
fn fibre(
    given: Option<FibreToml>,
    standard: Fibre,
    at: &dyn Fn(Option<Range<usize>>, String) -> PathTracedError,
) -> Result<Fibre, PathTracedError> {
    let mut fibre = standard;
    let Some(f) = given else { return Ok(fibre) };
    let values = [
        f.longitudinal_roughness,
        f.azimuthal_roughness,
        f.scale_tilt_degrees,
        f.eta,
    ];
    for (i, value) in values.into_iter().enumerate() {
        let (key, _, ok, bounds) = FIBRE_FIELDS[i];
        if let Some(v) = value {
            if !(v.get_ref().is_finite() && ok(*v.get_ref())) {
                return Err(at(Some(v.span()), format!("{key} must be {bounds}")));
            }
            *fibre_field(&mut fibre, i) = *v.get_ref();
        }
    }
    Ok(fibre)
}

/// `fibre` with the run's `--set params.chiang_…` applied (they win over
/// the file's `[fibre]`: the flag is what the user typed for this run),
/// each checked as the file's value is, the error naming the flag.
pub(super) fn fibre_with_sets(mut fibre: Fibre, sets: &[String]) -> Result<Fibre, PathTracedError> {
    for set in sets {
        let Some((key, value)) = set.split_once('=') else {
            continue;
        };
        let Some(i) = FIBRE_FIELDS.iter().position(|f| f.1 == key.trim()) else {
            continue;
        };
        let (name, _, ok, bounds) = FIBRE_FIELDS[i];
        match value.trim().parse::<f32>() {
            Ok(v) if v.is_finite() && ok(v) => *fibre_field(&mut fibre, i) = v,
            _ => {
                return Err(PathTracedError::FibreSet {
                    set: set.clone(),
                    message: format!("the path tracer's fibre {name} must be {bounds}"),
                });
            }
        }
    }
    Ok(fibre)
}

/// The run's `--set`s the path-traced reference does not follow: all but
/// the display (`params.exposure`, `techniques.tone_mapping = agx`) and the
/// fibre (`params.chiang_…`). They tune the pipelines; the path tracer
/// renders the scene and its fibre. Said in the run, never ignored silently.
pub(super) fn sets_not_followed(sets: &[String]) -> Vec<String> {
    sets.iter()
        .filter(|set| {
            let key = set.split_once('=').map_or(set.as_str(), |(k, _)| k).trim();
            !(key == "params.exposure"
                || key == "techniques.tone_mapping"
                || FIBRE_FIELDS.iter().any(|f| f.1 == key))
        })
        .cloned()
        .collect()
}

/// 1-based line and column (in characters) of byte `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// The path-traced reference `reference` is, if it is one; refused with
/// `--frames` (one still per scene) or a display it cannot follow.
pub(super) fn load_if_path_traced(
    reference: &Path,
    options: &super::AbOptions,
    library: &plait_gpu::PassLibrary,
) -> Result<Option<PathTraced>, PathTracedError> {
    if !is_path_traced(reference) {
        return Ok(None);
    }
    let mut spec = PathTraced::load(reference, library)?;
    if options.sequence.is_some() {
        return Err(PathTracedError::Frames);
    }
    display_exposure(&options.sets)?;
    spec.fibre = fibre_with_sets(spec.fibre, &options.sets)?;
    Ok(Some(spec))
}

/// Every scene exports (no spot light, no background image…), checked
/// before any GPU work or rendering.
pub(super) fn check_scenes(
    spec: &PathTraced,
    options: &super::AbOptions,
    scenes: &[super::ScenePlan],
) -> Result<(), PathTracedError> {
    let size = options.render_size(true);
    for scene in scenes {
        crate::mitsuba::plan(&scene.data, size, spec.fibre).map_err(|source| {
            PathTracedError::Export {
                scene: scene.name.clone(),
                source,
            }
        })?;
    }
    Ok(())
}

/// The exposure (`--set params.exposure`) the reference is shown at; a
/// `--set techniques.tone_mapping` other than agx cannot be followed.
pub(super) fn display_exposure(sets: &[String]) -> Result<f32, PathTracedError> {
    let mut exposure = 0.0;
    for set in sets {
        let Some((key, value)) = set.split_once('=') else {
            continue;
        };
        match key.trim() {
            "params.exposure" => {
                exposure = value
                    .trim()
                    .parse()
                    .map_err(|_| PathTracedError::Display(set.clone()))?;
            }
            "techniques.tone_mapping" if value.trim() != "agx" => {
                return Err(PathTracedError::Display(set.clone()));
            }
            _ => {}
        }
    }
    Ok(exposure)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The standard fibre of the library on the search path.
    fn standard() -> Fibre {
        Fibre::standard(&plait_passes::read_library(&[]))
    }

    fn load(text: &str) -> Result<PathTraced, PathTracedError> {
        let dir = std::env::temp_dir().join(format!("plait-pt-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("{:x}.toml", text.len() * 31 + text.lines().count()));
        std::fs::write(&path, text).unwrap();
        PathTraced::load(&path, &plait_passes::read_library(&[]))
    }

    const GOOD: &str = "[path_traced]\nrenderer = \"mitsuba\"\nspp = 8\nmax_depth = 16\nseeds = [0, 1]\nmax_noise_rmse = 0.01\n";

    #[test]
    fn the_shipped_reference_loads_with_the_default_fibre() {
        let path = crate::session::repo_root().join("references/path_traced.toml");
        assert!(is_path_traced(&path));
        let p = PathTraced::load(&path, &plait_passes::read_library(&[])).expect("loads");
        assert_eq!(p.fibre, standard());
        assert_eq!(p.renderer, "mitsuba");
        assert!(!is_path_traced(
            &crate::session::repo_root().join("pipelines/depth_peeling.toml")
        ));
    }

    #[test]
    fn bad_keys_and_values_are_named_at_their_place() {
        let p = load(GOOD).expect("good");
        assert_eq!((p.spp, p.max_depth, p.seeds), (8, 16, [0, 1]));
        let cases = [
            (GOOD.replace("spp = 8", "spq = 8"), 3, "spq"),
            (GOOD.replace("spp = 8", "spp = 0"), 3, "spp"),
            (GOOD.replace("[0, 1]", "[1, 1]"), 5, "seeds"),
            (GOOD.replace("\"mitsuba\"", "\"pbrt\""), 2, "pbrt"),
            (GOOD.replace("0.01", "-1.0"), 6, "max_noise_rmse"),
            (format!("{GOOD}[fibre]\neta = 0.5\n"), 8, "eta"),
        ];
        for (text, line, word) in cases {
            let e = load(&text).expect_err("error").to_string();
            assert!(e.contains(&format!(".toml:{line}:")), "{e}");
            assert!(e.contains(word), "{e}");
        }
    }

    #[test]
    fn chiang_sets_reach_the_fibre_and_other_sets_are_named() {
        let sets: Vec<String> = [
            "params.chiang_beta_m=0.2",
            "params.chiang_eta=1.6",
            "params.exposure=1",
            "params.shadow_weight=0.3",
            "techniques.transparency=linked_list",
        ]
        .map(String::from)
        .into();
        let f = fibre_with_sets(standard(), &sets).unwrap();
        assert_eq!(f.longitudinal_roughness, 0.2);
        assert_eq!(f.eta, 1.6);
        assert_eq!(f.azimuthal_roughness, standard().azimuthal_roughness);
        assert_eq!(
            sets_not_followed(&sets),
            [
                "params.shadow_weight=0.3",
                "techniques.transparency=linked_list"
            ]
        );
        let e = fibre_with_sets(standard(), &["params.chiang_eta=0.5".into()]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--set params.chiang_eta=0.5: the path tracer's fibre eta must be in (1, 4)"
        );
    }

    #[test]
    fn display_follows_the_exposure_and_refuses_other_operators() {
        assert_eq!(
            display_exposure(&["params.exposure=-1.5".into()]).unwrap(),
            -1.5
        );
        assert!(display_exposure(&["techniques.tone_mapping=agx".into()]).is_ok());
        assert!(display_exposure(&["techniques.tone_mapping=clip".into()]).is_err());
    }
}
