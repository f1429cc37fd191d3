//! More strand segments than one acceleration structure of the adapter
//! holds (issue 48, bad input) is refused before any GPU work, with the
//! numbers and the fix: the check takes the adapter's capabilities as a
//! value, so it is tested here with a BLAS primitive limit made small enough
//! for the small scene (400 strands × 17 points: 6,799 boxes).

use plait::session::{SceneData, compile_checked, repo_root};
use plait::structure_limit::{HairSize, check, mesh_sizes};
use plait_gpu::Capabilities;
use plait_graph::{CompileOptions, Schedule};

fn caps(max_blas_primitives: u32) -> Capabilities {
    caps_with(max_blas_primitives, (1 << 24) - 1)
}

fn caps_with(max_blas_primitives: u32, max_tlas_instances: u32) -> Capabilities {
    Capabilities {
        timestamps: false,
        float32_blendable: true,
        early_depth_test: true,
        max_texture_dimension: 8192,
        max_storage_buffer_binding_size: 1 << 30,
        ray_query: true,
        max_blas_primitives,
        max_tlas_instances,
    }
}

fn schedule(sets: &[&str]) -> Schedule {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let opts = CompileOptions {
        screen: (64, 48),
        ..CompileOptions::default()
    };
    compile_checked(&repo_root().join("pipelines/occupancy.toml"), &sets, &opts)
        .expect("the pipeline checks")
}

fn small_hair() -> HairSize {
    let path = repo_root().join("examples/scenes/small.toml");
    let scene = SceneData::load(Some(&path)).expect("small scene");
    HairSize::of(&scene.strands)
}

#[test]
fn more_segments_than_the_blas_limit_are_refused_with_the_numbers_and_the_fix() {
    let hair = small_hair();
    assert_eq!((hair.strands, hair.points), (400, 6800));
    for point in ["self_shadow", "ambient_occlusion"] {
        let s = schedule(&[&format!("techniques.{point}=ray_traced")]);
        // One box per pair of consecutive points: 6,799. A limit of 6,799 holds them…
        check(&s, hair, &[], &caps(6799), "`small` (test)")
            .expect("6,799 boxes fit a limit of 6,799");
        // …one fewer does not.
        let err = check(&s, hair, &[], &caps(6798), "`small` (test)")
            .expect_err("6,799 boxes past a limit of 6,798")
            .to_string();
        for wanted in [
            &format!("technique {point}/ray_traced"),
            &format!("techniques/{point}/ray_traced/technique.toml:"),
            "400 strands, 6800 points, 6799 boxes",
            "more than the 6798 primitives one bottom-level structure holds on adapter `small` (test) (max_blas_primitive_count)",
            // 6,799 primitives / 17 points per strand: 399 strands fit.
            "draw fewer strands (at most 399 of this groom's 17.0 points each)",
            "[hair.procedural] strands or segments",
        ] {
            assert!(err.contains(wanted), "{point}: `{wanted}` not in: {err}");
        }
    }
}

/// As DOTS (`strand_primitive = "dots"`) each segment is four triangles:
/// the 6,799 segments are 27,196 primitives, checked at load with that
/// count, and the message names the swept spheres' one box per segment.
#[test]
fn dots_are_checked_at_four_triangles_per_segment() {
    let hair = small_hair();
    let s = schedule(&[
        "techniques.self_shadow=ray_traced",
        "params.strand_primitive=\"dots\"",
    ]);
    check(&s, hair, &[], &caps(27_196), "`small` (test)").expect("27,196 triangles fit");
    let err = check(&s, hair, &[], &caps(27_195), "`small` (test)")
        .expect_err("27,196 triangles past a limit of 27,195")
        .to_string();
    for wanted in [
        "6799 segments as DOTS, 27196 triangles",
        "more than the 27195 primitives",
        "primitive = \"swept_sphere\" (one box per segment: 6799 primitives, which fit)",
    ] {
        assert!(err.contains(wanted), "`{wanted}` not in: {err}");
    }
}

#[test]
fn a_pipeline_without_a_structure_is_not_limited() {
    let s = schedule(&[]);
    assert!(s.passes.iter().all(|p| p.type_name != "strand_structure"));
    check(&s, small_hair(), &[], &caps(1), "test").expect("no structure, no limit");
}

/// The small scene's meshes: the head ellipsoid (32 × 64 quads, one
/// triangle each in the two rings at the poles: 3,968 triangles) and the
/// ground (2).
fn small_meshes() -> Vec<(String, u64)> {
    let path = repo_root().join("examples/scenes/small.toml");
    let scene = SceneData::load(Some(&path)).expect("small scene");
    mesh_sizes(&scene.meshes)
}

/// The meshes are in the structure too, one bottom-level structure and one
/// top-level instance each: a mesh of more triangles than one bottom-level
/// structure holds, or more instances than the top-level one holds, is
/// refused naming the mesh, the numbers and the limit.
#[test]
fn meshes_past_the_structure_limits_are_refused_naming_the_mesh() {
    let meshes = small_meshes();
    assert_eq!(
        meshes,
        vec![("head".to_owned(), 3968), ("ground".to_owned(), 2)]
    );
    // Few strands, so their boxes fit every limit here.
    let hair = HairSize {
        strands: 10,
        points: 170,
    };
    for point in ["self_shadow", "ambient_occlusion"] {
        let s = schedule(&[&format!("techniques.{point}=ray_traced")]);
        check(&s, hair, &meshes, &caps_with(3968, 3), "t")
            .expect("the head, the ground and the strands fit");
        let err = check(&s, hair, &meshes, &caps_with(3967, 3), "t")
            .expect_err("3,968 triangles past a limit of 3,967")
            .to_string();
        for wanted in [
            &format!("techniques/{point}/ray_traced/technique.toml:"),
            "mesh `head` has 3968 triangles, more than the 3967 primitives",
            "simplify the mesh",
        ] {
            assert!(err.contains(wanted), "{point}: `{wanted}` not in: {err}");
        }
        let err = check(&s, hair, &meshes, &caps_with(3968, 2), "t")
            .expect_err("3 instances past a limit of 2")
            .to_string();
        assert!(
            err.contains("needs 3 instances (the strands and 2 meshes), more than the 2 one top-level structure of adapter t holds (max_tlas_instance_count)"),
            "{point}: {err}"
        );
    }
}
