//! Path-traced references, rendered by Mitsuba and cached. The key hashes
//! everything that decides the image: the exported scene's files (strands,
//! meshes, camera, light, size are all in them), the renderer, its pinned
//! version and `render.py`'s bytes, the samples, depth and seeds. An entry
//! is a folder `<cache>/<key>/` with one EXR per seed and `entry.json`; it
//! is written under a temporary name and renamed, so an interrupt leaves
//! no half entry (at most a `.tmp-*` folder, never read, and removed by the
//! next run once its process is gone).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

use sha2::{Digest, Sha256};

use super::ScenePlan;
use super::path_traced::{PathTraced, PathTracedError};

/// Both seeds' mean at the run's `--size` and what the run needs to know of it.
pub(super) struct Reference {
    pub mean: image::Rgba32FImage,
    pub noise_rmse: f64,
    pub seconds: f64,
}

/// The scripts a path-traced reference runs, as library files: the search
/// path's copy (the checkout's, or one on `PLAIT_PATH`), else the one built
/// into the binary — an installed `plait` needs no checkout.
const RENDER_PY: &str = "scripts/mitsuba/render.py";
const ENSURE_MITSUBA: &str = "scripts/ensure-mitsuba.sh";

fn script_text(relative: &str) -> Result<String, PathTracedError> {
    let path = plait_assets::find(relative).unwrap_or_else(|| PathBuf::from(relative));
    plait_assets::read_to_string(&path)
        .map(|t| t.into_owned())
        .map_err(|source| PathTracedError::Read { path, source })
}

/// The Mitsuba version `scripts/ensure-mitsuba.sh` pins (render.py checks
/// the installed one is it), read from the script so the key cannot
/// disagree with what is installed without starting Python.
pub fn mitsuba_version() -> String {
    script_text(ENSURE_MITSUBA)
        .ok()
        .and_then(|t| {
            t.lines()
                .find_map(|l| l.strip_prefix("MITSUBA_VERSION="))
                .map(|v| v.split_whitespace().next().unwrap_or("").to_string())
        })
        .unwrap_or_else(|| "unknown".into())
}

/// A library script as a file a program can run: the checkout's own file
/// when it is one, else its text written under `<build folder>/plait-scripts/`
/// with a name from its hash (two versions never share a file; a second
/// run writes nothing; written under a temporary name and renamed).
fn script_file(relative: &str) -> Result<PathBuf, PathTracedError> {
    if let Some(path) = plait_assets::find(relative).filter(|p| !plait_assets::is_builtin(p)) {
        return Ok(path);
    }
    let text = script_text(relative)?;
    let hash: String = Sha256::digest(text.as_bytes())
        .iter()
        .take(8)
        .map(|b| format!("{b:02x}"))
        .collect();
    let name = Path::new(relative);
    let stem = name.file_stem().unwrap_or_default().to_string_lossy();
    let ext = name.extension().unwrap_or_default().to_string_lossy();
    let dir = target_dir().join("plait-scripts");
    let path = dir.join(format!("{stem}-{hash}.{ext}"));
    if !path.exists() {
        std::fs::create_dir_all(&dir).map_err(io(&dir))?;
        let tmp = dir.join(format!(".tmp-{}-{stem}.{ext}", std::process::id()));
        std::fs::write(&tmp, &text).map_err(io(&tmp))?;
        std::fs::rename(&tmp, &path).map_err(io(&path))?;
    }
    Ok(path)
}

/// The command that installs Mitsuba where [`python`] looks for it.
fn install_command() -> String {
    match script_file(ENSURE_MITSUBA) {
        Ok(script) if std::env::var_os("CARGO_TARGET_DIR").is_some() => {
            format!("bash {}", script.display())
        }
        // The script puts the venv in $CARGO_TARGET_DIR, else beside itself
        // in a checkout: name the folder plait looks in.
        Ok(script) => format!(
            "CARGO_TARGET_DIR={} bash {}",
            target_dir().display(),
            script.display()
        ),
        Err(_) => "bash scripts/ensure-mitsuba.sh".into(),
    }
}

