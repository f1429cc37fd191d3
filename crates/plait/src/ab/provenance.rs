//! Where the numbers came from: the adapter, the command, and a hash of
//! every file they depend on (pipelines, the files they extend, shaders,
//! scenes, the shaders built into the binary).

use std::path::{Path, PathBuf};

use plait_compare::report::{Adapter, FileHash, PipelineProvenance, Provenance};
use plait_gpu::Gpu;
use plait_graph::Schedule;
use sha2::Digest as _;

use super::{AbError, Plan};

/// How the report's metrics are defined (shown in the report).
const METRICS: &str = "RMSE and PSNR (peak 1) on 8-bit sRGB RGB values normalized to 0..1; SSIM (Wang et al. 2004) on Rec.601 luma, 11×11 Gaussian window σ=1.5, K1=0.01, K2=0.03; ꟻLIP: LDR-FLIP (nv-flip) at 67 pixels per degree, mean of the error map; visibility |ΔV|: every provider and the reference probed at the same points with the same light-map lookup (the texel the point falls in, no Fig. 9 jitter), hair in front = nearer the light by more than the self-shadow bias";

fn sha256_hex(bytes: &[u8]) -> String {
    sha2::Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

fn hash_file(path: &Path) -> Result<FileHash, AbError> {
    // A built-in copy (`<built-in>/pipelines/…`) is hashed as built in.
    let read = if plait_assets::is_builtin(path) {
        plait_assets::read_to_string(path).map(|t| t.into_owned().into_bytes())
    } else {
        std::fs::read(path)
    };
    let bytes = read.map_err(|source| AbError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(FileHash {
        path: path.display().to_string(),
        sha256: sha256_hex(&bytes),
        bytes: bytes.len() as u64,
    })
}

/// A path-traced reference's files: its TOML, the script that renders it
/// and the script that pins Mitsuba's version.
pub(super) fn path_traced_provenance(file: &Path) -> Result<PipelineProvenance, AbError> {
    // The library's copies (the checkout's, or the built-in ones): the ones
    // the reference ran.
    let script = |relative: &str| {
        let path = plait_assets::find(relative).unwrap_or_else(|| PathBuf::from(relative));
        hash_file(&path)
    };
    Ok(PipelineProvenance {
        path: file.display().to_string(),
        files: vec![
            hash_file(file)?,
            script("scripts/mitsuba/render.py")?,
            script("scripts/ensure-mitsuba.sh")?,
        ],
        shaders: Vec::new(),
    })
}

fn hash_text(name: &str, text: &str) -> FileHash {
    FileHash {
        path: name.to_string(),
        sha256: sha256_hex(text.as_bytes()),
        bytes: text.len() as u64,
    }
}

/// Quote an argument for a POSIX shell when it needs it.
pub fn shell_quote(arg: &str) -> String {
    if !arg.is_empty()
        && arg
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=:,@+%".contains(c))
    {
        arg.to_string()
    } else {
        format!("'{}'", arg.replace('\'', "'\\''"))
    }
}

/// A pipeline's files (itself and what it extends) and the WGSL its passes name.
pub(super) fn pipeline_provenance(
    path: &Path,
    s: &Schedule,
) -> Result<PipelineProvenance, AbError> {
    let files = s
        .files
        .iter()
        .map(|f| hash_file(f))
        .collect::<Result<Vec<_>, _>>()?;
    let mut shader_paths: Vec<&PathBuf> = s
        .passes
        .iter()
        .chain(s.culled.iter().map(|c| &c.pass))
        .filter_map(|p| p.shader.as_ref())
        .collect();
    shader_paths.sort();
    shader_paths.dedup();
    let shaders = shader_paths
        .into_iter()
        .map(|p| hash_file(p))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(PipelineProvenance {
        path: path.display().to_string(),
        files,
        shaders,
    })
}

/// A library shader, named as in the library, with the text the run uses:
/// the copy on the search path when there is one (`PLAIT_PATH`, the
/// checkout), else the built-in text.
fn as_used(library: &plait_gpu::PassLibrary, name: &str) -> (String, String) {
    let used = library
        .shaders
        .library_file(name)
        .map(|(_, used)| used.into_owned())
        .unwrap_or_default();
    (name.to_owned(), used)
}

fn builtin_shaders(library: &plait_gpu::PassLibrary) -> Vec<FileHash> {
    // The library as this run composes with it: every module found on the
    // search path, generated selectors included.
    let mut out: Vec<FileHash> = library
        .shaders
        .library()
        .map(|l| {
            l.modules
                .iter()
                .map(|m| hash_text(&m.key, &m.source))
                .collect()
        })
        .unwrap_or_default();
    // Pass types may share one WGSL file (the pass-type files of
    // shaders/passes name theirs): list each file once, with the pass types
    // that use it.
    let mut files: Vec<(String, String, Vec<&str>)> = Vec::new();
    for (type_name, t) in &library.types {
        if let Some(name) = t.shader() {
            let (path, used) = as_used(library, name);
            match files.iter_mut().find(|(n, x, _)| *n == path && *x == used) {
                Some((_, _, types)) => types.push(type_name),
                None => files.push((path, used, vec![type_name])),
            }
        }
    }
    for (name, text, types) in files {
        let what = if types.len() == 1 { "type" } else { "types" };
        out.push(hash_text(
            &format!("{name} (pass {what} {})", types.join(", ")),
            &text,
        ));
    }
    out
}

/// The provenance of a run of `plan` on `gpu`; `pipelines` from
/// [`pipeline_provenance`], each file once.
pub(super) fn provenance(
    plan: &Plan,
    gpu: &Gpu,
    pipelines: Vec<PipelineProvenance>,
    library: &plait_gpu::PassLibrary,
) -> Result<Provenance, AbError> {
    let o = &plan.options;
    // A scene at several camera distances is one file, hashed once.
    let mut scene_paths: Vec<&Path> = Vec::new();
    for path in plan.scenes.iter().filter_map(|s| s.path.as_deref()) {
        if !scene_paths.contains(&path) {
            scene_paths.push(path);
        }
    }
    let scenes = scene_paths
        .into_iter()
        .map(hash_file)
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Provenance {
        plait_version: env!("CARGO_PKG_VERSION").into(),
        adapter: Adapter {
            name: gpu.adapter_name().to_string(),
            backend: gpu.backend_name(),
            driver: gpu.info.driver.clone(),
            driver_info: gpu.info.driver_info.clone(),
        },
        timestamps: gpu.capabilities.timestamps,
        command_line: o
            .command
            .iter()
            .map(|a| shell_quote(a))
            .collect::<Vec<_>>()
            .join(" "),
        command: o.command.clone(),
        working_directory: std::env::current_dir()
            .map(|d| d.display().to_string())
            .unwrap_or_default(),
        size: [o.size.0, o.size.1],
        repeats: o.repeats,
        reference_repeats: o.reference_repeats,
        warmup_frames: 1,
        order: "interleaved".into(),
        sets: o.sets.clone(),
        reference: plan.reference.display().to_string(),
        metrics: METRICS.into(),
        pipelines,
        builtin_shaders: builtin_shaders(library),
        scenes,
        unix_time: std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_secs())
            .unwrap_or(0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoting() {
        assert_eq!(shell_quote("--size"), "--size");
        assert_eq!(shell_quote("a b"), "'a b'");
        assert_eq!(shell_quote("it's"), "'it'\\''s'");
    }

    #[test]
    fn each_builtin_shader_file_is_listed_once() {
        let shaders = builtin_shaders(&plait_passes::read_library(&[]));
        let hair: Vec<_> = shaders
            .iter()
            .filter(|f| f.path.starts_with("shaders/passes/hair_shade.wgsl"))
            .collect();
        assert_eq!(hair.len(), 1, "{hair:?}");
        assert!(
            hair[0].path.ends_with("(pass type hair_shade)"),
            "{}",
            hair[0].path
        );
        let mut paths: Vec<&str> = shaders.iter().map(|f| f.path.as_str()).collect();
        paths.sort();
        assert!(paths.windows(2).all(|w| w[0] != w[1]), "{paths:?}");
        assert!(shaders.iter().all(|f| f.sha256.len() == 64));
    }
}
