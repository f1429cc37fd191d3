//! A pipeline as the user named it, which a render loads once and loads
//! again only when something changes it (a bounded buffer grown, another
//! technique tried for an adapter that cannot run the one chosen).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use plait_gpu::PassLibrary;
use plait_graph::{CompileOptions, Errors, Location, Pipeline, Schedule};

/// A pipeline file, the `--set` flags applied to it, the textures made
/// outputs besides its own (`plait render --show`), and the library it is
/// compiled and built with.
#[derive(Clone)]
pub struct PipelineSource {
    pub path: PathBuf,
    pub sets: Vec<String>,
    /// Each with the flag that asked for it, where an error points.
    pub extra_outputs: Vec<(String, String)>,
    /// The session's library: every compile and build of this source uses
    /// it, so one render reads the library once.
    pub library: Arc<PassLibrary>,
}

impl std::fmt::Debug for PipelineSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PipelineSource")
            .field("path", &self.path)
            .field("sets", &self.sets)
            .field("extra_outputs", &self.extra_outputs)
            .finish_non_exhaustive()
    }
}

impl PipelineSource {
    /// `path` with `sets` and a library read for it now (the search path
    /// and the pipeline's own `techniques/`).
    pub fn new(path: &Path, sets: &[String]) -> Self {
        Self::with_library(path, sets, plait_passes::library_for(&[path]))
    }

    /// `path` with `sets`, compiled and built with `library` (one library
    /// for several pipelines: `plait ab`, `plait check A B`).
    pub fn with_library(path: &Path, sets: &[String], library: Arc<PassLibrary>) -> Self {
        PipelineSource {
            path: path.to_path_buf(),
            sets: sets.to_vec(),
            extra_outputs: Vec::new(),
            library,
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
        crate::session::check_pipeline(&self.library, &self.load(extra)?, opts)
    }
}
