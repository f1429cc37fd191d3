//! What every generated page draws on, gathered once: the gallery pipelines
//! (loaded by plait-graph, with the techniques they resolve to), the pass
//! library's params (from `plait passes --json`), the last measurement run
//! and the figure maker.

use std::path::{Path, PathBuf};

use crate::error::BookError;
use crate::figures::Figures;
use crate::measured::Run;
use crate::plait_cmd::Plait;

/// The pipeline every gallery file extends, and whose picture stands for
/// the default techniques.
pub const DEFAULT_PIPELINE: &str = "occupancy.toml";

/// One file of `pipelines/`.
#[derive(Clone, Debug)]
pub struct GalleryPipeline {
    pub path: PathBuf,
    /// `deep_opacity.toml`.
    pub file_name: String,
    /// Its page under `src/`.
    pub page: String,
    pub description: String,
    /// What its own `[techniques]` table says (not what it extends).
    pub own_choices: Vec<(String, String)>,
    /// Every technique it resolves to, extends included.
    pub chosen: Vec<(String, String)>,
}

impl GalleryPipeline {
    pub fn selects(&self, point: &str, name: &str) -> bool {
        self.chosen.iter().any(|(p, n)| p == point && n == name)
    }
}

/// A param a pass type declares: what it accepts and its doc.
#[derive(Clone, Debug)]
pub struct PassParam {
    pub pass_type: String,
    pub name: String,
    pub accepts: String,
    pub doc: String,
}

pub struct Context<'a> {
    pub repo: PathBuf,
    pub pipelines: Vec<GalleryPipeline>,
    pub pass_params: Vec<PassParam>,
    pub runs: Vec<Run>,
    pub figures: Figures<'a>,
    /// Whether the book has the live view (`live/`): pages link to it.
    pub live: bool,
}

impl Context<'_> {
    pub fn default_pipeline(&self) -> &GalleryPipeline {
        self.pipelines
            .iter()
            .find(|p| p.file_name == DEFAULT_PIPELINE)
            .expect("gallery() refuses a gallery without the default pipeline")
    }

    /// The param `name` of pass type `pass_type`.
    pub fn pass_param(&self, pass_type: &str, name: &str) -> Option<&PassParam> {
        self.pass_params
            .iter()
            .find(|p| p.pass_type == pass_type && p.name == name)
    }
}

/// Every `pipelines/*.toml`, by name, loaded as `plait render` loads it.
pub fn gallery(repo: &Path) -> Result<Vec<GalleryPipeline>, BookError> {
    let dir = repo.join("pipelines");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map_err(BookError::io(&dir))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    let mut out = Vec::new();
    for path in files {
        let loaded =
            plait_graph::load(&path, &[]).map_err(|e| BookError::content(&path, e.to_string()))?;
        let text = std::fs::read_to_string(&path).map_err(BookError::io(&path))?;
        let table: toml::Table =
            toml::from_str(&text).map_err(|e| BookError::content(&path, e.to_string()))?;
        let own_choices = table
            .get("techniques")
            .and_then(|t| t.as_table())
            .map(|t| {
                t.iter()
                    .filter_map(|(k, v)| Some((k.clone(), v.as_str()?.to_string())))
                    .collect()
            })
            .unwrap_or_default();
        let file_name = path.file_name().unwrap().to_string_lossy().into_owned();
        out.push(GalleryPipeline {
            page: format!("pipelines/{}.md", file_name.trim_end_matches(".toml")),
            description: loaded.description.value.clone(),
            own_choices,
            chosen: loaded
                .techniques
                .iter()
                .map(|t| (t.point.clone(), t.name.clone()))
                .collect(),
            file_name,
            path,
        });
    }
    if !out.iter().any(|p| p.file_name == DEFAULT_PIPELINE) {
        return Err(BookError::content(
            dir,
            format!("no {DEFAULT_PIPELINE}, the pipeline the gallery extends"),
        ));
    }
    Ok(out)
}

/// The pass library's params, from `plait passes --json`.
pub fn pass_params(plait: &Plait) -> Result<Vec<PassParam>, BookError> {
    let json = plait.json(&["passes", "--json"])?;
    let mut out = Vec::new();
    for spec in json.as_array().into_iter().flatten() {
        let pass_type = spec["name"].as_str().unwrap_or_default().to_string();
        for p in spec["params"].as_array().into_iter().flatten() {
            out.push(PassParam {
                pass_type: pass_type.clone(),
                name: p["name"].as_str().unwrap_or_default().to_string(),
                accepts: p["accepts"].as_str().unwrap_or_default().to_string(),
                doc: p["doc"].as_str().unwrap_or_default().to_string(),
            });
        }
    }
    Ok(out)
}
