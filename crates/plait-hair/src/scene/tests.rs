use std::path::{Path, PathBuf};

use glam::Vec3;

use super::*;
use crate::strands::Strands;

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes")
}

#[test]
fn default_toml_equals_builtin() {
    let s = Scene::load(examples().join("default.toml")).expect("default.toml loads");
    assert_eq!(s, Scene::builtin_default());
}

#[test]
fn all_example_scenes_load_and_validate() {
    // Every scene in the folder, so a new one is checked without being listed.
    let mut names: Vec<String> = std::fs::read_dir(examples())
        .expect("examples/scenes")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    for known in ["small.toml", "default.toml", "head_turn.toml", "dolly.toml"] {
        assert!(names.iter().any(|n| n == known), "{known} not found");
    }
    for name in names.iter().map(String::as_str) {
        let s = Scene::load(examples().join(name)).unwrap_or_else(|e| panic!("{e}"));
        // mesh_head.toml wears the USD groom make_assets writes.
        if name == "mesh_head.toml" {
            assert!(
                matches!(&s.hair.source, HairSource::File(f) if f.ends_with("groom.usda")),
                "{name}: groom.usda expected"
            );
            assert!(s.meshes.len() == 1 && s.meshes[0].mesh.head);
            continue;
        }
        let HairSource::Procedural(g) = &s.hair.source else {
            panic!("{name}: procedural expected")
        };
        match name {
            "small.toml" => assert!(g.strands <= 1000 && g.segments <= 16),
            "dense.toml" => assert!(g.strands >= 20_000),
            "stray.toml" | "stray_shake.toml" => assert!(g.stray_strands > 0),
            // A small groom whose camera dollies from 1× to 6× in a second.
            "dolly.toml" => {
                assert!(g.strands <= 1000);
                assert_eq!(s.camera_distance(0.0), 1.0);
                assert_eq!(s.camera_distance(1.0), 6.0);
            }
            _ => {}
        }
    }
    let small = Scene::load(examples().join("small.toml")).expect("small");
    let strands = small.strands().expect("generate");
    assert!(strands.strand_count() >= 100);
}

#[test]
fn builtin_default_frames_the_hair() {
    let s = Scene::builtin_default();
    let hair = s.strands().expect("procedural");
    assert!((9_000..=11_000).contains(&hair.strand_count()));
    assert_eq!(hair.segment_count(), hair.strand_count() * 32);
    let vp = s.camera.view_proj(16.0 / 9.0);
    let b = hair.bounds();
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for c in b.corners() {
        let p = vp.project_point3(c);
        lo = lo.min(p);
        hi = hi.max(p);
    }
    // the hair's bounds cover most of the view height and stay inside it
    assert!(
        hi.y - lo.y > 1.2,
        "hair spans {} of NDC height 2",
        hi.y - lo.y
    );
    assert!(
        lo.y > -1.2 && hi.y < 1.2 && lo.x > -1.2 && hi.x < 1.2,
        "{lo} {hi}"
    );
    assert!(lo.z > 0.0 && hi.z < 1.0);
    // light from above (travels downward)
    assert!(s.light.direction_to_light().y > 0.5);
    // the ground is below the hair
    let ground = s.ground.as_ref().expect("ground");
    assert!(ground.height < b.min.y);
    assert_eq!(s.opaque_meshes().len(), 2);
}

#[test]
fn the_head_turn_turns_the_head_and_comes_back() {
    let s = Scene::load(examples().join("head_turn.toml")).expect("head_turn.toml");
    assert_eq!(s.head_model(0.0), glam::Mat4::IDENTITY);
    assert!(s.head_model(2.0).abs_diff_eq(glam::Mat4::IDENTITY, 1e-6));
    // At 1 s the face (+Z) looks 45° towards +X.
    let forward = s.head_model(1.0).transform_vector3(Vec3::Z);
    let yaw = forward.x.atan2(forward.z).to_degrees();
    assert!((yaw - 45.0).abs() < 0.5, "yaw {yaw}");
    let still = Scene::load(examples().join("small.toml")).expect("small");
    assert_eq!(still.head_model(1.0), glam::Mat4::IDENTITY);
}

