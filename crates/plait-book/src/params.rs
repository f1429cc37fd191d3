//! A technique's params as its page lists them: the default as written, what
//! the pass that reads it accepts (the pass library's declared range), which
//! passes read it, and the comment its author wrote beside it.

use std::path::Path;

use plait_graph::techniques::TechniqueInfo;

use crate::context::Context;
use crate::error::BookError;

pub struct ParamRow {
    pub name: String,
    pub default: String,
    pub accepts: String,
    pub read_by: String,
    pub comment: String,
}

/// One `.toml` of the technique (its own file or one it includes).
struct Source {
    table: toml::Table,
    text: String,
}

pub fn param_rows(info: &TechniqueInfo, ctx: &Context) -> Result<Vec<ParamRow>, BookError> {
    let folder = info.path.parent().unwrap_or(Path::new(""));
    let mut sources = Vec::new();
    for f in info.files.iter().filter(|f| f.ends_with(".toml")) {
        let path = folder.join(f);
        let text = std::fs::read_to_string(&path).map_err(BookError::io(&path))?;
        let table = toml::from_str(&text).map_err(|e| BookError::content(&path, e.to_string()))?;
        sources.push(Source { table, text });
    }
    let mut rows = Vec::new();
    for (name, default) in &info.params {
        let reference = format!("${{{name}}}");
        let mut accepts = Vec::new();
        let mut read_by = Vec::new();
        let mut docs = Vec::new();
        for s in &sources {
            for (pass, pass_type, key) in pass_uses(&s.table, &reference) {
                read_by.push(format!("`{pass}` (`{pass_type}.{key}`)"));
                if let Some(p) = ctx.pass_param(&pass_type, &key) {
                    accepts.push(p.accepts.clone());
                    docs.push(p.doc.clone());
                }
            }
            for key in export_uses(&s.table, &reference) {
                read_by.push(format!("the passes that use the point (`{key}`)"));
                if let Some(p) = ctx.pass_params.iter().find(|p| p.name == key) {
                    accepts.push(p.accepts.clone());
                    docs.push(p.doc.clone());
                }
            }
            for res in size_uses(&s.table, &reference) {
                read_by.push(format!("the size of `{res}`"));
            }
        }
        accepts.dedup();
        read_by.dedup();
        rows.push(ParamRow {
            name: name.clone(),
            default: cell(default),
            accepts: if accepts.is_empty() {
                "a size: within the adapter's limits".into()
            } else {
                cell(&accepts.join("; "))
            },
            read_by: read_by.join(", "),
            // The author's comment, else the reading pass's doc.
            comment: sources
                .iter()
                .find_map(|s| comment_of(&s.text, name))
                .or_else(|| docs.into_iter().find(|d| !d.is_empty()))
                .map(|c| cell(&c))
                .unwrap_or_default(),
        });
    }
    Ok(rows)
}

fn mentions(v: &toml::Value, reference: &str) -> bool {
    match v {
        toml::Value::String(s) => s.contains(reference),
        toml::Value::Array(a) => a.iter().any(|x| mentions(x, reference)),
        toml::Value::Table(t) => t.values().any(|x| mentions(x, reference)),
        _ => false,
    }
}

/// `(pass, pass type, param key)` of every pass param that names `reference`.
fn pass_uses(table: &toml::Table, reference: &str) -> Vec<(String, String, String)> {
    let mut out = Vec::new();
    let Some(passes) = table.get("passes").and_then(|p| p.as_table()) else {
        return out;
    };
    for (pass, decl) in passes {
        let ty = decl
            .get("type")
            .and_then(|t| t.as_str())
            .unwrap_or("raster");
        if let Some(params) = decl.get("params").and_then(|p| p.as_table()) {
            for (key, v) in params {
                if mentions(v, reference) {
                    out.push((pass.clone(), ty.to_string(), key.clone()));
                }
            }
        }
    }
    out
}

/// Keys of `[technique.exports] params` that name `reference`.
fn export_uses(table: &toml::Table, reference: &str) -> Vec<String> {
    table
        .get("technique")
        .and_then(|t| t.get("exports"))
        .and_then(|e| e.get("params"))
        .and_then(|p| p.as_table())
        .map(|p| {
            p.iter()
                .filter(|(_, v)| mentions(v, reference))
                .map(|(k, _)| k.clone())
                .collect()
        })
        .unwrap_or_default()
}

/// Resources whose size names `reference`.
fn size_uses(table: &toml::Table, reference: &str) -> Vec<String> {
    table
        .get("resources")
        .and_then(|r| r.as_table())
        .map(|r| {
            r.iter()
                .filter(|(_, d)| d.get("size").is_some_and(|s| mentions(s, reference)))
                .map(|(k, _)| k.clone())
                .collect()
        })
        .unwrap_or_default()
}

/// The comment beside `name = …` in the file's `[params]` table, else the
/// comment lines right above it.
fn comment_of(text: &str, name: &str) -> Option<String> {
    let lines: Vec<&str> = text.lines().collect();
    let mut in_params = false;
    for (i, line) in lines.iter().enumerate() {
        let t = line.trim();
        if t.starts_with('[') {
            in_params = t == "[params]";
            continue;
        }
        let is_it = t
            .strip_prefix(name)
            .is_some_and(|rest| rest.trim_start().starts_with('='));
        if !in_params || !is_it {
            continue;
        }
        if let Some((_, c)) = t.split_once(" #") {
            return Some(c.trim().to_string());
        }
        let above: Vec<&str> = lines[..i]
            .iter()
            .rev()
            .take_while(|l| l.trim_start().starts_with('#'))
            .map(|l| l.trim_start().trim_start_matches('#').trim())
            .collect();
        if !above.is_empty() {
            return Some(above.into_iter().rev().collect::<Vec<_>>().join(" "));
        }
    }
    None
}

/// Text for a Markdown table cell.
pub fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_beside_or_above() {
        let text = "[params]\na = 1   # the a\n# about b,\n# two lines\nb = 2\n[passes.x]\nc = 3 # not a param\n";
        assert_eq!(comment_of(text, "a").as_deref(), Some("the a"));
        assert_eq!(comment_of(text, "b").as_deref(), Some("about b, two lines"));
        assert_eq!(comment_of(text, "c"), None);
    }

    #[test]
    fn uses_are_found() {
        let t: toml::Table = toml::from_str(
            "[passes.p]\ntype = \"deep_opacity\"\nparams = { layer_size = \"${d}\" }\n\
             [technique.exports]\nparams = { w = \"${d}\" }\n[resources.r]\nsize = \"${d} * 4\"\n",
        )
        .unwrap();
        assert_eq!(
            pass_uses(&t, "${d}"),
            [("p".into(), "deep_opacity".into(), "layer_size".into())]
        );
        assert_eq!(export_uses(&t, "${d}"), ["w"]);
        assert_eq!(size_uses(&t, "${d}"), ["r"]);
        assert!(pass_uses(&t, "${e}").is_empty());
    }
}
