//! Two things a technique file may say beyond its data, so no Rust has to
//! name the technique:
//!
//! ```toml
//! [technique]
//! engine = ["wisp_mesh"]      # what the engine does for it (ENGINE_NEEDS)
//!
//! [param_ranges]              # ranges of its own params its WGSL needs
//! chiang_beta_m = { min = 0.02, max = 1.0, doc = "below 0.02 M_p leaves f32" }
//! ```
//!
//! A range is checked against the pipeline's final value of the param (its
//! own `[params]` default, the pipeline's line, or a `--set` flag), at that
//! value's file:line:col or flag.

use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::load::{Node, Table};
use crate::schedule::ChosenTechnique;
use crate::suggest::did_you_mean;
use crate::value::Value;

/// The engine builds the wisps' triangle strips on the CPU at load
/// (`plait::wisps`), and every hair draw draws them instead of the strands.
pub const WISP_MESH: &str = "wisp_mesh";
/// The engine notes how many strands the level of detail leaves out at the
/// frame's camera (`plait::strand_lod`).
pub const STRAND_LOD_NOTE: &str = "strand_lod_note";
/// What `[technique] engine` may name.
pub const ENGINE_NEEDS: &[&str] = &[WISP_MESH, STRAND_LOD_NOTE];

/// One `[param_ranges]` entry.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamRange {
    pub name: String,
    pub min: f64,
    pub max: f64,
    pub doc: String,
    /// Its key in the technique file.
    pub at: Location,
}

/// The adapter can trace rays through acceleration structures
/// (`Features::EXPERIMENTAL_RAY_QUERY` in wgpu, `VK_KHR_ray_query` in
/// Vulkan): techniques whose WGSL says `enable wgpu_ray_query;` need it.
pub const RAY_QUERY: &str = "ray_query";
/// What `[technique] adapter` may name: capabilities some adapters lack. A
/// technique needing one is refused on an adapter without it before any GPU
/// work (`plait_gpu::support`), naming the adapter, the capability and how
/// to get it.
pub const ADAPTER_NEEDS: &[&str] = &[RAY_QUERY];

/// `[technique] engine`, each value one of [`ENGINE_NEEDS`].
pub(super) fn engine(technique: &Table, errors: &mut Vec<Error>) -> Vec<String> {
    let names = listed(
        technique,
        "engine",
        ("engine need", "needs"),
        ENGINE_NEEDS,
        errors,
    );
    names.into_iter().map(|n| n.value).collect()
}

/// `[technique] adapter`, each value one of [`ADAPTER_NEEDS`], with where
/// it is written (the refusal points there).
pub(super) fn adapter(technique: &Table, errors: &mut Vec<Error>) -> Vec<Spanned<String>> {
    let what = ("adapter capability", "capabilities");
    listed(technique, "adapter", what, ADAPTER_NEEDS, errors)
}

/// `[technique] <key>`: a list of names from `allowed`; `what` names one
/// and several in messages.
fn listed(
    technique: &Table,
    key: &str,
    (one, many): (&str, &str),
    allowed: &[&str],
    errors: &mut Vec<Error>,
) -> Vec<Spanned<String>> {
    let Some(e) = technique.get(key) else {
        return Vec::new();
    };
    let Node::List(items) = &e.value.value else {
        errors.push(schema(
            &e.value.location,
            format!("technique.{key} is a list of: {}", allowed.join(", ")),
        ));
        return Vec::new();
    };
    let mut out = Vec::new();
    for item in items {
        match &item.value {
            Node::Scalar(Value::Str(s)) if allowed.contains(&s.as_str()) => {
                out.push(Spanned::new(s.clone(), item.location.clone()))
            }
            _ => {
                let text = match &item.value {
                    Node::Scalar(Value::Str(s)) => s.clone(),
                    Node::Scalar(v) => v.to_string(),
                    _ => "a table".into(),
                };
                errors.push(schema(
                    &item.location,
                    format!(
                        "technique.{key}: no {one} `{text}`{} ({many}: {})",
                        did_you_mean(&text, allowed.iter().copied()),
                        allowed.join(", ")
                    ),
                ));
            }
        }
    }
    out
}