#[test]
fn bad_keyframes_are_reported_at_their_line_and_column() {
    let p = Path::new("s.toml");
    let keys = |second: &str| {
        format!(
            "[hair.procedural]\n{MINIMAL}[[animation.keys]]\ntime = 0.5\n[[animation.keys]]\n{second}\n"
        )
    };
    // MINIMAL is 7 lines; the second key's body is line 12.
    for (second, column, needle) in [
        ("time = 0.25", 8, "key times must increase"),
        ("time = nan", 8, "animation.keys[1].time must be finite"),
        (
            "time = 1.0\nrotate_degrees = [0, 30]",
            18,
            "expected an array of length 3",
        ),
        (
            "time = 1.0\ntranslate = [0, inf, 0]",
            13,
            "animation.keys[1].translate must be finite",
        ),
        ("time = 1.0\nspin = 3", 1, "unknown field `spin`"),
    ] {
        let e = Scene::from_toml_str(&keys(second), p)
            .unwrap_err()
            .to_string();
        let line = if second.contains('\n') { 13 } else { 12 };
        assert!(
            e.starts_with(&format!("s.toml:{line}:{column}: ")) && e.contains(needle),
            "{second}: {e}"
        );
    }
    let e = Scene::from_toml_str(
        &format!("[hair.procedural]\n{MINIMAL}[animation]\nkeys = []\n"),
        p,
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("s.toml:10:8: ") && e.contains("empty"), "{e}");
}

#[test]
fn parse_errors_have_line_and_column() {
    let p = Path::new("dir/scene.toml");
    let text = "[hair.procedural]\nstrands = 10\n\n[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\nfov_y_degrees = 40\nfov = 3\n";
    let e = Scene::from_toml_str(text, p).unwrap_err();
    let msg = e.to_string();
    assert!(msg.starts_with("dir/scene.toml:8:1:"), "{msg}");
    assert!(msg.contains("fov"), "{msg}");
    let e = Scene::from_toml_str("[hair.procedural]\nstyle = \"frizzy\"\n", p).unwrap_err();
    assert!(e.to_string().starts_with("dir/scene.toml:2:"), "{e}");
}

const MINIMAL: &str = "[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\nfov_y_degrees = 40\n[light]\ntype = \"directional\"\ndirection = [0, -1, 0]\n";

#[test]
fn relative_paths_resolve_against_scene_dir_and_missing_hair_is_named() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = format!(
        "hair = {{ file = \"models/x.hair\" }}\nbackground = {{ image = \"env.png\" }}\n{MINIMAL}"
    );
    let path = dir.path().join("s.toml");
    std::fs::write(&path, text).expect("write");
    let s = Scene::load(&path).expect("loads");
    assert_eq!(
        s.hair.source,
        HairSource::File(dir.path().join("models/x.hair"))
    );
    assert_eq!(s.background, Background::Image(dir.path().join("env.png")));
    let e = s.strands().unwrap_err();
    assert!(e.to_string().contains("x.hair"), "{e}");
    // and a real file loads
    std::fs::create_dir(dir.path().join("models")).expect("mkdir");
    let mut hs = Strands::new();
    hs.push_strand(&[Vec3::ZERO, Vec3::Y], |_| 0.1, |_| 1.0, Vec3::ONE);
    hs.to_hair_file()
        .expect("file")
        .write(dir.path().join("models/x.hair"))
        .expect("write");
    assert_eq!(s.strands().expect("reads").point_count(), 2);
}

#[test]
fn invalid_values_name_the_field() {
    let p = Path::new("s.toml");
    let e = Scene::from_toml_str(&format!("[hair.procedural]\nsegments = 0\n{MINIMAL}"), p)
        .unwrap_err();
    assert!(e.to_string().contains("hair.procedural.segments"), "{e}");
    let bad_light = MINIMAL.replace("directional", "spot");
    let e = Scene::from_toml_str(&format!("hair = {{ file = \"a.hair\" }}\n{bad_light}"), p)
        .unwrap_err();
    assert!(e.to_string().contains("position"), "{e}");
}

