//! Per-vertex ambient occlusion (issue 11, item 4): the precomputes'
//! per-vertex buffers read back and checked against what the papers say.
//!
//! - deep opacity maps from N directions (Xing et al. 2012 §4): visibility in
//!   [0, 1]; hair deep inside the volume more occluded than hair on its
//!   outside; the error against 100 directions falls as directions grow
//!   (9 > 25 > 64, the paper's Fig. 7 experiment);
//! - cylinders and scalp discs (Halén & Wester 2007 §3.3.1): visibility in
//!   [0, 1], inner hair darker, the scalp discs darken the roots, and a caster
//!   stride estimates the full sum.

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::vertex_ao::{correlation, inner_outer, mean_abs_diff, vertex_ao_report};
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (64, 48);

fn small_scene() -> SceneData {
    SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads")
}

const DIRECTIONS: &str = "deep_opacity_directions";
const CYLINDERS: &str = "cylinders";

/// Per-vertex ambient visibility by the `ambient_occlusion` technique
/// `technique` with `sets`, one value per hair vertex.
fn vertex_ao(gpu: &Gpu, scene: &SceneData, technique: &str, sets: &[String]) -> Vec<f32> {
    let (ao, report) = vertex_ao_report(gpu, scene, technique, sets, SIZE);
    plait::overflow::check_frame(&report).unwrap_or_else(|e| panic!("{technique} {sets:?}: {e}"));
    ao
}

fn directions(n: u32) -> Vec<String> {
    vec![format!("params.ao_directions={n}")]
}

/// Inner hair darker than outer hair by at least `margin`. With Xing et al.'s
/// whole-texel counts (`strand_coverage = false`) measured 0.753 / 0.851
/// (margin 0.05). With strands weighing by their share of a direction's
/// texel (issue 47, the default) the small groom's 0.01-wide strands block
/// less, and the two fifths read 0.902 / 0.948: the margin asserted there
/// is 0.03, re-measured, not the whole-texel 0.05 it no longer reaches.
#[test]
fn deep_opacity_directions_visibility_is_in_unit_range_and_deeper_hair_is_darker() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    for (coverage, margin, most) in [(false, 0.05, 0.9), (true, 0.03, 0.95)] {
        let mut sets = directions(25);
        sets.push(format!("params.strand_coverage={coverage}"));
        let ao = vertex_ao(&gpu, &scene, DIRECTIONS, &sets);
        assert_eq!(ao.len(), scene.strands.points.len());
        for (i, &a) in ao.iter().enumerate() {
            assert!(
                (0.0..=1.0).contains(&a),
                "vertex {i}: visibility {a} outside [0, 1]"
            );
        }
        let (inner, outer) = inner_outer(&scene, &ao);
        eprintln!(
            "deep opacity directions (25), coverage {coverage}: inner {inner:.3}, outer {outer:.3}"
        );
        assert!(
            outer > inner + margin,
            "coverage {coverage}: outer hair should see more of the sphere than inner hair by {margin}: outer {outer:.3}, inner {inner:.3}"
        );
        let min = ao.iter().copied().fold(f32::INFINITY, f32::min);
        assert!(
            min < most,
            "coverage {coverage}: some hair must be occluded (smallest visibility {min})"
        );
    }
}

#[test]
fn deep_opacity_directions_error_falls_as_directions_grow() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    let reference = vertex_ao(&gpu, &scene, DIRECTIONS, &directions(100));
    let errors: Vec<f64> = [9, 25, 64]
        .iter()
        .map(|&n| {
            let ao = vertex_ao(&gpu, &scene, DIRECTIONS, &directions(n));
            mean_abs_diff(&ao, &reference)
        })
        .collect();
    eprintln!(
        "mean |AO - AO_100|: 9 → {:.4}, 25 → {:.4}, 64 → {:.4}",
        errors[0], errors[1], errors[2]
    );
    assert!(
        errors[0] > errors[1] && errors[1] > errors[2],
        "the error against 100 directions should fall as directions grow: {errors:?}"
    );
    assert!(errors[2] > 0.0, "64 directions cannot equal 100 exactly");
}

fn assert_unit_range(ao: &[f32]) {
    for (i, &a) in ao.iter().enumerate() {
        assert!(
            (0.0..=1.0).contains(&a),
            "vertex {i}: visibility {a} outside [0, 1]"
        );
    }
}

/// Mean visibility of the strands' first and last vertices (roots, tips).
fn roots_tips(scene: &SceneData, ao: &[f32]) -> (f64, f64) {
    let offsets = &scene.strands.offsets;
    let strands = offsets.len() - 1;
    let roots = (0..strands)
        .map(|s| ao[offsets[s] as usize] as f64)
        .sum::<f64>();
    let tips = (0..strands)
        .map(|s| ao[offsets[s + 1] as usize - 1] as f64)
        .sum::<f64>();
    (roots / strands as f64, tips / strands as f64)
}

