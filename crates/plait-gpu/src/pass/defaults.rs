//! What a pass type gets unless it says otherwise: shader defines from its
//! params, and one compute thread per texel (or per 4 bytes) of its output.

use plait_graph::{ResourceDesc, Schedule, ScheduledPass, Value};

use crate::shader::Define;

fn upper(name: &str) -> String {
    name.to_ascii_uppercase()
}

/// Int params → `#{NAME}`, bools → `#ifdef NAME`, strings → `#ifdef
/// PARAM_VALUE`, `LIGHT_VIEW` for passes drawn from the light and
/// `DRAW_OPAQUE` for passes that draw the opaque geometry (whose vertices
/// carry a head weight at location 3, which hair vertices do not).
pub fn default_defines(pass: &ScheduledPass) -> Vec<(String, Define)> {
    let mut out = Vec::new();
    for (k, v) in &pass.params {
        match v {
            Value::Int(i) if *i >= 0 && *i <= u32::MAX as i64 => {
                out.push((upper(k), Define::UInt(*i as u32)))
            }
            Value::Int(i) => out.push((upper(k), Define::Int(*i as i32))),
            Value::Bool(b) => out.push((upper(k), Define::Bool(*b))),
            // `self_shadow = "modified_shadow_map"` → `#ifdef SELF_SHADOW_MODIFIED_SHADOW_MAP`.
            Value::Str(v) => out.push((format!("{}_{}", upper(k), upper(v)), Define::Bool(true))),
            _ => {}
        }
    }
    if pass.view == Some(plait_graph::View::Light) {
        out.push(("LIGHT_VIEW".into(), Define::Bool(true)));
    }
    if pass.draw == Some(plait_graph::Draw::Opaque) {
        out.push(("DRAW_OPAQUE".into(), Define::Bool(true)));
    }
    out
}

/// Threads of a compute pass: width × height × layers of the first written
/// texture, or one per 4 bytes of the first written buffer.
pub fn default_threads(pass: &ScheduledPass, schedule: &Schedule) -> [u32; 3] {
    match pass
        .writes
        .first()
        .and_then(|b| b.resolved(&schedule.resources))
        .map(|r| &r.desc)
    {
        Some(ResourceDesc::Texture {
            width,
            height,
            layers,
            ..
        }) => [*width, *height, *layers],
        Some(ResourceDesc::Buffer { size }) => [(size / 4).min(u32::MAX as u64) as u32, 1, 1],
        Some(ResourceDesc::AccelerationStructure) | None => [1, 1, 1],
    }
}
