//! `plait ab … --reference <path-traced reference>`: the small scene at
//! 32×24 against Mitsuba 3, the cache (a second run starts no Python; a
//! changed spp renders again), Mitsuba missing (exit 2 naming the install
//! script, before any GPU work), a bad key at file:line:col, and the CPU
//! display transform the reference is shown through against the GPU's.
//! Mitsuba is installed by `scripts/ensure-mitsuba.sh`; never skipped.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::{root, text};

/// `scripts/ensure-mitsuba.sh`'s environment (it installs what is missing).
fn mitsuba_env() -> Vec<(String, String)> {
    let out = Command::new("bash")
        .arg(root().join("scripts/ensure-mitsuba.sh"))
        .output()
        .expect("bash runs");
    assert!(out.status.success(), "{}", text(&out.stderr));
    text(&out.stdout)
        .lines()
        .filter_map(|l| l.strip_prefix("export "))
        .filter_map(|l| l.split_once('='))
        .map(|(k, v)| (k.to_string(), v.trim_matches('\'').to_string()))
        .collect()
}

/// A reference file of `spp` per seed, a bound no 4-spp image misses.
fn reference_file(dir: &Path, spp: u32) -> PathBuf {
    let path = dir.join(format!("pt{spp}.toml"));
    std::fs::write(
        &path,
        format!(
            "[path_traced]\nrenderer = \"mitsuba\"\nspp = {spp}\nmax_depth = 8\nseeds = [0, 1]\nmax_noise_rmse = 1.0\n"
        ),
    )
    .unwrap();
    path
}

fn good_file(dir: &Path) -> PathBuf {
    reference_file(dir, 4)
}

fn ab(reference: &Path, cache: &Path, out: &Path, env: &[(String, String)]) -> Output {
    ab_on("examples/scenes/small.toml", reference, cache, out, env)
}

fn ab_on(
    scene: &str,
    reference: &Path,
    cache: &Path,
    out: &Path,
    env: &[(String, String)],
) -> Output {
    Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .args(["ab", "pipelines/forward.toml", "--reference"])
        .arg(reference)
        .args(["--scene", scene, "--size", "32x24"])
        .args(["--repeats", "1", "--cache"])
        .arg(cache)
        .arg("--out")
        .arg(out)
        .envs(env.iter().map(|(k, v)| (k, v)))
        .output()
        .expect("run plait")
}

