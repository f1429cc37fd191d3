//! Loading features (extends, --set, ${param}, expressions) and what compile
//! produces (order, culling, lifetimes, memory sharing, DOT/SVG, snapshots).

mod common;

use common::*;
use plait_graph::*;
use std::path::{Path, PathBuf};

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn extends_merges_by_key_and_keeps_each_files_locations() {
    let dir = temp_dir("extends_merge");
    std::fs::write(dir.join("base.toml"), GOOD).unwrap();
    let child = r#"[pipeline]
name = "child"
extends = "base.toml"

[params]
size = 512

[passes.shade]
params = { strength = 2.5 }
"#;
    std::fs::write(dir.join("child.toml"), child).unwrap();
    let pipeline = load(&dir.join("child.toml"), &["params.size=128".into()]).unwrap();
    assert_eq!(
        pipeline.files,
        [dir.join("child.toml"), dir.join("base.toml")]
    );
    assert_eq!(pipeline.name.value, "child");
    // Kept from the base, with the base's location.
    assert_eq!(
        pipeline.outputs[0].location,
        Location::File {
            path: dir.join("base.toml"),
            line: 3,
            column: 12
        }
    );
    let shade = &pipeline.passes["shade"];
    assert_eq!(shade.type_name.value, "shade");
    assert_eq!(
        shade.type_name.location,
        Location::File {
            path: dir.join("base.toml"),
            line: 25,
            column: 8
        }
    );
    // Set by the child, with the child's location.
    assert_eq!(shade.params["strength"].value, Value::Float(2.5));
    assert_eq!(
        shade.params["strength"].location,
        Location::File {
            path: dir.join("child.toml"),
            line: 9,
            column: 23
        }
    );
    // --set wins over both files.
    assert_eq!(pipeline.params["size"].value, Value::Int(128));
    assert_eq!(
        pipeline.params["size"].location,
        Location::Flag {
            flag: "params.size=128".into()
        }
    );

    let schedule = compile(&pipeline, &registry(), &CompileOptions::default()).unwrap();
    let depth = &schedule.resources[schedule.resource("depth").unwrap()];
    assert_eq!(
        depth.desc,
        ResourceDesc::Texture {
            format: Format::Rg32Float,
            width: 128,
            height: 128,
            layers: 1,
            samples: 1
        }
    );
    assert_eq!(schedule.passes[1].params["strength"], Value::Float(2.5));
}

#[test]
fn set_is_the_same_as_editing_the_file() {
    let cases: &[(&str, &str, &str)] = &[
        (
            "passes.shade.params.strength=3.5",
            "writes = { color = \"final\" }",
            "writes = { color = \"final\" }\nparams = { strength = 3.5 }",
        ),
        (
            "passes.shade.params.color=[1,0.5,0.2]",
            "writes = { color = \"final\" }",
            "writes = { color = \"final\" }\nparams = { color = [1, 0.5, 0.2] }",
        ),
        (
            "passes.shade.params.mode=marschner",
            "writes = { color = \"final\" }",
            "writes = { color = \"final\" }\nparams = { mode = \"marschner\" }",
        ),
        (
            "resources.depth.format=rg16float",
            "format = \"rg32float\"",
            "format = \"rg16float\"",
        ),
        ("params.size=64", "size = 256", "size = 64"),
        (
            "resources.final.size=\"screen/2\"",
            "size = \"screen\"",
            "size = \"screen/2\"",
        ),
    ];
    for (flag, from, to) in cases {
        let by_flag = compile_text(GOOD, &[flag]).unwrap();
        let by_edit = compile_text(&edit(GOOD, from, to), &[]).unwrap();
        assert_eq!(
            schedule_text(&by_flag),
            schedule_text(&by_edit),
            "--set {flag}"
        );
    }
}

