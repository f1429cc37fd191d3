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
    assert!(text(&o.stderr).contains("x.obj: the output's extension must be .hair or .tfx"));
}