/// `$PLAIT_MITSUBA_PYTHON`, else the venv `scripts/ensure-mitsuba.sh`
/// makes in the build folder ([`target_dir`]).
fn python() -> Result<PathBuf, PathTracedError> {
    let candidate = match std::env::var_os("PLAIT_MITSUBA_PYTHON") {
        Some(p) => PathBuf::from(p),
        None => target_dir().join("mitsuba-venv/bin/python"),
    };
    if candidate.exists() {
        Ok(candidate)
    } else {
        Err(PathTracedError::NoMitsuba {
            tried: format!("no {}", candidate.display()),
            install: install_command(),
        })
    }
}

/// `$CARGO_TARGET_DIR`, else the build checkout's `target/` while it
/// exists, else `$XDG_CACHE_HOME/plait` (or `~/.cache/plait`): where the
/// venv, the cache and written scripts go.
fn target_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("CARGO_TARGET_DIR") {
        return PathBuf::from(dir);
    }
    if let Some(checkout) = plait_assets::build_checkout() {
        return checkout.join("target");
    }
    let cache_home = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(std::env::temp_dir);
    cache_home.join("plait")
}

/// The default `--cache`: `plait-references` in the build folder.
pub fn default_cache() -> PathBuf {
    target_dir().join("plait-references")
}

/// The LLVM Mitsuba's llvm variant needs, where ensure-mitsuba.sh finds it.
fn libllvm() -> Option<PathBuf> {
    [
        "/usr/lib/llvm-19/lib/libLLVM-19.so",
        "/usr/lib/x86_64-linux-gnu/libLLVM-19.so.1",
        "/usr/lib/llvm-19/lib/libLLVM.so",
    ]
    .into_iter()
    .map(PathBuf::from)
    .find(|p| p.exists())
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> PathTracedError + '_ {
    move |source| PathTracedError::Cache {
        path: path.to_path_buf(),
        source,
    }
}

/// The key of `spec` on the scene exported into `dir`.
fn key(spec: &PathTraced, dir: &Path) -> Result<String, PathTracedError> {
    let mut h = Sha256::new();
    h.update(b"plait path-traced reference 1\0");
    let mut names: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(io(dir))?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()
        .map_err(io(dir))?;
    names.sort();
    let mut files = Vec::new();
    for path in &names {
        let bytes = std::fs::read(path).map_err(io(path))?;
        files.push((
            path.file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned(),
            bytes,
        ));
    }
    // render.py's text, wherever it was found (same key as a file of that name).
    files.push(("render.py".into(), script_text(RENDER_PY)?.into_bytes()));
    for (name, bytes) in files {
        h.update(format!("{name}\0{}\0", bytes.len()).as_bytes());
        h.update(&bytes);
    }
    h.update(
        format!(
            "{}\0{}\0{}\0{}\0{:?}\0",
            spec.renderer,
            mitsuba_version(),
            spec.spp,
            spec.max_depth,
            spec.seeds
        )
        .as_bytes(),
    );
    let hex: String = h.finalize().iter().map(|b| format!("{b:02x}")).collect();
    Ok(hex[..32].to_string())
}