#[test]
fn cylinders_visibility_is_in_unit_range_deeper_hair_and_roots_darker() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    let ao = vertex_ao(&gpu, &scene, CYLINDERS, &[]);
    assert_unit_range(&ao);
    let (inner, outer) = inner_outer(&scene, &ao);
    let (roots, tips) = roots_tips(&scene, &ao);
    eprintln!("cylinders: inner {inner:.3}, outer {outer:.3}, roots {roots:.3}, tips {tips:.3}");
    assert!(
        outer > inner + 0.05,
        "outer hair should be less occluded than inner hair: outer {outer:.3}, inner {inner:.3}"
    );
    let no_scalp = vertex_ao(
        &gpu,
        &scene,
        CYLINDERS,
        &["params.ao_scalp_discs=false".into()],
    );
    assert_unit_range(&no_scalp);
    let (roots_without, _) = roots_tips(&scene, &no_scalp);
    // The thesis's own combination, 1 - S, is below exp(-S) everywhere.
    let sum = vertex_ao(&gpu, &scene, CYLINDERS, &["params.ao_combine=sum".into()]);
    assert_unit_range(&sum);
    let above = sum
        .iter()
        .zip(&ao)
        .filter(|(s, e)| **s > **e + 1e-6)
        .count();
    assert_eq!(above, 0, "1 - S exceeds exp(-S) at {above} vertices");
    eprintln!("cylinders without scalp discs: roots {roots_without:.3}");
    assert!(
        roots < roots_without - 0.05,
        "the scalp discs should darken the roots: {roots:.3} with, {roots_without:.3} without"
    );
}

#[test]
fn cylinders_caster_stride_estimates_the_full_sum() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    let full = vertex_ao(&gpu, &scene, CYLINDERS, &[]);
    let errors: Vec<f64> = [8, 2]
        .iter()
        .map(|k| {
            let strided = vertex_ao(
                &gpu,
                &scene,
                CYLINDERS,
                &[format!("params.ao_caster_stride={k}")],
            );
            mean_abs_diff(&strided, &full)
        })
        .collect();
    eprintln!(
        "cylinders, mean |AO_k - AO_1|: k = 8 → {:.4}, k = 2 → {:.4}",
        errors[0], errors[1]
    );
    assert!(
        errors[0] > errors[1],
        "a smaller stride should be closer: {errors:?}"
    );
    // Measured 0.029 on lavapipe (small scene); the bound leaves room for other adapters.
    assert!(
        errors[0] < 0.05,
        "stride 8 should stay within 0.05 of the full sum: {errors:?}"
    );
}

/// A groom with more vertices than the per-vertex buffer holds is an error
/// naming the param that sizes it, before any frame.
#[test]
fn too_small_a_vertex_buffer_names_its_param() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    let pipeline = repo_root().join("tests/fixtures/ambient_occlusion.toml");
    for technique in [DIRECTIONS, CYLINDERS] {
        let sets = [
            format!("techniques.ambient_occlusion={technique}"),
            "params.ao_max_vertices=100".into(),
        ];
        let message = match prepare(&gpu, &pipeline, &sets, &scene, SIZE) {
            Ok(_) => panic!("{technique}: 100 vertices cannot hold the small scene's hair"),
            Err(e) => e.to_string(),
        };
        assert!(
            message.contains("ao_max_vertices") && message.contains("6800"),
            "{technique}: the error should name the param and the vertex count: {message}"
        );
    }
}

/// Computed once per groom: later frames skip the precompute (reported as
/// cached) and the hair passes keep reading the same per-vertex values.
#[test]
fn occlusion_is_computed_once_and_kept_across_frames() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    for technique in [DIRECTIONS, CYLINDERS] {
        let sets = [
            format!("techniques.ambient_occlusion={technique}"),
            "params.ao_directions=9".into(),
        ];
        let sets = if technique == DIRECTIONS {
            &sets[..]
        } else {
            &sets[..1]
        };
        let prepared =
            prepare(&gpu, &pipeline, sets, &scene, SIZE).unwrap_or_else(|e| panic!("{e}"));
        let first = prepared.render_unchecked().expect("renders");
        let after_first = prepared.read_buffer("ao_vertex").expect("ao_vertex");
        let image_first = prepared.image().expect("image");
        let second = prepared.render_unchecked().expect("renders");
        let cached = |r: &plait_gpu::FrameReport| {
            r.passes
                .iter()
                .find(|p| p.name == "ambient_occlusion")
                .map(|p| p.cached)
                .expect("the precompute pass is scheduled")
        };
        assert!(
            !cached(&first) && cached(&second),
            "{technique}: runs on the first frame only"
        );
        assert_eq!(
            prepared.read_buffer("ao_vertex").expect("ao_vertex"),
            after_first,
            "{technique}: the per-vertex values are kept"
        );
        assert_eq!(
            prepared.image().expect("image"),
            image_first,
            "{technique}: same image"
        );
    }
}