#[test]
fn params_substitute_typed_and_textually_and_sizes_take_expressions() {
    let text = edit(
        GOOD,
        "size = 256",
        "size = 256\nname_suffix = \"x${size}\"\nslices = \"${size}\"\nhalf = \"${size} / 2\"",
    );
    let text = edit(
        &text,
        "writes = { color = \"final\" }",
        "writes = { color = \"final\" }\nparams = { slices = \"${half} - 28\" }",
    );
    let text = edit(
        &text,
        "size = \"screen\"",
        "size = [\"screen_width / 2\", \"screen_height/2 + ${size}\"]",
    );
    // A param nothing uses is an error (issue 41): the description uses the
    // two this test only inspects.
    let text = edit(
        &text,
        "name = \"good\"",
        "name = \"good\"\ndescription = \"${name_suffix} ${slices}\"",
    );
    let pipeline = load_text(&text, &[]).unwrap();
    assert_eq!(
        pipeline.params["name_suffix"].value,
        Value::Str("x256".into())
    );
    assert_eq!(
        pipeline.params["slices"].value,
        Value::Int(256),
        "a whole `${{x}}` keeps x's type"
    );
    let schedule = compile(
        &pipeline,
        &registry(),
        &CompileOptions {
            screen: (1000, 600),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(schedule.passes[1].params["slices"], Value::Int(100));
    let final_ = &schedule.resources[schedule.resource("final").unwrap()];
    assert_eq!(
        final_.desc,
        ResourceDesc::Texture {
            format: Format::Rgba16Float,
            width: 500,
            height: 556,
            layers: 1,
            samples: 1
        }
    );
}

#[test]
fn defaults_are_filled_in_the_types_param_order() {
    let schedule = compile_text(GOOD, &["passes.shade.params.strength=2"]).unwrap();
    let params: Vec<_> = schedule.passes[1]
        .params
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect();
    assert_eq!(
        params,
        [
            "color=[1, 1, 1]",
            "mode=\"kajiya\"",
            "strength=2",
            "slices=16"
        ]
    );
}

#[test]
fn culled_passes_are_reported_with_a_reason_and_their_resources_dropped() {
    let text = format!(
        "{GOOD}\n[resources.debug]\nkind = \"texture\"\nformat = \"rgba8unorm\"\nsize = [32, 32]\n\n[passes.debug_view]\ntype = \"blur\"\nreads = {{ src = \"depth\" }}\nwrites = {{ dst = \"debug\" }}\nparams = {{ radius = 1 }}\n"
    );
    let schedule = compile_text(&text, &[]).unwrap();
    assert_eq!(schedule.passes.len(), 2);
    assert_eq!(schedule.culled.len(), 1);
    assert_eq!(schedule.culled[0].pass.name, "debug_view");
    assert_eq!(
        schedule.culled[0].reason,
        "writes only `debug`, which no output depends on"
    );
    assert_eq!(schedule.dropped_resources, ["debug"]);
    assert!(schedule.resource("debug").is_none());
    assert_eq!(schedule.culled[0].pass.writes[0].resource, None);
    // Still validated: a bad param in a culled pass is an error.
    let bad = edit(&text, "radius = 1", "radius = 100");
    assert!(
        matches!(&errors_of(&bad, &[])[0].kind, ErrorKind::BadParam { pass, .. } if pass == "debug_view")
    );
}

const CHAIN: &str = r#"[pipeline]
name = "chain"
outputs = ["out"]

[resources.t1]
kind = "texture"
format = "rgba16float"
size = [256, 256]

[resources.t2]
kind = "texture"
format = "rgba16float"
size = [256, 256]

[resources.t3]
kind = "texture"
format = "rgba16float"
size = [256, 256]

[resources.out]
kind = "texture"
format = "rgba16float"
size = [256, 256]

[resources.src]
kind = "texture"
format = "rgba16float"
size = [256, 256]

[passes.d]
type = "blur"
reads = { src = "t3" }
writes = { dst = "out" }
params = { radius = 1 }

[passes.c]
type = "blur"
reads = { src = "t2" }
writes = { dst = "t3" }
params = { radius = 1 }

[passes.b]
type = "blur"
reads = { src = "t1" }
writes = { dst = "t2" }
params = { radius = 1 }

[passes.a]
type = "blur"
reads = { src = "src" }
writes = { dst = "t1" }
params = { radius = 1 }

[passes.source]
type = "fullscreen"
shader = "shaders/source.wgsl"
writes = { color = "src" }
"#;

#[test]
fn order_follows_resources_not_the_file() {
    let schedule = compile_text(CHAIN, &[]).unwrap();
    let names: Vec<_> = schedule.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["source", "a", "b", "c", "d"]);
    assert_eq!(
        schedule.passes[0].writes[0].access,
        Access::StorageWrite,
        "dynamic slots default to storage writes"
    );
}

#[test]
fn same_descriptor_resources_with_disjoint_lifetimes_share_memory() {
    let schedule = compile_text(CHAIN, &[]).unwrap();
    let id = |name: &str| schedule.resource(name).unwrap();
    let life = |name: &str| {
        (
            schedule.resources[id(name)].first_use,
            schedule.resources[id(name)].last_use,
        )
    };
    assert_eq!(life("src"), (0, 1));
    assert_eq!(life("t1"), (1, 2));
    assert_eq!(life("t2"), (2, 3));
    assert_eq!(life("t3"), (3, 4));
    assert_eq!(life("out"), (4, 4));
    // src [0,1], t2 [2,3] and out [4,4] are disjoint; t1 [1,2] and t3 [3,4] too,
    // so two allocations ping-pong like a hand-written post-processing chain.
    assert_eq!(schedule.shares_memory_with(id("src")), ["t2", "out"]);
    assert_eq!(schedule.shares_memory_with(id("t1")), ["t3"]);
    assert_eq!(schedule.shares_memory_with(id("out")), ["src", "t2"]);
    assert_eq!(schedule.physical.len(), 2);
    let one = 256 * 256 * 8;
    assert_eq!(
        schedule.memory,
        MemoryReport {
            peak_bytes: 2 * one,
            unpooled_bytes: 5 * one
        }
    );
    assert!(schedule.memory.peak_bytes < schedule.memory.unpooled_bytes);
}

#[test]
fn different_descriptors_never_share() {
    let text = edit(
        CHAIN,
        "[resources.t2]\nkind = \"texture\"\nformat = \"rgba16float\"",
        "[resources.t2]\nkind = \"texture\"\nformat = \"rgba8unorm\"",
    );
    let schedule = compile_text(&text, &[]).unwrap();
    assert!(
        schedule
            .shares_memory_with(schedule.resource("t2").unwrap())
            .is_empty()
    );
}

const ACCUMULATE: &str = r#"[pipeline]
name = "acc"
outputs = ["sum"]

[resources.sum]
kind = "texture"
format = "rgba16float"
size = "screen/2"

[resources.x]
kind = "texture"
format = "rgba16float"
size = "screen"

[passes.add_second]
type = "accumulate"
reads = { src = "x" }
writes = { acc = "sum" }

[passes.make_x]
type = "blur"
reads = { src = "x" }
writes = { dst = "x" }
params = { radius = 1 }

[passes.clear_sum]
type = "fullscreen"
shader = "clear.wgsl"
writes = { out = "sum" }
"#;

#[test]
fn load_writers_run_after_plain_writers_and_the_first_writer_clears() {
    // make_x reads and writes x with nothing before it: it must clear.
    let schedule = compile_text(ACCUMULATE, &[]).unwrap();
    let names: Vec<_> = schedule.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["make_x", "clear_sum", "add_second"]);
    assert!(
        schedule.passes[2].writes[0].loads,
        "accumulates over clear_sum's result"
    );
    let sum = &schedule.resources[schedule.resource("sum").unwrap()];
    assert_eq!(
        sum.desc,
        ResourceDesc::Texture {
            format: Format::Rgba16Float,
            width: 480,
            height: 360,
            layers: 1,
            samples: 1
        }
    );

    // Without clear_sum the accumulating pass is the first writer: loads is off.
    let schedule = compile_text(ACCUMULATE, &["passes.clear_sum.enabled=false"]).unwrap();
    let add = schedule
        .passes
        .iter()
        .find(|p| p.name == "add_second")
        .unwrap();
    assert!(!add.writes[0].loads);
}