#[test]
fn path_traced_reference_cached_and_compared() {
    let env = mitsuba_env();
    let tmp = tempfile::tempdir().unwrap();
    let cache = tmp.path().join("cache");
    let pt4 = reference_file(tmp.path(), 4);
    let out = tmp.path().join("r1");
    let first = ab(&pt4, &cache, &out, &env);
    let stdout = text(&first.stdout);
    assert!(first.status.success(), "{stdout}\n{}", text(&first.stderr));
    assert!(
        stdout.contains("Mitsuba seed 0") && stdout.contains("Mitsuba seed 1"),
        "{stdout}"
    );
    assert!(!stdout.contains("cache hit"), "{stdout}");

    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let variants = report["variants"].as_array().unwrap();
    let pt = variants.iter().find(|v| v["is_reference"] == true).unwrap();
    let label = pt["label"].as_str().unwrap();
    assert!(
        label.contains("Mitsuba 3.9.1") && label.contains("2 × 4 spp"),
        "{label}"
    );
    assert!(
        label.contains("max_depth 8") && label.contains("noise RMSE"),
        "{label}"
    );
    assert_eq!(pt["schedule_name"], "mitsuba 3.9.1");
    let run = &report["scenes"][0]["runs"][0];
    let rmse = run["metrics"]["rmse"].as_f64().unwrap();
    assert!(
        rmse > 0.0 && rmse.is_finite(),
        "forward against the path tracer: {rmse}"
    );
    let reference = image::open(out.join("small-reference.exr"))
        .unwrap()
        .into_rgba32f();
    assert_eq!(reference.dimensions(), (32, 24));
    assert!(reference.pixels().any(|p| p.0[0] > 0.0));

    // The CPU display transform against the GPU's, on the forward variant's
    // own radiance: within one 8-bit level everywhere.
    let radiance = image::open(out.join("small-forward.exr"))
        .unwrap()
        .into_rgba32f();
    let gpu = image::open(out.join("small-forward.png"))
        .unwrap()
        .into_rgba8();
    let cpu = plait::ab::display_agx(&radiance, 0.0);
    let worst = cpu
        .pixels()
        .zip(gpu.pixels())
        .flat_map(|(a, b)| (0..3).map(move |c| (a.0[c] as i32 - b.0[c] as i32).abs()))
        .max()
        .unwrap();
    assert!(
        worst <= 1,
        "CPU AgX differs from the GPU pass by {worst} levels"
    );

    // Second run: every reference from the cache, no Python started.
    let mut no_python = env.clone();
    no_python.retain(|(k, _)| k != "PLAIT_MITSUBA_PYTHON");
    no_python.push(("PLAIT_MITSUBA_PYTHON".into(), "/nonexistent/python".into()));
    let second = ab(&pt4, &cache, &tmp.path().join("r2"), &no_python);
    let stdout = text(&second.stdout);
    assert!(
        second.status.success(),
        "{stdout}\n{}",
        text(&second.stderr)
    );
    assert!(
        stdout.contains("cache hit") && !stdout.contains("Mitsuba seed"),
        "{stdout}"
    );
    let again = image::open(tmp.path().join("r2/small-reference.exr"))
        .unwrap()
        .into_rgba32f();
    assert_eq!(again, reference);

    // The noise bound is not part of the key (it decides no pixel): the
    // same cached images, held to a bound they miss, fail the run.
    let strict = tmp.path().join("strict.toml");
    let text4 = std::fs::read_to_string(&pt4).unwrap();
    std::fs::write(
        &strict,
        text4.replace("max_noise_rmse = 1.0", "max_noise_rmse = 0.000001"),
    )
    .unwrap();
    let noisy = ab(&strict, &cache, &tmp.path().join("r4"), &no_python);
    let stderr = text(&noisy.stderr);
    assert_eq!(noisy.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("too noisy") && stderr.contains("max_noise_rmse = 0.000001"),
        "{stderr}"
    );

    // A NaN in a cached image fails the run, naming the file.
    let entry = std::fs::read_dir(&cache)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.join("entry.json").exists())
        .unwrap();
    let mut poisoned = image::open(entry.join("seed1.exr")).unwrap().into_rgba32f();
    poisoned.get_pixel_mut(3, 4).0[1] = f32::NAN;
    image::DynamicImage::ImageRgba32F(poisoned)
        .save_with_format(entry.join("seed1.exr"), image::ImageFormat::OpenExr)
        .unwrap();
    let nan = ab(&pt4, &cache, &tmp.path().join("r5"), &no_python);
    let stderr = text(&nan.stderr);
    assert_eq!(nan.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("1 NaN or Inf") && stderr.contains("seed1.exr"),
        "{stderr}"
    );

    // A changed spp is another key: it must render, so without Mitsuba it
    // fails, naming the install script, with exit 2, before any GPU work.
    let pt5 = reference_file(tmp.path(), 5);
    let third = ab(&pt5, &cache, &tmp.path().join("r3"), &no_python);
    let stderr = text(&third.stderr);
    assert_eq!(third.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("bash scripts/ensure-mitsuba.sh"),
        "{stderr}"
    );
    assert!(!text(&third.stdout).contains("built"), "GPU work started");
    assert!(!tmp.path().join("r3").exists());
}

