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
        sweep_values: sweep
            .map(|x| IndexMap::from([("params.x".to_string(), x.to_string())]))
            .unwrap_or_default(),
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
        linear_image: None,
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
        overflow: vec![],
        temporal: None,
        shard: None,
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
            reference_repeats: None,
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
        sweeps: vec![Sweep {
            key: "params.x".into(),
            values: vec!["1".into(), "2".into()],
        }],
        camera_distances: vec![],
        variants: vec![
            variant("reference", true, None),
            variant("a@1", false, Some("1")),
            variant("a@2", false, Some("2")),
        ],
        scenes: vec![SceneResult {
            name: "s".into(),
            path: None,
            distance: None,
            hair_color: None,
            reference_image: "r.png".into(),
            reference_linear_image: None,
            runs: vec![run("reference", 0.0), run("a@1", 0.2), run("a@2", 0.1)],
        }],
        shards: vec![],
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

/// The sample with a second sweep: `a` at x ∈ {1, 2} × y ∈ {p, q, r}, one
/// combination (2, r) missing; ꟻLIP = x/4 + (index of y)/8, exact in binary.
fn grid_sample() -> Report {
    let mut r = sample();
    r.sweeps.push(Sweep {
        key: "techniques.y".into(),
        values: vec!["p".into(), "q".into(), "r".into()],
    });
    let template_variant = r.variants[1].clone();
    let template_run = r.scenes[0].runs[1].clone();
    r.variants.truncate(1);
    r.scenes[0].runs.truncate(1);
    for x in ["1", "2"] {
        for (i, y) in ["p", "q", "r"].into_iter().enumerate() {
            if (x, y) == ("2", "r") {
                continue;
            }
            let id = format!("a@{x}@{y}");
            let mut v = template_variant.clone();
            v.id = id.clone();
            v.label = id.clone();
            v.sweep_values = IndexMap::from([
                ("params.x".to_string(), x.to_string()),
                ("techniques.y".to_string(), y.to_string()),
            ]);
            r.variants.push(v);
            let mut run = template_run.clone();
            run.variant = id;
            run.metrics.flip_mean = x.parse::<f64>().unwrap() / 4.0 + i as f64 / 8.0;
            r.scenes[0].runs.push(run);
        }
    }
    r
}

#[test]
fn two_sweeps_make_a_grid_in_tables_charts_and_json() {
    let r = grid_sample();
    // Cells: rows = the first sweep's values, columns = the second's.
    let cells = charts::grid_cells(&r, &r.scenes[0], "pipelines/forward.toml", &|run| {
        Some(run.metrics.flip_mean)
    });
    assert_eq!(
        cells,
        vec![
            vec![Some(0.25), Some(0.375), Some(0.5)],
            vec![Some(0.5), Some(0.625), None],
        ]
    );
    let page = html(&r, &[]);
    assert!(
        page.contains("pipelines/forward.toml: params.x (rows) × techniques.y (columns)"),
        "{page}"
    );
    assert!(
        page.contains("<th class=l>params.x \\ techniques.y</th><th>p</th><th>q</th><th>r</th>")
    );
    assert!(page.contains("<tr><th class=l>2</th><td>0.50000</td><td>0.62500</td><td>–</td></tr>"));
    assert!(
        page.contains("<td class=l>1, q</td>"),
        "the summary's sweep column"
    );
    assert_eq!(page.matches("<th class=l>--sweep</th>").count(), 2);
    // error vs cost, three lines against params.x (one per value of y), and
    // the two grids (error, cost) of the one pipeline.
    let charts = scene_charts(&r, &r.scenes[0]);
    assert_eq!(charts.len(), 1 + 3 + 2);
    assert!(charts[1].contains(">forward, q</text>"), "{}", charts[1]);
    assert!(charts[1].contains("one line per pipeline and techniques.y"));
    assert!(charts[0].contains("labels: params.x, techniques.y"));
    assert!(
        !charts[1].contains("font-size=\"9\""),
        "no point labels on a grid's lines: the legend names them"
    );
    assert!(charts[4].contains("params.x = 1, techniques.y = q: 0.3750"));
    // Points of a grid are not joined across it on the error-vs-cost chart.
    assert!(!charts[0].contains("<polyline"));
    assert!(charts[1].contains("<polyline"));
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["schema"], "plait-ab/2");
    assert_eq!(json["sweeps"][1]["key"], "techniques.y");
    let v = &json["variants"][2];
    assert_eq!(v["sweep_values"]["params.x"], "1");
    assert_eq!(v["sweep_values"]["techniques.y"], "q");
    assert_eq!(
        v["sweep_values"]
            .as_object()
            .unwrap()
            .keys()
            .collect::<Vec<_>>(),
        ["params.x", "techniques.y"],
        "keys in the order of the sweeps"
    );
    assert!(
        json["variants"][0]["sweep_values"]
            .as_object()
            .unwrap()
            .is_empty()
    );
}

