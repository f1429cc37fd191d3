//! The book opened in a real browser: headless Chromium (Debian's package)
//! loads every page from a local HTTP server, one after the other in a frame
//! of a check page, and reports a page without content, an image that did not
//! load, or a script error. The server is a thread of this process; nothing
//! leaves the machine (Chromium runs with its background networking off).

use std::io::{BufRead, BufReader, Write};
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Why the browser check could not run or what it found.
#[derive(Debug, thiserror::Error)]
pub enum BrowserError {
    #[error(
        "no Chromium at {0}: install Debian's package (`apt-get install -y chromium`) or set PLAIT_CHROMIUM"
    )]
    NoChromium(PathBuf),
    #[error("chromium failed: {0}")]
    Failed(String),
    #[error("local server: {0}")]
    Server(std::io::Error),
}

/// The browser binary: `PLAIT_CHROMIUM`, else Debian's `/usr/bin/chromium`.
pub fn chromium() -> Result<PathBuf, BrowserError> {
    let path = std::env::var_os("PLAIT_CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"));
    if path.is_file() {
        Ok(path)
    } else {
        Err(BrowserError::NoChromium(path))
    }
}

/// Serves `root` on a free loopback port for the life of the process;
/// returns the base URL.
pub fn serve(root: &Path) -> Result<String, BrowserError> {
    let listener = TcpListener::bind("127.0.0.1:0").map_err(BrowserError::Server)?;
    let port = listener.local_addr().map_err(BrowserError::Server)?.port();
    let root = root.to_path_buf();
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let root = root.clone();
            std::thread::spawn(move || {
                let _ = answer(&root, stream);
            });
        }
    });
    Ok(format!("http://127.0.0.1:{port}"))
}

fn answer(root: &Path, mut stream: std::net::TcpStream) -> std::io::Result<()> {
    let mut line = String::new();
    let mut reader = BufReader::new(stream.try_clone()?);
    reader.read_line(&mut line)?;
    // Headers: read to the blank line, ignored.
    let mut header = String::new();
    while reader.read_line(&mut header)? > 2 {
        header.clear();
    }
    let path = line.split_whitespace().nth(1).unwrap_or("/");
    let path = path.split(['?', '#']).next().unwrap_or("/");
    let rel = path.trim_start_matches('/').replace("%20", " ");
    let mut file = root.join(&rel);
    if file.is_dir() {
        file = file.join("index.html");
    }
    // Nothing outside the book is served.
    let inside = !rel.split('/').any(|c| c == "..");
    match std::fs::read(&file) {
        Ok(body) if inside => {
            let kind = match file.extension().and_then(|x| x.to_str()).unwrap_or("") {
                "html" => "text/html; charset=utf-8",
                "css" => "text/css",
                "js" => "text/javascript",
                "svg" => "image/svg+xml",
                "png" => "image/png",
                "woff2" => "font/woff2",
                "woff" => "font/woff",
                "json" => "application/json",
                _ => "application/octet-stream",
            };
            write!(
                stream,
                "HTTP/1.1 200 OK\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                body.len()
            )?;
            stream.write_all(&body)
        }
        _ => write!(
            stream,
            "HTTP/1.1 404 Not Found\r\nContent-Length: 0\r\nConnection: close\r\n\r\n"
        ),
    }
}

