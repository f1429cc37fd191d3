//! `plait view` under Xvfb on lavapipe (issue 13, items 1–2): the viewer
//! opens a window, a shader it uses is broken (the error reaches stderr with
//! file:line:column while the last good pipeline keeps rendering) and then
//! fixed (it reloads without a restart), and its screenshot of the fixed
//! state matches `plait render` of the same state.
//!
//! Xvfb is started here with `-displayfd`, so the test needs no free display
//! number and stops its own server; `scripts/test.sh` installs Xvfb when it
//! is missing. Without Xvfb the test fails saying how to install it.

mod common;
use common::{root, text};

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

/// A child process killed when the test ends, however it ends.
struct Killed(Child);

impl Drop for Killed {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Start Xvfb on a free display; returns it and the `DISPLAY` value.
fn xvfb() -> (Killed, String) {
    let child = Command::new("Xvfb")
        .args([
            "-displayfd",
            "1",
            "-screen",
            "0",
            "1280x800x24",
            "-nolisten",
            "tcp",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| {
            panic!(
                "cannot start Xvfb ({e}): the viewer test needs an X server. Install it with \
                 `apt-get install -y xvfb` (scripts/test.sh does so when run as root)"
            )
        });
    let mut server = Killed(child);
    // Xvfb writes the display number it chose, then a newline, once it is ready.
    let mut out = server.0.stdout.take().expect("piped stdout");
    let mut number = String::new();
    let mut byte = [0u8; 1];
    while out.read(&mut byte).map(|n| n == 1).unwrap_or(false) && byte[0] != b'\n' {
        number.push(byte[0] as char);
    }
    assert!(
        !number.trim().is_empty(),
        "Xvfb did not report a display number"
    );
    (server, format!(":{}", number.trim()))
}

/// Lines of a child's stderr, as they come.
fn lines(stderr: impl Read + Send + 'static) -> Receiver<String> {
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    rx
}

/// Wait for a line containing `needle`; everything seen goes to `log`.
fn wait_for(
    rx: &Receiver<String>,
    needle: &str,
    within: Duration,
    log: &mut Vec<String>,
) -> String {
    let deadline = Instant::now() + within;
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        match rx.recv_timeout(left) {
            Ok(line) => {
                log.push(line.clone());
                if line.contains(needle) {
                    return line;
                }
            }
            Err(_) => panic!(
                "no line with `{needle}` from plait view within {within:?}; it printed:\n{}",
                log.join("\n")
            ),
        }
    }
}

/// Save as editors do: a whole new file renamed over the old one, so the
/// watcher never sees it half written.
fn save(path: &Path, text: &str) {
    let tmp = path.with_extension("tmp-save");
    std::fs::write(&tmp, text).expect("write");
    std::fs::rename(&tmp, path).expect("rename");
}

const PIPELINE: &str = r#"
[pipeline]
name = "reload"
extends = "forward.toml"        # the gallery's, found on the search path

[passes.compose]
shader = "compose.wgsl"         # this folder's copy: the file the test edits
"#;

fn mean_abs_difference(a: &Path, b: &Path) -> (f64, u8) {
    let a = image::open(a).expect("screenshot").to_rgb8();
    let b = image::open(b).expect("render").to_rgb8();
    assert_eq!(a.dimensions(), b.dimensions(), "sizes differ");
    let (mut sum, mut max) = (0u64, 0u8);
    for (p, q) in a.as_raw().iter().zip(b.as_raw()) {
        let d = p.abs_diff(*q);
        sum += d as u64;
        max = max.max(d);
    }
    (sum as f64 / a.as_raw().len() as f64, max)
}

#[test]
fn viewer_reloads_a_broken_then_fixed_shader_and_its_screenshot_matches_render() {
    let dir = tempfile::tempdir().expect("temp dir");
    let original =
        std::fs::read_to_string(root().join("shaders/compose_over.wgsl")).expect("compose_over");
    let shader = dir.path().join("compose.wgsl");
    std::fs::write(&shader, &original).expect("write shader");
    let pipeline = dir.path().join("reload.toml");
    std::fs::write(&pipeline, PIPELINE).expect("write pipeline");
    let scene = root().join("examples/scenes/small.toml");
    let shot = dir.path().join("shot.png");
    let common_args = [
        "--scene",
        scene.to_str().expect("utf-8"),
        "--size",
        "96x72",
        "--set",
        "params.light_size=256",
    ];

    let (_server, display) = xvfb();
    let mut viewer = Command::new(env!("CARGO_BIN_EXE_plait"));
    viewer
        .arg("view")
        .arg(&pipeline)
        .args(common_args)
        .arg("--screenshot")
        .arg(&shot)
        .args(["--after-frames", "2", "--after-reloads", "1"])
        .env("DISPLAY", &display)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let mut child = Killed(viewer.spawn().expect("start plait view"));
    let stderr = lines(child.0.stderr.take().expect("piped stderr"));
    let mut log = Vec::new();
    wait_for(
        &stderr,
        "plait view: built",
        Duration::from_secs(120),
        &mut log,
    );

    // Break it: an unknown name on a known line.
    let broken = format!("{original}\nfn broken() -> f32 {{\n    return not_defined;\n}}\n");
    let line = 1 + broken
        .lines()
        .position(|l| l.contains("not_defined"))
        .expect("the broken line");
    save(&shader, &broken);
    let first = wait_for(&stderr, "error: ", Duration::from_secs(120), &mut log);
    assert!(
        first.contains("reload.toml:7:") && first.contains("not_defined"),
        "the error should name the pass's `shader` line and the problem: {first}"
    );
    // naga's diagnostic points into the shader: file:line:column.
    wait_for(
        &stderr,
        &format!("compose.wgsl:{line}:12"),
        Duration::from_secs(10),
        &mut log,
    );

    // Fix it differently (half brightness), so the reload is visible in the image.
    let fixed = original.replace(
        "return vec4<f32>(c.rgb + (1.0 - c.a) * background_at(pixel.xy), c.a);",
        "return vec4<f32>(0.5 * (c.rgb + (1.0 - c.a) * background_at(pixel.xy)), c.a);",
    );
    assert_ne!(
        fixed, original,
        "compose_over.wgsl changed: update this test's edit"
    );
    let saved = Instant::now();
    save(&shader, &fixed);
    wait_for(
        &stderr,
        "plait view: reloaded",
        Duration::from_secs(120),
        &mut log,
    );
    eprintln!("reloaded {:?} after the fix was saved", saved.elapsed());
    wait_for(
        &stderr,
        "plait view: wrote",
        Duration::from_secs(120),
        &mut log,
    );
    let deadline = Instant::now() + Duration::from_secs(60);
    let status = loop {
        if let Some(s) = child.0.try_wait().expect("wait for plait view") {
            break s;
        }
        assert!(
            Instant::now() < deadline,
            "plait view did not quit after its screenshot"
        );
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(
        status.success(),
        "plait view failed: {status}\n{}",
        log.join("\n")
    );
    // An ordinary file, as `plait render` writes (it was 0600, the
    // temporary file's mode).
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::PermissionsExt;
        let status = std::fs::read_to_string("/proc/self/status").expect("status");
        let umask = status
            .lines()
            .find_map(|l| l.strip_prefix("Umask:"))
            .and_then(|m| u32::from_str_radix(m.trim(), 8).ok())
            .expect("the umask");
        let mode = std::fs::metadata(&shot).expect("shot").permissions().mode() & 0o777;
        assert_eq!(mode, 0o666 & !umask, "the screenshot's mode is {mode:o}");
    }

    // The same state through `plait render`.
    let reference = dir.path().join("render.png");
    let o = Command::new(env!("CARGO_BIN_EXE_plait"))
        .arg("render")
        .arg(&pipeline)
        .args(common_args)
        .arg("--out")
        .arg(&reference)
        .output()
        .expect("run plait render");
    assert!(o.status.success(), "plait render: {}", text(&o.stderr));
    // Same adapter, pipeline, scene, size and frame inputs: identical on
    // lavapipe (blending order is fixed by the draw order); one step of
    // 8-bit rounding is allowed for drivers that schedule differently.
    let (mean, max) = mean_abs_difference(&shot, &reference);
    assert!(
        max <= 1,
        "screenshot vs render: mean |Δ| {mean:.3}/255, max {max}/255"
    );
    // And the fix took effect: the original shader renders brighter.
    std::fs::write(&shader, &original).expect("restore the shader");
    let before = dir.path().join("before.png");
    let o = Command::new(env!("CARGO_BIN_EXE_plait"))
        .arg("render")
        .arg(&pipeline)
        .args(common_args)
        .arg("--out")
        .arg(&before)
        .output()
        .expect("run plait render");
    assert!(o.status.success(), "plait render: {}", text(&o.stderr));
    let (mean, _) = mean_abs_difference(&shot, &before);
    assert!(
        mean > 5.0,
        "the screenshot should show the fixed (darker) shader: mean |Δ| {mean:.2}"
    );
}

#[test]
fn render_watch_renders_again_on_every_save_and_survives_an_error() {
    let dir = tempfile::tempdir().expect("temp dir");
    let original =
        std::fs::read_to_string(root().join("shaders/compose_over.wgsl")).expect("compose_over");
    let shader = dir.path().join("compose.wgsl");
    std::fs::write(&shader, &original).expect("write shader");
    let pipeline = dir.path().join("reload.toml");
    std::fs::write(&pipeline, PIPELINE).expect("write pipeline");
    let scene = root().join("examples/scenes/small.toml");
    let out = dir.path().join("out.png");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_plait"));
    cmd.arg("render")
        .arg(&pipeline)
        .args([
            "--watch",
            "--size",
            "48x36",
            "--set",
            "params.light_size=128",
        ])
        .arg("--scene")
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let mut child = Killed(cmd.spawn().expect("start plait render --watch"));
    let stderr = lines(child.0.stderr.take().expect("piped stderr"));
    let mut log = Vec::new();
    wait_for(&stderr, "watching", Duration::from_secs(120), &mut log);
    let first = std::fs::read(&out).expect("the first render");

    save(&shader, &format!("{original}\nfn broken( {{\n"));
    wait_for(&stderr, "compose.wgsl:", Duration::from_secs(60), &mut log);
    wait_for(&stderr, "watching", Duration::from_secs(60), &mut log);
    assert_eq!(
        std::fs::read(&out).expect("still there"),
        first,
        "a failed render leaves the last image alone"
    );

    let darker = original.replace("c.rgb + (1.0 - c.a)", "0.5 * c.rgb + (1.0 - c.a)");
    assert_ne!(
        darker, original,
        "compose_over.wgsl changed: update this test's edit"
    );
    save(&shader, &darker);
    wait_for(&stderr, "watching", Duration::from_secs(60), &mut log);
    assert!(
        !log.iter()
            .skip_while(|l| !l.contains("compose.wgsl:"))
            .any(|l| l.contains("panicked")),
        "{}",
        log.join("\n")
    );
    assert_ne!(
        std::fs::read(&out).expect("rendered again"),
        first,
        "the fixed shader should have rendered a new image"
    );
}

/// `render --watch` reads a new library when a library module on the search
/// path changes: the edited `frame.wgsl` (every shader imports it) reaches
/// the next image with no restart.
#[test]
fn render_watch_reads_an_edited_library_module() {
    let library = tempfile::tempdir().expect("temp dir");
    copy_tree(&root().join("shaders"), &library.path().join("shaders"));
    let frame_wgsl = library.path().join("shaders/lib/frame.wgsl");
    let original = std::fs::read_to_string(&frame_wgsl).expect("frame.wgsl");
    let out = library.path().join("out.png");
    let mut child = Killed(
        Command::new(env!("CARGO_BIN_EXE_plait"))
            .arg("render")
            .arg(root().join("pipelines/forward.toml"))
            .arg("--scene")
            .arg(root().join("examples/scenes/small.toml"))
            .args(["--watch", "--size", "48x36"])
            .args(["--set", "params.light_size=128"])
            // Radiance in [0, 1] passes the display transform unchanged.
            .args(["--set", "techniques.tone_mapping=clip"])
            .arg("--out")
            .arg(&out)
            .env("PLAIT_PATH", library.path())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start plait render --watch"),
    );
    let stderr = lines(child.0.stderr.take().expect("piped stderr"));
    let mut log = Vec::new();
    wait_for(&stderr, "watching", Duration::from_secs(120), &mut log);
    let before = image::open(&out).expect("the first render").to_rgb8();
    assert_ne!(before.get_pixel(0, 0).0, [255, 0, 0], "red before the edit");

    let red = original.replace(
        "    return frame.background.rgb;\n}",
        "    return vec3<f32>(1.0, 0.0, 0.0);\n}",
    );
    assert_ne!(red, original, "frame.wgsl changed: update this test's edit");
    save(&frame_wgsl, &red);
    wait_for(&stderr, "watching", Duration::from_secs(120), &mut log);
    let after = image::open(&out).expect("rendered again").to_rgb8();
    assert_eq!(
        after.get_pixel(0, 0).0,
        [255, 0, 0],
        "the background should be the edited module's red: {}",
        log.join("\n")
    );
}

#[test]
fn without_a_display_the_viewer_says_what_to_do() {
    let o = Command::new(env!("CARGO_BIN_EXE_plait"))
        .arg("view")
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run plait view");
    assert_eq!(o.status.code(), Some(2), "{}", text(&o.stderr));
    let stderr = text(&o.stderr);
    assert!(
        stderr.starts_with("error: cannot open a window: ")
            && stderr.contains("DISPLAY")
            && stderr.contains("xvfb-run -a plait view")
            && stderr.contains("plait render --watch")
            && !stderr.contains(".rs:"),
        "{stderr}"
    );
}

#[test]
fn bad_screenshot_paths_fail_before_a_window_opens() {
    for (path, expected) in [
        ("/no/such/folder/shot.png", "no folder /no/such/folder"),
        ("shot.jpg", "the screenshot is a PNG"),
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_plait"))
            .args(["view", "--screenshot", path])
            .env_remove("DISPLAY")
            .output()
            .expect("run plait view");
        assert_eq!(o.status.code(), Some(2));
        let stderr = text(&o.stderr);
        assert!(
            stderr.starts_with(&format!("error: --screenshot {path}: {expected}")),
            "{stderr}"
        );
    }
}

/// Copy a folder tree.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("mkdir");
    for entry in std::fs::read_dir(from).expect("read_dir").flatten() {
        let (src, dst) = (entry.path(), to.join(entry.file_name()));
        if src.is_dir() {
            copy_tree(&src, &dst);
        } else {
            std::fs::copy(&src, &dst).expect("copy");
        }
    }
}

