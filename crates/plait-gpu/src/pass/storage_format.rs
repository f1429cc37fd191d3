//! A storage texture whose WGSL format differs from its resource's (issue
//! 41): the WGSL line declaring the binding is what the author wrote last
//! and most likely what to fix, so the error points there
//! (`file:line:column` of its `var`), and names the pipeline's slot with its
//! own location. naga's spans point into the composed module, not the
//! author's file, so the declaration is found in the text.

use std::path::Path;

use plait_graph::{Error as GraphError, ErrorKind, Location, ScheduledPass};

/// `errors` with each storage-format mismatch of `pass` moved to the WGSL
/// declaration of its binding when it is in `source`; `aliases` maps slots
/// to binding names ([`super::plan::binding_aliases`]).
pub(super) fn at_wgsl(
    errors: Vec<GraphError>,
    pass: &ScheduledPass,
    aliases: &[(String, String)],
    source: Option<(&Path, &str)>,
) -> Vec<GraphError> {
    let Some((path, text)) = source else {
        return errors;
    };
    errors
        .into_iter()
        .map(|e| match &e.kind {
            ErrorKind::FormatMismatch {
                resource,
                declared,
                slot,
                accepted,
                ..
            } if accepted.starts_with(STORAGE) => {
                let var = aliases
                    .iter()
                    .find(|(s, _)| s == slot)
                    .map_or(slot.as_str(), |(_, b)| b.as_str());
                let Some(at) = declaration(path, text, var) else {
                    return e;
                };
                let want = &accepted[STORAGE.len()..];
                GraphError::new(
                    at,
                    ErrorKind::Pass {
                        pass: pass.name.clone(),
                        message: format!(
                            "storage texture `{var}` is declared {want} here, but slot `{slot}` binds resource `{resource}`, which is {declared} ({}); declare `{var}` with {declared}, or give the resource format {want}",
                            e.location
                        ),
                    },
                )
            }
            _ => e,
        })
        .collect()
}

/// The start of [`crate::reflect::ShaderBinding::accepts_format`]'s reason
/// for a storage texture of another format.
pub(crate) const STORAGE: &str = "the shader declares storage format ";

/// `file:line:column` of `var NAME` (or `var<…> NAME`) followed by `:`.
fn declaration(path: &Path, text: &str, name: &str) -> Option<Location> {
    let mut from = 0;
    while let Some(i) = text[from..].find("var") {
        let start = from + i;
        from = start + 3;
        let before_ok = start == 0 || !is_ident(text[..start].chars().next_back()?);
        let mut rest = &text[start + 3..];
        if let Some(r) = rest.strip_prefix('<') {
            rest = &r[r.find('>')? + 1..];
        }
        let rest = rest.trim_start();
        let Some(after) = rest.strip_prefix(name) else {
            continue;
        };
        if before_ok && after.trim_start().starts_with(':') {
            let line = text[..start].matches('\n').count() as u32 + 1;
            let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
            let column = text[line_start..start].chars().count() as u32 + 1;
            return Some(Location::File {
                path: path.to_path_buf(),
                line,
                column,
            });
        }
    }
    None
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_declaration_not_a_longer_name() {
        let text = "@group(1) @binding(0) var out_wide: texture_storage_2d<r32float, write>;\n\
                    @group(1) @binding(1) var out: texture_storage_2d<rgba8unorm, write>;\n";
        let at = declaration(Path::new("a.wgsl"), text, "out").expect("found");
        assert_eq!(at.to_string(), "a.wgsl:2:23");
        assert!(declaration(Path::new("a.wgsl"), text, "missing").is_none());
    }
}
