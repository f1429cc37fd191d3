//! Meshes read from files (`[[meshes]]`, issue 24) on the GPU: the example
//! head (`examples/scenes/head.glb`, the default ellipsoid written as glTF)
//! renders as the `[head]` ellipsoid does — drawn, shading, occluding hair,
//! casting shadows through every opaque pass — and its absence or another
//! placement shows.

use std::path::Path;

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root, small_scene_with_head};

const SIZE: (u32, u32) = (96, 72);

/// `examples/scenes/small.toml` with its `[head]` replaced by `head`.
fn small_with(head: &str) -> SceneData {
    SceneData::new(small_scene_with_head(head)).expect("the scene loads")
}

fn mesh_head(role: &str, translate: [f32; 3]) -> String {
    let file = repo_root().join("examples/scenes/head.glb");
    format!(
        "[[meshes]]\nfile = {:?}\nrole = {role:?}\nalbedo = [0.75, 0.55, 0.45]\n[meshes.transform]\ntranslate = {translate:?}\n",
        file.display().to_string()
    )
}

fn render(scene: &SceneData) -> Vec<u8> {
    let (_lock, gpu) = open_gpu();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let p = prepare(&gpu, Path::new(&pipeline), &[], scene, SIZE).expect("pipeline builds");
    p.render().expect("renders");
    p.image().expect("image").into_raw()
}

/// (largest channel difference, pixels differing by more than 2).
fn difference(a: &[u8], b: &[u8]) -> (u8, usize) {
    let largest = a
        .iter()
        .zip(b)
        .map(|(x, y)| x.abs_diff(*y))
        .max()
        .unwrap_or(0);
    let pixels = a
        .chunks_exact(4)
        .zip(b.chunks_exact(4))
        .filter(|(p, q)| p.iter().zip(*q).any(|(x, y)| x.abs_diff(*y) > 2))
        .count();
    (largest, pixels)
}

#[test]
fn the_glb_head_renders_as_the_ellipsoid_head() {
    let ellipsoid = render(&small_with(
        "[head]\ncenter = [0.0, 0.0, 0.0]\nradii = [0.9, 1.05, 1.0]\n",
    ));
    let mesh = render(&small_with(&mesh_head("head", [0.0; 3])));
    // The same triangles (positions exact through the file, normals
    // renormalised): at most rounding (measured: identical).
    let (largest, pixels) = difference(&ellipsoid, &mesh);
    eprintln!(
        "glb head vs ellipsoid: largest channel difference {largest}, {pixels} pixels over 2"
    );
    assert!(largest <= 2, "the glb head renders differently: {largest}");
    // Without a head, or with the mesh moved aside, the image changes a lot:
    // the comparison above can fail.
    let none = render(&small_with(""));
    let aside = render(&small_with(&mesh_head("static", [3.0, 0.0, 0.0])));
    for (what, other) in [("no head", &none), ("the head moved aside", &aside)] {
        let (_, pixels) = difference(&mesh, other);
        eprintln!("{what}: {pixels} pixels differ");
        assert!(
            pixels > 500,
            "{what} should look different ({pixels} pixels)"
        );
    }
}
