//! The pipelines, shaders and example scenes plait ships, found at run time.
//!
//! A *library file* is named by its path inside a plait checkout
//! (`pipelines/occupancy.toml`, `techniques/self_shadow/occupancy/technique.toml`,
//! `shaders/passes/hair_shade.wgsl`, `examples/scenes/small.toml`). It is read
//! from the first folder of the search path that holds it — so editing a
//! shader needs no rebuild, and the viewer reloads it — and, when no folder
//! does, from the copy built into the binary, so an installed `plait` works
//! from any directory.
//!
//! The search path is `PLAIT_PATH` (folders separated as in `PATH`) when that
//! is set — set but empty means the built-in copies alone — and otherwise the
//! checkout plait was built from, while it still exists.
//!
//! A built-in copy has the path `<built-in>/RELATIVE` (e.g.
//! `<built-in>/pipelines/occupancy.toml`): messages print it as is, and
//! [`read_to_string`] and [`exists`] accept it wherever plait reads a pipeline
//! or shader file, so `extends` and `shader = "../shaders/x.wgsl"` work inside
//! the built-in copies exactly as on disk.

use std::borrow::Cow;
use std::ffi::OsString;
use std::path::{Component, Path, PathBuf};

include!(concat!(env!("OUT_DIR"), "/builtin.rs"));

/// The environment variable holding the search path.
pub const SEARCH_PATH_VAR: &str = "PLAIT_PATH";

/// The first component of a built-in copy's path.
pub const BUILTIN_ROOT: &str = "<built-in>";

/// The checkout this crate was built from.
const BUILD_CHECKOUT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The checkout plait was built from, if it still holds plait's shaders.
pub fn build_checkout() -> Option<PathBuf> {
    let root = Path::new(BUILD_CHECKOUT);
    if root.join("shaders/lib/frame.wgsl").is_file() {
        root.canonicalize().ok()
    } else {
        None
    }
}

/// The folders searched for library files, in order (the built-in copies come
/// after all of them).
pub fn search_path() -> Vec<PathBuf> {
    search_path_from(std::env::var_os(SEARCH_PATH_VAR))
}

/// [`search_path`] for a given value of `PLAIT_PATH` (`None`: unset).
pub fn search_path_from(var: Option<OsString>) -> Vec<PathBuf> {
    match var {
        Some(v) => std::env::split_paths(&v)
            .filter(|p| !p.as_os_str().is_empty())
            .collect(),
        None => build_checkout().into_iter().collect(),
    }
}

/// A relative path with `.` and `..` resolved lexically, `/`-separated; `None`
/// if it is absolute or climbs above its start.
fn normalize(relative: &Path) -> Option<String> {
    let mut parts: Vec<String> = Vec::new();
    for c in relative.components() {
        match c {
            Component::Normal(p) => parts.push(p.to_string_lossy().into_owned()),
            Component::CurDir => {}
            Component::ParentDir => {
                parts.pop()?;
            }
            Component::RootDir | Component::Prefix(_) => return None,
        }
    }
    Some(parts.join("/"))
}

/// The library-relative name of a built-in path (`<built-in>/a/../b` → `b`).
fn builtin_key(path: &Path) -> Option<String> {
    let rest = path.strip_prefix(BUILTIN_ROOT).ok()?;
    normalize(rest)
}

/// Whether `path` names a built-in copy (`<built-in>/…`).
pub fn is_builtin(path: &Path) -> bool {
    path.starts_with(BUILTIN_ROOT)
}

/// The built-in copy of a library file.
pub fn builtin(relative: &str) -> Option<&'static str> {
    let key = normalize(Path::new(relative))?;
    BUILTIN
        .iter()
        .find(|(k, _)| *k == key)
        .map(|(_, text)| *text)
}

/// Every built-in file as `(library-relative path, text)`, sorted by path.
pub fn builtin_files() -> &'static [(&'static str, &'static str)] {
    BUILTIN
}

/// `path` relative to the working directory when it lies inside it (shorter
/// messages in a checkout), else unchanged.
fn shorten(path: PathBuf) -> PathBuf {
    shorten_in(canonical_cwd().as_deref(), path)
}

/// The working directory, resolved (once per listing: resolving it walks
/// every component of the path through `readlink`).
fn canonical_cwd() -> Option<PathBuf> {
    let cwd = std::env::current_dir().ok()?;
    Some(cwd.canonicalize().unwrap_or(cwd))
}

/// [`shorten`] against an already resolved working directory.
fn shorten_in(cwd: Option<&Path>, path: PathBuf) -> PathBuf {
    match cwd.map(|cwd| path.strip_prefix(cwd)) {
        Some(Ok(rel)) if !rel.as_os_str().is_empty() => rel.to_path_buf(),
        _ => path,
    }
}

