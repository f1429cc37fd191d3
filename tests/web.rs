//! plait in a browser (issue 44): `scripts/web.sh` builds the engine for
//! WebAssembly and the live page; headless Chromium renders gallery
//! pipelines with WebGPU on SwiftShader, and each frame is held to the
//! native (lavapipe) render of the same pipeline, scene and size over the
//! hair pixels, as the goldens are ([`plait_tests::golden_images`]). No
//! console errors; nothing requested but the site's own files, from
//! 127.0.0.1.

#[path = "web/figures.rs"]
mod figures;
#[path = "web/page.rs"]
mod page;
#[path = "web/shown.rs"]
mod shown;
#[path = "web/timing.rs"]
mod timing;

use image::RgbaImage;
use page::run_page;
use plait::session::{SceneData, prepare};
use plait_tests::golden_images::{Comparison, compare};
use plait_tests::{open_gpu, repo_root};

/// Small: SwiftShader and lavapipe both rasterize on the CPU.
const SIZE: (u32, u32) = (96, 72);

/// The pipelines rendered in the page and compared with lavapipe.
const RENDERED: &[&str] = &[
    "occupancy.toml",
    "linked_list.toml",
    "depth_peeling.toml",
    "reference.toml",
    // The simulation's status is read back after the frame, awaited.
    "occupancy.toml;techniques.simulation=verlet",
];

/// The web frame against lavapipe's, hair pixels only. SwiftShader and
/// lavapipe rasterize the sub-pixel strands differently at their edges, so
/// the bound is far wider than the goldens' (one driver against itself):
/// at most 20% of the hair pixels off by more than 2/255 and a hair mean
/// within 2/255. Measured at 96x72 (tests/web.rs, `--nocapture`):
/// occupancy, linked_list, depth_peeling and reference 15% (201–203 of
/// 1328) and 1.26–1.28/255; a camera turned by 0.05 rad fails both bounds.
/// forward.toml is left out: its hair mean is 6.7/255 with 21 isolated
/// outliers. Its self-shadow reads one texel of a 1024² line-rasterized
/// hair depth map, and the two rasterizers cover nearly the same texels
/// (73205 in the page, 73240 on lavapipe) but 1798 differ (the opaque map:
/// 155 of 1048576), so a hair pixel on such a texel flips between lit and
/// shadowed (`forward_maps` below). What differs is which primitive covers
/// a texel, not how depth is interpolated: of the 1798, 1359 are covered in
/// one map alone and 439 in both with another depth, up to 42/255 apart (a
/// nearer strand covering it in one map only); the opaque map's 155 are all
/// such steps, up to 48/255, at silhouettes. Both drivers draw lines as
/// rectangles (`strictLines = true`), but SwiftShader snaps vertices to 1/16
/// of a texel (`subPixelPrecisionBits = 4`) and lavapipe to 1/256 (8):
/// `vulkaninfo` with `VK_ICD_FILENAMES` set to
/// `/usr/lib/chromium/vk_swiftshader_icd.json`, then to lavapipe's. Snapping
/// the hair map's window positions to 1/16 in the vertex shader (a trial,
/// not kept) left 1395 differing texels, with the page's map changed too
/// (73483 covered): SwiftShader's snap is not a round to the nearest 1/16 of
/// the position plait computes, and which edge rule or rounding makes the
/// rest is not yet traced pixel by pixel.
fn close_enough(c: &Comparison) -> bool {
    c.changed as f64 <= c.hair_pixels as f64 * 0.2 && c.hair_mean <= 2.0
}

/// lavapipe's frame for a page entry (`name.toml;--set value;…`).
fn native(entry: &str, scene: &SceneData) -> (RgbaImage, plait_gpu::FrameReport) {
    let (_lock, gpu) = open_gpu();
    let mut parts = entry.split(';');
    let pipeline = parts.next().unwrap_or_default();
    let sets: Vec<String> = parts.map(str::to_owned).collect();
    let path = repo_root().join("pipelines").join(pipeline);
    let prepared =
        prepare(&gpu, &path, &sets, scene, SIZE).unwrap_or_else(|e| panic!("{entry}: {e}"));
    let frame = prepared
        .render()
        .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
    let image = prepared
        .image()
        .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
    (image, frame.report)
}

