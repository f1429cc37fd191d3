//! A pipeline as the user named it, which a render loads once and loads
//! again only when something changes it (a bounded buffer grown, another
//! technique tried for an adapter that cannot run the one chosen).

use std::path::{Path, PathBuf};

use plait_graph::{CompileOptions, Errors, Location, Pipeline, Schedule};

/// A pipeline file, the `--set` flags applied to it, and the textures made
/// outputs besides its own (`plait render --show`).
#[derive(Clone, Debug)]
pub struct PipelineSource {
    pub path: PathBuf,
    pub sets: Vec<String>,
    /// Each with the flag that asked for it, where an error points.
    pub extra_outputs: Vec<(String, String)>,
}

impl PipelineSource {
    pub fn new(path: &Path, sets: &[String]) -> Self {
        PipelineSource {
            path: path.to_path_buf(),
            sets: sets.to_vec(),
            extra_outputs: Vec::new(),
        }
    }

    /// Also make texture `name` an output, asked for by `flag`.
    pub fn with_output(mut self, name: &str, flag: &str) -> Self {
        self.extra_outputs.push((name.to_owned(), flag.to_owned()));
        self
    }

    /// The pipeline with `extra` sets after the user's.
    pub fn load(&self, extra: &[String]) -> Result<Pipeline, Errors> {
        let mut pipeline = plait_graph::load(&self.path, &[self.sets.as_slice(), extra].concat())?;
        for (name, flag) in &self.extra_outputs {
            pipeline.add_output(name, Location::Flag { flag: flag.clone() });
        }
        Ok(pipeline)
    }

    /// [`Self::load`], then compile and check it with `opts` (shaders included).
    pub fn compile(&self, extra: &[String], opts: &CompileOptions) -> Result<Schedule, Errors> {
        crate::session::check_pipeline(&self.load(extra)?, opts)
    }
}
