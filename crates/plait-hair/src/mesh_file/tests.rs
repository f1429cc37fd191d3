//! The glTF reader on files the writer makes, and on each kind of bad input
//! the scene format promises an error for (naming the file and the mesh,
//! primitive or field), checked before anything is allocated.

use std::borrow::Cow;
use std::path::Path;

use glam::Vec3;
use serde_json::Value;

use super::write::to_glb;
use super::{Limits, read};
use crate::mesh::Mesh;

fn triangle() -> Mesh {
    let mut m = Mesh::ellipsoid(Vec3::ZERO, Vec3::ONE, 2, 3);
    m.name = "tri".into();
    m
}

/// `mesh` as .glb with its JSON edited by `edit`.
fn edited(mesh: &Mesh, edit: impl FnOnce(&mut Value)) -> Vec<u8> {
    let bytes = to_glb(mesh);
    let glb = gltf::binary::Glb::from_slice(&bytes).expect("the writer's output splits");
    let mut json: Value = serde_json::from_slice(&glb.json).expect("JSON");
    edit(&mut json);
    let mut text = serde_json::to_vec(&json).expect("serializes");
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    gltf::binary::Glb {
        header: glb.header,
        json: Cow::Owned(text),
        bin: glb.bin.clone(),
    }
    .to_vec()
    .expect("in memory")
}

fn error_of(bytes: &[u8]) -> String {
    super::gltf::read_bytes(bytes, Path::new("bad.glb"), &Limits::DEFAULT)
        .expect_err("the reader refuses it")
        .to_string()
}

#[test]
fn a_written_mesh_reads_back_exactly() {
    let head = Mesh::ellipsoid(Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.9, 1.05, 1.0), 8, 16);
    let read = super::gltf::read_bytes(&to_glb(&head), Path::new("head.glb"), &Limits::DEFAULT)
        .expect("reads");
    // Positions exactly; normals renormalised (a rounding apart).
    assert_eq!(read.vertices.len(), head.vertices.len());
    for (a, b) in read.vertices.iter().zip(&head.vertices) {
        assert_eq!(a.position, b.position);
        assert!((Vec3::from(a.normal) - Vec3::from(b.normal)).length() < 1e-6);
    }
    assert!(read.indices == head.indices, "indices differ");
    assert_eq!(read.name, "head");
}

/// The albedo is the material's `baseColorFactor`; without a material,
/// 0.8 grey.
#[test]
fn the_albedo_is_the_materials_base_colour() {
    let mesh = triangle().with_albedo([0.2, 0.4, 0.6]);
    let read = |bytes: &[u8]| {
        super::gltf::read_bytes(bytes, Path::new("m.glb"), &Limits::DEFAULT)
            .expect("reads")
            .albedo
    };
    assert_eq!(read(&to_glb(&mesh)), [0.2, 0.4, 0.6]);
    let bare = edited(&mesh, |json| {
        json.as_object_mut().unwrap().remove("materials");
        for p in json["meshes"][0]["primitives"].as_array_mut().unwrap() {
            p.as_object_mut().unwrap().remove("material");
        }
    });
    assert_eq!(read(&bare), [0.8, 0.8, 0.8]);
}

#[test]
fn the_committed_example_head_is_what_make_assets_writes() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/head.glb");
    let committed = std::fs::read(&path).expect("examples/scenes/head.glb is committed");
    assert!(
        committed == super::write::example_head_glb(),
        "examples/scenes/head.glb differs from what `cargo run --example make_assets` writes; run it"
    );
    let path = path.with_file_name("sculpted_head.glb");
    let committed = std::fs::read(&path).expect("examples/scenes/sculpted_head.glb is committed");
    assert!(
        committed == super::write::example_sculpted_head_glb(),
        "examples/scenes/sculpted_head.glb differs from what `cargo run --example make_assets` writes; run it"
    );
}

#[test]
fn the_committed_example_groom_is_what_make_assets_writes() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/groom.usda");
    let committed = std::fs::read(&path).expect("examples/scenes/groom.usda is committed");
    assert!(
        committed == crate::usd::example_groom_usda(),
        "examples/scenes/groom.usda differs from what `cargo run --example make_assets` writes; run it"
    );
}

