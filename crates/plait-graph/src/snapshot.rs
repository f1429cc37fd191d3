//! A stable, human-readable dump of a [`Schedule`], committed next to each
//! pipeline file so a change to the compiler or to a pipeline shows up as a
//! reviewable text diff (naga's `tests/in` → `tests/out` practice).
//!
//! Only deterministic data goes in: no hash-map iteration order, no absolute
//! paths beyond what the caller passed in.

use std::fmt::Write as _;

use crate::schedule::{Binding, Lifetime, ResourceId, Schedule};

/// The schedule as text: passes in order, culled passes with reasons,
/// resources with descriptor, bytes, lifetime and physical slot, memory.
pub fn schedule_text(s: &Schedule) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "pipeline {}", s.name);
    if !s.description.is_empty() {
        let _ = writeln!(out, "  {}", s.description);
    }
    let files: Vec<String> = s
        .files
        .iter()
        .filter(|f| !s.techniques.iter().any(|t| &t.path == *f))
        .map(|f| f.display().to_string())
        .collect();
    let _ = writeln!(out, "files: {}", files.join(" extends "));
    for t in &s.techniques {
        let _ = writeln!(
            out,
            "technique {} = {} ({})",
            t.point,
            t.name,
            t.path.display()
        );
    }
    if !s.params.is_empty() {
        let _ = writeln!(out, "\nparams:");
        for (k, v) in &s.params {
            let _ = writeln!(out, "  {k} = {v}");
        }
    }

    let _ = writeln!(out, "\npasses (execution order):");
    for (i, p) in s.passes.iter().enumerate() {
        pass_text(&mut out, &format!("{i:>3}"), p, s);
    }
    if !s.culled.is_empty() {
        let _ = writeln!(out, "\nculled:");
        for c in &s.culled {
            pass_text(&mut out, "  -", &c.pass, s);
            let _ = writeln!(out, "        culled: {}", c.reason);
        }
    }

    let _ = writeln!(out, "\nresources:");
    for (id, r) in s.resources.iter().enumerate() {
        let id = ResourceId::new(id);
        let shared = s.shares_memory_with(id);
        let shared = if shared.is_empty() {
            String::new()
        } else {
            format!(" (shared with {})", shared.join(", "))
        };
        let output = match (s.outputs.contains(&id), r.kept) {
            (true, _) => " [output]",
            (false, true) => " [kept across frames]",
            (false, false) => "",
        };
        let lifetime = match r.lifetime {
            // Sized by the scene's hair: nothing of the pipeline's.
            _ if r.scene => ", the scene's (persistent)".into(),
            Lifetime::Frame => String::new(),
            Lifetime::Persistent => ", persistent".into(),
            Lifetime::History { frames } => format!(", history {frames}"),
            Lifetime::Previous { of, frames_ago } => format!(
                ", previous of {}, {frames_ago} frame{} ago",
                s.resources.get(of.index()).map_or("?", |r| r.name.as_str()),
                if frames_ago == 1 { "" } else { "s" }
            ),
        };
        let _ = writeln!(
            out,
            "  {}{output}: {}, {} B, passes {}..={}, physical #{}{shared}{lifetime}",
            r.name,
            r.desc.label(),
            r.desc.bytes(),
            r.first_use,
            r.last_use,
            r.physical
        );
    }
    if !s.dropped_resources.is_empty() {
        let _ = writeln!(
            out,
            "  dropped (no live pass uses them): {}",
            s.dropped_resources.join(", ")
        );
    }
    if !s.history.is_empty() {
        let copies: Vec<String> = s
            .history
            .iter()
            .map(|c| format!("{} -> {}", s.resources[c.from].name, s.resources[c.to].name))
            .collect();
        let _ = writeln!(
            out,
            "\nhistory: {} (copied after each frame)",
            copies.join(", ")
        );
    }
    let _ = writeln!(
        out,
        "\nmemory: {} physical allocations, peak {} B, unpooled {} B",
        s.physical.len(),
        s.memory.peak_bytes,
        s.memory.unpooled_bytes
    );
    out
}

fn pass_text(out: &mut String, prefix: &str, p: &crate::schedule::ScheduledPass, s: &Schedule) {
    let mut head = format!("{prefix} {} [{}]", p.name, p.type_name);
    if let Some(view) = &p.view {
        head += &format!(" view={}", view.name());
    }
    if let Some(draw) = &p.draw {
        head += &format!(" draw={}", draw.name());
    }
    if p.run_once {
        head += " run=once";
    }
    let _ = writeln!(out, "{head}");
    if let Some(shader) = &p.shader {
        let _ = writeln!(out, "        shader: {}", shader.display());
    }
    if !p.raster.is_empty() {
        let _ = writeln!(out, "        state: {}", p.raster.describe());
    }
    if !p.params.is_empty() {
        let params: Vec<String> = p.params.iter().map(|(k, v)| format!("{k}={v}")).collect();
        let _ = writeln!(out, "        params: {}", params.join(", "));
    }
    let bindings = |list: &[Binding]| -> String {
        list.iter()
            .map(|b| {
                let dropped = if b.resolved(&s.resources).is_none() {
                    " (dropped)"
                } else {
                    ""
                };
                let loads = if b.loads { ", loads" } else { "" };
                format!(
                    "{}={}{dropped} ({:?}{loads})",
                    b.slot, b.resource_name, b.access
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    if !p.reads.is_empty() {
        let _ = writeln!(out, "        reads:  {}", bindings(&p.reads));
    }
    if !p.writes.is_empty() {
        let _ = writeln!(out, "        writes: {}", bindings(&p.writes));
    }
}
