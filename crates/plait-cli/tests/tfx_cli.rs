//! `plait hair info` / `plait hair convert` on TressFX `.tfx` files built
//! byte by byte (issue 14).

use std::path::{Path, PathBuf};

mod common;
use common::{plait, text};

/// A TressFX 4 file: 160-byte header, positions as float4, nothing else.
fn tfx(strands: u32, per: u32) -> Vec<u8> {
    let mut b = Vec::new();
    b.extend_from_slice(&4.0f32.to_le_bytes());
    b.extend_from_slice(&strands.to_le_bytes());
    b.extend_from_slice(&per.to_le_bytes());
    b.extend_from_slice(&160u32.to_le_bytes());
    b.resize(160, 0);
    for s in 0..strands {
        for k in 0..per {
            for c in [
                s as f32,
                -(k as f32) * 0.5,
                0.25,
                if k < 2 { 0.0 } else { 1.0 },
            ] {
                b.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    b
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write");
    path
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

#[test]
fn info_reads_a_tfx_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = write(dir.path(), "g.tfx", &tfx(3, 8));
    let o = plait(&["hair", "info", "--json", s(&file)]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(v["format"], "tfx");
    assert_eq!(v["strands"], 3);
    assert_eq!(v["vertices_per_strand"], 8);
    assert_eq!(v["points"], 24);
    assert_eq!(v["bounds"]["max"][0], 2.0);
    let o = plait(&["hair", "info", s(&file)]);
    assert!(
        text(&o.stdout).contains("TressFX .tfx, version 4"),
        "{}",
        text(&o.stdout)
    );
}

#[test]
fn convert_round_trips_tfx_through_hair() {
    let dir = tempfile::tempdir().expect("tempdir");
    let original = tfx(4, 16);
    let input = write(dir.path(), "in.tfx", &original);
    let hair = dir.path().join("mid.hair");
    let back = dir.path().join("out.tfx");
    let o = plait(&["hair", "convert", s(&input), s(&hair)]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(
        std::fs::read(&hair)
            .expect("hair written")
            .starts_with(b"HAIR")
    );
    let o = plait(&["hair", "convert", s(&hair), s(&back)]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    // No resampling was needed, so the bytes come back exactly.
    assert_eq!(std::fs::read(&back).expect("tfx written"), original);
    // Resampling to another count says so.
    let eight = dir.path().join("eight.tfx");
    let o = plait(&[
        "hair",
        "convert",
        s(&input),
        s(&eight),
        "--vertices-per-strand",
        "8",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(text(&o.stderr).contains("resampled"), "{}", text(&o.stderr));
    assert_eq!(
        std::fs::read(&eight).expect("written").len(),
        160 + 4 * 8 * 16
    );
}

#[test]
fn bad_tfx_input_exits_2_naming_the_file_and_writes_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let full = tfx(3, 4);
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "short.tfx",
            full[..200].to_vec(),
            "truncated positions array",
        ),
        ("zero.tfx", tfx(0, 4), "numHairStrands"),
        ("one.tfx", tfx(3, 1), "numVerticesPerStrand"),
        (
            "nan.tfx",
            {
                let mut b = full.clone();
                b[160 + 16 + 4..160 + 16 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
                b
            },
            "position of strand 0, vertex 1",
        ),
        (
            "huge.tfx",
            {
                let mut b = full.clone();
                b[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
                b
            },
            "field `offsetVertexPosition`",
        ),
    ];
    for (name, bytes, want) in cases {
        let input = write(dir.path(), name, &bytes);
        let out = dir.path().join(format!("{name}.hair"));
        for args in [
            vec!["hair", "info", s(&input)],
            vec!["hair", "convert", s(&input), s(&out)],
        ] {
            let o = plait(&args);
            let err = text(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
            assert!(err.contains(name) && err.contains(want), "{err}");
            assert!(!err.contains("panicked"), "{err}");
        }
        assert!(!out.exists(), "no output for a bad input");
    }
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .expect("list")
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with(".plait-"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
    let o = plait(&[
        "hair",
        "convert",
        s(&write(dir.path(), "ok.tfx", &full)),
        "x.obj",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o.stderr)
            .contains("x.obj: the output's extension must be .hair, .tfx, .usda, .usdc or .usdz")
    );
}

/// A scene naming a `.tfx` groom in its own units and axes, with follow
/// strands, a fitted camera and light and no head, renders framed.
#[test]
fn a_tfx_scene_renders_framed() {
    let dir = tempfile::tempdir().expect("tempdir");
    // 40 guides of 8 vertices, 200 units tall along +Z (a Z-up asset).
    let mut b = Vec::new();
    for w in [4.0f32.to_bits(), 40, 8, 160] {
        b.extend_from_slice(&w.to_le_bytes());
    }
    b.resize(160, 0);
    for s in 0..40 {
        for k in 0..8 {
            let x = (s % 8) as f32 * 10.0 + k as f32 * 2.0;
            let y = (s / 8) as f32 * 10.0;
            for c in [x, y, 200.0 - 25.0 * k as f32, 1.0] {
                b.extend_from_slice(&c.to_le_bytes());
            }
        }
    }
    write(dir.path(), "g.tfx", &b);
    let scene = write(
        dir.path(),
        "s.toml",
        b"camera = \"fit\"\nlight = \"fit\"\n[hair]\nfile = \"g.tfx\"\nfollow_strands = 3\nfollow_radius = 2\n\
          [hair.transform]\nrotate_degrees = [-90, 0, 0]\n[material]\ncolor = [0.8, 0.6, 0.4]\n",
    );
    let out = dir.path().join("g.png");
    let o = plait(&[
        "render",
        "--scene",
        s(&scene),
        "--size",
        "64x48",
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let img = image::open(&out).expect("png").to_rgba8();
    let background = *img.get_pixel(0, 0);
    let (mut lo, mut hi) = ((u32::MAX, u32::MAX), (0, 0));
    for (x, y, p) in img.enumerate_pixels() {
        if *p != background {
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
        }
    }
    // The groom fills most of the frame's height and is centred in it.
    assert!(
        hi.1 > lo.1 && hi.1 - lo.1 >= 30,
        "hair spans rows {lo:?}..{hi:?}"
    );
    let centre = (lo.0 + hi.0) / 2;
    assert!(
        (20..=44).contains(&centre),
        "hair centred at column {centre}"
    );
}
