//! Scenes from the command line (issue 20): a TressFX groom in the minimal
//! scene of `docs/formats.md` renders as hair, and `--scene NAME` finds the
//! example scenes from any directory, like a pipeline.

use std::path::Path;
use std::process::{Command, Output};

mod common;
use common::{plait, text};

/// A TressFX 4 file as TressFX's exporters write one: a 160-byte header and
/// positions (float4, w = inverse mass, the two root vertices pinned), no
/// thickness and no colour (offsets 0). Metres, Y up: a mohawk-like ridge
/// of `rows × 6` guides of 16 vertices rising from a curved scalp strip
/// and sweeping back, lengths 0.14–0.26 m.
fn mohawk_tfx(rows: u32) -> Vec<u8> {
    let (strands, per) = (rows * 6, 16u32);
    let mut b = Vec::new();
    b.extend_from_slice(&4.0f32.to_le_bytes());
    for word in [strands, per, 160] {
        b.extend_from_slice(&word.to_le_bytes());
    }
    b.resize(160, 0);
    for s in 0..strands {
        let (row, col) = (s / 6, s % 6);
        // Along the ridge (z) over a scalp arc of radius 0.1 m.
        let a = (row as f32 / (rows - 1) as f32 - 0.5) * 2.4;
        let x = (col as f32 - 2.5) * 0.008;
        let root = [x, 1.0 + 0.1 * a.cos(), 0.1 * a.sin()];
        let length = 0.2 + 0.06 * (s as f32 * 1.7).sin();
        for k in 0..per {
            let t = k as f32 / (per - 1) as f32;
            let p = [
                root[0] * (1.0 + 2.0 * t),
                root[1] + length * (0.9 * t - 0.35 * t * t),
                root[2] - length * 0.6 * t * t,
                if k < 2 { 0.0 } else { 1.0 },
            ];
            for c in p {
                b.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    b
}

/// The scene of `docs/formats.md` ("Grooms in a scene") without its
/// optional transform: fitted camera and light, follow strands, no
/// `[material]`.
const MINIMAL_SCENE: &str = "camera = \"fit\"\nlight = \"fit\"\n[hair]\nfile = \"mohawk.tfx\"\n\
follow_strands = 4\nfollow_radius = 0.004\nfollow_tip_spread = 1.0\n";

struct HairStats {
    pixels: usize,
    mean_luminance: f64,
    saturated: f64,
    distinct: usize,
    mean_rgb: [f64; 3],
}

/// Statistics of the pixels that are not background. The scene has no
/// head, ground or environment image, so the background is one colour
/// (checked at the four corners, which the fitted camera's margin keeps
/// clear) and every other pixel shows hair.
fn hair_stats(img: &image::RgbImage) -> HairStats {
    let (w, h) = img.dimensions();
    let background = *img.get_pixel(0, 0);
    for (x, y) in [(w - 1, 0), (0, h - 1), (w - 1, h - 1)] {
        assert_eq!(*img.get_pixel(x, y), background, "corner {x},{y}");
    }
    let hair: Vec<[u8; 3]> = img
        .pixels()
        .filter(|p| p.0.iter().zip(background.0).any(|(a, b)| a.abs_diff(b) > 8))
        .map(|p| p.0)
        .collect();
    let n = hair.len().max(1) as f64;
    let sum = |c: usize| hair.iter().map(|p| f64::from(p[c])).sum::<f64>() / n;
    let mean_rgb = [sum(0), sum(1), sum(2)];
    let distinct: std::collections::HashSet<[u8; 3]> = img.pixels().map(|p| p.0).collect();
    HairStats {
        pixels: hair.len(),
        // Rec. 709 weights on the stored (sRGB) values.
        mean_luminance: 0.2126 * mean_rgb[0] + 0.7152 * mean_rgb[1] + 0.0722 * mean_rgb[2],
        saturated: hair.iter().filter(|p| p.contains(&255)).count() as f64 / n,
        distinct: distinct.len(),
        mean_rgb,
    }
}

/// Issue 20 item 5. Before, the file's absent thickness and colour were read
/// as 1 and opaque white and the strands rendered as a saturated white
/// blob: on this groom at 160×120 on lavapipe, mean luminance 254.9, 0.995
/// of the hair pixels with a channel at 255, 17 distinct colours, R = G = B.
/// With the default groom's look (`plait_hair::groom::dress`): 167.2, 0.000,
/// 2,615, and R, G, B 199, 162, 125. The thresholds sit between, with
/// margins of ≥ 33 in luminance, 0.05 and 0.945 in the saturated fraction
/// and ×30 / ×5 in colours.
#[test]
fn a_tfx_groom_in_the_minimal_documented_scene_looks_like_hair() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("mohawk.tfx"), mohawk_tfx(80)).expect("write groom");
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, MINIMAL_SCENE).expect("write scene");
    let out = dir.path().join("hair.png");
    let o = plait(&[
        "render",
        "--scene",
        scene.to_str().expect("utf-8"),
        "--size",
        "160x120",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let stats = hair_stats(&image::open(&out).expect("png").to_rgb8());
    let s = &stats;
    eprintln!(
        "hair pixels {}, mean luminance {:.1}, saturated {:.3}, distinct colours {}, mean rgb {:?}",
        s.pixels, s.mean_luminance, s.saturated, s.distinct, s.mean_rgb
    );
    assert!(
        s.pixels > 160 * 120 / 50,
        "the groom is visible: {}",
        s.pixels
    );
    assert!(
        s.mean_luminance < 200.0,
        "mean luminance {}",
        s.mean_luminance
    );
    assert!(s.saturated < 0.05, "saturated fraction {}", s.saturated);
    assert!(s.distinct > 500, "distinct colours {}", s.distinct);
    // A hair colour: red over green over blue, as the default brown.
    let [r, g, b] = s.mean_rgb;
    assert!(r > g + 10.0 && g > b + 10.0, "{:?}", s.mean_rgb);
}

/// `plait ARGS...` from `cwd`, with `PLAIT_PATH` set when given.
fn plait_in(cwd: &Path, search_path: Option<&str>, args: &[&str]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_plait"));
    c.current_dir(cwd).args(args);
    if let Some(p) = search_path {
        c.env("PLAIT_PATH", p);
    }
    c.output().expect("run plait")
}

fn render_small(cwd: &Path, search_path: Option<&str>, scene: &str, out: &str) -> Output {
    plait_in(
        cwd,
        search_path,
        &["render", "--scene", scene, "--size", "32x24", "--out", out],
    )
}

/// Issue 20: `--scene small.toml` works from any directory — found on the
/// library search path under `examples/scenes/`, or built in — and a
/// built-in scene that names a file says which and what to do.
#[test]
fn scenes_are_found_by_name_from_any_directory() {
    let dir = tempfile::tempdir().expect("tempdir");
    let cwd = dir.path();
    // From the checkout (the search path's default), by name and by path.
    for given in ["small.toml", "examples/scenes/small.toml"] {
        let o = render_small(cwd, None, given, "disk.png");
        assert!(o.status.success(), "{given}: {}", text(&o.stderr));
    }
    // Only the built-in copies: the same scene, the same image.
    let o = render_small(cwd, Some(""), "small.toml", "builtin.png");
    assert!(o.status.success(), "{}", text(&o.stderr));
    let read = |name: &str| image::open(cwd.join(name)).expect("png").to_rgba8();
    assert!(
        read("builtin.png") == read("disk.png"),
        "built-in and disk scenes differ"
    );
    // A built-in scene naming an image it cannot carry.
    let o = render_small(cwd, Some(""), "env.toml", "env.png");
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("<built-in>/examples/scenes/env.toml")
            && err.contains("studio.hdr")
            && err.contains("PLAIT_PATH"),
        "{err}"
    );
    assert!(
        !cwd.join("env.png").exists(),
        "no output for a failed render"
    );
    // A name found nowhere is named as given.
    let o = render_small(cwd, None, "nope.toml", "nope.png");
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("nope.toml") && !err.contains("panicked"),
        "{err}"
    );
    // A file in the working directory comes first: three strands, not the
    // example's 400.
    std::fs::write(
        cwd.join("small.toml"),
        "[hair.procedural]\nstrands = 3\nsegments = 2\n",
    )
    .expect("write");
    let o = render_small(cwd, None, "small.toml", "local.png");
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(
        read("local.png") != read("disk.png"),
        "the local scene was not used"
    );
}