#[test]
fn bad_reference_files_exit_2_at_file_line_col() {
    let tmp = tempfile::tempdir().unwrap();
    let bad = tmp.path().join("bad.toml");
    std::fs::write(
        &bad,
        "[path_traced]\nrenderer = \"mitsuba\"\nspp = 4\nmax_depht = 8\nseeds = [0, 1]\nmax_noise_rmse = 1.0\n",
    )
    .unwrap();
    let out = ab(&bad, &tmp.path().join("c"), &tmp.path().join("r"), &[]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("bad.toml:4:1") && stderr.contains("max_depht"),
        "{stderr}"
    );
    // Mitsuba failing: its message, the scene, exit 2, before GPU work
    // (a stand-in "python" that fails as render.py does).
    let failing = tmp.path().join("failing-python");
    std::fs::write(
        &failing,
        "#!/bin/sh\necho 'mitsuba: out of cheese' >&2\nexit 2\n",
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt as _;
    std::fs::set_permissions(&failing, std::fs::Permissions::from_mode(0o755)).unwrap();
    let env = [(
        "PLAIT_MITSUBA_PYTHON".to_string(),
        failing.display().to_string(),
    )];
    let out = ab(
        &good_file(tmp.path()),
        &tmp.path().join("c"),
        &tmp.path().join("r"),
        &env,
    );
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("Mitsuba failed on scene small")
            && stderr.contains("out of cheese")
            && stderr.contains("failed-small"),
        "{stderr}"
    );
    assert!(!text(&out.stdout).contains("built"), "GPU work started");
    assert!(
        std::fs::read_dir(tmp.path().join("c"))
            .unwrap()
            .all(|e| { !e.unwrap().path().join("entry.json").exists() }),
        "a failed render left a cache entry"
    );

    // Mitsuba crashing without a word (a segfault in its native code): the
    // signal and the seed, exit 2.
    let crashing = tmp.path().join("crashing-python");
    std::fs::write(&crashing, "#!/bin/sh\nkill -SEGV $$\n").unwrap();
    std::fs::set_permissions(&crashing, std::fs::Permissions::from_mode(0o755)).unwrap();
    let env = [(
        "PLAIT_MITSUBA_PYTHON".to_string(),
        crashing.display().to_string(),
    )];
    let out = ab(
        &good_file(tmp.path()),
        &tmp.path().join("c"),
        &tmp.path().join("r"),
        &env,
    );
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("Mitsuba failed on scene small, seed 0")
            && stderr.contains("killed by signal 11 (SIGSEGV"),
        "{stderr}"
    );

    // A spot light whose cone leaves hair out of plait's shadow frustum
    // (Mitsuba's point light would shadow with it, plait does not): named,
    // with its scene, before any GPU work or Mitsuba. stray.toml's own
    // 50° cone holds its hair and exports as a point light.
    let stray = std::fs::read_to_string(root().join("examples/scenes/stray.toml")).unwrap();
    let narrow = tmp.path().join("narrow_spot.toml");
    std::fs::write(
        &narrow,
        stray.replace("cone_degrees = 50.0", "cone_degrees = 5.0"),
    )
    .unwrap();
    let good = good_file(tmp.path());
    let out = ab_on(
        narrow.to_str().unwrap(),
        &good,
        &tmp.path().join("c"),
        &tmp.path().join("r"),
        &[],
    );
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("scene narrow_spot")
            && stderr.contains("spot light whose shadow frustum leaves out occluders"),
        "{stderr}"
    );
    assert!(text(&out.stdout).is_empty(), "{}", text(&out.stdout));
}

/// `plait` copied out of the checkout (as `cargo install` puts it) and run
/// with no search path (`PLAIT_PATH=""`: the built-in copies alone) from a
/// folder of its own: the shipped reference by its library name, the
/// install script and `render.py` all come from the binary.
#[test]
fn an_installed_plait_runs_a_path_traced_reference_from_its_built_in_copies() {
    let env = mitsuba_env();
    let tmp = tempfile::tempdir().unwrap();
    let exe = tmp.path().join("plait");
    std::fs::copy(env!("CARGO_BIN_EXE_plait"), &exe).unwrap();
    let target = tmp.path().join("build");
    let run = |reference: &Path, out: &str, python: &str| {
        let mut cmd = Command::new(&exe);
        cmd.current_dir(tmp.path())
            .args(["ab", "forward.toml", "--reference"])
            .arg(reference)
            .args(["--scene", "small.toml", "--size", "16x12", "--repeats", "1"])
            .args(["--cache", "cache", "--out", out])
            .envs(env.iter().map(|(k, v)| (k, v)))
            .env("PLAIT_PATH", "")
            .env("CARGO_TARGET_DIR", &target)
            .env("PLAIT_MITSUBA_PYTHON", python);
        common::run_copied(&mut cmd)
    };

    // The shipped file, found by its library name; no Mitsuba: the message
    // names the built-in install script, written out where it can run.
    let missing = run(
        Path::new("references/path_traced.toml"),
        "r0",
        "/nonexistent/python",
    );
    let stderr = text(&missing.stderr);
    assert_eq!(missing.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("Mitsuba is not installed"), "{stderr}");
    let scripts = target.join("plait-scripts");
    let written: Vec<PathBuf> = std::fs::read_dir(&scripts)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    let ensure = written
        .iter()
        .find(|p| p.to_string_lossy().contains("ensure-mitsuba-"))
        .unwrap_or_else(|| panic!("no install script in {written:?}"));
    assert!(stderr.contains(&ensure.display().to_string()), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(ensure).unwrap(),
        std::fs::read_to_string(root().join("scripts/ensure-mitsuba.sh")).unwrap()
    );

    // With Mitsuba: render.py is the built-in copy, written out and run.
    let python = env
        .iter()
        .find(|(k, _)| k == "PLAIT_MITSUBA_PYTHON")
        .map(|(_, v)| v.clone())
        .unwrap();
    let reference = reference_file(tmp.path(), 4);
    let ok = run(&reference, "r1", &python);
    assert!(
        ok.status.success(),
        "{}\n{}",
        text(&ok.stdout),
        text(&ok.stderr)
    );
    let render_py = std::fs::read_dir(&scripts)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.to_string_lossy().contains("render-"))
        .expect("render.py written out");
    assert_eq!(
        std::fs::read_to_string(render_py).unwrap(),
        std::fs::read_to_string(root().join("scripts/mitsuba/render.py")).unwrap()
    );
    let report = std::fs::read_to_string(tmp.path().join("r1/report.json")).unwrap();
    assert!(report.contains("Mitsuba 3.9.1"), "{report}");
}

