//! The pictures of the generated pages: a render on each reference scene and
//! the schedule's SVG, made by the `plait` binary into the staged book, each
//! distinct command once (a technique's page shows the picture of the
//! gallery pipeline that selects it, not a second render of the same thing).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::error::BookError;
use crate::plait_cmd::{Figure, Plait};

/// Where and how the pictures are made.
#[derive(Clone, Debug)]
pub struct FigureSettings {
    /// Scenes by the name `--scene` finds (`small.toml`).
    pub scenes: Vec<String>,
    pub size: (u32, u32),
}

/// One picture on disk: its path relative to the book's `src/` and the
/// command that made it.
#[derive(Clone, Debug)]
pub struct Made {
    pub file: String,
    pub command: String,
}

/// Makes each figure once, under `src/figures/`.
pub struct Figures<'a> {
    plait: &'a Plait,
    src: PathBuf,
    pub settings: FigureSettings,
    made: HashMap<(Figure, String), Made>,
}

impl<'a> Figures<'a> {
    pub fn new(plait: &'a Plait, src: &Path, settings: FigureSettings) -> Result<Self, BookError> {
        let dir = src.join("figures");
        std::fs::create_dir_all(&dir).map_err(BookError::io(&dir))?;
        Ok(Figures {
            plait,
            src: src.to_path_buf(),
            settings,
            made: HashMap::new(),
        })
    }

    /// The figure's file name stem: its pipeline and sets, readable.
    fn stem(figure: &Figure) -> String {
        let mut stem = figure.pipeline.trim_end_matches(".toml").to_string();
        for set in &figure.sets {
            stem.push('-');
            stem.push_str(&set.replace(['.', '='], "_"));
        }
        stem
    }

    /// Renders `figure` on every reference scene; one `Made` per scene.
    pub fn renders(&mut self, figure: &Figure) -> Result<Vec<(String, Made)>, BookError> {
        let mut out = Vec::new();
        for scene in self.settings.scenes.clone() {
            let key = (figure.clone(), scene.clone());
            if let Some(m) = self.made.get(&key) {
                out.push((scene, m.clone()));
                continue;
            }
            let file = format!(
                "figures/{}-{}.png",
                Self::stem(figure),
                scene.trim_end_matches(".toml")
            );
            let command = figure.render(
                self.plait,
                &scene,
                self.settings.size,
                &self.src.join(&file),
            )?;
            let made = Made { file, command };
            self.made.insert(key, made.clone());
            out.push((scene, made));
        }
        Ok(out)
    }

    /// The schedule of `figure` as SVG.
    pub fn graph(&mut self, figure: &Figure) -> Result<Made, BookError> {
        let key = (figure.clone(), String::from("<graph>"));
        if let Some(m) = self.made.get(&key) {
            return Ok(m.clone());
        }
        let file = format!("figures/{}.svg", Self::stem(figure));
        let command = figure.graph(self.plait, &self.src.join(&file))?;
        let made = Made { file, command };
        self.made.insert(key, made.clone());
        Ok(made)
    }
}

/// The Markdown of a figure's renders (side by side) with their commands,
/// for a page `depth` folders below `src/`.
pub fn renders_markdown(renders: &[(String, Made)], depth: usize) -> String {
    let up = "../".repeat(depth);
    let mut out = String::from("| scene | picture |\n|---|---|\n");
    for (scene, m) in renders {
        out.push_str(&format!(
            "| `{scene}` | ![{} on {scene}]({up}{}) |\n",
            m.file, m.file
        ));
    }
    out.push_str("\nMade by\n\n```sh\n");
    for (_, m) in renders {
        out.push_str(&m.command);
        out.push_str(" --out picture.png\n");
    }
    out.push_str("```\n");
    out
}