/// A `.hair` file a scene names that is missing or cut short (plait issue
/// 41): the error names the scene file, line and column of the `file`
/// value, then the hair file's own problem; exit 2, no image.
#[test]
fn a_bad_hair_file_is_reported_where_the_scene_names_it() {
    let dir = tempfile::tempdir().expect("tempdir");
    // A header shorter than the format's 128 bytes, starting as one should.
    std::fs::write(dir.path().join("short.hair"), b"HAIR\x05\x00\x00\x00").expect("write");
    for (name, scene_text, at, problem) in [
        (
            "missing",
            "# no such groom\n[hair]\nfile = \"nope.hair\"\n",
            ":3:8: hair.file: ",
            "nope.hair: cannot read file",
        ),
        (
            "truncated",
            "hair = { file = \"short.hair\" }\n",
            ":1:17: hair.file: ",
            "short.hair: file is 8 bytes, shorter than the 128-byte .hair header",
        ),
    ] {
        let scene = dir.path().join(format!("{name}.toml"));
        std::fs::write(&scene, scene_text).expect("write scene");
        let png = dir.path().join(format!("{name}.png"));
        let o = plait(&[
            "render",
            "--scene",
            scene.to_str().expect("utf-8 path"),
            "--size",
            "64x48",
            "--out",
            png.to_str().expect("utf-8 path"),
        ]);
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        let want = format!("error: {}{at}", scene.display());
        assert!(
            err.contains(&want) && err.contains(problem),
            "{name}: wanted `{want}` … `{problem}`:\n{err}"
        );
        assert!(!png.exists(), "{name}: wrote an image");
    }
}

