use super::*;
use crate::Metrics;

fn stats(v: f64) -> Stats {
    Stats::of(&[v, v + 1.0]).unwrap()
}

fn sample() -> Report {
    let variant = |id: &str, reference: bool, sweep: Option<&str>| Variant {
        id: id.into(),
        label: id.into(),
        pipeline: "pipelines/forward.toml".into(),
        is_reference: reference,
        sweep_value: sweep.map(str::to_string),
        sets: vec![],
        schedule_name: "forward".into(),
        memory: Memory {
            peak_bytes: 1 << 20,
            unpooled_bytes: 2 << 20,
            allocations: 2,
            resources: vec![],
        },
        graph_svg: None,
    };
    let run = |id: &str, flip: f64| Run {
        variant: id.into(),
        image: format!("{id}.png"),
        diff_image: "d.png".into(),
        diff_scale: 1.0,
        flip_image: "f.png".into(),
        timing: Timing {
            total_gpu_ms: Some(stats(2.0)),
            wall_ms: stats(3.0),
            passes: vec![PassStats {
                name: "p".into(),
                type_name: "t".into(),
                gpu_ms: None,
            }],
        },
        metrics: Metrics {
            flip_mean: flip,
            ..Metrics::default()
        },
        visibility: None,
    };
    Report {
        schema: SCHEMA.into(),
        provenance: Provenance {
            plait_version: "0.1.0".into(),
            adapter: Adapter {
                name: "lavapipe".into(),
                backend: "vulkan".into(),
                driver: String::new(),
                driver_info: String::new(),
            },
            timestamps: true,
            command: vec!["plait".into()],
            command_line: "plait ab <x>".into(),
            working_directory: ".".into(),
            size: [4, 4],
            repeats: 2,
            warmup_frames: 1,
            order: "interleaved".into(),
            sets: vec![],
            reference: "pipelines/forward.toml".into(),
            metrics: String::new(),
            pipelines: vec![],
            builtin_shaders: vec![],
            scenes: vec![],
            unix_time: 0,
        },
        sweep: Some(Sweep {
            key: "params.x".into(),
            values: vec!["1".into(), "2".into()],
        }),
        variants: vec![
            variant("reference", true, None),
            variant("a@1", false, Some("1")),
            variant("a@2", false, Some("2")),
        ],
        scenes: vec![SceneResult {
            name: "s".into(),
            path: None,
            reference_image: "r.png".into(),
            runs: vec![run("reference", 0.0), run("a@1", 0.2), run("a@2", 0.1)],
        }],
    }
}

#[test]
fn html_is_self_contained_and_escaped() {
    let r = sample();
    let page = html(
        &r,
        &[("a@1".into(), "<?xml version=\"1.0\"?><svg></svg>".into())],
    );
    assert!(page.contains("plait ab &lt;x&gt;"));
    assert!(!page.contains("<?xml"));
    assert!(!page.contains("<script src") && !page.contains("<link"));
    assert!(page.contains("a@1.png") && page.contains("r.png"));
    assert!(page.contains("Not computed"));
}

fn visibility(provider: &str) -> Visibility {
    Visibility {
        provider: provider.into(),
        reference_provider: "exact".into(),
        rays_through_hair: 3,
        curves: vec![VisibilityCurve {
            light_uv: [0.5, 0.5],
            depth: vec![0.1, 0.2],
            exact: vec![1.0, 0.5],
            approx: vec![1.0, 0.6],
        }],
        mean_abs_error: 0.05,
        max_abs_error: 0.1,
    }
}

/// The reference's provider plotted against itself is noise: the report
/// says "the reference itself" instead; a real variant gets its curves.
#[test]
fn the_reference_gets_no_visibility_curves() {
    let mut r = sample();
    r.variants[1].pipeline = "pipelines/occupancy.toml".into();
    r.scenes[0].runs[0].visibility = Some(visibility("exact"));
    r.scenes[0].runs[1].visibility = Some(visibility("occupancy"));
    let page = html(&r, &[]);
    assert!(
        page.contains("reference (exact): the reference itself — no curves to compare"),
        "{page}"
    );
    assert!(page.contains("a@1: light uv"), "the variant's curve");
    assert!(
        !page.contains("reference: light uv"),
        "the reference's curve"
    );
    // The same pipeline as the reference (a@2 renders forward.toml too).
    r.scenes[0].runs[2].visibility = Some(visibility("exact"));
    r.variants[2].sets = r.variants[0].sets.clone();
    let page = html(&r, &[]);
    assert!(page.contains("a@2 (exact): the reference itself"), "{page}");
}

#[test]
fn provenance_lists_each_file_once() {
    let mut r = sample();
    let file = |path: &str| FileHash {
        path: path.into(),
        sha256: format!("sha-of-{path}"),
        bytes: 1,
    };
    let pipeline = |path: &str, extra: &str| PipelineProvenance {
        path: path.into(),
        files: vec![file(path), file("pipelines/occupancy.toml")],
        shaders: vec![file(extra)],
    };
    r.provenance.pipelines = vec![
        pipeline("pipelines/deep_opacity.toml", "shaders/compose_over.wgsl"),
        pipeline("pipelines/exact_shadow.toml", "shaders/compose_over.wgsl"),
    ];
    let page = html(&r, &[]);
    assert_eq!(
        page.matches("<code>pipelines/occupancy.toml ").count(),
        1,
        "{page}"
    );
    assert_eq!(page.matches("<code>shaders/compose_over.wgsl ").count(), 1);
    assert!(page.contains("file of pipelines/deep_opacity.toml, pipelines/exact_shadow.toml"));
}

#[test]
fn sweep_gives_extra_charts_and_json_has_nulls() {
    let r = sample();
    let charts = scene_charts(&r, &r.scenes[0]);
    assert_eq!(charts.len(), 4);
    let json = serde_json::to_value(&r).unwrap();
    assert!(json["scenes"][0]["runs"][0]["visibility"].is_null());
    assert_eq!(json["variants"].as_array().unwrap().len(), 3);
}