/// Every field may be left out: an empty scene is the default procedural
/// groom, fitted camera and light, no head, no ground (docs/formats.md).
#[test]
fn an_empty_scene_loads_with_the_documented_defaults() {
    let p = Path::new("empty.toml");
    for text in ["", "# nothing but a comment\n"] {
        let s = Scene::from_toml_str(text, p).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            s.hair.source,
            HairSource::Procedural(crate::groom::GroomSpec::default())
        );
        assert_eq!((s.head.as_ref(), s.ground.as_ref()), (None, None));
        assert_eq!(s.framing.camera, Some(CameraFit::default()));
        assert!(s.framing.light);
        assert_eq!(s.light.intensity, Light::FITTED_INTENSITY);
        assert_eq!(s.material, HairMaterial::default());
        assert_eq!(s.background, Background::Color([0.05, 0.06, 0.08]));
    }
    // A file groom alone, as docs/formats.md's "Grooms in a scene" starts.
    let s = Scene::from_toml_str("[hair]\nfile = \"g.tfx\"\n", p).expect("minimal");
    assert_eq!(s.hair.source, HairSource::File(PathBuf::from("g.tfx")));
    assert!(s.framing.camera.is_some() && s.framing.light);
}

/// A `[camera]` or `[light]` table that leaves out what would place it is
/// fitted; `light = "fit"` and `[light] type = "fit"` mean the same light.
#[test]
fn partial_camera_and_light_tables_are_fitted() {
    let p = Path::new("s.toml");
    let s = Scene::from_toml_str("[camera]\nfov_y_degrees = 50\n[light]\nintensity = 2\n", p)
        .expect("loads");
    assert_eq!(
        s.framing.camera.as_ref().map(|f| f.fov_y_degrees),
        Some(50.0)
    );
    assert!(s.framing.light);
    assert_eq!(s.light.intensity, 2.0);
    let short = Scene::from_toml_str("light = \"fit\"\n", p).expect("loads");
    let long = Scene::from_toml_str("[light]\ntype = \"fit\"\n", p).expect("loads");
    assert_eq!(short.light, long.light);
    // Half a fixed camera is an error naming what is missing.
    let e = Scene::from_toml_str("[camera]\neye = [0, 0, 5]\n", p).unwrap_err();
    assert!(e.to_string().contains("camera.target is missing"), "{e}");
    let e = Scene::from_toml_str("[camera]\nfit = false\n", p).unwrap_err();
    assert!(e.to_string().contains("camera.eye is missing"), "{e}");
    let e = Scene::from_toml_str("[camera]\nnear = 0.5\n", p).unwrap_err();
    assert!(e.to_string().contains("camera.near is computed"), "{e}");
}

/// Wrong names still fail at their line and column, with the nearest valid
/// name suggested, at the top level and inside tables.
#[test]
fn unknown_fields_name_their_place_and_the_nearest_field() {
    let p = Path::new("dir/s.toml");
    for (text, at, wrong, meant) in [
        (
            "ambient = 0.2\nambeint = 0.1\n",
            "2:1",
            "ambeint",
            "ambient",
        ),
        (
            "[hair]\nfile = \"g.tfx\"\nfollow_strand = 4\n",
            "3:1",
            "follow_strand",
            "follow_strands",
        ),
        (
            "[material]\nspecular_exponnet = 3\n",
            "2:1",
            "specular_exponnet",
            "specular_exponent",
        ),
        (
            "[camera]\nfov_y_degree = 40\n",
            "2:1",
            "fov_y_degree",
            "fov_y_degrees",
        ),
        ("[light]\nintensty = 2\n", "2:1", "intensty", "intensity"),
    ] {
        let e = Scene::from_toml_str(text, p).unwrap_err().to_string();
        assert!(e.starts_with(&format!("dir/s.toml:{at}: ")), "{text}: {e}");
        assert!(
            e.contains(&format!("unknown field `{wrong}`"))
                && e.contains(&format!("did you mean `{meant}`?")),
            "{text}: {e}"
        );
    }
    // Nothing close: no guess.
    let e = Scene::from_toml_str("zzzzzz = 1\n", p)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unknown field `zzzzzz`") && !e.contains("did you mean"),
        "{e}"
    );
}