#[test]
fn shader_paths_resolve_next_to_the_file_or_at_the_repo_root() {
    let root = temp_dir("shader_root");
    std::fs::create_dir_all(root.join("shaders")).unwrap();
    std::fs::create_dir_all(root.join("pipelines")).unwrap();
    std::fs::write(root.join("shaders/source.wgsl"), "").unwrap();
    std::fs::write(root.join("pipelines/clear.wgsl"), "").unwrap();
    std::fs::write(root.join("pipelines/chain.toml"), CHAIN).unwrap();
    std::fs::write(root.join("pipelines/acc.toml"), ACCUMULATE).unwrap();
    let chain = load(&root.join("pipelines/chain.toml"), &[]).unwrap();
    assert_eq!(
        chain.passes["source"].shader.as_ref().unwrap().value,
        root.join("shaders/source.wgsl")
    );
    let acc = load(&root.join("pipelines/acc.toml"), &[]).unwrap();
    assert_eq!(
        acc.passes["clear_sum"].shader.as_ref().unwrap().value,
        root.join("pipelines/clear.wgsl")
    );
}

#[test]
fn dot_shows_order_culling_and_outputs() {
    let text = format!(
        "{GOOD}\n[resources.debug]\nkind = \"texture\"\nformat = \"rgba8unorm\"\nsize = [32, 32]\n\n[passes.debug_view]\ntype = \"blur\"\nreads = {{ src = \"depth\" }}\nwrites = {{ dst = \"debug\" }}\nparams = {{ radius = 1 }}\n"
    );
    let schedule = compile_text(&text, &[]).unwrap();
    let dot = to_dot(&schedule);
    assert!(dot.starts_with("digraph \"good\" {"), "{dot}");
    assert!(
        dot.contains("p0 [shape=box, label=\"light_range\\ndepth_range\"];"),
        "{dot}"
    );
    assert!(
        dot.contains("p0 -> p1 [label=\"depth\\nrg32float 256x256\"];"),
        "{dot}"
    );
    assert!(
        dot.contains("p2 [shape=box, label=\"debug_view\\nblur (culled)\", style=dashed];"),
        "{dot}"
    );
    assert!(
        dot.contains("p0 -> p2 [label=\"depth\\nrg32float 256x256\", style=dashed];"),
        "{dot}"
    );
    assert!(
        dot.contains("p1 -> output [label=\"final\\nrgba16float 960x720\"];"),
        "{dot}"
    );
    let svg = to_svg(&schedule);
    assert!(svg.contains("<svg") && svg.contains("light_range"), "{svg}");
}

