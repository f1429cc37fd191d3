//! `--set key=value` flags: parsed, checked against what the pipeline has
//! (a key that names nothing is an error suggesting the nearest name), and
//! merged into the loaded tree through the same merge as `extends`.

use std::path::Path;

use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::load::{
    BUFFER_KEYS, Entry, Node, PASS_KEYS, PIPELINE_KEYS, SourceMap, TEXTURE_KEYS, TOP_KEYS, Table,
    convert_value, merge,
};
use crate::value::Value;

/// `implied_points` are the choice points every pipeline has whether its
/// `[techniques]` lists them or not (a point file's `draws`: `geometry`),
/// so `--set techniques.geometry=lod` works on any pipeline.
pub(crate) fn apply_override(
    root: &mut Spanned<Node>,
    flag: &str,
    implied_points: &[String],
    errors: &mut Vec<Error>,
) {
    let location = Location::Flag {
        flag: flag.to_owned(),
    };
    let malformed = |reason: &str| {
        Error::new(
            location.clone(),
            ErrorKind::MalformedSet {
                flag: flag.to_owned(),
                reason: reason.to_owned(),
            },
        )
    };
    let Some((key, value_text)) = flag.split_once('=') else {
        return errors.push(malformed("expected `key=value`, e.g. `params.slices=64`"));
    };
    let path: Vec<&str> = key.trim().split('.').map(str::trim).collect();
    if path.iter().any(|p| p.is_empty()) {
        return errors.push(malformed(
            "the key has an empty part; write a dotted path like `passes.shade.params.color`",
        ));
    }
    // Every key on the way must be a table (or absent, then it is created).
    let mut cursor = &root.value;
    for (depth, part) in path.iter().enumerate() {
        let Node::Table(table) = cursor else {
            let prefix = path[..depth].join(".");
            return errors.push(malformed(&format!(
                "`{prefix}` is a value, not a table, so `{key}` cannot be set"
            )));
        };
        match table.get(*part) {
            Some(entry) => cursor = &entry.value.value,
            None => break,
        }
    }
    if let Err(reason) = check_override_target(&root.value, &path, implied_points) {
        return errors.push(Error::new(
            location.clone(),
            ErrorKind::UnknownSetKey {
                key: key.trim().to_owned(),
                reason,
            },
        ));
    }
    let value_text = value_text.trim();
    // A value that starts like structured TOML must be valid TOML: a bare
    // word may be a string, but `[1,` is a mistake, not the text "[1,".
    if value_text.starts_with(['[', '{', '"', '\''])
        && toml::de::DeValue::parse(value_text).is_err()
    {
        let reason = toml::de::DeValue::parse(value_text)
            .err()
            .map(|e| e.message().to_owned())
            .unwrap_or_default();
        return errors.push(malformed(&format!(
            "the value `{value_text}` is not valid TOML: {reason}"
        )));
    }
    let mut node = Spanned::new(parse_flag_value(value_text, &location), location.clone());
    for part in path.iter().rev() {
        let mut table = Table::new();
        table.insert(
            (*part).to_owned(),
            Entry {
                key: location.clone(),
                value: node,
            },
        );
        node = Spanned::new(Node::Table(table), location.clone());
    }
    merge(root, node);
}

/// A `--set` key must name something the pipeline has: a param, a pass, a
/// resource, or a key such tables accept. A typo (`params.slice` for
/// `params.slices`) would otherwise add a key nothing reads and be silently
/// ignored. A pass's params and slots are checked against its type later,
/// where a param the file leaves at its default can still be set.
fn check_override_target(
    root: &Node,
    path: &[&str],
    implied_points: &[String],
) -> Result<(), String> {
    let Node::Table(top) = root else {
        return Ok(());
    };
    let keys_of = |section: &str| -> Vec<&str> {
        match top.get(section).map(|e| &e.value.value) {
            Some(Node::Table(t)) => t.keys().map(String::as_str).collect(),
            _ => Vec::new(),
        }
    };
    let unknown = |what: &str, name: &str, known: &[&str]| {
        let list = if known.is_empty() {
            "there are none".to_owned()
        } else {
            format!("known: {}", known.join(", "))
        };
        format!(
            "there is no {what} `{name}`{} ({list})",
            crate::suggest::did_you_mean(name, known.iter().copied())
        )
    };
    let section = path[0];
    if !TOP_KEYS.contains(&section) {
        return Err(unknown("section", section, TOP_KEYS));
    }
    let Some(&name) = path.get(1) else {
        return Ok(());
    };
    let field = path.get(2).copied();
    match section {
        "params" => {
            let params = keys_of("params");
            if !params.contains(&name) {
                return Err(unknown("param", name, &params));
            }
        }
        "passes" => {
            let passes = keys_of("passes");
            if !passes.contains(&name) {
                return Err(unknown("pass", name, &passes));
            }
            if let Some(field) = field
                && !PASS_KEYS.contains(&field)
            {
                return Err(unknown(
                    &format!("key in [passes.{name}]"),
                    field,
                    PASS_KEYS,
                ));
            }
        }
        "resources" => {
            let resources = keys_of("resources");
            if !resources.contains(&name) {
                return Err(unknown("resource", name, &resources));
            }
            let accepted: Vec<&str> = TEXTURE_KEYS
                .iter()
                .chain(BUFFER_KEYS)
                .copied()
                .collect::<indexmap::IndexSet<_>>()
                .into_iter()
                .collect();
            if let Some(field) = field
                && !accepted.contains(&field)
            {
                return Err(unknown(
                    &format!("key in [resources.{name}]"),
                    field,
                    &accepted,
                ));
            }
        }
        "techniques" => {
            let mut points = keys_of("techniques");
            for implied in implied_points {
                if !points.contains(&implied.as_str()) {
                    points.push(implied);
                }
            }
            if !points.contains(&name) {
                return Err(unknown("choice point in [techniques]", name, &points));
            }
        }
        "pipeline" if !PIPELINE_KEYS.contains(&name) => {
            return Err(unknown("key in [pipeline]", name, PIPELINE_KEYS));
        }
        _ => {}
    }
    Ok(())
}

/// TOML if it parses (`64`, `0.5`, `[1, 2]`, `"x"`), else the bare text as
/// a string, so `type=deep_opacity` needs no quotes.
fn parse_flag_value(text: &str, location: &Location) -> Node {
    let Ok(parsed) = toml::de::DeValue::parse(text) else {
        return Node::Scalar(Value::Str(text.to_owned()));
    };
    // Locations inside a flag all point at the flag itself.
    let map = SourceMap::new(Path::new(""), text);
    let mut errors = Vec::new();
    match convert_value(&parsed, &map, &mut errors) {
        Some(node) => relocate(node.value, location),
        None => Node::Scalar(Value::Str(text.to_owned())),
    }
}

fn relocate(node: Node, location: &Location) -> Node {
    match node {
        Node::Scalar(v) => Node::Scalar(v),
        Node::List(items) => Node::List(
            items
                .into_iter()
                .map(|i| Spanned::new(relocate(i.value, location), location.clone()))
                .collect(),
        ),
        Node::Table(t) => Node::Table(
            t.into_iter()
                .map(|(k, e)| {
                    let value = Spanned::new(relocate(e.value.value, location), location.clone());
                    (
                        k,
                        Entry {
                            key: location.clone(),
                            value,
                        },
                    )
                })
                .collect(),
        ),
    }
}