#[test]
fn an_edited_library_module_reaches_the_gpu_without_a_restart() {
    // The shader library on PLAIT_PATH, so the test edits a copy.
    let library = tempfile::tempdir().expect("temp dir");
    copy_tree(&root().join("shaders"), &library.path().join("shaders"));
    let frame_wgsl = library.path().join("shaders/lib/frame.wgsl");
    let original = std::fs::read_to_string(&frame_wgsl).expect("frame.wgsl");
    let plait_path = library.path().to_str().expect("utf-8").to_owned();
    let pipeline = root().join("pipelines/forward.toml");
    let scene = root().join("examples/scenes/small.toml");
    let shot = library.path().join("shot.png");
    let args = [
        "--scene",
        scene.to_str().expect("utf-8"),
        "--size",
        "96x72",
        "--set",
        "params.light_size=256",
        // The display transform passes radiance in [0, 1] through unchanged,
        // so the edited red is the screenshot's.
        "--set",
        "techniques.tone_mapping=clip",
    ];
    let (_server, display) = xvfb();
    let mut child = Killed(
        Command::new(env!("CARGO_BIN_EXE_plait"))
            .arg("view")
            .arg(&pipeline)
            .args(args)
            .arg("--screenshot")
            .arg(&shot)
            .args(["--after-frames", "1", "--after-reloads", "1"])
            .env("DISPLAY", &display)
            .env("PLAIT_PATH", &plait_path)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start plait view"),
    );
    let stderr = lines(child.0.stderr.take().expect("piped stderr"));
    let mut log = Vec::new();
    wait_for(
        &stderr,
        "plait view: built",
        Duration::from_secs(120),
        &mut log,
    );
    // Every shader imports frame.wgsl; a red background shows the edit arrived.
    let red = original.replace(
        "    return frame.background.rgb;\n}",
        "    return vec3<f32>(1.0, 0.0, 0.0);\n}",
    );
    assert_ne!(red, original, "frame.wgsl changed: update this test's edit");
    save(&frame_wgsl, &red);
    wait_for(
        &stderr,
        "plait view: wrote",
        Duration::from_secs(120),
        &mut log,
    );
    let image = image::open(&shot).expect("screenshot").to_rgb8();
    assert_eq!(
        image.get_pixel(0, 0).0,
        [255, 0, 0],
        "the background should be the edited module's red"
    );
}

