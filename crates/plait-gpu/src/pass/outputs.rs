//! A raster pass's fragment outputs against its colour targets (issue 41):
//! wgpu accepts an output at `@location(n)` past the last target (the
//! values are dropped) and reports a `vec4<u32>` written into a float target
//! only when the pipeline is created, as a raw validation message. Both are
//! errors at the WGSL's `@location(n)` here, before any GPU work.
//!
//! A target the shader does not write is an error too: Vulkan leaves such
//! an attachment undefined wherever a fragment is drawn (the Vulkan
//! specification, "Fragment Output Interface"), so the image would depend
//! on the driver, though wgpu creates the pipeline.

use std::path::Path;

use naga::{Binding, ScalarKind, ShaderStage, TypeInner};
use plait_graph::format::SampleType;
use plait_graph::{Location, ScheduledPass};

use super::plan::BindingPlan;

/// One `@location(n)` output of the fragment entry point.
struct Output {
    location: u32,
    kind: Option<ScalarKind>,
}

/// The errors, each with its location and message.
pub(super) fn check(
    module: &naga::Module,
    plan: &BindingPlan,
    pass: &ScheduledPass,
    source: Option<(&Path, &str)>,
) -> Vec<(Location, String)> {
    let Some(ep) = module
        .entry_points
        .iter()
        .find(|e| e.stage == ShaderStage::Fragment)
    else {
        return Vec::new();
    };
    let outputs = fragment_outputs(module, &ep.function);
    let at = |n: u32| output_location(source, &ep.name, n).unwrap_or_else(|| fallback(pass));
    let mut errors = Vec::new();
    for o in &outputs {
        let Some(target) = plan.colors.get(o.location as usize) else {
            let slots: Vec<&str> = plan.colors.iter().map(|c| c.slot.as_str()).collect();
            errors.push((at(o.location), format!(
                "fragment output @location({}) has no colour target: the pass has {} ({}), at @location(0) … in `writes` order, and wgpu would drop it",
                o.location,
                slots.len(),
                if slots.is_empty() { "none".into() } else { slots.join(", ") },
            )));
            continue;
        };
        let want = match target.format.sample_type() {
            SampleType::Uint => ScalarKind::Uint,
            _ => ScalarKind::Float,
        };
        if o.kind != Some(want) {
            errors.push((at(o.location), format!(
                "fragment output @location({}) is {}, but its target `{}` is {} ({} values): wgpu would refuse the pipeline",
                o.location,
                kind_name(o.kind),
                target.slot,
                target.format,
                kind_name(Some(want)),
            )));
        }
    }
    for (i, target) in plan.colors.iter().enumerate() {
        if !outputs.iter().any(|o| o.location as usize == i) {
            errors.push((fallback(pass), format!(
                "colour target `{}` ({}) is at @location({i}), but the fragment shader `{}` writes no output there; Vulkan leaves it undefined where fragments are drawn",
                target.slot, target.format, ep.name,
            )));
        }
    }
    errors
}

/// The `@location` outputs of a fragment function: its result, or the
/// members of the struct it returns.
fn fragment_outputs(module: &naga::Module, f: &naga::Function) -> Vec<Output> {
    let Some(result) = &f.result else {
        return Vec::new();
    };
    let kind = |ty: naga::Handle<naga::Type>| match &module.types[ty].inner {
        TypeInner::Scalar(s) => Some(s.kind),
        TypeInner::Vector { scalar, .. } => Some(scalar.kind),
        _ => None,
    };
    let output = |binding: &Option<Binding>, ty| match binding {
        Some(Binding::Location { location, .. }) => Some(Output {
            location: *location,
            kind: kind(ty),
        }),
        _ => None,
    };
    match &module.types[result.ty].inner {
        TypeInner::Struct { members, .. } if result.binding.is_none() => members
            .iter()
            .filter_map(|m| output(&m.binding, m.ty))
            .collect(),
        _ => output(&result.binding, result.ty).into_iter().collect(),
    }
}

fn kind_name(kind: Option<ScalarKind>) -> &'static str {
    match kind {
        Some(ScalarKind::Float) => "float",
        Some(ScalarKind::Uint) => "u32",
        Some(ScalarKind::Sint) => "i32",
        _ => "not a number or vector",
    }
}

/// The pass's `shader` key, else its header.
fn fallback(pass: &ScheduledPass) -> Location {
    pass.shader_location
        .clone()
        .unwrap_or_else(|| pass.location.clone())
}

/// Where `@location(n)` is written for entry point `entry` in its WGSL
/// source: in the function's signature, else in the struct it returns.
/// naga's spans point into the composed module, not the author's file, so
/// the text is searched; `None` when the entry point is not in this file.
fn output_location(source: Option<(&Path, &str)>, entry: &str, n: u32) -> Option<Location> {
    let (path, text) = source?;
    let fn_at = text.find(&format!("fn {entry}("))?;
    let body = fn_at + text[fn_at..].find('{')?;
    let signature = &text[fn_at..body];
    let needle = format!("@location({n})");
    let offset = match signature.rfind("->") {
        Some(arrow) if signature[arrow..].contains(&needle) => {
            fn_at + arrow + signature[arrow..].find(&needle)?
        }
        Some(arrow) => {
            let ty = signature[arrow + 2..].trim();
            let start = text.find(&format!("struct {ty}"))?;
            let end = start + text[start..].find('}')?;
            start + text[start..end].find(&needle)?
        }
        None => return None,
    };
    let line = text[..offset].matches('\n').count() as u32 + 1;
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let column = text[line_start..offset].chars().count() as u32 + 1;
    Some(Location::File {
        path: path.to_path_buf(),
        line,
        column,
    })
}
