//! The schedule as Graphviz DOT (for `dot -Tsvg`); the built-in SVG picture
//! is drawn by [`crate::svg`], with no Graphviz install needed.
//!
//! Passes are nodes in execution order; an edge goes from the pass that
//! produced the version of a resource a pass sees to that pass, labelled with
//! the resource. Culled passes and their edges are dashed; outputs flow into
//! a final `output` node.

use std::fmt::Write as _;

use crate::schedule::{Binding, Schedule, ScheduledPass};

/// Graphviz DOT of the schedule (for `dot -Tsvg`).
pub fn to_dot(schedule: &Schedule) -> String {
    render(schedule)
}

/// An SVG picture of the schedule: passes as rows, resources as lifetime
/// columns (see [`crate::svg`]).
pub fn to_svg(schedule: &Schedule) -> String {
    crate::svg::schedule_svg(schedule)
}

/// Escapes one piece of label text for a DOT string.
fn escape(s: &str) -> String {
    s.replace('\\', "\\\\").replace('"', "\\\"")
}

fn quote(s: &str) -> String {
    format!("\"{}\"", escape(s))
}

/// A quoted multi-line label from raw (unescaped) lines.
fn label(lines: &[&str]) -> String {
    let escaped: Vec<String> = lines.iter().map(|l| escape(l)).collect();
    format!("\"{}\"", escaped.join("\\n"))
}

fn resource_label(schedule: &Schedule, binding: &Binding) -> String {
    match binding.resolved(&schedule.resources) {
        Some(r) => label(&[&binding.resource_name, &r.desc.label()]),
        None => label(&[&binding.resource_name]),
    }
}

fn render(schedule: &Schedule) -> String {
    // Live passes in execution order, then culled ones; `p{i}` node ids.
    let all: Vec<(&ScheduledPass, bool)> = schedule
        .passes
        .iter()
        .map(|p| (p, false))
        .chain(schedule.culled.iter().map(|c| (&c.pass, true)))
        .collect();

    let mut out = String::new();
    let _ = writeln!(out, "digraph {} {{", quote(&schedule.name));
    let _ = writeln!(out, "  rankdir=TB;");
    let _ = writeln!(out, "  node [shape=box, fontname=\"sans-serif\"];");
    let _ = writeln!(out, "  edge [fontname=\"sans-serif\", fontsize=10];");
    for (i, (pass, culled)) in all.iter().enumerate() {
        let kind = format!(
            "{}{}",
            pass.type_name,
            if *culled { " (culled)" } else { "" }
        );
        let style = if *culled { ", style=dashed" } else { "" };
        let _ = writeln!(
            out,
            "  p{i} [shape=box, label={}{style}];",
            label(&[&pass.name, &kind])
        );
    }
    let _ = writeln!(out, "  output [shape=doublecircle, label=\"output\"];");
    // Each chosen technique's passes in a cluster: what a swap changes.
    for (k, technique) in schedule.techniques.iter().enumerate() {
        let label = technique.label();
        let members: Vec<String> = all
            .iter()
            .enumerate()
            .filter(|(_, (p, _))| p.technique.as_deref() == Some(label.as_str()))
            .map(|(i, _)| format!("p{i}"))
            .collect();
        if members.is_empty() {
            continue;
        }
        let _ = writeln!(
            out,
            "  subgraph cluster_{k} {{ label={}; style=rounded; color=grey; {}; }}",
            quote(&format!("technique {label}")),
            members.join("; ")
        );
    }

    for (i, (pass, culled)) in all.iter().enumerate() {
        // What this pass sees of a resource was made by the latest earlier writer.
        let consumed = pass
            .reads
            .iter()
            .chain(pass.writes.iter().filter(|b| b.loads));
        let mut seen = Vec::new();
        for binding in consumed {
            if seen.contains(&&binding.resource_name) {
                continue;
            }
            seen.push(&binding.resource_name);
            let writer = (0..i).rev().find(|&w| {
                all[w]
                    .0
                    .writes
                    .iter()
                    .any(|b| b.resource_name == binding.resource_name)
            });
            if let Some(w) = writer {
                let dashed = *culled || all[w].1;
                let style = if dashed { ", style=dashed" } else { "" };
                let _ = writeln!(
                    out,
                    "  p{w} -> p{i} [label={}{style}];",
                    resource_label(schedule, binding)
                );
            }
        }
    }
    for &output in &schedule.outputs {
        let name = &schedule.resources[output].name;
        let writer = (0..schedule.passes.len()).rev().find(|&w| {
            schedule.passes[w]
                .writes
                .iter()
                .any(|b| &b.resource_name == name)
        });
        if let Some(w) = writer {
            let text = label(&[name, &schedule.resources[output].desc.label()]);
            let _ = writeln!(out, "  p{w} -> output [label={text}];");
        }
    }
    if schedule.passes.len() > 1 {
        // Heavy invisible edges keep the execution order top-down.
        let chain: Vec<String> = (0..schedule.passes.len())
            .map(|i| format!("p{i}"))
            .collect();
        let _ = writeln!(out, "  {} [style=invis, weight=10];", chain.join(" -> "));
    }
    out.push_str("}\n");
    out
}