/// Issue 47's bad input: light, ambient and albedo out of the ranges of
/// docs/formats.md ("Light and units") are refused at their file:line:col
/// with exit 2, no image, and before any GPU work — shown by running with
/// no Vulkan driver at all, where a good scene fails for want of an adapter.
#[test]
fn light_and_albedo_out_of_range_exit_2_before_gpu_work() {
    let dir = tempfile::tempdir().expect("tempdir");
    let cwd = dir.path();
    for (body, at, needle) in [
        ("ambient = -0.1\n", "1:11", "ambient must be ≥ 0"),
        (
            "[light]\ntype = \"directional\"\ndirection = [0, -1, 0]\nintensity = nan\n",
            "4:13",
            "light.intensity must be finite",
        ),
        (
            "[ground]\nheight = -2\nhalf_size = 3\nalbedo = [0.5, 1.5, 0.5]\n",
            "4:10",
            "ground.albedo must be in [0, 1]",
        ),
        (
            "[head]\ncenter = [0, 0, 0]\nradii = [0.9, 1.05, 1.0]\nalbedo = [-0.1, 0.5, 0.5]\n",
            "4:10",
            "head.albedo must be in [0, 1]",
        ),
        (
            "[material]\ncolor = [1.0, 2.0, 1.0]\n",
            "2:9",
            "material.color must be in [0, 1]",
        ),
    ] {
        std::fs::write(
            cwd.join("bad.toml"),
            format!("{body}[hair.procedural]\nstrands = 10\n"),
        )
        .expect("write");
        let o = Command::new(env!("CARGO_BIN_EXE_plait"))
            .current_dir(cwd)
            .env("VK_ICD_FILENAMES", cwd.join("no-driver.json"))
            .env("WGPU_BACKEND", "vulkan")
            .args([
                "render", "--scene", "bad.toml", "--size", "32x24", "--out", "bad.png",
            ])
            .output()
            .expect("run plait");
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{body}: {err}");
        assert!(
            err.contains(&format!("bad.toml:{at}: {needle}")),
            "{body}: {err}"
        );
        assert!(
            !err.contains("adapter") && !err.contains("panicked"),
            "{body}: {err}"
        );
        assert!(!cwd.join("bad.png").exists(), "{body}: no output");
    }
}
