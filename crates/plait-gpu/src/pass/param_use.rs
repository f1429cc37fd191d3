//! Whether a data-only pass's params reach its shader.
//!
//! A pass type written in Rust or declared in a pass-type file lists the
//! params it takes, so a misspelt one is an error at load. A data-only pass
//! (`raster`, `fullscreen`, `compute`) takes whatever its shader reads, and
//! its shader reads params two ways: members of a `*params` uniform, filled
//! by name, and defines (`#ifdef NAME`, `#if NAME == 3`, `#{NAME}`; a string
//! param `k = "v"` is the define `K_V`). A param neither way reaches would be
//! ignored without a word — the misspelt `shadow_wieght` rendering with the
//! default — so each one is checked against both, and the nearest name the
//! shader does read is suggested.

use std::collections::BTreeSet;

use plait_graph::{ScheduledPass, Value};

/// The define names `source` tests or substitutes.
pub fn define_names(source: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in source.lines() {
        let line = line.trim_start();
        let rest = [
            "#ifdef",
            "#ifndef",
            "#else ifdef",
            "#else ifndef",
            "#else if",
            "#if",
        ]
        .iter()
        .find_map(|d| {
            line.strip_prefix(d)
                .filter(|r| r.starts_with(char::is_whitespace))
        });
        if let Some(rest) = rest
            && let Some(name) = rest.split_whitespace().next()
        {
            out.insert(name.to_owned());
        }
        let mut text = line;
        while let Some(at) = text.find("#{") {
            let after = &text[at + 2..];
            let Some(end) = after.find('}') else { break };
            out.insert(after[..end].to_owned());
            text = &after[end..];
        }
    }
    out
}

/// The params of `pass` that reach neither a uniform member (`members`) nor a
/// define of `defines`, each with the nearest name the shader reads.
pub fn unread_params(
    pass: &ScheduledPass,
    members: &BTreeSet<String>,
    defines: &BTreeSet<String>,
) -> Vec<String> {
    let mut out = Vec::new();
    for (name, value) in &pass.params {
        if members.contains(name) {
            continue;
        }
        let upper = name.to_ascii_uppercase();
        let as_define = match value {
            Value::Int(_) | Value::Bool(_) => defines.contains(&upper),
            // Any `K_…` define: the shader chooses by this param (the value
            // picked may be the `#else`, as a default provider is).
            Value::Str(_) => {
                let prefix = format!("{upper}_");
                defines.iter().any(|d| d.starts_with(&prefix))
            }
            _ => false,
        };
        if as_define {
            continue;
        }
        let lower: Vec<String> = defines.iter().map(|d| d.to_ascii_lowercase()).collect();
        let candidates = members
            .iter()
            .map(String::as_str)
            .chain(lower.iter().map(String::as_str));
        out.push(format!(
            "param `{name}` reaches nothing in the shader (no member of a `*params` uniform is named so, and no `#ifdef` tests it){}",
            plait_graph::suggest::did_you_mean(name, candidates)
        ));
    }
    out
}

/// Every define a library module tests: a param may reach the shader through
/// a module it imports (`SELF_SHADOW_DEEP_OPACITY` is the generated selector's).
pub fn library_define_names(shaders: &crate::modules::Shaders) -> BTreeSet<String> {
    shaders
        .library()
        .map(|l| {
            l.modules
                .iter()
                .flat_map(|m| define_names(&m.source))
                .collect()
        })
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defines_are_found_in_every_directive_and_substitution() {
        let names = define_names(
            "#ifdef A\n#else ifdef B_X\n#if SLICES == 3\n  #ifndef C\nlet n = #{WORDS};\n// #ifdefx no\n",
        );
        let want: BTreeSet<String> = ["A", "B_X", "SLICES", "C", "WORDS"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        assert_eq!(names, want);
    }
}
