//! GPU tier: hair hidden behind opaque geometry never counts.
//!
//! A fragment shader with storage writes performs them even when the depth
//! test that runs after it rejects the fragment; the engine forces the test to
//! run first (`plait_gpu::depth_guard`). These tests check the guarantee for
//! every map every pipeline builds, from the light and from the camera, and on
//! both of the engine's paths (early depth test, and the in-shader test used
//! where the adapter lacks `SHADER_EARLY_DEPTH_TEST`).
//!
//! Positive controls: the same strands moved out from behind the head change
//! every map these tests compare, and compute_raster bins and draws them — so
//! a depth test that let hidden hair through would be caught.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use glam::Vec3;
use plait::session::{SceneData, compile_checked, gpu_options, prepare};
use plait_gpu::Gpu;
use plait_graph::{Access, ResourceDesc};
use plait_tests::{
    open_gpu, pipeline_files, rel, repo_root, small_scene_with_head, strands_subset,
};

const SIZE: (u32, u32) = (96, 72);

/// The small test scene's groom, fewer strands so every pipeline runs in seconds.
fn small_scene() -> SceneData {
    let path = repo_root().join("examples/scenes/small.toml");
    let mut data = SceneData::load(Some(&path)).expect("examples/scenes/small.toml loads");
    data.strands = strands_subset(&data.strands, |s| s % 4 == 0);
    data
}

/// The small scene with its head read from `examples/scenes/head.glb` (the
/// same ellipsoid as a mesh, `[[meshes]]` with role "head") instead of
/// `[head]`: the guarantee covers mesh occluders.
fn small_mesh_head_scene() -> SceneData {
    let head = repo_root().join("examples/scenes/head.glb");
    let scene = small_scene_with_head(&format!(
        "[[meshes]]\nfile = {:?}\nrole = \"head\"",
        head.display().to_string()
    ));
    assert!(scene.head.is_none() && scene.head_mesh().is_some());
    let mut data = SceneData::new(scene).expect("the mesh head scene loads");
    data.strands = strands_subset(&data.strands, |s| s % 4 == 0);
    data
}

/// Short strands well inside the head (an ellipsoid of radii ≥ 0.9 at the
/// origin): every fragment of them is behind the head's surface, from the
/// light and from the camera.
fn add_hidden_strands(strands: &mut plait_hair::Strands, count: usize) {
    add_strands(strands, count, Vec3::ZERO);
}

/// [`add_hidden_strands`]'s strands, moved by `offset`. They are as wide as
/// the groom's mean strand (the mean over its points, as `frame.hair_width`
/// takes it): the depth-only shadow maps take the whole groom's mean width
/// (issue 47), so strands of another width would change every strand's
/// shadow by design, hidden or not. What this file checks is that hidden
/// hair is never drawn into a map.
fn add_strands(strands: &mut plait_hair::Strands, count: usize, offset: Vec3) {
    // (0.01 into an empty groom: these strands are then the whole groom.)
    let mean = if strands.thickness.is_empty() {
        0.01
    } else {
        (strands.thickness.iter().map(|&t| t as f64).sum::<f64>() / strands.thickness.len() as f64)
            as f32
    };
    for i in 0..count {
        let a = i as f32 * 2.399_963; // golden angle: spread without randomness
        let r = 0.15 + 0.3 * ((i * 7 % count) as f32 / count as f32);
        let start = offset
            + Vec3::new(
                r * a.cos(),
                0.4 * (i as f32 / count as f32) - 0.2,
                r * a.sin(),
            );
        let points: Vec<Vec3> = (0..8)
            .map(|k| start + Vec3::new(0.03 * k as f32, -0.04 * k as f32, 0.02 * k as f32))
            .collect();
        strands.push_strand(&points, |_| mean, |_| 0.8, Vec3::new(0.9, 0.2, 0.1));
    }
}

