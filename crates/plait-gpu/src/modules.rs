//! Composed shader modules, cached for the whole process.
//!
//! `plait check` and every build of a pass compose the same shader with the
//! same defines: checking a pipeline, building it, rendering it again at
//! another size and every variant of an A/B run. Composition (naga_oil, then
//! naga validation) costs far more than a lookup, so each distinct
//! (path, source, defines) is composed once and shared.
//!
//! The library modules are read from the search path, so they can change
//! while plait runs (the viewer reloads on an edit): when any of them has
//! changed on disk ([`library_stamp`]), the library is loaded again and
//! everything composed with the old one is dropped.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use crate::shader::{Define, ShaderError, ShaderLibrary};

type Key = (PathBuf, String, Vec<(String, Define)>);

#[derive(Default)]
struct Modules {
    /// Created on first use: loading the library modules is itself a cost.
    /// With the [`library_stamp`] it was loaded at.
    library: Option<(u64, ShaderLibrary)>,
    composed: HashMap<Key, Arc<naga::Module>>,
}

static MODULES: Mutex<Option<Modules>> = Mutex::new(None);

/// The composed, validated module of `source` with `defines` (`path` names it
/// in messages). Failures are not cached: they are reported, then fixed.
pub fn compose(
    path: &Path,
    source: &str,
    defines: &[(String, Define)],
) -> Result<Arc<naga::Module>, ShaderError> {
    // A panic elsewhere while holding the lock leaves a cache that is still
    // consistent (entries are inserted whole), so a poisoned lock is reused.
    let mut guard = MODULES.lock().unwrap_or_else(|p| p.into_inner());
    let modules = guard.get_or_insert_with(Modules::default);
    let stamp = library_stamp();
    if modules.library.as_ref().is_some_and(|(s, _)| *s != stamp) {
        modules.library = None;
        modules.composed.clear();
    }
    let key: Key = (path.to_owned(), source.to_owned(), defines.to_vec());
    if let Some(m) = modules.composed.get(&key) {
        return Ok(m.clone());
    }
    let library = match &mut modules.library {
        Some((_, l)) => l,
        None => &mut modules.library.insert((stamp, ShaderLibrary::new()?)).1,
    };
    let module = Arc::new(library.compose(path, source, defines)?);
    modules.composed.insert(key, module.clone());
    Ok(module)
}

/// Load the shader library (or reuse the loaded one): a broken library
/// module fails here once, rather than in every pass that imports it.
pub fn check_library() -> Result<(), ShaderError> {
    let mut guard = MODULES.lock().unwrap_or_else(|p| p.into_inner());
    let modules = guard.get_or_insert_with(Modules::default);
    let stamp = library_stamp();
    if modules.library.as_ref().is_some_and(|(s, _)| *s == stamp) {
        return Ok(());
    }
    modules.library = Some((stamp, ShaderLibrary::new()?));
    modules.composed.clear();
    Ok(())
}

thread_local! {
    /// The stamp pinned by the outermost live [`LibrarySnapshot`] of this
    /// thread, and how many snapshots are live.
    static PINNED: std::cell::Cell<(usize, u64)> = const { std::cell::Cell::new((0, 0)) };
}

/// While alive, [`library_stamp`] on this thread returns the stamp taken when
/// the outermost snapshot was made instead of walking the library's folders
/// again. One compile or build asks for the stamp hundreds of times (every
/// composition, every provider lookup) and should see one library anyway: a
/// file saved halfway through is picked up by the next compile, not half of
/// this one.
pub struct LibrarySnapshot {
    _not_send: std::marker::PhantomData<*const ()>,
}

impl LibrarySnapshot {
    pub fn take() -> Self {
        let (depth, stamp) = PINNED.get();
        let stamp = if depth == 0 {
            walk_library_stamp()
        } else {
            stamp
        };
        PINNED.set((depth + 1, stamp));
        LibrarySnapshot {
            _not_send: std::marker::PhantomData,
        }
    }
}

impl Drop for LibrarySnapshot {
    fn drop(&mut self) {
        let (depth, stamp) = PINNED.get();
        PINNED.set((depth.saturating_sub(1), stamp));
    }
}

/// Where each library module is read from and when it last changed, hashed:
/// cheap (no file is read) and different after an edit, or when a copy on
/// the search path appears or goes. Within a [`LibrarySnapshot`], the stamp
/// it took.
pub fn library_stamp() -> u64 {
    match PINNED.get() {
        (0, _) => walk_library_stamp(),
        (_, stamp) => stamp,
    }
}

fn walk_library_stamp() -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::hash::DefaultHasher::new();
    for (key, path) in crate::library::library_files() {
        key.hash(&mut h);
        if plait_assets::is_builtin(&path) {
            continue;
        }
        let meta = std::fs::metadata(&path).ok();
        (&path, meta.as_ref().map(|m| m.len())).hash(&mut h);
        meta.and_then(|m| m.modified().ok()).hash(&mut h);
    }
    h.finish()
}

/// Digest of the library modules' text as loaded for the last composition,
/// for pipeline cache keys (an edited module changes every shader).
pub fn library_digest() -> u64 {
    MODULES
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .as_ref()
        .and_then(|m| m.library.as_ref())
        .map_or(0, |(_, l)| l.library_digest())
}

/// How many distinct modules have been composed (for tests of the cache).
pub fn composed_count() -> usize {
    MODULES
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .as_ref()
        .map_or(0, |m| m.composed.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_shader_is_composed_once() {
        let source = "@compute @workgroup_size(1) fn main() {}";
        let path = Path::new("cache_test.wgsl");
        let a = compose(path, source, &[]).expect("composes");
        let b = compose(path, source, &[]).expect("composes");
        assert!(Arc::ptr_eq(&a, &b), "the second compose is a cache hit");
        let c = compose(path, source, &[("X".into(), Define::Bool(true))]).expect("composes");
        assert!(!Arc::ptr_eq(&a, &c), "other defines are another module");
    }
}