/// The small scene with its head tessellated into `stacks × slices` and
/// listed `copies` times (no ground): the scalp discs' sum over more
/// triangles than one loop of lavapipe's may run.
fn scene_with_heads(copies: usize, stacks: u32, slices: u32) -> SceneData {
    let mut scene = small_scene();
    let head = scene
        .scene
        .head
        .as_ref()
        .expect("the small scene has a head");
    let mesh =
        plait_hair::mesh::Mesh::ellipsoid(head.center.into(), head.radii.into(), stacks, slices)
            .with_name("head")
            .as_head();
    scene.meshes = vec![mesh; copies];
    scene
}

/// The summed shadow S = -ln(visibility) (the default `combine = "exp"`).
fn shadow(ao: &[f32]) -> Vec<f64> {
    ao.iter().map(|&v| -(v as f64).ln()).collect()
}

/// The sum over casters is linear: with the head listed twice each vertex's
/// scalp shadow doubles, S₂ - S₁ = S₁ - S₀ (S₀ without scalp discs). Twice
/// ~39,600 triangles plus 6,800 hair casters is ~86,000 loop iterations, past
/// lavapipe's 65,535 per group of 8 invocations: one long loop stops after
/// ~58,700 triangles (the old shader), the chunked sum takes them all.
#[test]
fn cylinders_sum_every_caster_past_the_loop_budget() {
    let (_lock, gpu) = open_gpu();
    let once = scene_with_heads(1, 100, 200);
    let twice = scene_with_heads(2, 100, 200);
    let triangles: usize = twice.meshes.iter().map(|m| m.indices.len() / 3).sum();
    let casters = twice.strands.points.len();
    assert!(
        casters + triangles > 65_535 + 15_000,
        "the scene must be well past the budget: {casters} casters + {triangles} triangles"
    );
    let s0 = shadow(&vertex_ao(
        &gpu,
        &once,
        CYLINDERS,
        &["params.ao_scalp_discs=false".into()],
    ));
    let s1 = shadow(&vertex_ao(&gpu, &once, CYLINDERS, &[]));
    let s2 = shadow(&vertex_ao(&gpu, &twice, CYLINDERS, &[]));
    let scalp: Vec<f64> = s1.iter().zip(&s0).map(|(a, b)| a - b).collect();
    let most = scalp.iter().cloned().fold(0.0, f64::max);
    let mean = scalp.iter().sum::<f64>() / scalp.len() as f64;
    let (worst, at) = s2
        .iter()
        .zip(&s1)
        .zip(&scalp)
        .map(|((two, one), head)| (two - one - head).abs())
        .zip(0..)
        .fold((0.0, 0), |m, (e, i)| if e > m.0 { (e, i) } else { m });
    eprintln!(
        "cylinders past the budget: {casters} casters + {triangles} triangles; scalp shadow mean {mean:.4}, max {most:.4}; worst |S2 - S1 - (S1 - S0)| {worst:.2e} at vertex {at}"
    );
    // The head must matter, or the check below could not fail.
    assert!(
        most > 0.2 && mean > 0.01,
        "the scalp discs should shadow the roots: mean {mean}, max {most}"
    );
    assert!(
        worst < 1e-3 * most,
        "the second head's shadow differs from the first's by {worst} at vertex {at} (S0 {}, S1 {}, S2 {}): the sum was cut short",
        s0[at],
        s1[at],
        s2[at]
    );
}

/// A sum still cut short fails the frame: one dispatch of a million
/// iterations (`ao_chunk_iterations`) runs past lavapipe's budget, and the
/// shader counts the vertices it could not finish in `ao_status`, the
/// `incomplete` word of its overflow declaration. (The default chunks count
/// none on the same scene: `vertex_ao` checks every frame, and
/// `cylinders_sum_every_caster_past_the_loop_budget` renders it.)
#[test]
fn cylinders_count_the_vertices_a_cut_sum_left_unfinished() {
    let (_lock, gpu) = open_gpu();
    let scene = scene_with_heads(2, 100, 200);
    let incomplete = |sets: &[String]| {
        let (_, report) = vertex_ao_report(&gpu, &scene, CYLINDERS, sets, SIZE);
        let status = report
            .overflow
            .iter()
            .find(|o| o.counter == "ao_status")
            .unwrap_or_else(|| panic!("ao_status is read back: {:?}", report.overflow));
        (status.incomplete, plait::overflow::check_frame(&report))
    };
    let (count, check) = incomplete(&["params.ao_chunk_iterations=1000000".into()]);
    let adapter = &gpu.info.name;
    eprintln!("one chunk on {adapter}: {count} vertices unfinished");
    if gpu
        .loop_budget()
        .expect("the loop-budget probe runs")
        .is_some()
    {
        let n = scene.strands.points.len() as u64;
        assert!(
            count > n / 2,
            "most of the {n} vertices should be cut on lavapipe: {count}"
        );
        let e = check.expect_err("a cut frame fails").to_string();
        assert!(
            e.contains("shader invocations of pass `ambient_occlusion` could not finish"),
            "{e}"
        );
    } else {
        assert_eq!(count, 0, "no loop budget: every vertex finishes");
        check.expect("a complete frame passes");
    }
}

