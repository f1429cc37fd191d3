//! `Mesh` prims read as scene meshes: units, axis, transforms, fans, and
//! each bad input naming the file, prim and field.

use std::path::PathBuf;

use glam::Vec3;

use crate::mesh_file::{Limits, read, read_prim};

/// A unit cube of quads (two faces as one hexagon-free quad each), in a
/// stage with the given header metadata and prim body.
fn stage(meta: &str, body: &str) -> String {
    format!("#usda 1.0\n(\n{meta}\n)\n\ndef Xform \"Head\"\n{{\n{body}\n}}\n")
}

const CUBE: &str = r#"    def Mesh "Cube"
    {
        point3f[] points = [(-1,-1,-1),(1,-1,-1),(1,1,-1),(-1,1,-1),(-1,-1,1),(1,-1,1),(1,1,1),(-1,1,1)]
        int[] faceVertexCounts = [4,4,4,4,4,4]
        int[] faceVertexIndices = [0,3,2,1, 4,5,6,7, 0,1,5,4, 2,3,7,6, 1,2,6,5, 0,4,7,3]
        color3f[] primvars:displayColor = [(0.5,0.25,0.125)]
    }"#;

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("plait-usd-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn bounds(m: &crate::mesh::Mesh) -> (Vec3, Vec3) {
    m.vertices.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), v| (lo.min(v.position.into()), hi.max(v.position.into())),
    )
}

#[test]
fn a_cube_of_quads_in_metres_y_up() {
    let path = write(
        "cube.usda",
        &stage("metersPerUnit = 1\nupAxis = \"Y\"", CUBE),
    );
    let m = read(&path, &Limits::DEFAULT).unwrap();
    assert_eq!(m.vertices.len(), 8);
    // Six quads, each a fan of two triangles.
    assert_eq!(m.indices.len(), 6 * 2 * 3);
    assert_eq!(m.albedo, [0.5, 0.25, 0.125]);
    let (lo, hi) = bounds(&m);
    assert_eq!((lo, hi), (Vec3::splat(-1.0), Vec3::ONE));
    // Front faces point outward: each triangle's normal away from the centre.
    for t in m.indices.chunks(3) {
        let p = |i: u32| Vec3::from(m.vertices[i as usize].position);
        let n = (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
        let c = (p(t[0]) + p(t[1]) + p(t[2])) / 3.0;
        assert!(n.dot(c) > 0.0, "triangle {t:?} faces inward");
    }
}

#[test]
fn centimetres_z_up_and_a_transform() {
    let body = format!(
        "    double3 xformOp:translate = (0, 0, 100)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n{CUBE}"
    );
    let path = write(
        "cube_cm.usda",
        &stage("metersPerUnit = 0.01\nupAxis = \"Z\"", &body),
    );
    let m = read(&path, &Limits::DEFAULT).unwrap();
    let (lo, hi) = bounds(&m);
    // Translated 100 cm up Z, which is plait's +Y; ±1 cm.
    let centre = (lo + hi) / 2.0;
    assert!(
        (centre - Vec3::new(0.0, 1.0, 0.0)).length() < 1e-5,
        "{centre}"
    );
    assert!(
        ((hi - lo) - Vec3::splat(0.02)).length() < 1e-5,
        "{}",
        hi - lo
    );
}

fn error(name: &str, body: &str, prim: Option<&str>) -> String {
    let path = write(name, &stage("metersPerUnit = 1", body));
    let e = read_prim(&path, prim, &Limits::DEFAULT)
        .unwrap_err()
        .to_string();
    assert!(e.contains(name), "{e}");
    e
}

#[test]
fn bad_meshes_name_file_prim_and_field() {
    let e = error("range.usda", &CUBE.replace("0,4,7,3]", "0,4,7,8]"), None);
    assert!(
        e.contains("/Head/Cube") && e.contains("faceVertexIndices") && e.contains("is 8"),
        "{e}"
    );
    let e = error(
        "counts.usda",
        &CUBE.replace("[4,4,4,4,4,4]", "[4,4,4,4,4,5]"),
        None,
    );
    assert!(
        e.contains("/Head/Cube") && e.contains("faceVertexIndices") && e.contains("sums to 25"),
        "{e}"
    );
    let e = error(
        "two.usda",
        &CUBE.replace("[4,4,4,4,4,4]", "[4,4,4,4,4,2,2]"),
        None,
    );
    assert!(
        e.contains("/Head/Cube") && e.contains("faceVertexCounts") && e.contains("at least 3"),
        "{e}"
    );
    let e = error("nan.usda", &CUBE.replace("(1,1,1)", "(1,nan,1)"), None);
    assert!(
        e.contains("/Head/Cube") && e.contains("points") && e.contains("point 6"),
        "{e}"
    );
    let e = error("none.usda", "    def Xform \"Empty\" {}", None);
    assert!(e.contains("no Mesh prim under `/`"), "{e}");
    let e = error("where.usda", CUBE, Some("/Head/Cub"));
    assert!(
        e.contains("`/Head/Cub` is not on the stage") && e.contains("did you mean `/Head/Cube`"),
        "{e}"
    );
    let e = error(
        "under.usda",
        &format!("{CUBE}\n    def Xform \"Empty\" {{}}"),
        Some("/Head/Empty"),
    );
    assert!(e.contains("no Mesh prim under `/Head/Empty`"), "{e}");
}

#[test]
fn limits_are_checked() {
    let path = write("small.usda", &stage("metersPerUnit = 1", CUBE));
    let limits = Limits {
        vertices: 7,
        ..Limits::DEFAULT
    };
    let e = read(&path, &limits).unwrap_err().to_string();
    assert!(
        e.contains("/Head/Cube") && e.contains("points") && e.contains("more than 7"),
        "{e}"
    );
    let limits = Limits {
        triangles: 11,
        ..Limits::DEFAULT
    };
    let e = read(&path, &limits).unwrap_err().to_string();
    assert!(
        e.contains("faceVertexCounts") && e.contains("more than 11"),
        "{e}"
    );
}

#[test]
fn a_scene_names_usd_meshes_under_a_prim() {
    let path = write("scene_cube.usda", &stage("metersPerUnit = 1", CUBE));
    let scene_path = path.with_file_name("scene.toml");
    let scene = |extra: &str, file: &str| {
        format!(
            "[hair.procedural]\nstrands = 10\nsegments = 4\n\n[[meshes]]\nfile = \"{file}\"\nrole = \"static\"\n{extra}\n"
        )
    };
    let s = crate::scene::Scene::from_toml_str(
        &scene("prim = \"/Head\"", "scene_cube.usda"),
        &scene_path,
    )
    .expect("a USD mesh under /Head loads");
    assert_eq!(s.meshes.len(), 1);
    assert_eq!(s.meshes[0].mesh.albedo, [0.5, 0.25, 0.125]);
    let e = crate::scene::Scene::from_toml_str(
        &scene("prim = \"/Hed\"", "scene_cube.usda"),
        &scene_path,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("scene_cube.usda") && e.contains("did you mean `/Head`"),
        "{e}"
    );
    let e = crate::scene::Scene::from_toml_str(
        &scene("prim = \"Head\"", "scene_cube.usda"),
        &scene_path,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("meshes[0].prim must be an absolute prim path"),
        "{e}"
    );
}