#[test]
fn one_sweep_keeps_its_charts_and_no_grid() {
    let r = sample();
    let page = html(&r, &[]);
    assert!(!page.contains("(rows) ×"));
    let charts = scene_charts(&r, &r.scenes[0]);
    assert!(charts[1].contains("s: ꟻLIP mean vs params.x"));
    assert!(charts[1].contains("<polyline"), "the sweep's points joined");
    assert!(
        charts[0].contains("<polyline"),
        "error vs cost joins one sweep too"
    );
}

fn overflow(dropped: u64) -> super::Overflow {
    super::Overflow {
        pass: "hair_lists".into(),
        counter: "list_counter".into(),
        of: "list_nodes".into(),
        dropped,
        needed: 40000,
        capacity: 25600,
        param: "nodes_per_pixel".into(),
        value: 1,
        value_needed: 2,
    }
}

/// A run whose capped buffer dropped data says so in every form of the
/// report; one that held everything shows its counter without a count.
#[test]
fn dropped_data_is_in_json_html_and_markdown() {
    let mut report = sample();
    report.scenes[0].runs[0].overflow = vec![overflow(0)];
    let quiet = markdown(&report);
    assert!(
        !quiet.contains("dropped"),
        "no column without drops:\n{quiet}"
    );
    report.scenes[0].runs[1].overflow = vec![overflow(14400)];
    let json = serde_json::to_value(&report).expect("json");
    assert_eq!(
        json["scenes"][0]["runs"][1]["overflow"][0]["dropped"],
        14400
    );
    assert_eq!(json["scenes"][0]["runs"][0]["overflow"][0]["dropped"], 0);
    let page = html(&report, &[]);
    assert!(page.contains("Bounded buffers"), "no overflow table");
    assert!(
        page.contains("<td>14400</td>"),
        "count missing from the HTML"
    );
    assert!(page.contains("nodes_per_pixel=1 (needs 2)"));
    let md = markdown(&report);
    assert!(md.contains(" dropped |"), "no dropped column:\n{md}");
    assert!(md.contains(" 14400 |"), "count missing:\n{md}");
}

/// The sample seen from three camera distances, `a@1`'s error growing with
/// the distance (ꟻLIP = factor / 10) and `a@2`'s constant.
fn distance_sample() -> Report {
    let mut r = sample();
    r.sweeps.clear();
    r.camera_distances = vec![1.0, 2.0, 4.0];
    let template = r.scenes.remove(0);
    for factor in [1.0, 2.0, 4.0] {
        let mut scene = template.clone();
        scene.name = format!("s@d{factor}");
        scene.distance = Some(CameraDistance {
            scene: "s".into(),
            factor,
        });
        scene.runs[1].metrics.flip_mean = factor / 10.0;
        r.scenes.push(scene);
    }
    r
}

#[test]
fn a_camera_distance_sweep_is_a_table_and_charts_in_every_form() {
    let r = distance_sample();
    let md = distance_markdown(&r);
    let rows: Vec<&str> = md.lines().filter(|l| l.ends_with('|')).collect();
    // Header, rule, a row per distance; columns named by variant id.
    assert_eq!(rows.len(), 2 + 3, "{md}");
    assert_eq!(
        rows[0],
        "| distance | a@1 ꟻLIP | a@1 GPU ms | a@2 ꟻLIP | a@2 GPU ms | reference GPU ms |"
    );
    assert_eq!(rows[3], "| 2× | 0.2000 | 2.50 | 0.1000 | 2.50 | 2.50 |");
    assert_eq!(rows[4], "| 4× | 0.4000 | 2.50 | 0.1000 | 2.50 | 2.50 |");
    assert!(markdown(&r).contains(&md), "report.md holds the table");
    // Error and time against distance for the one scene.
    let charts = distance_charts(&r);
    assert_eq!(charts.len(), 2);
    assert!(charts[0].contains("s: error vs camera distance"));
    assert!(
        !charts[0].contains(">reference</text>"),
        "the reference's error is 0 by construction"
    );
    assert!(charts[1].contains(">reference</text>"), "{}", charts[1]);
    let page = html(&r, &[]);
    assert!(page.contains("<h2>Camera distance</h2>"));
    assert!(page.contains("<tr><td>4×</td><td>0.40000</td>"), "{page}");
    let json = serde_json::to_value(&r).expect("json");
    assert_eq!(json["camera_distances"], serde_json::json!([1.0, 2.0, 4.0]));
    assert_eq!(json["scenes"][2]["distance"]["factor"], 4.0);
    assert_eq!(json["scenes"][2]["distance"]["scene"], "s");
    // Without the sweep: nothing of it anywhere.
    let plain = sample();
    assert!(distance_markdown(&plain).is_empty());
    assert!(!html(&plain, &[]).contains("Camera distance"));
    let json = serde_json::to_value(&plain).expect("json");
    assert!(json.get("camera_distances").is_none());
    assert!(json["scenes"][0].get("distance").is_none());
}