/// Chromium's flags for a headless run on a machine without network.
fn base_args(profile: &Path) -> Vec<String> {
    [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--disable-extensions",
        "--hide-scrollbars",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain([format!("--user-data-dir={}", profile.display())])
    .collect()
}

/// The check page: loads each page into a frame, waits for it, and writes
/// one line per problem into `#result` (`OK n` when there is none).
fn check_page(pages: &[String]) -> String {
    let list = serde_json::to_string(pages).expect("strings serialize");
    format!(
        r#"<!doctype html><meta charset="utf-8"><title>book check</title>
<pre id="result">RUNNING</pre><iframe id="f" style="width:1200px;height:900px"></iframe>
<script>
const pages = {list};
const problems = [];
const frame = document.getElementById('f');
function visit(i) {{
  if (i === pages.length) {{
    document.getElementById('result').textContent =
      problems.length ? problems.join('\n') : 'OK ' + pages.length;
    return;
  }}
  frame.onload = () => setTimeout(() => {{
    const doc = frame.contentDocument;
    // toc.html is mdBook's sidebar for readers without JavaScript (a frame
    // of every page): it has chapter links, not a <main>.
    if (pages[i].endsWith('/toc.html')) {{
      if (!doc || doc.querySelectorAll('ol.chapter a').length < 10) problems.push(pages[i] + ': no chapter list');
    }} else {{
      const main = doc && doc.querySelector('main');
      if (!main || main.innerText.trim().length < 20) problems.push(pages[i] + ': no content');
    }}
    for (const img of doc ? doc.images : []) {{
      if (!img.complete || img.naturalWidth === 0) problems.push(pages[i] + ': image did not load: ' + img.getAttribute('src'));
    }}
    if (doc && doc.title.startsWith('404')) problems.push(pages[i] + ': not found');
    visit(i + 1);
  }}, 50);
  frame.src = pages[i];
}}
visit(0);
</script>"#
    )
}

/// Opens every page of the book at `root` (relative paths, as
/// [`crate::check::pages`] lists them) in Chromium; returns the problems, one
/// per line. Script errors are read off Chromium's console log.
pub fn check_pages(root: &Path, pages: &[PathBuf]) -> Result<Vec<String>, BrowserError> {
    let exe = chromium()?;
    let base = serve(root)?;
    let profile = tempfile::tempdir().map_err(BrowserError::Server)?;
    let names: Vec<String> = pages.iter().map(|p| format!("/{}", p.display())).collect();
    let check = root.join("__browser_check.html");
    std::fs::write(&check, check_page(&names)).map_err(BrowserError::Server)?;
    let out = Command::new(&exe)
        .args(base_args(profile.path()))
        .args([
            "--enable-logging=stderr",
            "--v=0",
            "--virtual-time-budget=600000",
            "--dump-dom",
        ])
        .arg(format!("{base}/__browser_check.html"))
        .output();
    let _ = std::fs::remove_file(&check);
    let out = out.map_err(|e| BrowserError::Failed(e.to_string()))?;
    let dom = String::from_utf8_lossy(&out.stdout);
    let log = String::from_utf8_lossy(&out.stderr);
    let result = dom
        .split("<pre id=\"result\">")
        .nth(1)
        .and_then(|r| r.split("</pre>").next())
        .map(|r| r.replace("&amp;", "&"))
        .ok_or_else(|| BrowserError::Failed(format!("no result in the page; stderr:\n{log}")))?;
    let mut problems: Vec<String> = log
        .lines()
        .filter(|l| l.contains("CONSOLE") && (l.contains("Uncaught") || l.contains("Error")))
        .map(|l| format!("script error: {l}"))
        .collect();
    match result.trim() {
        r if r == format!("OK {}", pages.len()) => {}
        "RUNNING" => problems.push("the check page never finished".into()),
        r => problems.extend(r.lines().map(str::to_owned)),
    }
    Ok(problems)
}

/// A screenshot of `page` (relative to the book's root) at 1200×900.
pub fn screenshot(root: &Path, page: &str, png: &Path) -> Result<(), BrowserError> {
    let exe = chromium()?;
    let base = serve(root)?;
    let profile = tempfile::tempdir().map_err(BrowserError::Server)?;
    let status = Command::new(&exe)
        .args(base_args(profile.path()))
        .args([
            "--window-size=1200,900",
            "--virtual-time-budget=5000",
            &format!("--screenshot={}", png.display()),
        ])
        .arg(format!("{base}/{page}"))
        .output()
        .map_err(|e| BrowserError::Failed(e.to_string()))?;
    if png.is_file() {
        Ok(())
    } else {
        Err(BrowserError::Failed(
            String::from_utf8_lossy(&status.stderr).into_owned(),
        ))
    }
}
