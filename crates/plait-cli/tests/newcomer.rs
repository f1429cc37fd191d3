//! What a newcomer met on a fresh clone (issue 13, "The CLI, as a newcomer
//! met it"): each item as the binary shows it.

mod common;
use common::{plait, root, text};

use std::path::Path;
use std::process::{Command, Output, Stdio};

/// `plait ARGS` with its standard output a pipe whose reader has already
/// gone, as in `plait passes | head -1` once `head` has its line.
fn plait_into_closed_pipe(args: &[&str]) -> Output {
    let (reader, writer) = std::io::pipe().expect("pipe");
    drop(reader);
    let child = Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .args(args)
        .stdout(Stdio::from(writer))
        .stderr(Stdio::piped())
        .spawn()
        .expect("run plait");
    child.wait_with_output().expect("wait for plait")
}

#[test]
fn a_closed_pipe_ends_every_command_quietly() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let hair = dir.path().join("x.hair");
    let (png, hair) = (png.to_str().expect("utf-8"), hair.to_str().expect("utf-8"));
    let runs: Vec<Vec<&str>> = vec![
        vec!["passes"],
        vec!["passes", "--json"],
        vec!["check", "pipelines/forward.toml"],
        vec!["graph", "pipelines/occupancy.toml"],
        vec!["graph", "pipelines/occupancy.toml", "--format", "text"],
        vec!["graph", "pipelines/occupancy.toml", "--format", "svg"],
        vec![
            "hair",
            "generate",
            "--strands",
            "10",
            "--segments",
            "4",
            "--out",
            hair,
        ],
        vec!["hair", "info", hair],
        vec!["hair", "info", hair, "--json"],
        vec![
            "render",
            "pipelines/forward.toml",
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            "32x24",
            "--out",
            png,
        ],
        vec!["render", "--help"],
    ];
    for args in runs {
        let o = plait_into_closed_pipe(&args);
        let stderr = text(&o.stderr);
        assert!(
            o.status.success() && !stderr.contains("panicked") && !stderr.contains("Broken pipe"),
            "plait {args:?} into a closed pipe: exit {:?}\n{stderr}",
            o.status.code()
        );
    }
}

/// Mesa's device-select layer asks for a Wayland display on every device
/// plait opens; without XDG_RUNTIME_DIR, libwayland used to print this line
/// on every GPU command.
#[test]
fn a_headless_gpu_command_prints_no_display_noise() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let o = Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .env_remove("NODEVICE_SELECT")
        .args([
            "render",
            "pipelines/forward.toml",
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            "32x24",
            "--out",
            png.to_str().expect("utf-8"),
        ])
        .output()
        .expect("run plait");
    let stderr = text(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        !stderr.contains("XDG_RUNTIME_DIR"),
        "display noise on a headless render:\n{stderr}"
    );
}

/// Every `--set` example the help texts give works on the default pipeline.
#[test]
fn every_set_example_in_the_help_works() {
    let mut examples = Vec::new();
    for command in ["render", "check", "graph", "ab"] {
        let o = plait(&[command, "--help"]);
        assert!(o.status.success(), "plait {command} --help");
        let help = text(&o.stdout);
        for part in help.split('`').skip(1).step_by(2) {
            if let Some(set) = part.strip_prefix("--set ") {
                examples.push(set.to_owned());
            }
        }
    }
    assert!(
        examples.len() >= 2,
        "the help gives no --set examples: {examples:?}"
    );
    examples.sort();
    examples.dedup();
    for set in &examples {
        let o = plait(&["check", "pipelines/occupancy.toml", "--set", set]);
        assert!(
            o.status.success(),
            "the help's `--set {set}` fails:\n{}",
            text(&o.stderr)
        );
    }
    // And they render, all at once, on the GPU.
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let mut args = vec![
        "render",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "32x24",
        "--out",
        png.to_str().expect("utf-8"),
    ];
    for set in &examples {
        args.extend(["--set", set.as_str()]);
    }
    let o = plait(&args);
    assert!(o.status.success(), "{}", text(&o.stderr));
}

