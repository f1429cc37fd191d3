//! Issue 44's figures, measured for the book (`bash scripts/web.sh
//! --figures`): the wasm's size, the first frame's time in the page on
//! SwiftShader beside lavapipe's running the same engine code natively, and
//! which gallery pipelines pass the adapter check within WebGPU's default
//! limits. Not `plait ab` runs, so not in docs/figures.toml: the block goes
//! between markers on the book's browser page with the command and commit.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use plait_tests::{open_gpu, repo_root};

use crate::page::{run_page, site_dir};
use crate::{SIZE, check_text_at, gallery, with_webgpu_default_limits};

/// The pipelines timed, each on a fresh page and a fresh engine.
const TIMED: &[&str] = &["occupancy.toml", "depth_peeling.toml"];

/// The page's own default frame size (`state.size` in site/app.js).
const PAGE_SIZE: (u32, u32) = (480, 360);

/// Fresh pages and engines per pipeline: one sample is at the mercy of
/// whatever else the machine runs.
const REPEATS: usize = 3;

/// `median ms (min–max)` of `times`.
fn spread(mut times: Vec<f64>) -> String {
    times.sort_by(f64::total_cmp);
    let (lo, mid, hi) = (times[0], times[times.len() / 2], times[times.len() - 1]);
    format!("{mid:.0} ms ({lo:.0}–{hi:.0})")
}

const BEGIN: &str = "<!-- web-figures -->";
const END: &str = "<!-- /web-figures -->";

#[test]
#[ignore = "figures for the book, CPU-heavy, run by hand: bash scripts/web.sh --figures"]
fn figures() {
    let mut rows = Vec::new();
    let mut web_adapter = String::new();
    let mut native_adapter = String::new();
    for name in TIMED {
        let (mut web, mut native) = (Vec::new(), Vec::new());
        // Interleaved, so a burst of other work on the machine hits both.
        for _ in 0..REPEATS {
            let (ms, adapter) = web_first_frame(name);
            web.push(ms);
            web_adapter = adapter;
            let (ms, adapter) = native_first_frame(name);
            native.push(ms);
            native_adapter = adapter;
        }
        rows.push(format!(
            "| `{name}` | {} | {} |",
            spread(web),
            spread(native)
        ));
    }
    let block = [
        wasm_section(&site_dir().join("plait_web_bg.wasm")),
        times_section(&web_adapter, &native_adapter, &rows),
        limits_section(),
        page_section(),
    ]
    .join("\n");
    println!("{block}");
    if let Some(page) = std::env::var_os("PLAIT_WEB_FIGURES_PAGE") {
        write_between_markers(Path::new(&page), &block);
    }
}

/// The page's first frame of `name` (a fresh page, as a reader opening the
/// live view on it gets), ms, and the adapter the page names.
fn web_first_frame(name: &str) -> (f64, String) {
    let (posted, console, _) = run_page(&[name]);
    if let Some(fatal) = &posted.fatal {
        panic!("the page failed: {fatal}");
    }
    assert!(
        console.is_empty(),
        "console errors:\n{}",
        console.join("\n")
    );
    let [outcome] = &posted.results[..] else {
        panic!("one result: {posted:?}");
    };
    // A failed frame has no time worth publishing.
    assert_eq!(outcome.error, None, "{name} in the page");
    (outcome.ms, posted.adapter.clone().unwrap_or_default())
}

/// lavapipe's first frame of `name`, ms: plait-web's `Engine` natively (the
/// page's code) on a fresh engine, its device opened before the clock starts.
fn native_first_frame(name: &str) -> (f64, String) {
    // Held so no other GPU test of this process runs meanwhile.
    let (_lock, gpu) = open_gpu();
    drop(gpu);
    let mut engine = plait_gpu::wait::wait_for(plait_web::Engine::open())
        .expect("wait natively")
        .unwrap_or_else(|e| panic!("the engine natively: {e}"));
    let request = plait_web::Request {
        pipeline: name.to_owned(),
        width: SIZE.0,
        height: SIZE.1,
        sets: Vec::new(),
        yaw: 0.0,
        pitch: 0.0,
        read: None,
    };
    let started = Instant::now();
    plait_gpu::wait::wait_for(engine.render(&request))
        .expect("wait natively")
        .unwrap_or_else(|e| panic!("{name} natively: {e}"));
    (started.elapsed().as_secs_f64() * 1e3, engine.adapter())
}

