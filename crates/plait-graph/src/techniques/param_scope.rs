//! Which names a pipeline's `[params]` may hold. A key nothing reads (a typo,
//! `shadow_wieght = 0.2`) would otherwise be accepted silently while the
//! technique goes on with its default, so every key must be:
//!
//! - a param a chosen technique defines (its `[params]`), or
//! - a name some `${…}` of the pipeline or its techniques uses (after the
//!   techniques' exports reached the passes that `uses` them), or
//! - one of [`ENGINE_PARAMS`], read by the engine itself.
//!
//! A key that belongs to a technique the pipeline does not choose is a note,
//! not an error: gallery pipelines extend `occupancy.toml`, whose `[params]`
//! tune the default techniques, and one `--set techniques.X=…` swaps a
//! technique out; failing then would make every swap fail on the base file's
//! tuning. The note still names the technique, so nothing is silent. Any
//! other key is an error at its own line with the nearest valid name.

use std::path::Path;

use super::{TechniqueRoots, read_technique, table};
use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::load::{Node, Table};
use crate::schedule::ChosenTechnique;
use crate::suggest::{did_you_mean, nearest_first};
use crate::value::Value;

/// Params the engine reads from the schedule itself (not through `${…}`):
/// `strand_coverage` (`plait::session::strand_coverage`).
pub const ENGINE_PARAMS: &[&str] = &["strand_coverage"];

/// Checks every key of `root`'s `[params]` (the pipeline after techniques,
/// exports and `--set`) against the names in use; errors for keys nothing
/// uses, notes for keys of techniques not chosen.
pub(crate) fn check_param_names(
    root: &Spanned<Node>,
    chosen: &[ChosenTechnique],
    pipeline_path: &Path,
    errors: &mut Vec<Error>,
    notes: &mut Vec<String>,
) {
    let Some(params) = table(root, "params") else {
        return;
    };
    let mut valid: Vec<String> = chosen.iter().flat_map(|c| c.params.clone()).collect();
    valid.extend(ENGINE_PARAMS.iter().map(|s| (*s).to_owned()));
    collect_references(root, &mut valid);
    let unused: Vec<(&String, &Location)> = params
        .iter()
        .filter(|(name, _)| !valid.contains(name))
        .map(|(name, e)| (name, &e.key))
        .collect();
    if unused.is_empty() {
        return;
    }
    let roots = TechniqueRoots::for_pipeline(pipeline_path);
    for (name, at) in unused {
        match owner_not_chosen(&roots, chosen, name) {
            Some((point, technique)) => notes.push(format!(
                "{at}: param `{name}` is for {point} technique {technique}, which this pipeline does not choose: it has no effect here"
            )),
            None => errors.push(unknown_param(name, at, &valid)),
        }
    }
}

/// A `--set params.X=…` naming no param (an error already) whose `X` is a
/// param of a technique not chosen: the reason says which, and the flag
/// that chooses it. An error, not a note as in a file: the flag was typed
/// for this run and would change nothing.
pub(crate) fn explain_unchosen_sets(
    errors: &mut [Error],
    chosen: &[ChosenTechnique],
    pipeline_path: &Path,
) {
    let roots = TechniqueRoots::for_pipeline(pipeline_path);
    for e in errors.iter_mut() {
        let ErrorKind::UnknownSetKey { key, reason } = &mut e.kind else {
            continue;
        };
        let Some(name) = key.strip_prefix("params.") else {
            continue;
        };
        if let Some((point, technique)) = owner_not_chosen(&roots, chosen, name) {
            reason.push_str(&format!(
                "; `{name}` is for {point} technique {technique}, which this pipeline does not choose (choose it with --set techniques.{point}={technique})"
            ));
        }
    }
}

fn unknown_param(name: &str, at: &Location, valid: &[String]) -> Error {
    let mut known: Vec<&str> = valid.iter().map(String::as_str).collect();
    known.sort_unstable();
    known.dedup();
    let ranked = nearest_first(name, known.iter().copied());
    Error::new(
        at.clone(),
        ErrorKind::Schema(format!(
            "unknown param `{name}`: no chosen technique defines it and nothing uses `${{{name}}}`{} (params in use: {})",
            did_you_mean(name, known.iter().copied()),
            ranked.join(", ")
        )),
    )
}

/// Every `${name}` in the strings of `node`, added to `out`.
fn collect_references(node: &Spanned<Node>, out: &mut Vec<String>) {
    match &node.value {
        Node::Scalar(Value::Str(s)) => {
            let mut rest = s.as_str();
            while let Some(start) = rest.find("${") {
                let Some(len) = rest[start + 2..].find('}') else {
                    break;
                };
                let name = &rest[start + 2..start + 2 + len];
                if !out.iter().any(|n| n == name) {
                    out.push(name.to_owned());
                }
                rest = &rest[start + 3 + len..];
            }
        }
        Node::Scalar(_) => {}
        Node::List(items) => items.iter().for_each(|i| collect_references(i, out)),
        Node::Table(t) => collect_table(t, out),
    }
}

fn collect_table(t: &Table, out: &mut Vec<String>) {
    for e in t.values() {
        collect_references(&e.value, out);
    }
}

/// `("transparency", "occupancy_order")` when a technique not chosen
/// defines param `name` in its `[params]` or uses `${name}` (a pipeline
/// param such as `shadow_weight` that self-shadowing techniques export).
fn owner_not_chosen(
    roots: &TechniqueRoots,
    chosen: &[ChosenTechnique],
    name: &str,
) -> Option<(String, String)> {
    for point in roots.points() {
        for technique in roots.choices(&point) {
            if chosen
                .iter()
                .any(|c| c.point == point && c.name == technique)
            {
                continue;
            }
            let super::Located::Found(path) = roots.locate(&point, &technique) else {
                continue;
            };
            let Ok(tree) = read_technique(&path) else {
                continue;
            };
            let mut used = Vec::new();
            collect_references(&tree, &mut used);
            if table(&tree, "params").is_some_and(|p| p.contains_key(name))
                || used.iter().any(|u| u == name)
            {
                return Some((point, technique));
            }
        }
    }
    None
}