#[test]
fn snapshot_text_is_stable_and_complete() {
    let schedule = compile_text(CHAIN, &[]).unwrap();
    let text = schedule_text(&schedule);
    assert_eq!(text, schedule_text(&compile_text(CHAIN, &[]).unwrap()));
    let expected = "\
pipeline chain
files: pipelines/test.toml

passes (execution order):
  0 source [fullscreen]
        shader: pipelines/shaders/source.wgsl
        writes: color=src (StorageWrite)
  1 a [blur]
        params: radius=1
        reads:  src=src (Sampled)
        writes: dst=t1 (ColorTarget)
  2 b [blur]
        params: radius=1
        reads:  src=t1 (Sampled)
        writes: dst=t2 (ColorTarget)
  3 c [blur]
        params: radius=1
        reads:  src=t2 (Sampled)
        writes: dst=t3 (ColorTarget)
  4 d [blur]
        params: radius=1
        reads:  src=t3 (Sampled)
        writes: dst=out (ColorTarget)

resources:
  t1: rgba16float 256x256, 524288 B, passes 1..=2, physical #1 (shared with t3)
  t2: rgba16float 256x256, 524288 B, passes 2..=3, physical #0 (shared with src, out)
  t3: rgba16float 256x256, 524288 B, passes 3..=4, physical #1 (shared with t1)
  out [output]: rgba16float 256x256, 524288 B, passes 4..=4, physical #0 (shared with src, t2)
  src: rgba16float 256x256, 524288 B, passes 0..=1, physical #0 (shared with t2, out)

memory: 2 physical allocations, peak 1048576 B, unpooled 2621440 B
";
    assert_eq!(text, expected);
}