/// Bytes and `gzip -9` bytes of a file.
fn sizes(wasm: &Path) -> (u64, usize) {
    let bytes = std::fs::metadata(wasm)
        .unwrap_or_else(|e| panic!("{}: {e}", wasm.display()))
        .len();
    let gzip = Command::new("gzip")
        .args(["-9", "-c"])
        .arg(wasm)
        .output()
        .expect("gzip runs");
    assert!(gzip.status.success(), "gzip failed: {:?}", gzip.status);
    (bytes, gzip.stdout.len())
}

/// The wasm the page loads (the tests' `dev` profile) and, where
/// `scripts/web.sh --figures` built one (`PLAIT_WEB_RELEASE_WASM`), the
/// `release` profile's: bytes and gzipped bytes of each.
fn wasm_section(wasm: &Path) -> String {
    let mut rows = vec![("dev", sizes(wasm))];
    let release = std::env::var_os("PLAIT_WEB_RELEASE_WASM");
    if let Some(release) = &release {
        rows.push(("release", sizes(Path::new(release))));
    }
    let rows: Vec<String> = rows
        .iter()
        .map(|(profile, (bytes, gz))| format!("| `{profile}` | {bytes} | {gz} |"))
        .collect();
    let release_note = if release.is_some() {
        ""
    } else {
        " (no release build: `PLAIT_WEB_RELEASE_WASM` unset)"
    };
    format!(
        "**The wasm** (`plait_web_bg.wasm` after wasm-bindgen, by cargo profile{release_note}; \
         the tests and the site build `dev`):\n\n\
         | profile | bytes | with `gzip -9` |\n|---|---|---|\n{}\n",
        rows.join("\n")
    )
}

/// The first frame's time in the page beside lavapipe's, with what each includes.
fn times_section(web_adapter: &str, native_adapter: &str, rows: &[String]) -> String {
    let native_profile = if cfg!(debug_assertions) {
        "dev"
    } else {
        "release"
    };
    format!(
        "**The first frame** on the built-in small scene at {}x{}, wall clock, \
         measured in one run on one machine while it did other work (compare the \
         columns, not runs): the median (least–most) of {REPEATS} samples, each the \
         first frame of a fresh page or engine (as a reader opening the live view on \
         the pipeline gets), page and native interleaved. In the page \
         (headless Chromium with `--use-webgpu-adapter=swiftshader`; it names its adapter \
         `{web_adapter}`): `performance.now()` around the page's `render()` — compile \
         with the adapter check, fit to the scene, build, one frame, read-back of the \
         output, drawing it on the canvas; the device was opened before. Natively \
         (`{native_adapter}`, Mesa's shader disk cache off): the same engine code \
         (`plait_web::Engine::render`, cargo profile `{native_profile}`) without the \
         canvas; the device opened before.\n\n\
         | pipeline | in the page (SwiftShader) | natively (lavapipe) |\n\
         |---|---|---|\n{}\n",
        SIZE.0,
        SIZE.1,
        rows.join("\n")
    )
}

/// Which gallery pipelines pass `plait check --adapter` on lavapipe with
/// WebGPU's default limits (what the page's device has), at the test's size
/// and the page's; any refused, with the check's text.
fn limits_section() -> String {
    let (_lock, mut gpu) = open_gpu();
    with_webgpu_default_limits(&mut gpu);
    let names = gallery();
    let mut passing = Vec::new();
    let mut refused = Vec::new();
    for name in &names {
        let texts: Vec<String> = [SIZE, PAGE_SIZE]
            .iter()
            .filter_map(|&size| {
                check_text_at(&gpu, name, &[], size)
                    .map(|e| format!("at {}x{}:{}", size.0, size.1, code_item(&e)))
            })
            .collect();
        if texts.is_empty() {
            passing.push(format!("`{name}`"));
        } else {
            refused.push(format!("- `{name}` {}", texts.join("\n\n  and ")));
        }
    }
    let refused = if refused.is_empty() {
        "None is refused.".to_owned()
    } else {
        format!("Refused:\n\n{}\n", refused.join("\n"))
    };
    format!(
        "**Within WebGPU's default limits**: {} of {} gallery pipelines pass \
         the check `plait check --adapter` runs, on lavapipe with WebGPU's default limits (the \
         limits the page's device asks for) at {}x{} and {}x{}: {}. {refused}\n",
        passing.len(),
        names.len(),
        SIZE.0,
        SIZE.1,
        PAGE_SIZE.0,
        PAGE_SIZE.1,
        passing.join(", ")
    )
}