#[test]
fn json_gltf_with_an_external_bin_reads() {
    let dir = tempfile::tempdir().expect("temp dir");
    let bytes = to_glb(&triangle());
    let glb = gltf::binary::Glb::from_slice(&bytes).expect("splits");
    let mut json: Value = serde_json::from_slice(&glb.json).expect("JSON");
    json["buffers"][0]["uri"] = "tri.bin".into();
    std::fs::write(
        dir.path().join("tri.gltf"),
        serde_json::to_vec(&json).expect("json"),
    )
    .expect("write");
    let missing = read(&dir.path().join("tri.gltf"), &Limits::DEFAULT)
        .unwrap_err()
        .to_string();
    assert!(
        missing.contains("tri.bin") && missing.contains("buffer 0"),
        "{missing}"
    );
    std::fs::write(dir.path().join("tri.bin"), glb.bin.as_deref().expect("bin")).expect("write");
    let mesh = read(&dir.path().join("tri.gltf"), &Limits::DEFAULT).expect("reads");
    assert_eq!(mesh.indices, triangle().indices);
}

#[test]
fn bad_files_are_named_with_the_mesh_primitive_and_field() {
    let m = triangle();
    let cases: Vec<(Vec<u8>, &[&str])> = vec![
        (
            edited(&m, |j| {
                j["meshes"][0]["primitives"][0]["attributes"]
                    .as_object_mut()
                    .expect("attributes")
                    .remove("POSITION");
            }),
            // The gltf crate's validation names the field.
            &[
                "bad.glb",
                "meshes[0].primitives[0].attributes[\"POSITION\"]",
                "Missing",
            ],
        ),
        (
            // Index 0 of the index buffer's first u32 made huge.
            {
                let mut b = to_glb(&m);
                let n = b.len();
                let count = m.indices.len();
                b[n - 4 * count..n - 4 * count + 4].copy_from_slice(&1000u32.to_le_bytes());
                b
            },
            &["bad.glb", "primitive 0", "indices: index 0 is 1000", "has"],
        ),
        (
            edited(&m, |j| j["accessors"][0]["count"] = 3_000_000_000u64.into()),
            &[
                "bad.glb",
                "POSITION claims 3000000000 vertices",
                "limit of 1048576",
            ],
        ),
        (
            edited(&m, |j| j["accessors"][0]["count"] = 500_000.into()),
            &["bad.glb", "POSITION", "do not fit in bufferView 0"],
        ),
        (
            edited(&m, |j| j["accessors"][2]["count"] = 9_000_000.into()),
            &["bad.glb", "claims 3000000 triangles", "limit"],
        ),
        (
            {
                let mut b = to_glb(&m);
                // The first position's x: the BIN chunk starts after the JSON.
                let glb = gltf::binary::Glb::from_slice(&b).expect("splits");
                let at = 12 + 8 + glb.json.len() + 8;
                b[at..at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
                b
            },
            &["bad.glb", "primitive 0", "POSITION: vertex 0 is not finite"],
        ),
        (
            edited(&m, |j| j["meshes"][0]["primitives"][0]["mode"] = 1.into()),
            &["bad.glb", "primitive 0", "triangle lists only"],
        ),
        (
            edited(&m, |j| {
                j["buffers"][0]["uri"] = "data:application/octet-stream;base64,AAAA".into()
            }),
            &["bad.glb", "data: URI"],
        ),
        (
            edited(&m, |j| j["accessors"][0]["type"] = "VEC2".into()),
            &["bad.glb", "POSITION", "VEC3 of 32-bit floats"],
        ),
        (
            edited(&m, |j| {
                j["meshes"][0]["primitives"][0]["indices"] = 7.into()
            }),
            &["bad.glb", "not a valid glTF 2.0 file"],
        ),
        (to_glb(&m)[..40].to_vec(), &["bad.glb", "not a valid glTF"]),
        // Found by tests/fuzz.rs, each a panic inside gltf 1.4.1: a GLB
        // length below its header's, and a POSITION accessor out of range.
        (
            {
                let mut b = to_glb(&m);
                b[8..12].copy_from_slice(&3u32.to_le_bytes());
                b
            },
            &["bad.glb", "GLB header's length is 3"],
        ),
        (
            edited(&m, |j| {
                j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9.into()
            }),
            &[
                "bad.glb",
                "meshes[0].primitives[0].attributes[\"POSITION\"] is accessor 9, but the file has 3",
            ],
        ),
    ];
    for (bytes, wanted) in cases {
        let e = error_of(&bytes);
        for w in wanted {
            assert!(e.contains(w), "`{w}` not in: {e}");
        }
    }
}

#[test]
fn missing_files_and_unknown_formats_are_named() {
    let e = read(Path::new("/nonexistent/head.glb"), &Limits::DEFAULT)
        .unwrap_err()
        .to_string();
    assert!(e.contains("/nonexistent/head.glb: cannot read file"), "{e}");
    let e = read(Path::new("head.obj"), &Limits::DEFAULT)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("head.obj: unknown mesh format `.obj`") && e.contains("`.glb`"),
        "{e}"
    );
}