/// The first of `roots` holding the library file `relative`.
pub fn find_in(roots: &[PathBuf], relative: &str) -> Option<PathBuf> {
    let relative = normalize(Path::new(relative))?;
    roots
        .iter()
        .map(|root| root.join(&relative))
        .find(|p| p.is_file())
        .map(shorten)
}

/// The library file `relative` on disk: the first folder of the search path
/// holding it.
pub fn find_on_disk(relative: &str) -> Option<PathBuf> {
    find_in(&search_path(), relative)
}

/// The library file `relative`: on disk if a folder of the search path holds
/// it, else its built-in copy (`<built-in>/…`).
pub fn find(relative: &str) -> Option<PathBuf> {
    find_on_disk(relative).or_else(|| {
        let key = normalize(Path::new(relative))?;
        builtin(&key).map(|_| Path::new(BUILTIN_ROOT).join(key))
    })
}

/// A file named inside a pipeline (`extends = "occupancy.toml"`, `shader =
/// "../shaders/x.wgsl"`) that is not next to it: looked up on the library
/// search path as written without leading `./` and `../`, then inside
/// `folder` (`pipelines` for `extends`, `shaders` for `shader`).
pub fn find_named(written: &str, folder: &str) -> Option<PathBuf> {
    let trimmed: PathBuf = Path::new(written)
        .components()
        .skip_while(|c| matches!(c, Component::CurDir | Component::ParentDir))
        .collect();
    if trimmed.as_os_str().is_empty() || trimmed.is_absolute() {
        return None;
    }
    let as_written = trimmed.to_string_lossy().into_owned();
    find(&as_written).or_else(|| find(&format!("{folder}/{as_written}")))
}

/// Read a pipeline or shader file: from disk, or a built-in copy for a
/// `<built-in>/…` path.
pub fn read_to_string(path: &Path) -> std::io::Result<Cow<'static, str>> {
    if is_builtin(path) {
        return builtin_key(path)
            .and_then(|key| builtin(&key))
            .map(Cow::Borrowed)
            .ok_or_else(|| {
                std::io::Error::new(
                    std::io::ErrorKind::NotFound,
                    "plait has no built-in file of that name",
                )
            });
    }
    std::fs::read_to_string(path).map(Cow::Owned)
}

/// Whether [`read_to_string`] can find `path`.
pub fn exists(path: &Path) -> bool {
    if is_builtin(path) {
        builtin_key(path).is_some_and(|key| builtin(&key).is_some())
    } else {
        path.exists()
    }
}

/// Whether `path` is a folder: on disk, or a folder of the built-in copies
/// (`<built-in>/techniques`).
pub fn is_dir(path: &Path) -> bool {
    if !is_builtin(path) {
        return path.is_dir();
    }
    match builtin_key(path) {
        Some(key) if key.is_empty() => true,
        Some(key) => BUILTIN
            .iter()
            .any(|(k, _)| k.strip_prefix(&key).is_some_and(|r| r.starts_with('/'))),
        None => false,
    }
}

/// The entries of a folder (files and folders), on disk or built in; empty
/// when it cannot be read.
pub fn read_dir(path: &Path) -> Vec<PathBuf> {
    if !is_builtin(path) {
        return std::fs::read_dir(path)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.path())
            .collect();
    }
    let Some(key) = builtin_key(path) else {
        return Vec::new();
    };
    let prefix = if key.is_empty() {
        key
    } else {
        format!("{key}/")
    };
    let mut names: Vec<&str> = BUILTIN
        .iter()
        .filter_map(|(k, _)| k.strip_prefix(&prefix))
        .map(|rest| rest.split('/').next().unwrap_or(rest))
        .collect();
    names.sort_unstable();
    names.dedup();
    names.into_iter().map(|n| path.join(n)).collect()
}

/// The library folder `relative` (`techniques`): the first folder of the
/// search path that has it, else the built-in copies' (`<built-in>/…`).
pub fn find_dir(relative: &str) -> Option<PathBuf> {
    let relative = normalize(Path::new(relative))?;
    search_path()
        .into_iter()
        .map(|root| root.join(&relative))
        .find(|p| p.is_dir())
        .map(shorten)
        .or_else(|| {
            let builtin = Path::new(BUILTIN_ROOT).join(&relative);
            is_dir(&builtin).then_some(builtin)
        })
}

/// Every file `folder/*.EXT` of the library (`list("pipelines", "toml")`): one
/// per file name, the first in search order (disk before built-in), sorted by
/// name.
pub fn list(folder: &str, ext: &str) -> Vec<PathBuf> {
    list_in(&search_path(), folder, ext)
}