/// The reference of `scene` rendered at `size` pixels (`--size` ×
/// `supersample`) and filtered down: from `cache` when it holds it, else
/// rendered by Mitsuba (one process per seed) and stored there.
pub(super) fn reference(
    spec: &PathTraced,
    scene: &ScenePlan,
    (size, supersample): ((u32, u32), u32),
    cache: &Path,
    progress: &mut dyn FnMut(&str) -> std::io::Result<()>,
) -> Result<Reference, super::AbError> {
    std::fs::create_dir_all(cache).map_err(io(cache))?;
    sweep_interrupted(cache);
    let export = cache.join(format!(".tmp-export-{}-{}", std::process::id(), scene.name));
    let _ = std::fs::remove_dir_all(&export);
    let exported = crate::mitsuba::plan(&scene.data, size, spec.fibre)
        .and_then(|m| m.write(&export))
        .map_err(|source| PathTracedError::Export {
            scene: scene.name.clone(),
            source,
        });
    let result = (|| -> Result<Reference, super::AbError> {
        exported?;
        let key = key(spec, &export)?;
        let entry = cache.join(&key);
        let say = |p: &mut dyn FnMut(&str) -> std::io::Result<()>, line: String| {
            p(&line).map_err(super::AbError::Progress)
        };
        if entry.join("entry.json").exists() {
            say(
                progress,
                format!(
                    "{}: path-traced reference: cache hit {}",
                    scene.name,
                    entry.display()
                ),
            )?;
        } else {
            render(spec, scene, size, &export, &entry, progress)?;
        }
        read(spec, scene, &entry, supersample)
    })();
    let _ = std::fs::remove_dir_all(&export);
    result
}

/// Removes the temporaries (`.tmp-PID-…`, `.tmp-export-PID-…`) of runs that
/// no longer exist: an interrupted run ends without its destructors and
/// leaves its half-rendered folder, which is never read but would stay. A
/// folder of a live process (another run sharing the cache) is kept. Only
/// where `/proc` says which processes live; elsewhere they stay, unread.
fn sweep_interrupted(cache: &Path) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(cache) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = name
            .strip_prefix(".tmp-export-")
            .or_else(|| name.strip_prefix(".tmp-"))
        else {
            continue;
        };
        let Some(pid) = rest.split('-').next().and_then(|p| p.parse::<u32>().ok()) else {
            continue;
        };
        if !Path::new("/proc").join(pid.to_string()).exists() {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}

/// Both seeds rendered into a temporary folder, renamed to `entry` once complete.
fn render(
    spec: &PathTraced,
    scene: &ScenePlan,
    size: (u32, u32),
    export: &Path,
    entry: &Path,
    progress: &mut dyn FnMut(&str) -> std::io::Result<()>,
) -> Result<(), super::AbError> {
    let python = python()?;
    let render_py = script_file(RENDER_PY)?;
    let tmp = entry.with_file_name(format!(
        ".tmp-{}-{}",
        std::process::id(),
        entry.file_name().unwrap_or_default().to_string_lossy()
    ));
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).map_err(io(&tmp))?;
    let mut seconds = Vec::new();
    let last = entry.with_file_name("last-seed.json");
    for seed in spec.seeds {
        let estimate = match seconds.first() {
            Some(s) => format!("estimate {s:.0} s (as seed {})", spec.seeds[0]),
            None => last_seed(&last),
        };
        progress(&format!(
            "{}: path-traced reference: Mitsuba seed {seed}, {} spp, max_depth {}, {}x{}, {estimate}",
            scene.name, spec.spp, spec.max_depth, size.0, size.1
        ))
        .map_err(super::AbError::Progress)?;
        let start = Instant::now();
        let mut command = Command::new(&python);
        command
            .arg(&render_py)
            .arg(export)
            .arg(tmp.join(format!("seed{seed}.exr")))
            .args(["--spp", &spec.spp.to_string()])
            .args(["--max-depth", &spec.max_depth.to_string()])
            .args(["--seed", &seed.to_string()])
            .args(["--expect-version", &mitsuba_version()])
            .stdin(Stdio::null())
            .stdout(Stdio::null());
        if std::env::var_os("DRJIT_LIBLLVM_PATH").is_none()
            && let Some(llvm) = libllvm()
        {
            command.env("DRJIT_LIBLLVM_PATH", llvm);
        }
        let out = command.output().map_err(|e| PathTracedError::NoMitsuba {
            tried: format!("{}: {e}", python.display()),
            install: install_command(),
        })?;
        if !out.status.success() {
            // Keep the exported scene for the user to look at or re-run;
            // drop the partial entry.
            let _ = std::fs::remove_dir_all(&tmp);
            let kept = entry.with_file_name(format!("failed-{}", scene.name));
            let _ = std::fs::remove_dir_all(&kept);
            let dir = match std::fs::rename(export, &kept) {
                Ok(()) => kept,
                Err(_) => export.to_path_buf(),
            };
            return Err(PathTracedError::Mitsuba {
                scene: scene.name.clone(),
                dir,
                seed,
                why: failure(out.status, &out.stderr),
            }
            .into());
        }
        seconds.push(start.elapsed().as_secs_f64());
        let record = serde_json::json!({
            "seconds": seconds[seconds.len() - 1],
            "spp": spec.spp, "max_depth": spec.max_depth, "size": [size.0, size.1],
        });
        // Only a hint for the next run's first estimate: a failed write costs nothing.
        let _ = std::fs::write(&last, record.to_string());
    }
    let meta = serde_json::json!({
        "renderer": spec.renderer,
        "mitsuba": mitsuba_version(),
        "spp": spec.spp,
        "max_depth": spec.max_depth,
        "seeds": spec.seeds,
        "seconds": seconds.iter().sum::<f64>(),
        "size": [size.0, size.1],
    });
    let path = tmp.join("entry.json");
    std::fs::write(&path, meta.to_string()).map_err(io(&path))?;
    // Another run may have stored the same entry meanwhile: theirs stays.
    if std::fs::rename(&tmp, entry).is_err() && entry.join("entry.json").exists() {
        let _ = std::fs::remove_dir_all(&tmp);
    } else if !entry.exists() {
        return Err(PathTracedError::Cache {
            path: entry.to_path_buf(),
            source: std::io::Error::other("could not rename the rendered entry into place"),
        }
        .into());
    }
    Ok(())
}