/// A USD groom: `prim` and `segments_per_span` reach the reader; they are
/// refused for other files; out-of-range values name the field.
#[test]
fn a_usd_groom_reads_the_prim_the_scene_names() {
    let dir = tempfile::tempdir().expect("tempdir");
    let curves = |x: i32| {
        format!(
            "    def BasisCurves \"C\"\n    {{\n        uniform token type = \"cubic\"\n        uniform token basis = \"bspline\"\n        int[] curveVertexCounts = [5]\n        point3f[] points = [({x},0,0),({x},1,0),({x},2,0),({x},3,0),({x},4,0)]\n    }}\n"
        )
    };
    let usda = format!(
        "#usda 1.0\n(\n    metersPerUnit = 1\n)\ndef Xform \"A\"\n{{\n{}}}\ndef Xform \"B\"\n{{\n{}}}\n",
        curves(1),
        curves(2)
    );
    std::fs::write(dir.path().join("g.usda"), usda).expect("write");
    let path = dir.path().join("s.toml");
    std::fs::write(
        &path,
        "[hair]\nfile = \"g.usda\"\nprim = \"/B\"\nsegments_per_span = 3\n",
    )
    .expect("write");
    let s = Scene::load(&path).expect("loads");
    let strands = s.strands().expect("reads");
    // One curve of 2 B-spline spans at 3 segments each: 7 points, all at x = 2.
    assert_eq!(strands.point_count(), 7);
    assert!(
        strands.points.iter().all(|p| (p.x - 2.0).abs() < 1e-5),
        "{:?}",
        strands.points
    );
    std::fs::write(&path, "[hair]\nfile = \"g.usda\"\nprim = \"/Nope\"\n").expect("write");
    let e = Scene::load(&path).expect("loads").strands().unwrap_err();
    assert!(e.to_string().contains("g.usda: prim `/Nope`"), "{e}");

    let p = Path::new("s.toml");
    let e = Scene::from_toml_str("[hair]\nfile = \"g.hair\"\nprim = \"/A\"\n", p).unwrap_err();
    assert!(
        e.to_string()
            .contains("hair.prim and hair.segments_per_span apply to a USD file"),
        "{e}"
    );
    let e =
        Scene::from_toml_str("[hair]\nfile = \"g.usdz\"\nsegments_per_span = 0\n", p).unwrap_err();
    assert!(
        e.to_string()
            .contains("hair.segments_per_span must be in 1..=256"),
        "{e}"
    );
    let e = Scene::from_toml_str("[hair]\nfile = \"g.usdc\"\nprim = \"B\"\n", p).unwrap_err();
    assert!(
        e.to_string()
            .contains("hair.prim must be an absolute prim path"),
        "{e}"
    );
}

/// The mesh head example: the head is the mesh (named "head", so it moves
/// with the animation), its pivot the neck, the camera fitted to the groom
/// and the mesh together.
#[test]
fn a_mesh_head_is_opaque_geometry_that_moves_and_frames() {
    let mut s = Scene::load(examples().join("mesh_head.toml")).expect("mesh_head.toml loads");
    assert!(s.head.is_none());
    let head = s.head_mesh().expect("a head mesh");
    assert_eq!(head.mesh.name, "head");
    assert_eq!(head.sdf_resolution, 32);
    let meshes = s.opaque_meshes();
    assert_eq!(meshes.iter().filter(|m| m.head).count(), 1);
    let b = s.file_mesh_bounds();
    // The sculpted head: the ellipsoid's skull (top at 1.05), a nose in
    // front of it, a neck below.
    assert!((b.max.y - 1.05).abs() < 1e-3, "{b:?}");
    assert!(b.max.z > 1.1 && b.min.y < -1.5, "{b:?}");
    // Fitting: with a tiny groom far off to the side, the camera still sees the head.
    let far = Strands::new();
    let mut tiny = far.clone();
    tiny.push_strand(
        &[Vec3::new(5.0, 0.0, 0.0), Vec3::new(5.0, 0.1, 0.0)],
        |_| 0.01,
        |_| 1.0,
        Vec3::ONE,
    );
    s.frame(tiny.bounds());
    let c = &s.camera;
    let target = Vec3::from(c.target);
    assert!(
        target.x < 4.0,
        "the fit ignores the head mesh: target {target}"
    );
}

