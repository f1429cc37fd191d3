//! `plait hair generate` / `plait hair info` end to end (issue 3).

use std::path::Path;

mod common;
use common::{plait, text};

fn generate(dir: &Path, name: &str) -> std::path::PathBuf {
    let out = dir.join(name);
    let o = plait(&[
        "hair",
        "generate",
        "--style",
        "wavy",
        "--strands",
        "40",
        "--segments",
        "8",
        "--seed",
        "9",
        "--out",
        out.to_str().expect("utf-8 path"),
    ]);
    assert!(o.status.success(), "generate failed: {}", text(&o.stderr));
    out
}

#[test]
fn generate_then_info_json() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = generate(dir.path(), "g.hair");
    let o = plait(&["hair", "info", "--json", file.to_str().expect("utf-8")]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    assert_eq!(v["strands"], 40);
    assert_eq!(v["points"], 40 * 9);
    assert_eq!(v["segments"], 40 * 8);
    assert!(
        v["arrays"]
            .as_array()
            .expect("arrays")
            .iter()
            .any(|a| a == "points")
    );
    assert_eq!(v["bounds"]["min"].as_array().expect("min").len(), 3);
    assert_eq!(v["bounds"]["max"].as_array().expect("max").len(), 3);
    assert!(v["defaults"].is_object());
    assert_eq!(v["warnings"].as_array().expect("warnings").len(), 0);
    // deterministic: same flags, same bytes
    let again = generate(dir.path(), "h.hair");
    assert_eq!(
        std::fs::read(&file).expect("read"),
        std::fs::read(&again).expect("read")
    );
}

#[test]
fn info_on_an_independently_written_file() {
    // Built byte by byte from the published layout.
    let mut b: Vec<u8> = Vec::new();
    b.extend_from_slice(b"HAIR");
    b.extend_from_slice(&3u32.to_le_bytes()); // strands
    b.extend_from_slice(&6u32.to_le_bytes()); // points
    b.extend_from_slice(&2u32.to_le_bytes()); // points array only
    b.extend_from_slice(&1u32.to_le_bytes()); // default segments
    b.extend_from_slice(&0.5f32.to_le_bytes());
    b.extend_from_slice(&0.25f32.to_le_bytes());
    for c in [0.1f32, 0.2, 0.3] {
        b.extend_from_slice(&c.to_le_bytes());
    }
    b.extend_from_slice(&[0u8; 88]);
    for i in 0..6 {
        for c in [i as f32, 0.0, -1.0] {
            b.extend_from_slice(&c.to_le_bytes());
        }
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("indep.hair");
    std::fs::write(&path, &b).expect("write");
    let o = plait(&["hair", "info", "--json", path.to_str().expect("utf-8")]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("json");
    assert_eq!(v["strands"], 3);
    assert_eq!(v["points"], 6);
    assert_eq!(v["segments"], 3);
    assert_eq!(v["arrays"], serde_json::json!(["points"]));
    assert_eq!(v["defaults"]["segments"], 1);
    assert_eq!(v["defaults"]["thickness"], 0.5);
    assert_eq!(v["defaults"]["transparency"], 0.25);
    assert_eq!(v["bounds"]["max"][0], 5.0);
    // text mode works too
    let o = plait(&["hair", "info", path.to_str().expect("utf-8")]);
    assert!(o.status.success());
    assert!(text(&o.stdout).contains("strands"));
}

#[test]
fn bad_files_exit_2_and_name_the_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let good = std::fs::read(generate(dir.path(), "g.hair")).expect("read");
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "sig.hair",
            [b"NOPE".as_slice(), &good[4..]].concat(),
            "HAIR",
        ),
        ("trunc.hair", good[..good.len() - 10].to_vec(), "bytes"),
        ("short.hair", good[..50].to_vec(), "header"),
        (
            "huge.hair",
            {
                let mut b = good[..1024].to_vec();
                b[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
                b[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
                b
            },
            "points",
        ),
    ];
    for (name, bytes, needle) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).expect("write");
        let o = plait(&["hair", "info", path.to_str().expect("utf-8")]);
        assert_eq!(o.status.code(), Some(2), "{name}: {}", text(&o.stderr));
        let err = text(&o.stderr);
        assert!(err.contains(name), "{name}: {err}");
        assert!(err.contains(needle), "{name}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
    let o = plait(&[
        "hair",
        "info",
        dir.path().join("missing.hair").to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o.stderr).contains("missing.hair"));
}

#[test]
fn generate_validates_flags() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("x.hair");
    let out = out.to_str().expect("utf-8");
    for (flag, args) in [
        ("--strands", vec!["--strands", "0", "--segments", "4"]),
        ("--segments", vec!["--strands", "4", "--segments", "0"]),
        ("--segments", vec!["--strands", "4", "--segments", "70000"]),
        (
            "--style",
            vec!["--style", "frizzy", "--strands", "4", "--segments", "4"],
        ),
    ] {
        let mut all = vec!["hair", "generate"];
        all.extend(args);
        all.extend(["--out", out]);
        let o = plait(&all);
        assert_eq!(o.status.code(), Some(2), "{all:?}");
        assert!(
            text(&o.stderr).contains(flag),
            "{all:?}: {}",
            text(&o.stderr)
        );
    }
    assert!(!Path::new(out).exists());
}