/// The first seed's estimate: the cache's last seed (Mitsuba's start-up
/// dominates small images, so its time is a fair first guess), or none.
fn last_seed(path: &Path) -> String {
    let value = std::fs::read_to_string(path)
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok());
    match value {
        Some(v) if v["seconds"].is_f64() => format!(
            "estimate ~{:.0} s (the last seed rendered here: {}x{}, {} spp, max_depth {})",
            v["seconds"].as_f64().unwrap_or(0.0),
            v["size"][0],
            v["size"][1],
            v["spp"],
            v["max_depth"]
        ),
        _ => "estimate: after this seed".into(),
    }
}

/// An entry's seeds read back, checked finite, each box-filtered down by
/// `supersample` (so the noise is the compared image's), averaged, their
/// noise estimated and held to the bound.
fn read(
    spec: &PathTraced,
    scene: &ScenePlan,
    entry: &Path,
    supersample: u32,
) -> Result<Reference, super::AbError> {
    let mut images = Vec::new();
    for seed in spec.seeds {
        let path = entry.join(format!("seed{seed}.exr"));
        let img = image::open(&path)
            .map_err(|source| PathTracedError::Image {
                path: path.clone(),
                source,
            })?
            .into_rgba32f();
        images.push(filtered_seed(scene, &path, &img, supersample)?);
    }
    let meta = std::fs::read_to_string(entry.join("entry.json")).unwrap_or_default();
    let seconds = serde_json::from_str::<serde_json::Value>(&meta)
        .ok()
        .and_then(|v| v["seconds"].as_f64())
        .unwrap_or(0.0);
    let [a, b]: [image::Rgba32FImage; 2] = images.try_into().expect("two seeds");
    Ok(of_seeds(spec, scene, [&a, &b], seconds)?)
}

/// One seed's image (read from `path`) filtered down to the run's size;
/// refused with a NaN or Inf value, which no mean of seeds could hide.
pub(super) fn filtered_seed(
    scene: &ScenePlan,
    path: &Path,
    img: &image::Rgba32FImage,
    supersample: u32,
) -> Result<image::Rgba32FImage, PathTracedError> {
    let count = img
        .pixels()
        .flat_map(|p| &p.0[..3])
        .filter(|v| !v.is_finite())
        .count();
    if count > 0 {
        return Err(PathTracedError::NotFinite {
            scene: scene.name.clone(),
            path: path.to_path_buf(),
            count,
        });
    }
    Ok(super::supersample::box_filter_linear(img, supersample))
}

