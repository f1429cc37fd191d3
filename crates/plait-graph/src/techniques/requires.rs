//! What a technique needs of the techniques chosen at other points, in its
//! own file, so no Rust names a technique:
//!
//! ```toml
//! [technique]
//! provides = ["hair_strands_along_light"]    # optional functions it defines
//!
//! [technique.requires.self_shadow]           # of the technique chosen there
//! provides = "hair_strands_along_light"
//! why = "Zinke et al. 2008 §4: the strands in front of and behind the point"
//!
//! [technique.requires.shading]
//! one_of = ["chiang"]
//! why = "…"
//! ```
//!
//! An unchosen point counts as its WGSL default (`point.toml`). A combination
//! that fails is refused at the choice, naming what works.

use crate::error::{Error, Location, Spanned};
use crate::load::{Node, Table};
use crate::value::Value;

use super::{Located, TechniqueRoots, read_technique, schema, table, technique_table};

/// One chosen technique: its point, name, where it was chosen, and its file.
pub(super) struct Chosen {
    pub(super) point: String,
    pub(super) name: String,
    pub(super) at: Location,
    pub(super) tree: Spanned<Node>,
}

/// Errors for every `[technique.requires]` entry a chosen technique fails.
pub(super) fn check(roots: &TechniqueRoots, chosen: &[Chosen]) -> Vec<Error> {
    let mut errors = Vec::new();
    for c in chosen {
        let Some(requires) = technique_table(&c.tree).and_then(|t| match t.get("requires") {
            Some(e) => match &e.value.value {
                Node::Table(r) => Some(r),
                _ => None,
            },
            None => None,
        }) else {
            continue;
        };
        for (point, entry) in requires {
            let Node::Table(rule) = &entry.value.value else {
                errors.push(schema(
                    &entry.value.location,
                    format!("technique.requires.{point} is a table (`provides`, `one_of`, `why`)"),
                ));
                continue;
            };
            if let Some(e) = check_rule(roots, chosen, c, point, rule, &entry.key) {
                errors.push(e);
            }
        }
    }
    errors
}

/// The `--set`s (`techniques.POINT=NAME`) that meet a technique's
/// `one_of` rules, the first name of each list, read from its file's text:
/// what a page or a test that shows the technique alone on a pipeline adds,
/// so `dual_scattering` is shown with `shading = chiang`. A `provides` rule
/// is left to the pipeline's own choice; a text that does not parse gives
/// none (loading it says why).
pub fn required_choices(technique_toml: &str) -> Vec<String> {
    let Ok(table) = technique_toml.parse::<toml::Table>() else {
        return Vec::new();
    };
    let requires = table
        .get("technique")
        .and_then(|t| t.get("requires"))
        .and_then(toml::Value::as_table);
    requires
        .into_iter()
        .flatten()
        .filter_map(|(point, rule)| {
            let first = rule.get("one_of")?.as_array()?.first()?.as_str()?;
            Some(format!("techniques.{point}={first}"))
        })
        .collect()
}

/// The technique chosen for `point`, or the point's WGSL default.
fn chosen_at(roots: &TechniqueRoots, chosen: &[Chosen], point: &str) -> Option<String> {
    if let Some(c) = chosen.iter().find(|c| c.point == point) {
        return Some(c.name.clone());
    }
    match roots.point_file(point) {
        Some(Ok(f)) => f.wgsl.map(|w| w.default.value),
        _ => None,
    }
}

fn string(rule: &Table, key: &str) -> Option<String> {
    match &rule.get(key)?.value.value {
        Node::Scalar(Value::Str(s)) => Some(s.clone()),
        _ => None,
    }
}

fn strings(rule: &Table, key: &str) -> Option<Vec<String>> {
    match &rule.get(key)?.value.value {
        Node::List(items) => Some(
            items
                .iter()
                .filter_map(|i| match &i.value {
                    Node::Scalar(Value::Str(s)) => Some(s.clone()),
                    _ => None,
                })
                .collect(),
        ),
        _ => None,
    }
}

/// `[technique] provides` of technique `point/name`; empty if it has none
/// or cannot be read (reading it as the choice reports why).
fn provides(roots: &TechniqueRoots, point: &str, name: &str) -> Vec<String> {
    let Located::Found(path) = roots.locate(point, name) else {
        return Vec::new();
    };
    read_technique(&path)
        .ok()
        .and_then(|tree| table(&tree, "technique").and_then(|t| strings(t, "provides")))
        .unwrap_or_default()
}

fn check_rule(
    roots: &TechniqueRoots,
    chosen: &[Chosen],
    c: &Chosen,
    point: &str,
    rule: &Table,
    key: &Location,
) -> Option<Error> {
    let why = string(rule, "why").unwrap_or_default();
    let have = chosen_at(roots, chosen, point).unwrap_or_else(|| "(none)".into());
    let who = format!("{} `{}`", c.point, c.name);
    if let Some(one_of) = strings(rule, "one_of")
        && !one_of.contains(&have)
    {
        return Some(schema(
            &c.at,
            format!(
                "{who} composes with {point} {} only ({why}; declared at {key}); this pipeline's {point} is `{have}` — set `techniques.{point} = \"{}\"`",
                one_of
                    .iter()
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
                one_of.first().map_or("", String::as_str),
            ),
        ));
    }
    if let Some(function) = string(rule, "provides")
        && !provides(roots, point, &have).contains(&function)
    {
        let working: Vec<String> = roots
            .choices(point)
            .into_iter()
            .filter(|n| provides(roots, point, n).contains(&function))
            .collect();
        return Some(schema(
            &c.at,
            format!(
                "{who} needs a {point} technique that provides `{function}` ({why}; declared at {key}); `{have}` does not — set `techniques.{point} = \"{}\"` (providers: {})",
                working.first().map_or("", String::as_str),
                working.join(", ")
            ),
        ));
    }
    None
}
