//! Embeds every `pipelines/*.toml`, `techniques/**/*.{toml,wgsl}`,
//! `shaders/**/*.{wgsl,toml}`, `examples/scenes/*.toml`, `references/*.toml`
//! and the two scripts a path-traced reference runs (`scripts/mitsuba/render.py`,
//! `scripts/ensure-mitsuba.sh`) of the checkout as
//! the built-in copies (the fallback when no folder of the search path holds a
//! file), so new gallery files need no list to be kept by hand.

use std::fmt::Write;
use std::path::{Path, PathBuf};

fn collect(root: &Path, dir: &Path, ext: &str, recursive: bool, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            if recursive {
                collect(root, &path, ext, recursive, out);
            }
        } else if path.extension().is_some_and(|e| e == ext) {
            out.push(path.strip_prefix(root).unwrap_or(&path).to_path_buf());
        }
    }
}

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let root = manifest.join("../..");
    let mut files = Vec::new();
    collect(&root, &root.join("pipelines"), "toml", false, &mut files);
    // plait's path tracer, a reference's renderer (`renderer = "plait"`):
    // kept out of `pipelines/*.toml`, which every pipeline test renders.
    collect(
        &root,
        &root.join("pipelines/physical"),
        "toml",
        false,
        &mut files,
    );
    collect(&root, &root.join("techniques"), "toml", true, &mut files);
    // A technique's own WGSL lives in its folder, next to its TOML.
    collect(&root, &root.join("techniques"), "wgsl", true, &mut files);
    collect(&root, &root.join("shaders"), "wgsl", true, &mut files);
    // Pass-type files (`shaders/passes/*.toml`), found by the pass library.
    collect(&root, &root.join("shaders"), "toml", true, &mut files);
    // The scenes' text only: files they name (studio.hdr) are not embedded,
    // and plait-hair says so when a built-in scene names one.
    collect(
        &root,
        &root.join("examples/scenes"),
        "toml",
        false,
        &mut files,
    );
    // `plait ab --reference references/path_traced.toml` from any directory:
    // the reference file, the script that renders it and the one that pins
    // (and installs) Mitsuba.
    collect(&root, &root.join("references"), "toml", false, &mut files);
    files.push(PathBuf::from("scripts/mitsuba/render.py"));
    files.push(PathBuf::from("scripts/ensure-mitsuba.sh"));
    files.sort();
    let mut code = String::from("pub(crate) const BUILTIN: &[(&str, &str)] = &[\n");
    for rel in &files {
        let key = rel
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect::<Vec<_>>()
            .join("/");
        let abs = root.join(rel).canonicalize().expect("listed file exists");
        writeln!(
            code,
            "    ({key:?}, include_str!({:?})),",
            abs.display().to_string()
        )
        .expect("writing to a String");
    }
    code.push_str("];\n");
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("set by cargo")).join("builtin.rs");
    std::fs::write(&out, code).expect("writing builtin.rs");
    // A directory makes cargo rescan it for any change (new files included).
    println!("cargo:rerun-if-changed=../../pipelines");
    println!("cargo:rerun-if-changed=../../techniques");
    println!("cargo:rerun-if-changed=../../shaders");
    println!("cargo:rerun-if-changed=../../examples/scenes");
    println!("cargo:rerun-if-changed=../../references");
    println!("cargo:rerun-if-changed=../../scripts/mitsuba/render.py");
    println!("cargo:rerun-if-changed=../../scripts/ensure-mitsuba.sh");
}