/// [`list`] over the given roots.
pub fn list_in(roots: &[PathBuf], folder: &str, ext: &str) -> Vec<PathBuf> {
    let mut found: std::collections::BTreeMap<String, PathBuf> = Default::default();
    for root in roots {
        let Ok(entries) = std::fs::read_dir(root.join(folder)) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_file() && path.extension().is_some_and(|e| e == ext) {
                let name = entry.file_name().to_string_lossy().into_owned();
                found.entry(name).or_insert_with(|| shorten(path));
            }
        }
    }
    let prefix = format!("{folder}/");
    for (key, _) in BUILTIN {
        if let Some(name) = key.strip_prefix(&prefix)
            && !name.contains('/')
            && name.ends_with(&format!(".{ext}"))
        {
            found
                .entry(name.to_owned())
                .or_insert_with(|| Path::new(BUILTIN_ROOT).join(key));
        }
    }
    found.into_values().collect()
}

/// Every file `folder/**/*.EXT` of the library, at any depth, as
/// `(library-relative path, where it is read from)`: one per relative path,
/// the first in search order (disk before built-in), sorted by path. This is
/// how the engine finds shader modules and point contracts without a list.
pub fn list_tree(folder: &str, ext: &str) -> Vec<(String, PathBuf)> {
    list_tree_in(&search_path(), folder, ext)
}