fn scene_with_meshes(text: &str) -> Result<Scene, SceneError> {
    Scene::from_toml_str(text, &examples().join("mesh_test.toml"))
}

#[test]
fn mesh_entries_are_checked_and_named() {
    let missing = scene_with_meshes("[[meshes]]\nfile = \"nothing.glb\"\nrole = \"head\"\n")
        .unwrap_err()
        .to_string();
    assert!(
        missing.contains("nothing.glb: cannot read file") && missing.contains("mesh_test.toml:2:8"),
        "{missing}"
    );
    let role = scene_with_meshes("[[meshes]]\nfile = \"head.glb\"\nrole = \"hed\"\n")
        .unwrap_err()
        .to_string();
    assert!(
        role.contains("mesh_test.toml:3:8") && role.contains("head"),
        "{role}"
    );
    let two = scene_with_meshes(
        "[[meshes]]\nfile = \"head.glb\"\nrole = \"head\"\n[[meshes]]\nfile = \"head.glb\"\nrole = \"head\"\n",
    )
    .unwrap_err()
    .to_string();
    assert!(two.contains("2 meshes have role = \"head\""), "{two}");
    let sdf = scene_with_meshes(
        "[[meshes]]\nfile = \"head.glb\"\nrole = \"static\"\nsdf_resolution = 16\n",
    )
    .unwrap_err()
    .to_string();
    assert!(
        sdf.contains("meshes[0].sdf_resolution applies to role = \"head\" only"),
        "{sdf}"
    );
    let res = scene_with_meshes(
        "[[meshes]]\nfile = \"head.glb\"\nrole = \"head\"\nsdf_resolution = 1000\n",
    )
    .unwrap_err()
    .to_string();
    assert!(
        res.contains("meshes[0].sdf_resolution must be in 4..=128"),
        "{res}"
    );
    let transform = scene_with_meshes(
        "[[meshes]]\nfile = \"head.glb\"\nrole = \"static\"\n[meshes.transform]\nscale = 0.0\n",
    )
    .unwrap_err()
    .to_string();
    assert!(
        transform.contains("meshes[0].transform is not invertible"),
        "{transform}"
    );
    // A static mesh, placed: moved by the transform, keeps its file's name.
    let placed = scene_with_meshes(
        "[[meshes]]\nfile = \"head.glb\"\nrole = \"static\"\n[meshes.transform]\ntranslate = [3.0, 0.0, 0.0]\n",
    )
    .expect("loads");
    assert!(placed.head_mesh().is_none());
    assert!((placed.file_mesh_bounds().min.x - 2.1).abs() < 1e-3);
    assert!(placed.opaque_meshes().iter().all(|m| !m.head));
    // No `albedo`: the file's material colour (head.glb's baseColorFactor).
    let file_mesh = placed.opaque_meshes();
    let file_mesh = file_mesh
        .iter()
        .find(|m| m.name == "head")
        .expect("the mesh");
    assert_eq!(file_mesh.albedo, [0.75, 0.55, 0.45]);
}

/// A head mesh must be closed (its collision field's sign counts
/// crossings); an open one is refused naming the file, a static one is fine.
#[test]
fn an_open_head_mesh_is_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut open = crate::mesh::Mesh::ellipsoid(Vec3::ZERO, Vec3::ONE, 8, 16);
    open.indices.truncate(open.indices.len() - 3 * 16);
    let file = dir.path().join("open.glb");
    std::fs::write(&file, crate::mesh_file::write::to_glb(&open)).expect("write");
    let text = |role: &str| {
        format!(
            "[[meshes]]\nfile = {:?}\nrole = {role:?}\n",
            file.display().to_string()
        )
    };
    let e = scene_with_meshes(&text("head")).unwrap_err().to_string();
    assert!(
        e.contains("open.glb: the head mesh is not closed: 16 edges") && e.contains("meshes[0]"),
        "{e}"
    );
    scene_with_meshes(&text("static")).expect("an open static mesh is fine");
}

