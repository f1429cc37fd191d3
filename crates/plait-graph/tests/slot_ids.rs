//! Slots resolved once, at compile: each binding carries its slot's handle
//! (`Binding::slot_id`), an `X_resolve` the index of the `X` it receives,
//! and each blend the index of the write it names, so build compares
//! indices, never names.

mod common;

use common::*;
use plait_graph::*;

fn pass<'s>(schedule: &'s Schedule, name: &str) -> &'s ScheduledPass {
    schedule.passes.iter().find(|p| p.name == name).unwrap()
}

#[test]
fn bindings_carry_their_declared_slots_handle() {
    let schedule = compile_text(GOOD, &[]).unwrap();
    let shade = pass(&schedule, "shade");
    assert_eq!(shade.reads[0].slot_id, Some(SlotId::Input(0)));
    assert_eq!(shade.writes[0].slot_id, Some(SlotId::Output(0)));
    // Found by handle: the binding whose slot is `shadow` reads `depth`.
    assert_eq!(
        shade.bound(SlotId::Input(0)).unwrap().resource_name,
        "depth"
    );
    assert_eq!(
        shade.bound(SlotId::Output(0)).unwrap().resource_name,
        "final"
    );
    assert!(shade.bound(SlotId::Output(1)).is_none());
}

/// Two slots of one type bound in the file in the other order: the handles
/// follow the names, not the file's order.
#[test]
fn handles_follow_names_not_file_order() {
    let mut r = registry();
    let tex = |name: &str, access| SlotSpec {
        name: name.into(),
        kind: ResourceKind::Texture,
        access,
        formats: Formats::Any,
        loads: false,
        optional: false,
        doc: String::new(),
        binding: None,
    };
    r.register(PassTypeSpec {
        inputs: vec![tex("a", Access::Sampled), tex("b", Access::Sampled)],
        outputs: vec![tex("out", Access::ColorTarget)],
        ..PassTypeSpec::new("two", PassShape::Fullscreen, "", "")
    });
    let text = format!(
        "{GOOD}\n[resources.other]\nkind = \"texture\"\nformat = \"rgba16float\"\nsize = \"screen\"\n\n\
         [passes.two]\ntype = \"two\"\nreads = {{ b = \"final\", a = \"depth\" }}\nwrites = {{ out = \"other\" }}\n"
    );
    let text = edit(&text, "outputs = [\"final\"]", "outputs = [\"other\"]");
    let pipeline = load_text(&text, &[]).unwrap();
    let schedule = compile(&pipeline, &r, &CompileOptions::default()).unwrap();
    let two = pass(&schedule, "two");
    assert_eq!(two.reads[0].slot, "b");
    assert_eq!(two.reads[0].slot_id, Some(SlotId::Input(1)));
    assert_eq!(two.bound(SlotId::Input(0)).unwrap().resource_name, "depth");
    assert_eq!(two.bound(SlotId::Input(1)).unwrap().resource_name, "final");
}

/// A data-only pass: its slots are its shader's, so no handle; the resolve
/// and the blend are paired with their writes by index at compile.
#[test]
fn resolves_and_blends_are_paired_at_compile() {
    let text = edit(
        GOOD,
        "[passes.shade]",
        "[resources.msaa]\nkind = \"texture\"\nformat = \"rgba16float\"\nsize = \"screen\"\nsamples = 4\n\n\
         [passes.draw]\ntype = \"fullscreen\"\nshader = \"x.wgsl\"\n\
         writes = { color_resolve = \"final\", color = \"msaa\" }\nblend = { color = \"additive\" }\n\n\
         [passes.shade]",
    );
    let text = edit(
        &text,
        "writes = { color = \"final\" }",
        "writes = { color = \"depth2\" }",
    );
    let text = edit(
        &text,
        "[resources.final]",
        "[resources.depth2]\nkind = \"texture\"\nformat = \"rgba16float\"\nsize = \"screen\"\n\n[resources.final]",
    );
    let text = edit(
        &text,
        "outputs = [\"final\"]",
        "outputs = [\"final\", \"depth2\"]",
    );
    let schedule = compile_text(&text, &[]).unwrap();
    let draw = pass(&schedule, "draw");
    assert_eq!(draw.writes[0].slot, "color_resolve");
    assert_eq!(draw.writes[0].slot_id, None);
    assert_eq!(draw.writes[0].resolves, Some(1));
    assert_eq!(draw.writes[1].resolves, None);
    assert_eq!(draw.blend_writes, vec![Some(1)]);
}
