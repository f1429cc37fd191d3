//! The browser side of tests/web.rs: the site built by `scripts/web.sh`,
//! served from 127.0.0.1 by a tiny HTTP server that records every path asked
//! for, and headless Chromium (WebGPU on SwiftShader) driving the page's
//! `?test=` mode, which posts its frames back as JSON.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use plait_tests::repo_root;

use crate::SIZE;

/// What the page posts: a frame or an error per pipeline.
#[derive(serde::Deserialize, Debug)]
pub struct Posted {
    pub adapter: Option<String>,
    pub fatal: Option<String>,
    #[serde(default)]
    pub results: Vec<Outcome>,
}

#[derive(serde::Deserialize, Debug)]
pub struct Outcome {
    pub pipeline: String,
    pub ms: f64,
    pub error: Option<String>,
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub pixels: Option<Vec<u8>>,
    /// The frame's report (`FrameReport` as JSON); null when it failed.
    #[serde(default)]
    pub report: Option<serde_json::Value>,
    /// The GPU-time table's cells as shown, row by row (pass, type,
    /// technique, GPU ms, note).
    #[serde(default)]
    pub table: Vec<Vec<String>>,
    /// The line naming the missing timestamp feature, when shown.
    #[serde(default)]
    pub missing: Option<String>,
    /// The schedule's SVG as the page put it in, and whether an `<svg>` is drawn.
    #[serde(default)]
    pub graph: Option<String>,
    #[serde(default)]
    pub graph_drawn: bool,
}

/// Where [`build_site`] writes the site: `web-test` in the build folder.
pub fn site_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo_root().join("target"))
        .join("web-test")
}

/// `scripts/web.sh` into the build folder, once per test process; the
/// site's directory. Once: the tests run two at a time, and two builds into
/// one folder race (one's `cp` met the other's file: "File exists").
fn build_site() -> PathBuf {
    static SITE: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    SITE.get_or_init(|| {
        let out = site_dir();
        let status = Command::new("bash")
            .arg(repo_root().join("scripts/web.sh"))
            .arg(&out)
            .status()
            .expect("bash runs");
        assert!(status.success(), "scripts/web.sh failed: {status}");
        out
    })
    .clone()
}

/// Serves `root` on 127.0.0.1; every path asked for goes to `asked`, a
/// POST to /result to `posted`.
fn serve(root: PathBuf, asked: mpsc::Sender<String>, posted: mpsc::Sender<String>) -> String {
    let listener = TcpListener::bind("127.0.0.1:0").expect("a loopback port");
    let port = listener.local_addr().expect("address").port();
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let (root, asked, posted) = (root.clone(), asked.clone(), posted.clone());
            std::thread::spawn(move || answer(&root, stream, &asked, &posted));
        }
    });
    format!("http://127.0.0.1:{port}")
}

fn answer(
    root: &Path,
    mut stream: TcpStream,
    asked: &mpsc::Sender<String>,
    posted: &mpsc::Sender<String>,
) {
    let mut reader = BufReader::new(stream.try_clone().expect("clone"));
    let mut line = String::new();
    if reader.read_line(&mut line).is_err() {
        return;
    }
    let mut length = 0usize;
    let mut header = String::new();
    while reader.read_line(&mut header).is_ok_and(|n| n > 2) {
        if let Some(v) = header.to_ascii_lowercase().strip_prefix("content-length:") {
            length = v.trim().parse().unwrap_or(0);
        }
        header.clear();
    }
    let mut parts = line.split_whitespace();
    let (method, path) = (parts.next().unwrap_or(""), parts.next().unwrap_or("/"));
    let path = path.split(['?', '#']).next().unwrap_or("/").to_owned();
    let _ = asked.send(path.clone());
    if method == "POST" {
        let mut body = vec![0; length];
        let _ = reader.read_exact(&mut body);
        let _ = posted.send(String::from_utf8_lossy(&body).into_owned());
        let _ = write!(
            stream,
            "HTTP/1.1 204 No Content\r\nConnection: close\r\n\r\n"
        );
        return;
    }
    let rel = path.trim_start_matches('/');
    let file = root.join(if rel.is_empty() { "index.html" } else { rel });
    let kind = match file.extension().and_then(|x| x.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js") => "text/javascript",
        Some("css") => "text/css",
        Some("wasm") => "application/wasm",
        _ => "application/octet-stream",
    };
    match std::fs::read(&file) {
        Ok(body) if !rel.contains("..") => {
            let _ = write!(
                stream,
                "HTTP/1.1 200 OK\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                body.len()
            );
            let _ = stream.write_all(&body);
        }
        _ => {
            let _ = write!(
                stream,
                "HTTP/1.1 404 Not Found\r\nContent-Length: 0\r\nConnection: close\r\n\r\n"
            );
        }
    }
}

/// Chromium with WebGPU on SwiftShader, headless, no network of its own.
fn chromium(url: &str, profile: &Path) -> std::process::Child {
    let exe = std::env::var_os("PLAIT_CHROMIUM").unwrap_or_else(|| "/usr/bin/chromium".into());
    Command::new(&exe)
        .args([
            "--headless=new",
            "--no-sandbox",
            "--enable-unsafe-webgpu",
            "--use-webgpu-adapter=swiftshader",
            "--enable-unsafe-swiftshader",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-extensions",
            "--no-first-run",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(url)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| {
            panic!("cannot start {exe:?} (scripts/ensure-chromium.sh installs it): {e}")
        })
}

/// The page's results for `pipelines`, and Chromium's console errors.
pub fn run_page(pipelines: &[&str]) -> (Posted, Vec<String>, Vec<String>) {
    let site = build_site();
    let (asked_tx, asked) = mpsc::channel();
    let (posted_tx, posted) = mpsc::channel();
    let base = serve(site, asked_tx, posted_tx);
    let profile = tempfile::tempdir().expect("profile dir");
    let url = format!(
        "{base}/?test={}&size={}x{}",
        pipelines.join(","),
        SIZE.0,
        SIZE.1
    );
    let mut browser = chromium(&url, profile.path());
    let body = posted.recv_timeout(Duration::from_secs(600));
    let _ = browser.kill();
    let mut log = String::new();
    if let Some(mut err) = browser.stderr.take() {
        let _ = err.read_to_string(&mut log);
    }
    let _ = browser.wait();
    let body = body
        .unwrap_or_else(|_| panic!("the page posted nothing in 10 minutes; Chromium said:\n{log}"));
    let console: Vec<String> = log
        .lines()
        .filter(|l| {
            l.contains("CONSOLE")
                && (l.contains("Uncaught") || l.contains("Error") || l.contains("error"))
        })
        .map(str::to_owned)
        .collect();
    let paths: Vec<String> = asked.try_iter().collect();
    let posted: Posted = serde_json::from_str(&body).expect("the page's JSON");
    (posted, console, paths)
}