/// `text` (a message over several lines) as a code block in a list item,
/// with paths from the repository rather than this checkout.
fn code_item(text: &str) -> String {
    let root = format!("{}/", repo_root().display());
    let text = text.replace(&root, "").replace('\n', "\n  ");
    format!("\n\n  ```text\n  {text}\n  ```")
}

/// Every gallery pipeline rendered in one page at the test's size: which
/// gave a frame, which an error (the page's text). Not compared with
/// lavapipe here: the browser test compares the ones it names.
fn page_section() -> String {
    let names = gallery();
    let entries: Vec<&str> = names.iter().map(String::as_str).collect();
    let (posted, console, _) = run_page(&entries);
    if let Some(fatal) = &posted.fatal {
        panic!("the page failed: {fatal}");
    }
    assert!(
        console.is_empty(),
        "console errors:\n{}",
        console.join("\n")
    );
    assert_eq!(posted.results.len(), names.len(), "a result per pipeline");
    let (framed, failed): (Vec<_>, Vec<_>) = posted.results.iter().partition(|o| o.error.is_none());
    let failed: Vec<String> = failed
        .iter()
        .map(|o| {
            format!(
                "- `{}`:{}",
                o.pipeline,
                code_item(o.error.as_deref().unwrap_or(""))
            )
        })
        .collect();
    let failed = if failed.is_empty() {
        "None failed.".to_owned()
    } else {
        format!("Failed:\n\n{}\n", failed.join("\n"))
    };
    format!(
        "**Rendered in the page** (one page, SwiftShader, {}x{}; a frame, not compared \
         with lavapipe here — `tests/web.rs` compares {}): {} of {} gallery pipelines \
         gave a frame. {failed}\n",
        SIZE.0,
        SIZE.1,
        crate::RENDERED
            .iter()
            .map(|e| format!("`{e}`"))
            .collect::<Vec<_>>()
            .join(", "),
        framed.len(),
        names.len()
    )
}

/// `block` between the page's markers, with the command and commit under it.
fn write_between_markers(page: &Path, block: &str) {
    let text = std::fs::read_to_string(page).unwrap_or_else(|e| panic!("{}: {e}", page.display()));
    let (Some(a), Some(b)) = (text.find(BEGIN), text.find(END)) else {
        panic!("{}: no {BEGIN} … {END} markers", page.display());
    };
    let git = |args: &[&str]| {
        let out = Command::new("git")
            .args(args)
            .current_dir(repo_root())
            .output()
            .expect("git runs");
        String::from_utf8_lossy(&out.stdout).trim().to_owned()
    };
    // Work not yet committed is said, so the commit is not taken for all of it.
    let dirty = git(&["status", "--porcelain", "--untracked-files=no"])
        .lines()
        .any(|l| !page.ends_with(l[3..].trim()));
    let commit = format!(
        "{}{}",
        git(&["rev-parse", "--short=12", "HEAD"]),
        if dirty {
            " with uncommitted changes"
        } else {
            ""
        }
    );
    let date = String::from_utf8_lossy(
        &Command::new("date")
            .args(["-u", "+%Y-%m-%d %H:%M UTC"])
            .output()
            .expect("date runs")
            .stdout,
    )
    .trim()
    .to_owned();
    let written = format!(
        "{BEGIN}\n{block}\n*Written by `bash scripts/web.sh --figures` at commit `{commit}`, \
         {date}; not typed by hand.*\n"
    );
    let text = format!("{}{written}{}", &text[..a], &text[b..]);
    std::fs::write(page, text).unwrap_or_else(|e| panic!("{}: {e}", page.display()));
}