/// The chunks add the casters in the order one loop over them all would, so
/// their size changes nothing: 7 chunks of 1,000 casters give the bits one
/// chunk gives (scalp discs off: each chunk of triangles adds its own sum,
/// which rounds differently).
#[test]
fn cylinders_chunk_size_does_not_change_the_sum() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    let off = "params.ao_scalp_discs=false".to_string();
    let one = vertex_ao(&gpu, &scene, CYLINDERS, std::slice::from_ref(&off));
    let seven = vertex_ao(
        &gpu,
        &scene,
        CYLINDERS,
        &[off, "params.ao_chunk_iterations=1000".into()],
    );
    let differ = one.iter().zip(&seven).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "{differ} of {} vertices differ", one.len());
    assert!(one.iter().any(|&v| v < 0.9), "the hair occludes itself");
}

/// Measured on small (32³): mean |Δ| 0.153 against deep-opacity directions
/// (25), which count whole texels (0.753 / 0.851 inner / outer; 0.902 /
/// 0.948 with shares, docs/design.md) where the volume counts strand widths;
/// per-vertex correlation 0.598 with them and 0.643 with cylinders.
const DENSITY_AO_MAX_DIFF: f64 = 0.18;
const DENSITY_AO_MIN_CORRELATION: f64 = 0.5;

/// The density volume's occlusion (techniques/ambient_occlusion/density_volume,
/// issue 43): in [0, 1], inner hair darker than outer (measured 0.945 /
/// 0.963: strand widths, not whole texels, so a smaller margin than the other
/// techniques' 0.05), within the convention gap of deep-opacity directions
/// (25) — both average exp(−w · hair crossed) over sphere directions with
/// w = 0.15 — and darkening the vertices the other two darken.
#[test]
fn density_volume_occlusion_is_in_unit_range_deeper_hair_darker_and_near_directions() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    let ao = vertex_ao(&gpu, &scene, "density_volume", &[]);
    assert_unit_range(&ao);
    let (inner, outer) = inner_outer(&scene, &ao);
    let reference = vertex_ao(&gpu, &scene, DIRECTIONS, &directions(25));
    let diff = mean_abs_diff(&ao, &reference);
    let cylinders = vertex_ao(&gpu, &scene, CYLINDERS, &[]);
    let diff_cyl = mean_abs_diff(&ao, &cylinders);
    let mean = |a: &[f32]| a.iter().map(|&x| x as f64).sum::<f64>() / a.len() as f64;
    let (ri, ro) = inner_outer(&scene, &reference);
    let (ci, co) = inner_outer(&scene, &cylinders);
    eprintln!(
        "density volume: inner {inner:.3}, outer {outer:.3}, mean {:.3}; deep opacity directions (25) inner {ri:.3} outer {ro:.3} mean {:.3}, mean |Δ| {diff:.4}; cylinders inner {ci:.3} outer {co:.3} mean {:.3}, mean |Δ| {diff_cyl:.4}",
        mean(&ao),
        mean(&reference),
        mean(&cylinders)
    );
    assert!(
        outer > inner + 0.01,
        "outer hair should see more of the sphere than inner hair: outer {outer:.3}, inner {inner:.3}"
    );
    let (r_dod, r_cyl) = (correlation(&ao, &reference), correlation(&ao, &cylinders));
    eprintln!("correlation per vertex: deep opacity directions {r_dod:.3}, cylinders {r_cyl:.3}");
    assert!(
        diff < DENSITY_AO_MAX_DIFF,
        "mean |Δ| {diff:.4} against deep opacity directions"
    );
    assert!(
        r_dod > DENSITY_AO_MIN_CORRELATION && r_cyl > DENSITY_AO_MIN_CORRELATION,
        "the volume should darken the vertices the other techniques darken: r {r_dod:.3}, {r_cyl:.3}"
    );
}