/// Every pass stat of a report (`pass.stat` → value): what a pass found out
/// while recording, e.g. depth peeling's `layers` and `capped`.
fn stats(report: &serde_json::Value) -> Vec<(String, f64)> {
    let passes = report["passes"].as_array().cloned().unwrap_or_default();
    passes
        .iter()
        .flat_map(|p| {
            let pass = p["name"].as_str().unwrap_or("?").to_owned();
            let stats = p["stats"].as_array().cloned().unwrap_or_default();
            stats.into_iter().map(move |s| {
                (
                    format!("{pass}.{}", s[0].as_str().unwrap_or("?")),
                    s[1].as_f64().unwrap_or(f64::NAN),
                )
            })
        })
        .collect()
}

/// The same stats, each within 10% (at least 1) of lavapipe's: the two
/// rasterizers cover strand edges differently, so a pixel's depth complexity
/// (depth peeling's `layers`) may differ by one — measured 26 layers in the
/// page, 25 on lavapipe for depth_peeling.toml at 96x72. A page that stopped
/// peeling at its first read-back (4 layers) is far outside.
fn stats_agree(web: &[(String, f64)], native: &[(String, f64)]) -> bool {
    web.len() == native.len()
        && web
            .iter()
            .zip(native)
            .all(|((a, x), (b, y))| a == b && (x - y).abs() <= (0.1 * y.abs()).max(1.0))
}

fn small_scene() -> SceneData {
    SceneData::load(Some(&repo_root().join("examples/scenes/small.toml"))).expect("small scene")
}