/// [`list_tree`] over the given roots.
pub fn list_tree_in(roots: &[PathBuf], folder: &str, ext: &str) -> Vec<(String, PathBuf)> {
    fn walk(dir: &Path, key: &str, ext: &str, out: &mut Vec<(String, PathBuf)>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            let name = entry.file_name().to_string_lossy().into_owned();
            let key = format!("{key}/{name}");
            if path.is_dir() {
                walk(&path, &key, ext, out);
            } else if path.extension().is_some_and(|e| e == ext) {
                out.push((key, path));
            }
        }
    }
    let Some(folder) = normalize(Path::new(folder)) else {
        return Vec::new();
    };
    let mut found: std::collections::BTreeMap<String, PathBuf> = Default::default();
    let cwd = canonical_cwd();
    for root in roots {
        let mut here = Vec::new();
        walk(&root.join(&folder), &folder, ext, &mut here);
        for (key, path) in here {
            found
                .entry(key)
                .or_insert_with(|| shorten_in(cwd.as_deref(), path));
        }
    }
    let prefix = format!("{folder}/");
    let suffix = format!(".{ext}");
    for (key, _) in BUILTIN {
        if key.starts_with(&prefix) && key.ends_with(&suffix) {
            found
                .entry((*key).to_owned())
                .or_insert_with(|| Path::new(BUILTIN_ROOT).join(key));
        }
    }
    found.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gallery_and_the_shader_library_are_built_in() {
        for name in [
            "pipelines/occupancy.toml",
            "pipelines/forward.toml",
            "shaders/lib/frame.wgsl",
            "shaders/passes/hair_shade.wgsl",
            "shaders/compose_over.wgsl",
            "techniques/self_shadow/occupancy/technique.toml",
            "examples/scenes/small.toml",
            "examples/scenes/default.toml",
        ] {
            let text = builtin(name).unwrap_or_else(|| panic!("{name} is not built in"));
            assert!(!text.is_empty(), "{name} is empty");
        }
        assert!(builtin("pipelines/nope.toml").is_none());
        assert!(builtin("../Cargo.toml").is_none());
    }

    #[test]
    fn built_in_folders_list_like_disk_folders() {
        let root = Path::new("<built-in>/techniques");
        assert!(is_dir(root));
        assert!(is_dir(Path::new("<built-in>/techniques/self_shadow")));
        assert!(!is_dir(Path::new(
            "<built-in>/techniques/self_shadow/occupancy/technique.toml"
        )));
        assert!(!is_dir(Path::new("<built-in>/nothing")));
        let points = read_dir(root);
        assert!(points.contains(&root.join("self_shadow")), "{points:?}");
        assert!(points.contains(&root.join("transparency")), "{points:?}");
        let files = read_dir(&root.join("self_shadow"));
        // Techniques are folders; fragments they include are files.
        assert!(
            files.contains(&root.join("self_shadow/occupancy")),
            "{files:?}"
        );
        assert!(
            files.contains(&root.join("self_shadow/light_range.toml")),
            "{files:?}"
        );
        assert!(read_dir(Path::new("<built-in>/nothing")).is_empty());
    }

    #[test]
    fn built_in_paths_resolve_dot_dot_like_disk_paths() {
        let p = Path::new("<built-in>/pipelines/../shaders/compose_over.wgsl");
        assert!(exists(p));
        assert_eq!(
            read_to_string(p).expect("built in"),
            builtin("shaders/compose_over.wgsl").expect("built in")
        );
        assert!(!exists(Path::new("<built-in>/pipelines/missing.toml")));
        let err = read_to_string(Path::new("<built-in>/../etc/passwd")).expect_err("escapes");
        assert_eq!(err.kind(), std::io::ErrorKind::NotFound);
    }

    #[test]
    fn plait_path_replaces_the_build_checkout_and_empty_means_built_in_only() {
        assert!(search_path_from(Some(OsString::new())).is_empty());
        assert_eq!(
            search_path_from(Some(OsString::from("/a:/b"))),
            vec![PathBuf::from("/a"), PathBuf::from("/b")]
        );
        // Unset: the checkout these tests run in.
        let unset = search_path_from(None);
        assert_eq!(unset.len(), 1);
        assert!(unset[0].join("shaders/lib/frame.wgsl").is_file());
    }

    #[test]
    fn earlier_folders_win_and_the_built_in_copies_fill_in() {
        let first = tempfile::tempdir().expect("temp dir");
        let second = tempfile::tempdir().expect("temp dir");
        std::fs::create_dir_all(first.path().join("pipelines")).expect("mkdir");
        std::fs::create_dir_all(second.path().join("pipelines")).expect("mkdir");
        std::fs::write(first.path().join("pipelines/mine.toml"), "a").expect("write");
        std::fs::write(second.path().join("pipelines/mine.toml"), "b").expect("write");
        std::fs::write(second.path().join("pipelines/forward.toml"), "c").expect("write");
        let roots = vec![first.path().to_path_buf(), second.path().to_path_buf()];
        assert_eq!(
            find_in(&roots, "pipelines/mine.toml"),
            Some(first.path().join("pipelines/mine.toml"))
        );
        let listed = list_in(&roots, "pipelines", "toml");
        assert!(listed.contains(&first.path().join("pipelines/mine.toml")));
        assert!(listed.contains(&second.path().join("pipelines/forward.toml")));
        assert!(listed.contains(&PathBuf::from("<built-in>/pipelines/occupancy.toml")));
        assert_eq!(
            listed
                .iter()
                .filter(|p| p.file_name().is_some_and(|n| n == "forward.toml"))
                .count(),
            1,
            "one entry per file name: {listed:?}"
        );
    }

    #[test]
    fn a_tree_lists_files_at_any_depth_nearest_root_first() {
        let first = tempfile::tempdir().expect("temp dir");
        let second = tempfile::tempdir().expect("temp dir");
        let deep = "shaders/lib/visibility";
        std::fs::create_dir_all(first.path().join(deep)).expect("mkdir");
        std::fs::create_dir_all(second.path().join(deep)).expect("mkdir");
        std::fs::write(first.path().join(deep).join("mine.wgsl"), "a").expect("write");
        std::fs::write(second.path().join(deep).join("mine.wgsl"), "b").expect("write");
        std::fs::write(second.path().join("shaders/lib/frame.wgsl"), "c").expect("write");
        let roots = vec![first.path().to_path_buf(), second.path().to_path_buf()];
        let listed = list_tree_in(&roots, "shaders/lib", "wgsl");
        let at = |key: &str| {
            listed
                .iter()
                .find(|(k, _)| k == key)
                .map(|(_, p)| p.clone())
        };
        assert_eq!(
            at("shaders/lib/visibility/mine.wgsl"),
            Some(first.path().join(deep).join("mine.wgsl"))
        );
        assert_eq!(
            at("shaders/lib/frame.wgsl"),
            Some(second.path().join("shaders/lib/frame.wgsl"))
        );
        // Built-in copies fill in what no root holds, at any depth.
        assert!(
            listed
                .iter()
                .any(|(k, p)| k == "shaders/lib/cube.wgsl" && is_builtin(p)),
            "{listed:?}"
        );
        let keys: Vec<&String> = listed.iter().map(|(k, _)| k).collect();
        let mut sorted = keys.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(keys, sorted, "one entry per path, sorted");
    }

    #[test]
    fn names_written_in_pipelines_are_found_as_written_or_in_their_folder() {
        // The build checkout (or the built-in copy) has both.
        let a = find_named("occupancy.toml", "pipelines").expect("found");
        assert!(a.ends_with("pipelines/occupancy.toml"), "{}", a.display());
        let b = find_named("../shaders/compose_over.wgsl", "shaders").expect("found");
        assert!(b.ends_with("shaders/compose_over.wgsl"), "{}", b.display());
        assert!(find_named("nothing.toml", "pipelines").is_none());
        assert!(find_named("/etc/passwd", "pipelines").is_none());
    }
}
