//! `plait techniques`: what every technique folder says about itself.

use std::path::{Path, PathBuf};

use crate::error::{Error, Spanned};
use crate::load::Node;
use crate::value::Value;

use super::{Located, TECHNIQUE_FILE, TechniqueRoots, read_technique, table, technique_table};

/// What one technique file says about itself, for `plait techniques`.
#[derive(Clone, Debug)]
pub struct TechniqueInfo {
    pub point: String,
    pub name: String,
    pub path: PathBuf,
    pub description: String,
    pub source: String,
    pub memory: String,
    /// Its `[params]`, as written (`${…}` not substituted).
    pub params: Vec<(String, String)>,
    /// What it consists of: the files of its folder (`technique.toml` and
    /// its WGSL), then the fragments it `includes`, relative to the folder.
    pub files: Vec<String>,
}

/// Every technique in `roots`, by point then name; files that do not parse
/// are reported as errors.
pub fn catalog(roots: &TechniqueRoots) -> Result<Vec<TechniqueInfo>, Vec<Error>> {
    let mut out = Vec::new();
    let mut errors = roots.problems();
    for point in roots.points() {
        for name in roots.choices(&point) {
            let Located::Found(path) = roots.locate(&point, &name) else {
                continue; // in `problems` above
            };
            match read_technique(&path) {
                Ok(tree) => {
                    let text = |key: &str| {
                        technique_table(&tree)
                            .and_then(|t| t.get(key))
                            .and_then(|e| match &e.value.value {
                                Node::Scalar(Value::Str(s)) => Some(s.clone()),
                                _ => None,
                            })
                            .unwrap_or_default()
                    };
                    // An included file's params come along with its data, but
                    // the including file may replace what used them
                    // (occupancy_no_slab's slab buffer has no `${slabs}`): a
                    // param nothing refers to tunes nothing, so it is not listed.
                    let mut used = Vec::new();
                    references(&tree, &mut used);
                    let params = table(&tree, "params")
                        .map(|t| {
                            t.iter()
                                .filter(|(k, _)| used.contains(k))
                                .map(|(k, e)| (k.clone(), describe(&e.value.value)))
                                .collect()
                        })
                        .unwrap_or_default();
                    let mut files: Vec<String> =
                        plait_assets::read_dir(path.parent().unwrap_or(Path::new("")))
                            .iter()
                            .filter_map(|p| p.file_name()?.to_str().map(str::to_owned))
                            .collect();
                    files.sort_by_key(|f| (f != TECHNIQUE_FILE, f.clone()));
                    files.extend(includes_of(&tree));
                    out.push(TechniqueInfo {
                        files,
                        point: point.clone(),
                        name: name.clone(),
                        description: text("description"),
                        source: text("source"),
                        memory: text("memory"),
                        params,
                        path,
                    });
                }
                Err(mut e) => errors.append(&mut e),
            }
        }
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(errors)
    }
}

/// The `includes` a technique names, as written (from the tree already
/// read, its includes merged under it).
fn includes_of(tree: &Spanned<Node>) -> Vec<String> {
    match technique_table(tree)
        .and_then(|t| t.get("includes"))
        .map(|e| &e.value.value)
    {
        Some(Node::List(items)) => items
            .iter()
            .filter_map(|i| match &i.value {
                Node::Scalar(Value::Str(s)) => Some(s.clone()),
                _ => None,
            })
            .collect(),
        _ => Vec::new(),
    }
}

/// Every `${name}` a tree's strings refer to.
fn references(node: &Spanned<Node>, out: &mut Vec<String>) {
    match &node.value {
        Node::Scalar(Value::Str(s)) => {
            let mut rest = s.as_str();
            while let Some(start) = rest.find("${") {
                let Some(len) = rest[start + 2..].find('}') else {
                    break;
                };
                out.push(rest[start + 2..start + 2 + len].to_owned());
                rest = &rest[start + 3 + len..];
            }
        }
        Node::Scalar(_) => {}
        Node::List(items) => items.iter().for_each(|i| references(i, out)),
        Node::Table(t) => t.values().for_each(|e| references(&e.value, out)),
    }
}

fn describe(node: &Node) -> String {
    match node {
        Node::Scalar(v) => v.to_string(),
        Node::List(items) => format!(
            "[{}]",
            items
                .iter()
                .map(|i| describe(&i.value))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Node::Table(_) => "{…}".into(),
    }
}