fn fails_with(o: &Output, parts: &[&str]) -> String {
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    for p in parts {
        assert!(stderr.contains(p), "stderr lacks `{p}`:\n{stderr}");
    }
    stderr
}

#[test]
fn a_set_key_that_matches_nothing_suggests_the_nearest() {
    let o = plait(&[
        "check",
        "pipelines/occupancy.toml",
        "--set",
        "params.slice=64",
    ]);
    fails_with(&o, &["--set params.slice=64", "did you mean `slices`?"]);
    let o = plait(&[
        "check",
        "pipelines/occupancy.toml",
        "--set",
        "passes.hiar.params.shadow_weight=1",
    ]);
    fails_with(&o, &["no pass `hiar`", "did you mean `hair`?"]);
    let o = plait(&[
        "check",
        "pipelines/occupancy.toml",
        "--set",
        "passes.hair.params.shadow_wieght=1",
    ]);
    fails_with(&o, &["did you mean `shadow_weight`?"]);
    let o = plait(&["check", "tests/fixtures/bad/unknown_pass_type.toml"]);
    fails_with(
        &o,
        &["unknown pass type `shadow_mapp`; did you mean `shadow_map`?"],
    );
}

#[test]
fn passes_prints_words_not_rust_debug_forms() {
    let o = plait(&["passes"]);
    assert!(o.status.success());
    let out = text(&o.stdout);
    for debug_form in [
        "Float {",
        "Int {",
        "Enum(",
        "min:",
        "Sampled",
        "StorageWrite",
        "StorageRead",
        "DepthTarget",
        "ColorTarget",
        "(Raster)",
        "(Fullscreen)",
        ".txt",
    ] {
        assert!(
            !out.contains(debug_form),
            "`plait passes` prints `{debug_form}`:\n{out}"
        );
    }
    for words in [
        "number 1e-6 … 1e6",
        "one of frame | pixel",
        "rg32float texture, sampled",
        "buffer, storage, written",
        "depth32float texture, depth target",
        "Sintorn & Assarsson 2009",
        "docs/bibliography.md",
    ] {
        assert!(
            out.contains(words),
            "`plait passes` lacks `{words}`:\n{out}"
        );
    }
    assert!(root().join("docs/bibliography.md").is_file());
    let o = plait(&["passes", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let hair = v
        .as_array()
        .expect("array")
        .iter()
        .find(|p| p["name"] == "hair_shade")
        .expect("hair_shade");
    let shading = hair["params"]
        .as_array()
        .expect("params")
        .iter()
        .find(|p| p["name"] == "shading")
        .expect("shading");
    assert_eq!(shading["type"]["kind"], "one_of");
    let choices = shading["type"]["choices"].as_array().expect("choices");
    for name in ["kajiya_kay", "marschner", "chiang"] {
        assert!(choices.iter().any(|c| c == name), "{name}: {choices:?}");
    }
}

#[test]
fn show_checks_the_name_before_rendering() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let started = std::time::Instant::now();
    let o = plait(&[
        "render",
        "--show",
        "light_rnage",
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    let stderr = fails_with(&o, &["--show light_rnage", "did you mean `light_range`?"]);
    // Listed nearest first, before any GPU work (a default render takes seconds).
    let listing = stderr.split("its textures: ").nth(1).expect("a list");
    assert!(listing.starts_with("light_range, "), "{stderr}");
    assert!(
        started.elapsed().as_secs_f64() < 2.0,
        "the name was checked after rendering"
    );
    let o = plait(&[
        "render",
        "--show",
        "light_bits",
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    fails_with(&o, &["`light_bits` is a buffer"]);
    assert!(!png.exists());
}

/// `--show light_range` used to be saturated red: the range texture's clear
/// value (1, 0) is left out, the hair's depths spread over the levels.
#[test]
fn show_maps_a_depth_range_to_visible_levels() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("range.png");
    let o = plait(&[
        "render",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "32x24",
        "--set",
        "params.light_size=64",
        "--show",
        "light_range",
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    let stderr = text(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("note: --show light_range (rg32float): values")
            && stderr.contains("mapped linearly"),
        "no note on the range used:\n{stderr}"
    );
    let img = image::open(&png).expect("PNG").to_rgb8();
    assert_eq!(img.dimensions(), (64, 64), "the light map's own size");
    let saturated = img.pixels().filter(|p| p[0] == 255 && p[1] == 0).count();
    let reds: std::collections::BTreeSet<u8> = img.pixels().map(|p| p[0]).collect();
    assert!(
        saturated * 2 < (64 * 64) as usize,
        "{saturated} of 4096 texels saturated red"
    );
    assert!(
        reds.len() > 16,
        "only {} levels of red: {reds:?}",
        reds.len()
    );
}

#[test]
fn out_names_the_image_format() {
    let dir = tempfile::tempdir().expect("tempdir");
    let jpg = dir.path().join("x.jpg");
    let o = plait(&[
        "render",
        "pipelines/forward.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "32x24",
        "--out",
        jpg.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let bytes = std::fs::read(&jpg).expect("written");
    assert_eq!(&bytes[..3], [0xff, 0xd8, 0xff], "not JPEG bytes");
    assert_eq!(
        image::guess_format(&bytes).expect("known"),
        image::ImageFormat::Jpeg
    );
    for bad in ["x.bmp", "x"] {
        let out = dir.path().join(bad);
        let o = plait(&["render", "--out", out.to_str().expect("utf-8")]);
        fails_with(&o, &["--out", ".png", ".jpg"]);
        assert!(!out.exists());
    }
}

/// The README says `--size WxH`; either x is accepted, the same everywhere.
#[test]
fn size_takes_either_x() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (size, expected) in [("40x30", (40, 30)), ("40X30", (40, 30))] {
        let png = dir.path().join(format!("{size}.png"));
        let o = plait(&[
            "render",
            "pipelines/forward.toml",
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            size,
            "--out",
            png.to_str().expect("utf-8"),
        ]);
        assert!(o.status.success(), "{}", text(&o.stderr));
        let img = image::open(&png).expect("PNG");
        assert_eq!((img.width(), img.height()), expected);
    }
    let help = text(&plait(&["render", "--help"]).stdout);
    assert!(help.contains("WIDTHxHEIGHT"), "{help}");
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    assert!(readme.contains("--size WxH"), "README");
}

#[test]
fn a_missing_pipeline_is_named_without_a_line() {
    let o = plait(&["check", "pipelines/nope.toml"]);
    let stderr = fails_with(&o, &["pipelines/nope.toml: cannot read file"]);
    assert!(!stderr.contains(":1:1"), "{stderr}");
}

/// A check with several errors prints each once, one per line.
#[test]
fn several_errors_are_printed_once_each() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    // Too large for the device: found once the GPU is open, inside the render.
    let o = plait(&[
        "render",
        "pipelines/forward.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "32x24",
        "--set",
        "params.light_size=100000",
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    let stderr = fails_with(&o, &["opaque_shadow", "hair_depth"]);
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 2, "{stderr}");
    assert_eq!(stderr.matches("error:").count(), 2, "{stderr}");
    // And without a GPU, from one file.
    let pipeline = dir.path().join("two.toml");
    std::fs::write(
        &pipeline,
        "[pipeline]\nname = \"x\"\noutputs = [\"final\"]\nbogus = 1\n\
         [resources.final]\nkind = \"texture\"\nformat = \"rgba8unorm\"\nsize = \"screen\"\ncolour = 3\n",
    )
    .expect("write");
    let o = plait(&["check", pipeline.to_str().expect("utf-8")]);
    let stderr = fails_with(&o, &["two.toml:4:1", "two.toml:9:1"]);
    assert_eq!(stderr.lines().count(), 2, "{stderr}");
}

/// `scripts/render.sh --out mine.png` writes where the user is: the script
/// runs cargo from the user's directory with the checkout's manifest. It
/// builds first with cargo's progress shown (a first build takes minutes;
/// `cargo run --quiet` alone showed nothing), then runs quietly. A stand-in
/// `cargo` records how it was called.
#[test]
fn render_script_keeps_the_users_directory_and_shows_the_build() {
    let dir = tempfile::tempdir().expect("tempdir");
    let bin = dir.path().join("bin");
    let work = dir.path().join("work");
    std::fs::create_dir_all(&bin).expect("bin");
    std::fs::create_dir_all(&work).expect("work");
    let record = dir.path().join("cargo-calls");
    let fake_cargo = bin.join("cargo");
    std::fs::write(
        &fake_cargo,
        format!(
            "#!/bin/sh\necho '--- call' >> '{0}'\npwd >> '{0}'\nfor a in \"$@\"; do echo \"$a\" >> '{0}'; done\n",
            record.display()
        ),
    )
    .expect("write stand-in");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&fake_cargo, std::fs::Permissions::from_mode(0o755))
            .expect("chmod");
    }
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let o = Command::new("bash")
        .arg(root().join("scripts/render.sh"))
        .args(["--out", "mine.png"])
        .current_dir(&work)
        .env("PATH", path)
        .output()
        .expect("run render.sh");
    assert!(o.status.success(), "{}", text(&o.stderr));
    let calls = std::fs::read_to_string(&record).expect("cargo was called");
    let calls: Vec<Vec<&str>> = calls
        .split("--- call\n")
        .filter(|c| !c.is_empty())
        .map(|c| c.lines().collect())
        .collect();
    assert_eq!(calls.len(), 2, "a build, then a run: {calls:?}");
    let manifest = root().join("Cargo.toml");
    for call in &calls {
        assert_eq!(
            Path::new(call[0]).canonicalize().expect("cwd"),
            work.canonicalize().expect("work"),
            "cargo ran elsewhere: {call:?}"
        );
        let args = &call[1..];
        assert!(
            args.windows(2)
                .any(|w| w[0] == "--manifest-path" && Path::new(w[1]) == manifest),
            "{args:?}"
        );
        assert!(args.contains(&"--locked"), "{args:?}");
    }
    let (build, run) = (&calls[0][1..], &calls[1][1..]);
    assert_eq!(build[0], "build", "{build:?}");
    assert!(
        !build.contains(&"--quiet") && !build.contains(&"-q"),
        "the build hides cargo's progress: {build:?}"
    );
    assert_eq!(run[0], "run", "{run:?}");
    assert!(
        run.contains(&"--quiet"),
        "the run mixes cargo's lines in: {run:?}"
    );
    // Flags alone: the script names pipelines/default.toml (issue 43).
    let default = root().join("pipelines/default.toml");
    let default = default.to_str().expect("utf-8");
    assert!(
        run.ends_with(&["render", default, "--out", "mine.png"]),
        "{run:?}"
    );
}

#[test]
fn the_default_output_is_ignored_by_git() {
    let ignore = std::fs::read_to_string(root().join(".gitignore")).expect(".gitignore");
    assert!(ignore.lines().any(|l| l.trim() == "plait.png"), "{ignore}");
}

/// `cargo install` without `--locked` resolves newer crates than
/// Cargo.lock's (wgpu, naga 30.0.1 → 30.0.2 on a fresh clone): the binary
/// installed would not be the one tested. Every install command the README
/// gives is locked.
#[test]
fn the_readme_says_how_to_put_plait_on_path_with_the_tested_crates() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README");
    assert!(
        readme.contains("cargo install --locked --path crates/plait-cli"),
        "README lacks the install command"
    );
    let unlocked: Vec<&str> = readme
        .lines()
        .filter(|l| l.contains("cargo install --path"))
        .collect();
    assert!(
        unlocked.is_empty(),
        "unlocked installs in the README: {unlocked:?}"
    );
}
