//! Ctrl-C during `plait ab` or `plait render` leaves no temporary directory,
//! no temporary file and no partial output (issue 14).

mod common;
use common::{root, text};

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn spawn(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start plait")
}

/// Names in `dir` starting with `.plait-`.
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .expect("list")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".plait-"))
        .collect()
}

/// Waits for a temporary to appear (the command is past its checks and
/// rendering), then sends SIGINT as a terminal's Ctrl-C does, and returns
/// the exit code and standard error.
fn interrupt_when_started(mut child: Child, dir: &Path) -> (Option<i32>, String) {
    let start = Instant::now();
    while temporaries(dir).is_empty() {
        if let Some(status) = child.try_wait().expect("wait") {
            let out = child.wait_with_output().expect("output");
            panic!(
                "finished ({status}) before it could be interrupted: {}",
                text(&out.stderr)
            );
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "no temporary appeared"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    // The temporary is registered for removal right after it is created.
    std::thread::sleep(Duration::from_millis(300));
    assert!(
        child.try_wait().expect("wait").is_none(),
        "still running when interrupted"
    );
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("run kill");
    assert!(sent.success());
    let out = child.wait_with_output().expect("output");
    (out.status.code(), text(&out.stderr))
}

#[test]
fn interrupting_ab_leaves_no_temporary_directory() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("report");
    let child = spawn(&[
        "ab",
        "pipelines/forward.toml",
        "--reference",
        "pipelines/forward.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "320x240",
        "--repeats",
        "50",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    let (code, stderr) = interrupt_when_started(child, tmp.path());
    assert_eq!(code, Some(130), "{stderr}");
    assert!(stderr.contains("interrupted"), "{stderr}");
    assert_eq!(temporaries(tmp.path()), Vec::<String>::new());
    assert!(!out.exists(), "no partial report");
}

#[test]
fn interrupting_render_leaves_no_temporary_file() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("frame.png");
    let child = spawn(&[
        "render",
        "--scene",
        "examples/scenes/default.toml",
        "--size",
        "640x480",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    let (code, stderr) = interrupt_when_started(child, tmp.path());
    assert_eq!(code, Some(130), "{stderr}");
    assert_eq!(temporaries(tmp.path()), Vec::<String>::new());
    assert!(!out.exists(), "no partial image");
}