/// Issue 20 item 4: with Vulkan hidden the viewer runs on llvmpipe's GL and
/// refuses the default pipeline before any GPU work, printing what the
/// adapter lacks and what to do; the window stays open for a fix (a live
/// technique edit), so no screenshot is written.
#[test]
fn without_vulkan_the_viewer_refuses_what_the_adapter_cannot_run() {
    let dir = tempfile::tempdir().expect("temp dir");
    let shot = dir.path().join("shot.png");
    let (_server, display) = xvfb();
    let mut viewer = Command::new(env!("CARGO_BIN_EXE_plait"));
    viewer
        .args(["view", "--size", "96x72", "--screenshot"])
        .arg(&shot)
        .env("DISPLAY", &display)
        .env("VK_ICD_FILENAMES", "/nonexistent.json")
        .env_remove("VK_DRIVER_FILES")
        .env_remove("WGPU_BACKEND")
        .current_dir(root())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let mut child = Killed(viewer.spawn().expect("start plait view"));
    let stderr = lines(child.0.stderr.take().expect("piped stderr"));
    let mut log = Vec::new();
    let first = wait_for(
        &stderr,
        "cannot run pipeline `occupancy`",
        Duration::from_secs(120),
        &mut log,
    );
    assert!(first.contains("(gl backend"), "{first}");
    wait_for(
        &stderr,
        "Texture usages TextureUsages(RENDER_ATTACHMENT) are not allowed on a texture of type Rg32Float",
        Duration::from_secs(10),
        &mut log,
    );
    wait_for(
        &stderr,
        "help: install Mesa's Vulkan driver",
        Duration::from_secs(10),
        &mut log,
    );
    assert!(
        !log.iter().any(|l| l.contains("plait view: built")),
        "{log:#?}"
    );
    assert!(!shot.exists(), "nothing rendered, no screenshot");
}
