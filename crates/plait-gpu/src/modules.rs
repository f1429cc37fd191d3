//! The shader side of a library value: the WGSL library read once, the
//! composer loaded with it, every module composed with it and every shader
//! text read for it.
//!
//! `plait check` and every build of a pass compose the same shader with the
//! same defines: checking a pipeline, building it, rendering it again at
//! another size and every variant of an A/B run. Composition (naga_oil, then
//! naga validation) costs far more than a lookup, so each distinct
//! (path, source, defines) is composed once per [`Shaders`] value and shared.
//!
//! A [`Shaders`] is a value with no global behind it: the text it composes is
//! the text it read, first at compile, so a build never reads a shader file
//! again (an edit halfway through a render is not half picked up). The
//! viewer and `render --watch` read a new one when a file changes.

use std::borrow::Cow;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard};

use crate::library::Library;
use crate::shader::{Define, ShaderError, ShaderLibrary};

type Key = (PathBuf, String, Vec<(String, Define)>);

/// The shader library of one session (see the module docs).
pub struct Shaders {
    /// The WGSL library as read, or why it could not be (every compile with
    /// it reports that, at its file, line and column).
    library: Result<Library, ShaderError>,
    /// Digest of the library modules' text, for pipeline cache keys.
    digest: u64,
    state: Mutex<State>,
}

#[derive(Default)]
struct State {
    /// The composer with the library's modules added; created on first use
    /// (loading the modules into naga_oil is itself a cost), once.
    composer: Option<Result<ShaderLibrary, ShaderError>>,
    composed: HashMap<Key, Arc<naga::Module>>,
    /// Shader files read for this library, by the name asked for (a library
    /// path, or a pipeline's `shader = …` path), with the path messages name.
    texts: HashMap<PathBuf, (PathBuf, Arc<str>)>,
    /// How many shader files were read from disk or the built-in copies.
    reads: usize,
}

impl Default for Shaders {
    /// An empty library: no modules, no points (tests of a lone shader).
    fn default() -> Self {
        Shaders::new(Ok(Library::default()))
    }
}

impl Shaders {
    /// The WGSL library of the search path with the `techniques/` of
    /// `own_roots` before it ([`Library::read`]); a library that cannot be
    /// read is kept as its error.
    pub fn read(own_roots: &[PathBuf]) -> Self {
        Shaders::new(Library::read(own_roots))
    }

    pub fn new(library: Result<Library, ShaderError>) -> Self {
        use std::hash::{Hash, Hasher};
        let mut h = std::hash::DefaultHasher::new();
        for module in library.iter().flat_map(|l| &l.modules) {
            module.source.hash(&mut h);
        }
        Shaders {
            library,
            digest: h.finish(),
            state: Mutex::new(State::default()),
        }
    }

    /// The WGSL library, or why it could not be read.
    pub fn library(&self) -> Result<&Library, &ShaderError> {
        self.library.as_ref()
    }

    /// The providers found for the point whose param is `param`; none when
    /// the library could not be read (compiling reports why).
    pub fn providers(&self, param: &str) -> Vec<String> {
        self.library
            .as_ref()
            .map(|l| l.providers(param))
            .unwrap_or_default()
    }