/// Ctrl-C (SIGINT to the process group, as a terminal sends it) while
/// Mitsuba renders a seed: exit 130, no cache entry, and the next run
/// removes the interrupted run's temporary folder and renders afresh.
#[test]
fn interrupting_a_path_traced_reference_leaves_no_cache_entry() {
    use std::io::BufRead;
    use std::os::unix::process::CommandExt;
    let env = mitsuba_env();
    let tmp = tempfile::tempdir().unwrap();
    let cache = tmp.path().join("cache");
    // Enough samples that a seed takes seconds after Mitsuba starts.
    let slow = reference_file(tmp.path(), 4096);
    let mut child = Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .args(["ab", "pipelines/forward.toml", "--reference"])
        .arg(&slow)
        .args(["--scene", "examples/scenes/small.toml", "--size", "32x24"])
        .args(["--repeats", "1", "--cache"])
        .arg(&cache)
        .arg("--out")
        .arg(tmp.path().join("r"))
        .envs(env.iter().map(|(k, v)| (k, v)))
        .process_group(0)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("start plait");
    let stdout = std::io::BufReader::new(child.stdout.take().unwrap());
    let mut seen = Vec::new();
    for line in stdout.lines() {
        let line = line.unwrap();
        seen.push(line.clone());
        if line.contains("Mitsuba seed 0") {
            break;
        }
    }
    assert!(
        seen.last().is_some_and(|l| l.contains("Mitsuba seed 0")),
        "{seen:?}"
    );
    // Python is started right after the line; give it time to be rendering.
    std::thread::sleep(std::time::Duration::from_secs(3));
    let pgid = format!("-{}", child.id());
    let sent = Command::new("kill")
        .args(["-INT", "--", &pgid])
        .status()
        .expect("run kill");
    assert!(sent.success());
    let out = child.wait_with_output().expect("output");
    assert_eq!(out.status.code(), Some(130), "{}", text(&out.stderr));
    let names = |dir: &Path| -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect()
    };
    let left = names(&cache);
    assert!(
        left.iter()
            .all(|n| n.starts_with(".tmp-") || n == "last-seed.json"),
        "an entry after an interrupt: {left:?}"
    );
    assert!(left.iter().any(|n| n.starts_with(".tmp-")), "{left:?}");

    // The next run: the dead run's temporaries are gone, its own entry stored.
    let done = ab(&good_file(tmp.path()), &cache, &tmp.path().join("r2"), &env);
    assert!(done.status.success(), "{}", text(&done.stderr));
    let left = names(&cache);
    assert!(
        left.iter().all(|n| !n.starts_with(".tmp-")),
        "temporaries of the interrupted run stayed: {left:?}"
    );
    assert!(
        left.iter()
            .any(|n| cache.join(n).join("entry.json").exists()),
        "{left:?}"
    );
}