#[test]
fn the_page_renders_gallery_pipelines_as_lavapipe_does() {
    let asked: Vec<&str> = RENDERED.to_vec();
    let (posted, console, paths) = run_page(&asked);
    if let Some(fatal) = &posted.fatal {
        panic!("the page failed: {fatal}");
    }
    let adapter = posted.adapter.clone().unwrap_or_default();
    eprintln!("web adapter: {adapter}");
    let scene = small_scene();
    let mut bare = scene.clone();
    bare.strands = plait_tests::hair_taken_away(&bare.strands);
    bare.guides = plait_hair::guides::Guides::default();
    let (no_hair, _) = native("occupancy.toml", &bare);
    let mut failures = Vec::new();
    for outcome in &posted.results {
        let name = outcome.pipeline.as_str();
        let (None, Some(w), Some(h), Some(pixels), Some(report)) = (
            &outcome.error,
            outcome.width,
            outcome.height,
            outcome.pixels.clone(),
            &outcome.report,
        ) else {
            failures.push(format!("{name}: no frame: {:?}", outcome.error));
            continue;
        };
        let web = RgbaImage::from_raw(w, h, pixels).expect("RGBA of the frame's size");
        // Lavapipe's first frame, timed as the page times its own: compile,
        // build, one frame, readback (wall clock, this machine, same run).
        let started = std::time::Instant::now();
        let (reference, native_report) = native(name, &scene);
        let native_ms = started.elapsed().as_secs_f64() * 1e3;
        let c = compare(&web, &reference, &no_hair);
        // What the passes found out (depth peeling's layers) must agree: a
        // browser that stopped peeling early would report fewer.
        let native_stats = stats(&serde_json::to_value(&native_report).expect("report as JSON"));
        let web_stats = stats(report);
        eprintln!(
            "{name}: first frame in the page (SwiftShader) {:.0} ms, natively (lavapipe, device opening included) {native_ms:.0} ms; vs lavapipe: {}; pass stats web {web_stats:?}, native {native_stats:?}",
            outcome.ms,
            c.summary()
        );
        if std::env::var_os("PLAIT_WEB_KEEP").is_some() {
            let dir = repo_root().join("target/web-frames");
            std::fs::create_dir_all(&dir).ok();
            web.save(dir.join(format!("{name}.web.png"))).ok();
            reference.save(dir.join(format!("{name}.native.png"))).ok();
        }
        if !close_enough(&c) {
            failures.push(format!(
                "{name}: the page's frame differs from lavapipe's: {}",
                c.summary()
            ));
        }
        if !stats_agree(&web_stats, &native_stats) {
            failures.push(format!(
                "{name}: the page's pass stats {web_stats:?}, lavapipe's {native_stats:?}"
            ));
        }
    }
    assert_eq!(
        posted.results.len(),
        asked.len(),
        "a result per pipeline: {posted:?}"
    );
    let site_files = [
        "/",
        "/app.js",
        "/style.css",
        "/plait_web.js",
        "/plait_web_bg.wasm",
        "/result",
        "/favicon.ico",
    ];
    let strays: Vec<&String> = paths
        .iter()
        .filter(|p| !site_files.contains(&p.as_str()))
        .collect();
    assert!(
        strays.is_empty(),
        "the page asked for files the site does not have: {strays:?}"
    );
    assert!(
        console.is_empty(),
        "console errors:\n{}",
        console.join("\n")
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// lavapipe checked as the page's device is: with WebGPU's default limits,
/// what `Gpu::new_async` asks for in a browser (so a pipeline the page
/// refuses is refused here by the same check, with the same text).
fn with_webgpu_default_limits(gpu: &mut plait_gpu::Gpu) {
    gpu.support.limits = Default::default();
    let l = &gpu.support.limits;
    gpu.capabilities.max_texture_dimension = l.max_texture_dimension_2d;
    gpu.capabilities.max_storage_buffer_binding_size =
        l.max_storage_buffer_binding_size.min(l.max_buffer_size);
}

/// The gallery's pipelines, by file name.
fn gallery() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(repo_root().join("pipelines"))
        .expect("pipelines/")
        .flatten()
        .filter_map(|e| e.file_name().into_string().ok())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    names
}

/// `plait check --adapter`'s text for `pipeline` with `sets` on lavapipe
/// with WebGPU's default limits, at the page's test size; `None` if it passes.
fn check_text(gpu: &plait_gpu::Gpu, pipeline: &str, sets: &[String]) -> Option<String> {
    check_text_at(gpu, pipeline, sets, SIZE)
}

/// [`check_text`] at another frame size (texture limits depend on it).
fn check_text_at(
    gpu: &plait_gpu::Gpu,
    pipeline: &str,
    sets: &[String],
    size: (u32, u32),
) -> Option<String> {
    let library = plait_passes::library_for(&[]);
    let path = repo_root().join("pipelines").join(pipeline);
    plait::adapter::check_on_adapter(gpu, &library, &path, sets, size)
        .err()
        .map(|e| e.to_string())
}

/// Every gallery pipeline passes the adapter check within WebGPU's default
/// limits (what the page's device has), natively: the page can render them all.
#[test]
fn gallery_pipelines_fit_webgpus_default_limits() {
    let (_lock, mut gpu) = open_gpu();
    with_webgpu_default_limits(&mut gpu);
    let refused: Vec<String> = gallery()
        .iter()
        .filter_map(|name| check_text(&gpu, name, &[]).map(|e| format!("{name}: {e}")))
        .collect();
    eprintln!(
        "{} of {} gallery pipelines pass the check within WebGPU's default limits",
        gallery().len() - refused.len(),
        gallery().len()
    );
    assert!(refused.is_empty(), "{}", refused.join("\n"));
}

/// A message as the page gives it: the built-in library's paths (`<built-in>/`, `plait_assets::BUILTIN_ROOT`) for the
/// repository's, and the adapter (`adapter `…` (… backend…) cannot run`)
/// left out, since the page's is another.
fn as_the_page_says(text: &str) -> String {
    let root = format!("{}/", repo_root().display());
    let text = text.replace(&root, "<built-in>/");
    match (text.find("adapter "), text.find(" cannot run pipeline")) {
        (Some(a), Some(b)) if a < b => format!("{}adapter …{}", &text[..a], &text[b..]),
        _ => text,
    }
}

/// A bad param and a pipeline beyond WebGPU's default limits, changed on the
/// page as a reader would: each shows the CLI's text for the same flags
/// (`plait check --adapter`'s, for the same limits) and the picture stays the
/// last good frame.
#[test]
fn the_page_refuses_and_reports_as_the_cli_does() {
    let good = "linked_list.toml";
    let bad_param = ["params.max_sorted=1000".to_owned()];
    // compute_raster's tile_blend binds 8 storage buffers, WebGPU's default
    // maxStorageBuffersPerShaderStage; per-vertex ambient occlusion adds one.
    let too_many = ["techniques.ambient_occlusion=cylinders".to_owned()];
    let entries = [
        good.to_owned(),
        format!("{good};{}", bad_param[0]),
        format!("compute_raster.toml;{}", too_many[0]),
    ];
    let asked: Vec<&str> = entries.iter().map(String::as_str).collect();
    let (posted, console, _) = run_page(&asked);
    if let Some(fatal) = &posted.fatal {
        panic!("the page failed: {fatal}");
    }
    let (_lock, mut gpu) = open_gpu();
    let bad_param_text = check_text(&gpu, good, &bad_param).expect("max_sorted=1000 is refused");
    with_webgpu_default_limits(&mut gpu);
    let limits_text =
        check_text(&gpu, "compute_raster.toml", &too_many).expect("refused within the limits");
    drop(_lock);
    let [first, param, limits] = &posted.results[..] else {
        panic!("three results: {posted:?}");
    };
    assert_eq!(first.error, None, "the good frame");
    for (outcome, native) in [(param, &bad_param_text), (limits, &limits_text)] {
        eprintln!("{}: the page says:\n{:?}", outcome.pipeline, outcome.error);
        assert_eq!(
            outcome.error.as_deref().map(as_the_page_says),
            Some(as_the_page_says(native)),
            "{}: the page's text against the CLI's",
            outcome.pipeline
        );
        assert_eq!(
            (outcome.width, outcome.height, &outcome.pixels),
            (first.width, first.height, &first.pixels),
            "{}: the page should keep showing the last good frame",
            outcome.pipeline
        );
    }
    // The refusals are expected; Chromium logs nothing else.
    assert!(
        console.is_empty(),
        "console errors:\n{}",
        console.join("\n")
    );
}

/// forward.toml's difference isolated (issue 44): its light-view maps read
/// back from the page and from lavapipe, texel by texel.
#[test]
#[ignore = "an investigation, run by hand: cargo test -p plait-tests --test web forward_maps -- --ignored --nocapture"]
fn forward_maps() {
    let maps = ["hair_depth", "opaque_shadow", "radiance"];
    let entries: Vec<String> = maps
        .iter()
        .map(|m| format!("forward.toml;read={m}"))
        .collect();
    let asked: Vec<&str> = entries.iter().map(String::as_str).collect();
    let (posted, _, _) = run_page(&asked);
    let scene = small_scene();
    let (_lock, gpu) = open_gpu();
    let path = repo_root().join("pipelines/forward.toml");
    let prepared = prepare(&gpu, &path, &[], &scene, SIZE).expect("forward");
    prepared.render().expect("frame");
    for (map, outcome) in maps.iter().zip(&posted.results) {
        let native = prepared.read_resource(map).expect("map").to_image();
        let web = outcome.pixels.clone().unwrap_or_default();
        let covered = |px: &[u8]| px.chunks(4).filter(|p| p[0] < 255).count();
        let pairs: Vec<(&[u8], &[u8])> = native.as_raw().chunks(4).zip(web.chunks(4)).collect();
        let differ = pairs.iter().filter(|(a, b)| a[0] != b[0]).count();
        // A differing texel is covered by one rasterizer alone, or by both
        // with another value (depth interpolated or rounded otherwise).
        let one_only = pairs
            .iter()
            .filter(|(a, b)| (a[0] < 255) != (b[0] < 255))
            .count();
        let steps: Vec<i32> = pairs
            .iter()
            .filter(|(a, b)| a[0] < 255 && b[0] < 255 && a[0] != b[0])
            .map(|(a, b)| b[0] as i32 - a[0] as i32)
            .collect();
        let largest = steps.iter().map(|d| d.abs()).max().unwrap_or(0);
        eprintln!(
            "{map}: {:?}; covered texels web {} native {}; differing {differ}: covered by one alone {one_only}, by both with another value {} (largest step {largest}/255)",
            outcome.error,
            covered(&web),
            covered(native.as_raw()),
            steps.len()
        );
        if std::env::var_os("PLAIT_WEB_KEEP").is_some() {
            let dir = repo_root().join("target/web-frames");
            std::fs::create_dir_all(&dir).ok();
            native
                .save(dir.join(format!("forward-{map}.native.png")))
                .ok();
            if let (Some(w), Some(h)) = (outcome.width, outcome.height)
                && let Some(img) = RgbaImage::from_raw(w, h, web)
            {
                img.save(dir.join(format!("forward-{map}.web.png"))).ok();
            }
        }
    }
}
