//! Writing a [`Mesh`] as binary glTF 2.0 (`.glb`): what
//! `cargo run --example make_assets` uses to write the example head, and
//! tests to make files for the reader. One buffer: positions, normals, then
//! 32-bit indices; one mesh, one node. The JSON is built with `serde_json`
//! (already a dependency) rather than `gltf-json`'s typed structs, whose
//! every optional field would have to be spelled out; the reader checks
//! what it writes. Its bytes depend only on the mesh (serde_json sorts
//! object keys), so a committed file can be checked to be reproducible.

use std::borrow::Cow;

use serde_json::json;

use crate::mesh::Mesh;

/// The mesh as `.glb` bytes.
pub fn to_glb(mesh: &Mesh) -> Vec<u8> {
    let count = mesh.vertices.len();
    let mut bin: Vec<u8> = Vec::with_capacity(count * 24 + mesh.indices.len() * 4);
    for v in &mesh.vertices {
        bin.extend(v.position.iter().flat_map(|c| c.to_le_bytes()));
    }
    for v in &mesh.vertices {
        bin.extend(v.normal.iter().flat_map(|c| c.to_le_bytes()));
    }
    bin.extend(mesh.indices.iter().flat_map(|i| i.to_le_bytes()));
    let (mut min, mut max) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for v in &mesh.vertices {
        for k in 0..3 {
            min[k] = min[k].min(v.position[k]);
            max[k] = max[k].max(v.position[k]);
        }
    }
    let document = json!({
        "asset": { "version": "2.0", "generator": "plait make_assets" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0, "name": mesh.name }],
        "meshes": [{
            "name": mesh.name,
            "primitives": [{
                "attributes": { "POSITION": 0, "NORMAL": 1 },
                "indices": 2,
                "mode": 4,
                "material": 0
            }]
        }],
        "materials": [{
            "pbrMetallicRoughness": {
                "baseColorFactor": [mesh.albedo[0], mesh.albedo[1], mesh.albedo[2], 1.0],
                "metallicFactor": 0.0
            }
        }],
        "buffers": [{ "byteLength": bin.len() }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": count * 12, "target": 34962 },
            { "buffer": 0, "byteOffset": count * 12, "byteLength": count * 12, "target": 34962 },
            { "buffer": 0, "byteOffset": count * 24, "byteLength": mesh.indices.len() * 4, "target": 34963 }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3", "min": min, "max": max },
            { "bufferView": 1, "componentType": 5126, "count": count, "type": "VEC3" },
            { "bufferView": 2, "componentType": 5125, "count": mesh.indices.len(), "type": "SCALAR" }
        ]
    });
    let mut text = serde_json::to_vec(&document).expect("a JSON value serializes");
    // Chunks are 4-byte aligned: JSON padded with spaces, BIN with zeros.
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let length = 12 + 8 + text.len() + 8 + bin.len();
    let glb = gltf::binary::Glb {
        header: gltf::binary::Header {
            magic: *b"glTF",
            version: 2,
            length: length as u32,
        },
        json: Cow::Owned(text),
        bin: Some(Cow::Owned(bin)),
    };
    glb.to_vec().expect("writing to memory cannot fail")
}

/// The example head (`examples/scenes/head.glb`): the built-in scene's head
/// ellipsoid as a mesh.
pub fn example_head_glb() -> Vec<u8> {
    let head =
        crate::mesh::Mesh::ellipsoid(glam::Vec3::ZERO, glam::Vec3::new(0.9, 1.05, 1.0), 32, 64)
            .with_name("head")
            .with_albedo([0.75, 0.55, 0.45]);
    to_glb(&head)
}

/// The sculpted example head (`examples/scenes/sculpted_head.glb`, the head
/// of `mesh_head.toml`): the same ellipsoid with a face, ears, a jaw and a
/// neck (`crate::sculpted_head`), its scalp unchanged.
pub fn example_sculpted_head_glb() -> Vec<u8> {
    to_glb(&crate::sculpted_head::sculpted_head(96, 128))
}