/// The reference from its two seeds' images (at the run's `--size`): their
/// mean, refused when its noise estimate is past the file's bound.
pub(super) fn of_seeds(
    spec: &PathTraced,
    scene: &ScenePlan,
    [a, b]: [&image::Rgba32FImage; 2],
    seconds: f64,
) -> Result<Reference, PathTracedError> {
    let mean = image::Rgba32FImage::from_fn(a.width(), a.height(), |x, y| {
        let (p, q) = (a.get_pixel(x, y).0, b.get_pixel(x, y).0);
        image::Rgba([
            0.5 * (p[0] + q[0]),
            0.5 * (p[1] + q[1]),
            0.5 * (p[2] + q[2]),
            1.0,
        ])
    });
    let noise_rmse = noise_of_mean(a, b);
    if noise_rmse > spec.max_noise_rmse {
        return Err(PathTracedError::TooNoisy {
            scene: scene.name.clone(),
            noise: noise_rmse,
            bound: spec.max_noise_rmse,
            file: spec.file.clone(),
        });
    }
    Ok(Reference {
        mean,
        noise_rmse,
        seconds,
    })
}

/// Two independent renders a, b of the same image, each with per-value
/// noise σ: RMSE(a, b) = √2 σ, and their mean has noise σ/√2 = RMSE(a, b)/2
/// (over the RGB values, as the run's linear RMSE is).
pub(super) fn noise_of_mean(a: &image::Rgba32FImage, b: &image::Rgba32FImage) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for (p, q) in a.pixels().zip(b.pixels()) {
        for c in 0..3 {
            let d = (p.0[c] - q.0[c]) as f64;
            sum += d * d;
            n += 1;
        }
    }
    (sum / n.max(1) as f64).sqrt() / 2.0
}

/// What a failed render.py said, or — when it died without a word (a
/// crash inside Mitsuba's native code) — how it ended.
fn failure(status: std::process::ExitStatus, stderr: &[u8]) -> String {
    let text = String::from_utf8_lossy(stderr).trim().to_string();
    #[cfg(unix)]
    if let Some(signal) = std::os::unix::process::ExitStatusExt::signal(&status) {
        let name = match signal {
            11 => " (SIGSEGV: a crash inside Mitsuba)",
            9 => " (SIGKILL: out of memory?)",
            6 => " (SIGABRT)",
            _ => "",
        };
        return format!(
            "killed by signal {signal}{name}{}",
            if text.is_empty() {
                String::new()
            } else {
                format!(": {text}")
            }
        );
    }
    if text.is_empty() {
        format!("{status} with no message")
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The estimate recovers a known noise: two images of the same value
    /// plus independent uniform noise of σ = 0.1/√3 ≈ 0.0577; the mean's is
    /// σ/√2 ≈ 0.0408.
    #[test]
    fn noise_of_mean_recovers_a_known_sigma() {
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 33) as f64 / (1u64 << 31) as f64) as f32 * 0.2 - 0.1
        };
        let mut img = || {
            image::Rgba32FImage::from_fn(200, 200, |_, _| {
                image::Rgba([0.5 + next(), 0.5 + next(), 0.5 + next(), 1.0])
            })
        };
        let (a, b) = (img(), img());
        let expected = (0.1f64 / 3f64.sqrt()) / 2f64.sqrt();
        let got = noise_of_mean(&a, &b);
        assert!((got / expected - 1.0).abs() < 0.02, "{got} vs {expected}");
    }

    #[test]
    fn the_pinned_version_is_read_from_the_install_script() {
        assert_eq!(mitsuba_version(), "3.9.1");
    }
}