    // A panic elsewhere while holding the lock leaves a state that is still
    // consistent (entries are inserted whole), so a poisoned lock is reused.
    fn state(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Load the library into the composer (once): a broken library module
    /// fails here, rather than in every pass that imports it.
    pub fn check(&self) -> Result<(), ShaderError> {
        let mut state = self.state();
        self.composer(&mut state).map(|_| ())
    }

    fn composer<'s>(&self, state: &'s mut State) -> Result<&'s mut ShaderLibrary, ShaderError> {
        let library = &self.library;
        let made = state
            .composer
            .get_or_insert_with(|| ShaderLibrary::new(library.as_ref().map_err(Clone::clone)?));
        made.as_mut().map_err(|e| e.clone())
    }

    /// The composed, validated module of `source` with `defines` (`path`
    /// names it in messages). Failures are not kept: they are reported, then
    /// fixed, and the fix is read by a new library value.
    pub fn compose(
        &self,
        path: &Path,
        source: &str,
        defines: &[(String, Define)],
    ) -> Result<Arc<naga::Module>, ShaderError> {
        let mut state = self.state();
        let key: Key = (path.to_owned(), source.to_owned(), defines.to_vec());
        if let Some(m) = state.composed.get(&key) {
            return Ok(m.clone());
        }
        let module = Arc::new(self.composer(&mut state)?.compose(path, source, defines)?);
        state.composed.insert(key, module.clone());
        Ok(module)
    }

    /// Digest of the library modules' text, for pipeline cache keys (an
    /// edited module changes every shader).
    pub fn digest(&self) -> u64 {
        self.digest
    }

    /// How many distinct modules have been composed (for tests of the cache).
    pub fn composed_count(&self) -> usize {
        self.state().composed.len()
    }

    /// How many shader files this value read (each at most once).
    pub fn file_reads(&self) -> usize {
        self.state().reads
    }

    /// The text of a library file (a pass type's shader,
    /// `shaders/passes/occupancy.wgsl`) with the path messages name: read on
    /// first use ([`crate::shader::library_file`]), then the same text.
    pub fn library_file(&self, name: &str) -> Result<(PathBuf, Cow<'static, str>), ShaderError> {
        self.text(Path::new(name), || crate::shader::library_file(name))
    }

    /// The text of a shader a pipeline names (`shader = "…"`): read on first
    /// use, then the same text.
    pub fn shader_file(&self, path: &Path) -> std::io::Result<Cow<'static, str>> {
        let mut error = None;
        let got = self.text(path, || {
            crate::shader::read_shader_file(path)
                .map(|t| (path.to_owned(), t))
                .map_err(|e| {
                    let message = e.to_string();
                    error = Some(e);
                    ShaderError {
                        path: path.to_owned(),
                        message,
                    }
                })
        });
        match (got, error) {
            (Ok((_, text)), _) => Ok(text),
            (Err(_), Some(e)) => Err(e),
            (Err(e), None) => Err(std::io::Error::other(e.message)),
        }
    }

    fn text(
        &self,
        key: &Path,
        read: impl FnOnce() -> Result<(PathBuf, Cow<'static, str>), ShaderError>,
    ) -> Result<(PathBuf, Cow<'static, str>), ShaderError> {
        if let Some((path, text)) = self.state().texts.get(key) {
            return Ok((path.clone(), Cow::Owned(text.to_string())));
        }
        // Read outside the lock; a failed read is not kept (a file that
        // appears later is read then).
        let (path, text) = read()?;
        let mut state = self.state();
        state.reads += 1;
        let entry = state
            .texts
            .entry(key.to_owned())
            .or_insert_with(|| (path, Arc::from(text.as_ref())));
        Ok((entry.0.clone(), Cow::Owned(entry.1.to_string())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_shader_is_composed_once() {
        let shaders = Shaders::read(&[]);
        let source = "@compute @workgroup_size(1) fn main() {}";
        let path = Path::new("cache_test.wgsl");
        let a = shaders.compose(path, source, &[]).expect("composes");
        let b = shaders.compose(path, source, &[]).expect("composes");
        assert!(Arc::ptr_eq(&a, &b), "the second compose is a cache hit");
        let c = shaders
            .compose(path, source, &[("X".into(), Define::Bool(true))])
            .expect("composes");
        assert!(!Arc::ptr_eq(&a, &c), "other defines are another module");
        assert_eq!(shaders.composed_count(), 2);
    }

    /// A shader file is read once per library value: what a build composes
    /// is the text compile read, even if the file changed in between.
    #[test]
    fn a_shader_file_is_read_once_per_value() {
        let file =
            std::env::temp_dir().join(format!("plait-read-once-{}.wgsl", std::process::id()));
        std::fs::write(&file, "// first\n").expect("write");
        let shaders = Shaders::default();
        assert_eq!(shaders.shader_file(&file).expect("read"), "// first\n");
        std::fs::write(&file, "// second\n").expect("write");
        assert_eq!(shaders.shader_file(&file).expect("read"), "// first\n");
        assert_eq!(shaders.file_reads(), 1);
        assert_eq!(
            Shaders::default().shader_file(&file).expect("read"),
            "// second\n",
            "a new value reads the file as it is now"
        );
        let _ = std::fs::remove_file(&file);
    }
}