/// Every resource a hair-drawing raster pass writes (the light and camera maps
/// of every technique), as `--set pipeline.outputs=[…]` so none of them
/// shares memory with a later resource and each can be read after the frame.
fn hair_maps(gpu: &Gpu, pipeline: &Path) -> (Vec<(String, bool)>, String) {
    let schedule = compile_checked(pipeline, &[], &gpu_options(gpu, SIZE))
        .unwrap_or_else(|e| panic!("{}: {e}", rel(pipeline)));
    let mut maps: Vec<(String, bool)> = Vec::new();
    for pass in schedule
        .passes
        .iter()
        .filter(|p| p.draw == Some(plait_graph::Draw::Hair))
    {
        for w in &pass.writes {
            if !matches!(w.access, Access::StorageWrite | Access::ColorTarget) {
                continue;
            }
            let desc = &schedule.resources[w.id()].desc;
            let readable = match desc {
                ResourceDesc::Buffer { .. } => true,
                ResourceDesc::Texture { samples, .. } => *samples == 1,
                ResourceDesc::AccelerationStructure => false,
            };
            // Fragment lists hold node indices in the order the GPU's threads
            // allocated them, which adding geometry may change; their fragment
            // count (`list_counter`) and the resolved image are compared instead.
            let pointers = matches!(w.slot.as_str(), "list_heads" | "list_nodes");
            if readable && !pointers && !maps.iter().any(|(n, _)| n == &w.resource_name) {
                maps.push((
                    w.resource_name.clone(),
                    matches!(desc, ResourceDesc::Buffer { .. }),
                ));
            }
        }
    }
    let mut outputs: Vec<String> = schedule
        .outputs
        .iter()
        .map(|&id| schedule.resources[id].name.clone())
        .collect();
    // The final image is compared too.
    for name in &outputs {
        if !maps.iter().any(|(n, _)| n == name) {
            maps.push((name.clone(), false));
        }
    }
    outputs.extend(maps.iter().map(|(n, _)| n.clone()));
    outputs.dedup();
    let set = format!(
        "pipeline.outputs=[{}]",
        outputs
            .iter()
            .map(|n| format!("{n:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    (maps, set)
}

/// Each map's contents after one frame, in an order-independent form: the
/// sorted 32-bit words (fragment lists fill in whatever order the GPU runs
/// fragments; counts, bits and depths must still agree exactly).
fn render_maps(gpu: &Gpu, pipeline: &Path, scene: &SceneData) -> Vec<(String, Vec<u32>)> {
    let (maps, set) = hair_maps(gpu, pipeline);
    // With the defaults (strand coverage on): occupancy-order blending's mean
    // alpha is measured per pixel from the visible fragments (alpha_sum), so
    // hidden hair cannot change it.
    let prepared = prepare(gpu, pipeline, &[set], scene, SIZE)
        .unwrap_or_else(|e| panic!("preparing {}: {e}", rel(pipeline)));
    prepared
        .render_unchecked()
        .unwrap_or_else(|e| panic!("rendering {}: {e}", rel(pipeline)));
    maps.into_iter()
        .map(|(name, is_buffer)| {
            let bytes = if is_buffer {
                prepared.read_buffer(&name)
            } else {
                prepared.read_resource(&name).map(|t| t.bytes)
            }
            .unwrap_or_else(|e| panic!("{}: reading {name}: {e}", rel(pipeline)));
            let mut words: Vec<u32> = bytes
                .chunks_exact(4)
                .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                .collect();
            words.sort_unstable();
            (name, words)
        })
        .collect()
}

/// The fewest pipelines (greedily, in file order) that together run every
/// hair-drawing pass any pipeline has (its technique, type and shader). The paths that do not
/// depend on the technique — the in-shader depth test, a mesh occluder in the
/// opaque passes — are checked on these: every hair pass is still exercised
/// on them once, at a fraction of the cost of every pipeline twice.
fn pipelines_covering_every_hair_pass(gpu: &Gpu) -> Vec<PathBuf> {
    let mut seen: BTreeSet<String> = BTreeSet::new();
    let mut chosen = Vec::new();
    for pipeline in pipeline_files() {
        let schedule = compile_checked(&pipeline, &[], &gpu_options(gpu, SIZE))
            .unwrap_or_else(|e| panic!("{}: {e}", rel(&pipeline)));
        let mut new = false;
        for pass in schedule
            .passes
            .iter()
            .filter(|p| p.draw == Some(plait_graph::Draw::Hair))
        {
            // A pass is its type and shader, in the technique that declares it.
            let key = format!("{:?}/{}/{:?}", pass.technique, pass.type_name, pass.shader);
            new |= seen.insert(key);
        }
        if new {
            chosen.push(pipeline);
        }
    }
    chosen
}

fn assert_same_maps(
    gpu: &Gpu,
    pipelines: &[PathBuf],
    visible: &SceneData,
    with_hidden: &SceneData,
    path_name: &str,
) {
    let mut failures = Vec::new();
    let mut checked = 0;
    for pipeline in pipelines {
        let pipeline = pipeline.as_path();
        let a = render_maps(gpu, pipeline, visible);
        let b = render_maps(gpu, pipeline, with_hidden);
        for ((name, wa), (_, wb)) in a.iter().zip(&b) {
            checked += 1;
            if wa != wb {
                let differing = wa.iter().zip(wb).filter(|(x, y)| x != y).count();
                failures.push(format!(
                    "{}: `{name}` differs once hidden hair is added ({differing} of {} words)",
                    rel(pipeline),
                    wa.len()
                ));
            }
        }
    }
    assert!(
        checked > 2 * pipelines.len(),
        "only {checked} maps were compared"
    );
    assert!(
        failures.is_empty(),
        "hidden hair changed maps ({path_name}):\n{}",
        failures.join("\n")
    );
}

/// Half the hair hidden inside the head gives exactly the maps of the scene
/// with that half removed — for every resource every hair pass of every
/// pipeline writes.
#[test]
fn hidden_hair_leaves_every_map_as_if_it_were_absent() {
    let (_lock, gpu) = open_gpu();
    assert!(
        gpu.capabilities.early_depth_test,
        "lavapipe has SHADER_EARLY_DEPTH_TEST; this test checks the early-test path"
    );
    let visible = small_scene();
    let mut hidden = small_scene();
    add_hidden_strands(&mut hidden.strands, visible.strands.strand_count());
    // The light frustum is fitted to the hair's bounds: the hidden strands lie
    // inside the visible groom's box, so both scenes frame the same maps.
    assert_eq!(visible.strands.bounds(), hidden.strands.bounds());
    assert_same_maps(
        &gpu,
        &pipeline_files(),
        &visible,
        &hidden,
        "early depth test",
    );
}

/// The hidden strands moved out of the head: below it, inside the hanging
/// groom's box (so the light and camera frame the same maps), where the head
/// hides them neither from the light nor from the camera.
const BELOW_THE_HEAD: Vec3 = Vec3::new(0.0, -1.5, 0.0);

/// Maps that no hair changes at this size, by design: (pipeline, map).
/// The exact reference's overflow counter stays 0 while its lists hold
/// every fragment; depth peeling's layer target holds its last layer, which
/// is empty when the occlusion query stops peeling.
const UNCHANGED_BY_DESIGN: [(&str, &str); 2] = [
    ("depth_peeling", "peel_layer"),
    ("exact_shadow", "light_overflow"),
];

/// Positive control for the tests above: the same strands, placed where the
/// head does not hide them, change every map those tests compare, on every
/// hair pass any pipeline has — so each map would catch them if the depth
/// test let hidden hair through.
#[test]
fn the_hidden_strands_register_when_nothing_hides_them() {
    let (_lock, gpu) = open_gpu();
    let visible = small_scene();
    let mut shown = small_scene();
    add_strands(
        &mut shown.strands,
        visible.strands.strand_count(),
        BELOW_THE_HEAD,
    );
    assert_eq!(visible.strands.bounds(), shown.strands.bounds());
    let mut unchanged = Vec::new();
    let mut compared = 0;
    for pipeline in pipelines_covering_every_hair_pass(&gpu) {
        let a = render_maps(&gpu, &pipeline, &visible);
        let b = render_maps(&gpu, &pipeline, &shown);
        for ((name, wa), (_, wb)) in a.iter().zip(&b) {
            compared += 1;
            let differing = wa.iter().zip(wb).filter(|(x, y)| x != y).count();
            println!(
                "{}: `{name}`: {differing} of {} words change",
                rel(&pipeline),
                wa.len()
            );
            if wa == wb {
                unchanged.push(format!("{}: `{name}`", rel(&pipeline)));
            }
        }
    }
    assert!(compared > 0, "no maps were compared");
    // Either list out of date fails: a map that stopped registering hair, or
    // an exception that now does.
    let expected: Vec<String> = UNCHANGED_BY_DESIGN
        .iter()
        .map(|(pipeline, map)| format!("pipelines/{pipeline}.toml: `{map}`"))
        .collect();
    assert_eq!(
        unchanged, expected,
        "maps the visible strands leave unchanged (they cannot catch hidden hair)"
    );
}

/// Hair that lies entirely behind the head leaves every storage map at zero.
#[test]
fn hair_entirely_behind_the_head_writes_no_map() {
    let (_lock, gpu) = open_gpu();
    let mut scene = small_scene();
    scene.strands = plait_hair::Strands::new();
    add_hidden_strands(&mut scene.strands, 200);
    let mut failures = Vec::new();
    let mut checked = 0;
    for pipeline in pipeline_files() {
        let (maps, _) = hair_maps(&gpu, &pipeline);
        // Only storage buffers are checked here: a pipeline whose hair passes
        // write none has nothing to count (its images are compared above).
        if !maps.iter().any(|(_, is_buffer)| *is_buffer) {
            continue;
        }
        checked += 1;
        for (name, words) in render_maps(&gpu, &pipeline, &scene) {
            let is_buffer = maps.iter().any(|(n, b)| n == &name && *b);
            if is_buffer && words.iter().any(|&w| w != 0) {
                failures.push(format!(
                    "{}: `{name}` has {} non-zero words",
                    rel(&pipeline),
                    words.iter().filter(|&&w| w != 0).count()
                ));
            }
        }
    }
    assert!(checked >= 3, "only {checked} pipelines write storage maps");
    assert!(
        failures.is_empty(),
        "hidden hair was counted:\n{}",
        failures.join("\n")
    );
}

/// The same guarantee where the adapter has no early depth test: the engine
/// tests depth in the shader instead (`PLAIT_DISABLE_FEATURES` pretends the
/// feature is missing).
#[test]
fn in_shader_depth_test_gives_the_same_guarantee() {
    let (_lock, _) = open_gpu();
    let gpu = Gpu::new_without_features(&["SHADER_EARLY_DEPTH_TEST"]).expect("GPU");
    assert!(!gpu.capabilities.early_depth_test);
    let visible = small_scene();
    let mut hidden = small_scene();
    add_hidden_strands(&mut hidden.strands, visible.strands.strand_count());
    let pipelines = pipelines_covering_every_hair_pass(&gpu);
    assert_same_maps(&gpu, &pipelines, &visible, &hidden, "in-shader depth test");
}

/// Hair entirely inside a head read from a glTF file leaves every storage
/// map at zero and every image as without it: the depth guarantee covers
/// mesh occluders (they are drawn by the same opaque passes), for every hair
/// pass any pipeline has.
#[test]
fn hair_hidden_in_a_mesh_head_is_not_counted() {
    let (_lock, gpu) = open_gpu();
    let visible = small_mesh_head_scene();
    let mut hidden = small_mesh_head_scene();
    add_hidden_strands(&mut hidden.strands, visible.strands.strand_count());
    assert_eq!(visible.strands.bounds(), hidden.strands.bounds());
    let pipelines = pipelines_covering_every_hair_pass(&gpu);
    assert_same_maps(&gpu, &pipelines, &visible, &hidden, "mesh head");
}

/// compute_raster bins segments in compute, not in a hair draw, so the maps
/// above see only its image: hair entirely behind the head must not be
/// binned into any tile either (tile_depth's conservative cull), so it takes
/// no tile capacity and is never counted as overflow — and is not drawn.
/// The same for the quads of wisps (narrow ones, inside the head too).
/// Positive control: the same strands below the head are binned and drawn.
#[test]
fn compute_raster_bins_no_hidden_hair() {
    let (_lock, gpu) = open_gpu();
    let pipeline = repo_root().join("pipelines/compute_raster.toml");
    let mut scene = small_scene();
    scene.strands = plait_hair::Strands::new();
    add_hidden_strands(&mut scene.strands, 200);
    scene.guides = plait_hair::guides::Guides::default();
    let mut shown = scene.clone();
    shown.strands = plait_hair::Strands::new();
    add_strands(&mut shown.strands, 200, BELOW_THE_HEAD);
    let wisps = [
        "techniques.geometry=wisps",
        "params.wisp_width=0.02",
        "params.wisp_count=50",
        "params.wisp_texture_size=32",
    ];
    for (label, extra) in [("strands", &[][..]), ("wisps", &wisps[..])] {
        let mut sets = vec![
            "pipeline.outputs=[\"final\", \"tile_ranges\", \"raster_counter\", \"hair\"]"
                .to_string(),
        ];
        sets.extend(extra.iter().map(|s| s.to_string()));
        let render = |scene: &SceneData| {
            let prepared = prepare(&gpu, &pipeline, &sets, scene, SIZE)
                .unwrap_or_else(|e| panic!("preparing compute_raster ({label}): {e}"));
            prepared.render_unchecked().expect("renders");
            // Every word: each tile's count and first slot; what was dropped
            // or needed and tile_blend's unfinished invocations.
            let words = |name: &str| {
                let bytes = prepared.read_buffer(name).expect(name);
                bytes.chunks_exact(4).filter(|w| w != &[0; 4]).count()
            };
            let hair = prepared.read_resource("hair").expect("hair").bytes;
            let drawn = hair.iter().filter(|&&b| b != 0).count();
            (words("tile_ranges"), words("raster_counter"), drawn)
        };
        let (tiles, counter, drawn) = render(&scene);
        assert_eq!(tiles, 0, "{label}: `tile_ranges`: hidden hair was binned");
        assert_eq!(
            counter, 0,
            "{label}: `raster_counter`: hidden hair was binned"
        );
        assert_eq!(drawn, 0, "{label}: hidden hair was drawn");
        let (tiles, counter, drawn) = render(&shown);
        println!(
            "{label} below the head: {tiles} tile_ranges words, {counter} raster_counter words, \
             {drawn} hair bytes non-zero"
        );
        assert!(
            tiles > 0 && drawn > 0,
            "{label}: the strands below the head were not binned ({tiles}) or drawn ({drawn})"
        );
    }
}