/// `[param_ranges]`: each names a param of the technique's `[params]`,
/// with `min ≤ max` and a `doc` saying why.
pub(super) fn ranges(tree: &Spanned<Node>, errors: &mut Vec<Error>) -> Vec<ParamRange> {
    let Some(t) = super::table(tree, "param_ranges") else {
        return Vec::new();
    };
    let own = super::table(tree, "params");
    let mut out = Vec::new();
    for (name, e) in t {
        if !own.is_some_and(|p| p.contains_key(name)) {
            let names = own.map(|p| p.keys().cloned().collect::<Vec<_>>());
            let names = names.unwrap_or_default();
            errors.push(schema(
                &e.key,
                format!(
                    "param_ranges.{name}: the technique has no param `{name}`{} (its [params]: {})",
                    did_you_mean(name, names.iter().map(String::as_str)),
                    names.join(", ")
                ),
            ));
            continue;
        }
        if let Some(r) = read_range(name, e, errors) {
            out.push(r);
        }
    }
    out
}

fn read_range(name: &str, e: &crate::load::Entry, errors: &mut Vec<Error>) -> Option<ParamRange> {
    let ctx = format!("param_ranges.{name}");
    let Node::Table(t) = &e.value.value else {
        errors.push(schema(
            &e.value.location,
            format!("{ctx} is `{{ min = …, max = …, doc = \"why\" }}`"),
        ));
        return None;
    };
    let mut ok = true;
    for key in t.keys() {
        if !["min", "max", "doc"].contains(&key.as_str()) {
            errors.push(schema(
                &t[key].key,
                format!(
                    "{ctx}: unknown key `{key}`{} (keys: min, max, doc)",
                    did_you_mean(key, ["min", "max", "doc"])
                ),
            ));
            ok = false;
        }
    }
    let mut field = |key: &str| -> Option<&Spanned<Node>> {
        let f = t.get(key).map(|f| &f.value);
        if f.is_none() {
            errors.push(schema(&e.key, format!("{ctx} needs `{key}`")));
        }
        f
    };
    let (min, max, doc) = (field("min"), field("max"), field("doc"));
    let number = |n: Option<&Spanned<Node>>, errors: &mut Vec<Error>| match n.map(|n| &n.value) {
        Some(Node::Scalar(Value::Int(i))) => Some(*i as f64),
        Some(Node::Scalar(Value::Float(f))) if f.is_finite() => Some(*f),
        Some(_) => {
            errors.push(schema(
                &n?.location,
                format!("{ctx}: min and max are finite numbers"),
            ));
            None
        }
        None => None,
    };
    let (lo, hi) = (number(min, errors), number(max, errors));
    let doc = match doc.map(|d| &d.value) {
        Some(Node::Scalar(Value::Str(s))) => Some(s.clone()),
        Some(_) => {
            errors.push(schema(&doc?.location, format!("{ctx}.doc is a string")));
            None
        }
        None => None,
    };
    let (lo, hi, doc) = (lo?, hi?, doc?);
    if lo > hi {
        errors.push(schema(
            &e.value.location,
            format!("{ctx}: min {lo} is above max {hi}"),
        ));
        return None;
    }
    ok.then(|| ParamRange {
        name: name.to_owned(),
        min: lo,
        max: hi,
        doc,
        at: e.key.clone(),
    })
}

/// Each chosen technique's `[param_ranges]` against the value the pipeline
/// ends with (after its techniques and `--set`), at that value.
pub(crate) fn check_param_ranges(
    root: &Spanned<Node>,
    chosen: &[ChosenTechnique],
    errors: &mut Vec<Error>,
) {
    let Some(params) = super::table(root, "params") else {
        return;
    };
    for t in chosen {
        for r in &t.ranges {
            let Some(e) = params.get(&r.name) else {
                continue;
            };
            let value = match &e.value.value {
                Node::Scalar(Value::Int(i)) => *i as f64,
                Node::Scalar(Value::Float(f)) => *f,
                _ => {
                    errors.push(schema(
                        &e.value.location,
                        format!(
                            "param `{}` must be a number: {} technique {} holds it to {}…{} ({})",
                            r.name, t.point, t.name, r.min, r.max, r.at
                        ),
                    ));
                    continue;
                }
            };
            // `!(…)` so NaN is out of range too.
            if !(r.min <= value && value <= r.max) {
                errors.push(schema(
                    &e.value.location,
                    format!(
                        "param `{}` = {value} is out of {} technique {}'s range {}…{} ({}): {}",
                        r.name, t.point, t.name, r.min, r.max, r.at, r.doc
                    ),
                ));
            }
        }
    }
}

fn schema(at: &Location, message: String) -> Error {
    Error::new(at.clone(), ErrorKind::Schema(message))
}
