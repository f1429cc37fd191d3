//! A chosen technique's exports reach the passes that use its point: those
//! that list it in `uses`, and every pass drawing a geometry its point file
//! `draws` (the `geometry` point: every hair draw). A compute pass that draws
//! hair its own way (the compute rasterizer) `uses` such a point too, and,
//! like a draw, gets its default when the pipeline does not choose it.

use crate::error::{Error, Location, Spanned};
use crate::load::{Entry, Node, Table, merge};
use crate::suggest::did_you_mean;
use crate::value::Value;

use super::schema;

/// What a chosen point's technique exports to the passes that use it.
pub(super) struct PointExports {
    pub(super) point: String,
    pub(super) reads: Option<Table>,
    pub(super) params: Option<Table>,
    /// The geometries whose every pass uses the point without `uses`
    /// (its point file's `draws`).
    pub(super) draws: Vec<String>,
}

/// Merge each used point's exports into the passes that `uses` it, and into
/// every pass drawing a geometry a point's file `draws`.
pub(super) fn give_exports(
    root: &mut Spanned<Node>,
    exports: &[PointExports],
    implicit: &[String],
    has_table: bool,
    errors: &mut Vec<Error>,
) {
    let Node::Table(top) = &mut root.value else {
        return;
    };
    let Some(Entry {
        value: Spanned {
            value: Node::Table(passes),
            ..
        },
        ..
    }) = top.get_mut("passes")
    else {
        return;
    };
    for (pass_name, pass) in passes.iter_mut() {
        let Node::Table(fields) = &mut pass.value.value else {
            continue;
        };
        let mut used: Vec<(&PointExports, Location)> = Vec::new();
        if let Some(uses) = fields.shift_remove("uses") {
            let Node::List(items) = &uses.value.value else {
                errors.push(schema(
                    &uses.value.location,
                    format!(
                        "passes.{pass_name}.uses lists choice points, e.g. `uses = [\"self_shadow\"]`"
                    ),
                ));
                continue;
            };
            for item in items {
                let Node::Scalar(Value::Str(point)) = &item.value else {
                    errors.push(schema(
                        &item.location,
                        "`uses` lists choice point names".into(),
                    ));
                    continue;
                };
                let Some(export) = exports.iter().find(|e| &e.point == point) else {
                    // Unchosen, a point joined to every draw (`draws`, the
                    // `geometry` point) is its WGSL default: nothing to give,
                    // as for the draws themselves.
                    if implicit.contains(point) {
                        continue;
                    }
                    let known: Vec<&str> = exports.iter().map(|e| e.point.as_str()).collect();
                    errors.push(schema(
                        &item.location,
                        if has_table {
                            format!(
                                "pass `{pass_name}` uses `{point}`, which [techniques] does not choose{} (chosen: {})",
                                did_you_mean(point, known.iter().copied()),
                                known.join(", ")
                            )
                        } else {
                            format!("pass `{pass_name}` uses `{point}`, but the pipeline has no [techniques] table choosing one")
                        },
                    ));
                    continue;
                };
                used.push((export, item.location.clone()));
            }
        }
        // A point the pass's geometry joins it to, unless `uses` named it.
        if let Some(draw) = fields.get("draw")
            && let Node::Scalar(Value::Str(geometry)) = &draw.value.value
        {
            for export in exports.iter().filter(|e| e.draws.contains(geometry)) {
                if !used.iter().any(|(u, _)| u.point == export.point) {
                    used.push((export, draw.value.location.clone()));
                }
            }
        }
        for (export, at) in used {
            give(fields, export, &at);
        }
    }
}

/// Merges one point's exports into a pass's `reads` and `params` (the
/// pass's own entries win); `at` is where the pass came to use it.
fn give(fields: &mut Table, export: &PointExports, at: &Location) {
    for (section, export) in [("reads", &export.reads), ("params", &export.params)] {
        let Some(export) = export else { continue };
        let exported = Spanned::new(Node::Table(export.clone()), at.clone());
        match fields.get_mut(section) {
            Some(own) => {
                // The pass's own entries win: merge them over the exports.
                let mine = std::mem::replace(&mut own.value, exported);
                merge(&mut own.value, mine);
            }
            None => {
                fields.insert(
                    section.to_owned(),
                    Entry {
                        key: at.clone(),
                        value: exported,
                    },
                );
            }
        }
    }
}