/// Light, radiance and albedo out of the ranges of docs/formats.md ("Light
/// and units") are refused at the value's line and column: negative or
/// non-finite light intensity, colour, ambient; an albedo (head, ground,
/// hair material colour) below 0 or above 1; kd + ks above 1.
#[test]
fn light_and_albedo_out_of_range_are_refused_where_written() {
    let p = Path::new("s.toml");
    // The body is appended after MINIMAL (7 lines): its first line is 8.
    for (body, line, column, needle) in [
        ("intensity = -1.0", 8, 13, "light.intensity must be ≥ 0"),
        ("intensity = nan", 8, 13, "light.intensity must be finite"),
        ("intensity = inf", 8, 13, "light.intensity must be finite"),
        ("color = [1.0, -0.1, 1.0]", 8, 9, "light.color must be ≥ 0"),
        (
            "[material]\ncolor = [1.2, 0.5, 0.5]",
            9,
            9,
            "material.color must be in [0, 1]",
        ),
        (
            "[material]\ncolor = [-0.2, 0.5, 0.5]",
            9,
            9,
            "material.color must be in [0, 1]",
        ),
        (
            "[material]\ndiffuse = -0.5",
            9,
            11,
            "material.diffuse must be ≥ 0",
        ),
        (
            "[material]\ndiffuse = 0.8\nspecular = 0.3",
            9,
            11,
            "material.diffuse + material.specular must be ≤ 1",
        ),
        (
            "[head]\ncenter = [0, 0, 0]\nradii = [1, 1, 1]\nalbedo = [0.5, 1.5, 0.5]",
            11,
            10,
            "head.albedo must be in [0, 1]",
        ),
        (
            "[ground]\nheight = -2\nhalf_size = 3\nalbedo = [0.5, -0.5, 0.5]",
            11,
            10,
            "ground.albedo must be in [0, 1]",
        ),
        (
            "[ground]\nheight = -2\nhalf_size = 3\nalbedo = [0.5, nan, 0.5]",
            11,
            10,
            "ground.albedo must be finite",
        ),
    ] {
        let text = format!("[hair.procedural]\n{MINIMAL}{body}\n");
        // MINIMAL's [light] is open: a bare key belongs to it; the hair table
        // adds one line before it.
        let e = Scene::from_toml_str(&text, p).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("s.toml:{}:{column}: ", line + 1)) && e.contains(needle),
            "{body}: {e}"
        );
    }
    for (top, needle) in [
        ("ambient = -0.1", "ambient must be ≥ 0"),
        ("ambient = inf", "ambient must be finite"),
    ] {
        let text = format!("{top}\n[hair.procedural]\n{MINIMAL}");
        let e = Scene::from_toml_str(&text, p).unwrap_err().to_string();
        assert!(
            e.starts_with("s.toml:1:11: ") && e.contains(needle),
            "{top}: {e}"
        );
    }
}

/// A hair file's strand colours are albedos too: a channel above 1, below 0
/// or not finite is refused naming the scene's `file =` value (line and
/// column), the file, and the strand and point; a colour within [0, 1] loads.
#[test]
fn hair_file_colours_outside_the_albedo_range_are_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("s.toml");
    std::fs::write(&path, format!("hair = {{ file = \"x.hair\" }}\n{MINIMAL}")).expect("write");
    let s = Scene::load(&path).expect("loads");
    let write = |color: Vec3| {
        let mut hs = Strands::new();
        hs.push_strand(&[Vec3::ZERO, Vec3::Y], |_| 0.1, |_| 1.0, Vec3::splat(0.5));
        hs.push_strand(&[Vec3::X, Vec3::ONE], |_| 0.1, |_| 1.0, color);
        hs.to_hair_file()
            .expect("file")
            .write(dir.path().join("x.hair"))
            .expect("write");
    };
    for bad in [
        Vec3::new(0.5, 1.2, 0.5),
        Vec3::new(-0.1, 0.5, 0.5),
        Vec3::new(0.5, 0.5, f32::NAN),
    ] {
        write(bad);
        let e = s.strands().unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("{}:1:", path.display()))
                && e.contains("x.hair")
                && e.contains("strand 1, point 0")
                && e.contains("within [0, 1]"),
            "{bad}: {e}"
        );
    }
    write(Vec3::new(1.0, 0.0, 0.25));
    assert_eq!(s.strands().expect("an albedo in range").strand_count(), 2);
}
