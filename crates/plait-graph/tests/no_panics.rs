//! Whatever the input, load and compile answer with errors, never a panic:
//! every truncation and every single-line deletion of real pipelines, plus
//! odd `--set` values.

mod common;

use common::*;
use plait_graph::*;

fn check(text: &str, sets: &[&str]) {
    if let Ok(schedule) = compile_text(text, sets) {
        let _ = schedule_text(&schedule);
        let _ = to_dot(&schedule);
    }
}

#[test]
fn truncated_files_never_panic() {
    for (cut, _) in GOOD.char_indices() {
        check(&GOOD[..cut], &[]);
    }
}

#[test]
fn files_missing_a_line_never_panic() {
    let lines: Vec<&str> = GOOD.lines().collect();
    for skip in 0..lines.len() {
        let text: Vec<&str> = lines
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != skip)
            .map(|(_, l)| *l)
            .collect();
        check(&text.join("\n"), &[]);
    }
}

#[test]
fn odd_values_never_panic() {
    let sets = [
        "params.size=-5",
        "params.size=0",
        "params.size=\"1/0\"",
        "params.size=\"(((\"",
        "params.size=99999999999999999999",
        "params.size=1e308",
        "params.size=[1, [2]]",
        "params.size={ a = 1 }",
        "params.size=\"${size}\"",
        "resources.final.size=\"screen/0\"",
        "resources.final.size=[]",
        "resources.final.layers=\"-1\"",
        "resources.final.kind=buffer",
        "resources.depth.format=nope",
        "passes.shade.params.color=[1, \"x\", 2]",
        "passes.shade.params.slices=\"screen_width * 99999999\"",
        "passes.shade=3",
        "passes=[]",
        "pipeline.outputs=[]",
        "pipeline.outputs=\"final\"",
        "passes.shade.reads.shadow=[1]",
        "passes.new.type=shade",
        "résumé.ü=1",
    ];
    for set in sets {
        check(GOOD, &[set]);
    }
}
