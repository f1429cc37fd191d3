//! `[wgsl.optional]` of a point file: a function only some providers
//! define (the self_shadow point's `hair_strands_along_light`), and the part
//! of the generated selector that defines its `call` (see
//! [`super::point_file`]'s module docs).

use crate::error::Spanned;
use crate::node_reader::Reader;

use super::point_file::{WgslPoint, split_signature};

/// `[wgsl.optional]`: a function some providers define besides `function`.
#[derive(Clone, Debug, PartialEq)]
pub struct OptionalFunction {
    pub function: String,
    pub arguments: String,
    pub returns: String,
    pub call: String,
    pub doc: String,
}

impl OptionalFunction {
    /// The argument names, in order.
    pub(super) fn argument_names(&self) -> Vec<&str> {
        argument_names(&self.arguments)
    }
}

pub fn argument_names(arguments: &str) -> Vec<&str> {
    arguments
        .split(',')
        .filter_map(|a| a.split(':').next())
        .map(str::trim)
        .filter(|a| !a.is_empty())
        .collect()
}

impl WgslPoint {
    /// `call` of the optional function: the provider's when the chosen
    /// provider defines it, else −1 in every component ("no count":
    /// `TYPE(-1.0)`, a splat for a vector), so a module that calls it
    /// composes with any provider (the contract check composes each with no
    /// defines). A pipeline never reaches the −1: a technique that reads the
    /// function requires a provider that defines it (`[technique.requires]`,
    /// refused at load).
    pub(super) fn optional_source(&self, o: &OptionalFunction, with_optional: &[String]) -> String {
        let mut s = format!(
            "\n// {}\nfn {}({}) -> {} {{\n",
            o.doc, o.call, o.arguments, o.returns
        );
        for (i, name) in with_optional.iter().enumerate() {
            let directive = if i == 0 { "#ifdef" } else { "#else ifdef" };
            s += &format!(
                "{directive} {}\n    return {}({});\n",
                self.define(name),
                o.function,
                o.argument_names().join(", ")
            );
        }
        if !with_optional.is_empty() {
            s += "#else\n";
        }
        s += &format!("    return {}(-1.0);\n", o.returns);
        if !with_optional.is_empty() {
            s += "#endif\n";
        }
        s += "}\n";
        s
    }
}

/// `[wgsl.optional]` or `[wgsl.also]` (`table`): `function`, `call` and `doc`.
pub(super) fn read_optional(
    r: &mut Reader<'_>,
    e: &crate::load::Entry,
    table: &str,
) -> Option<OptionalFunction> {
    let label = format!("[wgsl.{table}]");
    let t = r.table(&e.value, &label)?;
    r.keys(t, &["function", "call", "doc"], &label);
    let mut field = |key: &str| -> Option<Spanned<String>> {
        let Some(x) = t.get(key) else {
            r.schema(&e.key, format!("{label} needs `{key}`"));
            return None;
        };
        let s = r.string(&x.value, &format!("wgsl.{table}.{key}"))?;
        Some(Spanned::new(s, x.value.location.clone()))
    };
    let (function, call, doc) = (field("function"), field("call"), field("doc"));
    let function = function?;
    let Some((name, arguments, returns)) = split_signature(&function.value) else {
        r.schema(
            &function.location,
            format!(
                "wgsl.{table}.function must read `fn NAME(ARGUMENTS) -> TYPE`, not `{}`",
                function.value
            ),
        );
        return None;
    };
    Some(OptionalFunction {
        function: name,
        arguments,
        returns,
        call: call?.value,
        doc: doc?.value,
    })
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::super::point_file::parse;

    use super::super::point_file::tests::GOOD;

    #[test]
    fn an_optional_function_is_defined_for_the_providers_that_have_it() {
        let text = format!(
            "{GOOD}\n[wgsl.optional]\nfunction = \"fn hair_strands_along_light(world: vec3<f32>) -> vec2<f32>\"\ncall = \"strands_along_light\"\ndoc = \"Strands in front of and behind the point.\"\n"
        );
        let p = parse("self_shadow", Path::new("point.toml"), &text)
            .expect("parses")
            .wgsl
            .expect("a [wgsl] table");
        let s = p.selector_source(
            &["deep_opacity".into(), "none".into()],
            &["deep_opacity".into()],
        );
        assert!(
            s.contains(
                "#ifdef SELF_SHADOW_DEEP_OPACITY\n#import plait::self_shadow::deep_opacity::hair_visibility\n#import plait::self_shadow::deep_opacity::hair_strands_along_light\n"
            ),
            "{s}"
        );
        assert!(
            s.contains(
                "fn strands_along_light(world: vec3<f32>) -> vec2<f32> {\n#ifdef SELF_SHADOW_DEEP_OPACITY\n    return hair_strands_along_light(world);\n#else\n    return vec2<f32>(-1.0);\n#endif\n}"
            ),
            "{s}"
        );
        // `none` lacks it: no import of it anywhere.
        assert!(!s.contains("none::hair_strands_along_light"), "{s}");
        let bad = text.replace(
            "fn hair_strands_along_light(world: vec3<f32>) -> vec2<f32>",
            "strands",
        );
        let e = parse("self_shadow", Path::new("point.toml"), &bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains("wgsl.optional.function must read"), "{e}");
    }

    #[test]
    fn a_second_function_is_selected_for_every_provider() {
        let text = format!(
            "{GOOD}\n[wgsl.also]\nfunction = \"fn hair_uniform(to_eye: vec3<f32>) -> vec3<f32>\"\ncall = \"shade_uniform\"\ndoc = \"Under a uniform environment.\"\n"
        );
        let p = parse("self_shadow", Path::new("point.toml"), &text)
            .expect("parses")
            .wgsl
            .expect("a [wgsl] table");
        let s = p.selector_source(&["deep_opacity".into(), "none".into()], &[]);
        for provider in ["deep_opacity", "none"] {
            assert!(
                s.contains(&format!(
                    "#import plait::self_shadow::{provider}::hair_uniform\n"
                )),
                "{s}"
            );
        }
        assert!(
            s.contains(
                "fn shade_uniform(to_eye: vec3<f32>) -> vec3<f32> {\n    return hair_uniform(to_eye);\n}"
            ),
            "{s}"
        );
        let bad = text.replace("fn hair_uniform(to_eye: vec3<f32>) -> vec3<f32>", "uniform");
        let e = parse("self_shadow", Path::new("point.toml"), &bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains("wgsl.also.function must read"), "{e}");
    }
}
