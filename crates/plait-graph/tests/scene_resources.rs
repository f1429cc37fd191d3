//! Scene resources (`plait_graph::scene_resources`): a pass that writes the
//! hair's vertices runs before every hair draw and lives as long as one
//! does; the scene's buffers are never cleared or shared; read-only ones
//! cannot be written and none may be declared.

mod common;

use common::{GOOD, edit, load_text, registry};
use plait_graph::*;

/// GOOD plus a data-only compute pass writing the hair, declared last.
fn with_simulation(writes: &str) -> String {
    format!(
        "{GOOD}\n[passes.simulate]\ntype = \"compute\"\nshader = \"sim.wgsl\"\nreads = {{ rest = \"guide_rest\" }}\nwrites = {{ {writes} }}\n"
    )
}

fn compile_text(text: &str) -> Result<Schedule, Errors> {
    let mut r = registry();
    let mut compute = PassTypeSpec::new("compute", PassShape::Compute, "", "");
    compute.dynamic_slots = true;
    compute.needs_shader = true;
    r.register(compute);
    compile(&load_text(text, &[])?, &r, &CompileOptions::default())
}

#[test]
fn a_hair_writer_runs_before_every_hair_draw_and_is_live() {
    let s = compile_text(&with_simulation("vertices = \"hair_vertices\"")).unwrap();
    let names: Vec<_> = s.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        ["simulate", "light_range", "shade"],
        "declared last, runs first"
    );
    let id = s
        .resource("hair_vertices")
        .expect("a scene resource in the schedule");
    let r = &s.resources[id];
    assert!(r.scene);
    assert_eq!(r.desc.bytes(), 0, "the pipeline allocates nothing for it");
    let write = &s.passes[0].writes[0];
    assert!(write.loads, "the scene's contents are never cleared");
    assert!(
        s.physical[r.physical].users == vec![id],
        "never shared with another resource"
    );
}

#[test]
fn without_a_hair_draw_the_writer_is_culled() {
    // No pass draws hair: nothing needs the vertices.
    let text = edit(
        &with_simulation("vertices = \"hair_vertices\""),
        "draw = \"hair\"",
        "draw = \"opaque\"",
    );
    let s = compile_text(&text).unwrap();
    assert!(s.passes.iter().all(|p| p.name != "simulate"));
    assert!(s.culled.iter().any(|c| c.pass.name == "simulate"));
}

#[test]
fn writing_a_read_only_scene_resource_is_an_error_at_the_slot() {
    let text = with_simulation("indices = \"hair_indices\"");
    let errors = compile_text(&text).unwrap_err().0;
    assert_eq!(errors.len(), 1, "{errors:?}");
    let message = errors[0].to_string();
    assert!(
        message.contains("scene resource `hair_indices` is read-only"),
        "{message}"
    );
    let line = text
        .lines()
        .position(|l| l.contains("hair_indices"))
        .unwrap() as u32
        + 1;
    assert!(
        matches!(errors[0].location, Location::File { line: l, .. } if l == line),
        "points at the slot: {:?}",
        errors[0].location
    );
}

#[test]
fn declaring_a_scene_resource_is_an_error() {
    let text = format!(
        "{}\n[resources.guide_positions]\nkind = \"buffer\"\nsize = 64\n",
        with_simulation("positions = \"guide_positions\"")
    );
    let message = compile_text(&text).unwrap_err().to_string();
    assert!(message.contains("is a scene resource"), "{message}");
}

/// A data-only type may declare params of its own beside the shader's: the
/// declared ones get their defaults and come first, the shader's follow in
/// file order (they used to vanish when the type declared any).
#[test]
fn a_data_only_pass_keeps_its_declared_defaults_and_its_shader_params() {
    let mut r = registry();
    let mut compute = PassTypeSpec::new("compute", PassShape::Compute, "", "");
    compute.dynamic_slots = true;
    compute.needs_shader = true;
    compute.params.push(ParamSpec {
        name: "steps".into(),
        ty: ParamType::Int { min: 1, max: 64 },
        default: Some(Value::Int(4)),
        doc: String::new(),
    });
    r.register(compute);
    let text = format!(
        "{}params = {{ stiffness = 0.5, damping = 0.25 }}\n",
        with_simulation("vertices = \"hair_vertices\"")
    );
    let s = compile(
        &load_text(&text, &[]).unwrap(),
        &r,
        &CompileOptions::default(),
    )
    .unwrap();
    let simulate = s.passes.iter().find(|p| p.name == "simulate").unwrap();
    let names: Vec<&str> = simulate.params.keys().map(String::as_str).collect();
    assert_eq!(names, ["steps", "stiffness", "damping"]);
    assert_eq!(simulate.params["steps"], Value::Int(4));
}
