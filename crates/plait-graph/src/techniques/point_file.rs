//! What a choice point promises, declared as data: `techniques/<point>/point.toml`.
//!
//! ```toml
//! [point]
//! writes = ["final"]                    # every technique of the point writes these
//! draws = ["hair"]                      # every pass drawing these uses the point, unasked
//!
//! [wgsl]                                # a point answered in WGSL
//! param = "self_shadow"
//! param = "self_shadow"                  # the pass param naming the provider
//! providers = "plait::self_shadow"       # provider NAME is module plait::self_shadow::NAME
//! function = "fn hair_visibility(world: vec3<f32>) -> f32"   # what each provider defines
//! module = "plait::self_shadow"         # the selector plait generates
//! call = "self_shadow"                  # its function, same signature
//! default = "none"                      # the provider when the param is unset
//! doc = "Fraction of the light reaching `world` through the hair."
//!
//! [wgsl.optional]                       # a second function only some providers define
//! function = "fn hair_strands_along_light(world: vec3<f32>) -> vec2<f32>"
//! call = "strands_along_light"          # defined by the selector only for those providers
//! doc = "Strands between `world` and the key light (x) and behind it along the light's ray (y)."
//!
//! [wgsl.also]                           # a second function every provider defines
//! function = "fn hair_uniform(tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32>"
//! call = "shade_uniform"                # the selector's, as for `function`
//! doc = "Radiance towards the eye per unit radiance of a uniform environment."
//! ```
//!
//! `[point] implicit = true` lets a pass `uses` the point when the pipeline
//! does not choose it (its WGSL default applies), as `draws` does: a point
//! added to every hair-shading pass (`multiple_scattering`) leaves every
//! pipeline that does not name it as it was.
//!
//! An optional function is part of a provider's contract only if the
//! provider defines it; a technique says so in its `[technique] provides`
//! list, and another technique's `[technique.requires]` names it
//! (`super::requires`). The selector defines `call` inside an `#ifdef` over
//! the providers that define it, so a pass whose provider lacks it fails to
//! compose rather than reading a made-up value — the load check refuses that
//! combination first.
//!
//! `writes` is checked when a technique is chosen: one of its passes must
//! write each resource named (a transparency technique composes `final`).
//! `draws` makes the point part of every pass that draws that geometry, as
//! if the pass listed it in `uses`: the `geometry` point decides which
//! strands every hair draw rasterizes, so no pass, technique or pipeline
//! file has to remember to ask for it.
//!
//! Every technique of a WGSL point ships a WGSL module declaring
//! `#define_import_path <providers>::<name>` wherever it lives on the search
//! path (usually its own technique folder). The shader library finds those
//! modules, checks each defines `function` with this signature, and
//! generates the selector `module`: an `#ifdef <PARAM>_<NAME>` chain over the
//! providers it found, so no selector is edited by hand and no list names a
//! provider.

use std::path::Path;

use crate::error::{Errors, Location, Spanned};
use crate::load::{Node, parse_file};
use crate::node_reader::Reader;

use super::point_contract::{self, PointContract};
use super::point_optional::{OptionalFunction, argument_names, read_optional};

/// The file in a point's folder that declares its WGSL contract.
pub const POINT_FILE: &str = "point.toml";

/// One point's WGSL contract (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct WgslPoint {
    /// The point's folder name (`self_shadow`).
    pub point: String,
    /// The file it was read from.
    pub file: Location,
    pub param: String,
    pub providers: String,
    /// The provider function's name, arguments (`world: vec3<f32>`) and
    /// return type, from `function`.
    pub function: String,
    pub arguments: String,
    pub returns: String,
    pub module: String,
    pub call: String,
    pub default: Spanned<String>,
    pub doc: String,
    /// Its providers' bindings, slots and params (`point_contract`).
    pub contract: PointContract,
    /// The function only some providers define (`[wgsl.optional]`).
    pub optional: Option<OptionalFunction>,
    /// A second function every provider defines (`[wgsl.also]`): checked
    /// and selected as `function` is.
    pub also: Option<OptionalFunction>,
}

const KEYS: &[&str] = &[
    "param",
    "providers",
    "function",
    "module",
    "call",
    "default",
    "doc",
    "optional",
    "also",
];

impl WgslPoint {
    /// `fn NAME(ARGS) -> RET`, as a provider must write it.
    pub fn signature(&self) -> String {
        format!(
            "fn {}({}) -> {}",
            self.function, self.arguments, self.returns
        )
    }

    /// The define a pass's param value turns into (`SELF_SHADOW_DEEP_OPACITY`).
    pub fn define(&self, provider: &str) -> String {
        format!("{}_{}", self.param, provider).to_ascii_uppercase()
    }

    /// The argument names, in order (`world`).
    pub fn argument_names(&self) -> Vec<&str> {
        argument_names(&self.arguments)
    }

    /// The selector module's WGSL for the providers found (sorted names):
    /// the generated text is the only place the chain exists. `with_optional`
    /// names the providers that define the optional function.
    pub fn selector_source(&self, providers: &[String], with_optional: &[String]) -> String {
        let mut s = format!(
            "// Generated by plait from {} and the providers found on the search path.\n\
             #define_import_path {}\n\n",
            self.file, self.module
        );
        for (i, name) in providers.iter().enumerate() {
            let directive = if i == 0 { "#ifdef" } else { "#else ifdef" };
            s += &format!(
                "{directive} {}\n#import {}::{name}::{}\n",
                self.define(name),
                self.providers,
                self.function
            );
            if let Some(o) = &self.optional
                && with_optional.contains(name)
            {
                s += &format!("#import {}::{name}::{}\n", self.providers, o.function);
            }
            if let Some(a) = &self.also {
                s += &format!("#import {}::{name}::{}\n", self.providers, a.function);
            }
        }
        if !providers.is_empty() {
            s += "#else\n";
        }
        s += &format!(
            "#import {}::{}::{}\n",
            self.providers, self.default.value, self.function
        );
        if let Some(a) = &self.also {
            s += &format!(
                "#import {}::{}::{}\n",
                self.providers, self.default.value, a.function
            );
        }
        if !providers.is_empty() {
            s += "#endif\n";
        }
        s += &format!(
            "\n// {}\nfn {}({}) -> {} {{\n    return {}({});\n}}\n",
            self.doc,
            self.call,
            self.arguments,
            self.returns,
            self.function,
            self.argument_names().join(", ")
        );
        if let Some(a) = &self.also {
            s += &format!(
                "\n// {}\nfn {}({}) -> {} {{\n    return {}({});\n}}\n",
                a.doc,
                a.call,
                a.arguments,
                a.returns,
                a.function,
                a.argument_names().join(", ")
            );
        }
        if let Some(o) = &self.optional {
            s += &self.optional_source(o, with_optional);
        }
        s
    }
}

/// A point file: what the point's techniques write, and its WGSL contract.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PointFile {
    /// Resources one of each technique's passes must write.
    pub writes: Vec<Spanned<String>>,
    /// Geometries (`draw` values) whose every pass uses the point.
    pub draws: Vec<Spanned<String>>,
    /// A pass may `uses` the point unchosen: its WGSL default applies.
    pub implicit: bool,
    pub wgsl: Option<WgslPoint>,
}

/// Parse a point file (`point` is its folder's name; `path` names it in messages).
pub fn parse(point: &str, path: &Path, text: &str) -> Result<PointFile, Errors> {
    let root = parse_file(path, text)?;
    let mut errors = Vec::new();
    let parsed = read(
        &mut Reader {
            errors: &mut errors,
        },
        point,
        &root,
    );
    match parsed {
        Some(p) if errors.is_empty() => Ok(p),
        _ => Err(Errors(errors)),
    }
}

fn read(r: &mut Reader<'_>, point: &str, root: &Spanned<Node>) -> Option<PointFile> {
    let top = r.table(root, "a point file")?;
    r.keys(
        top,
        &["point", "wgsl", "inputs", "params", "params_from"],
        "a point file",
    );
    let mut file = PointFile::default();
    let mut point_table = None;
    if let Some(p) = top.get("point") {
        let t = r.table(&p.value, "[point]")?;
        point_table = Some(t);
        r.keys(
            t,
            &[&["writes", "draws", "implicit"], point_contract::POINT_KEYS].concat(),
            "[point]",
        );
        if let Some(e) = t.get("implicit") {
            match &e.value.value {
                Node::Scalar(crate::value::Value::Bool(b)) => file.implicit = *b,
                _ => r.schema(&e.value.location, "point.implicit is true or false".into()),
            }
        }
        for (key, what, list) in [
            ("writes", "resource names", &mut file.writes),
            ("draws", "geometries (`draw` values)", &mut file.draws),
        ] {
            let Some(w) = t.get(key) else { continue };
            let Node::List(items) = &w.value.value else {
                r.schema(
                    &w.value.location,
                    format!("point.{key} must be a list of {what}"),
                );
                return None;
            };
            for item in items {
                let name = r.string(item, &format!("point.{key}"))?;
                list.push(Spanned::new(name, item.location.clone()));
            }
        }
        for d in &file.draws {
            if !crate::Draw::NAMES.contains(&d.value.as_str()) {
                r.schema(
                    &d.location,
                    format!(
                        "point.draws: no geometry `{}`{} (draw values: {})",
                        d.value,
                        crate::suggest::did_you_mean(&d.value, crate::Draw::NAMES.iter().copied()),
                        crate::Draw::NAMES.join(", ")
                    ),
                );
            }
        }
    }
    let contract = point_contract::read(r, top, point_table);
    if let Some(wgsl) = top.get("wgsl") {
        let mut w = read_wgsl(r, point, root, wgsl)?;
        w.contract = contract;
        file.wgsl = Some(w);
    } else if contract != PointContract::default() {
        r.schema(
            &root.location,
            "bindings, [inputs], [params] and [params_from] are a WGSL point's: this file has no [wgsl]".into(),
        );
    }
    Some(file)
}

fn read_wgsl(
    r: &mut Reader<'_>,
    point: &str,
    root: &Spanned<Node>,
    wgsl: &crate::load::Entry,
) -> Option<WgslPoint> {
    let t = r.table(&wgsl.value, "[wgsl]")?;
    r.keys(t, KEYS, "[wgsl]");
    let mut field = |key: &str| -> Option<Spanned<String>> {
        let Some(e) = t.get(key) else {
            r.schema(&wgsl.key, format!("[wgsl] needs `{key}`"));
            return None;
        };
        let s = r.string(&e.value, &format!("wgsl.{key}"))?;
        Some(Spanned::new(s, e.value.location.clone()))
    };
    let (param, providers, function, module, call, default, doc) = (
        field("param"),
        field("providers"),
        field("function"),
        field("module"),
        field("call"),
        field("default"),
        field("doc"),
    );
    let optional = match t.get("optional") {
        Some(e) => Some(read_optional(r, e, "optional")?),
        None => None,
    };
    let also = match t.get("also") {
        Some(e) => Some(read_optional(r, e, "also")?),
        None => None,
    };
    let function = function?;
    let Some((name, arguments, returns)) = split_signature(&function) else {
        r.schema(
            &function.location,
            format!(
                "wgsl.function must read `fn NAME(ARGUMENTS) -> TYPE`, not `{}`",
                function.value
            ),
        );
        return None;
    };
    Some(WgslPoint {
        point: point.to_owned(),
        file: match &root.location {
            Location::File { path, .. } => Location::Path { path: path.clone() },
            other => other.clone(),
        },
        param: param?.value,
        providers: providers?.value,
        function: name,
        arguments,
        returns,
        module: module?.value,
        call: call?.value,
        default: default?,
        doc: doc?.value,
        contract: PointContract::default(),
        optional,
        also,
    })
}

/// The resources a technique's passes (its includes' too) write.
fn written(technique: &Spanned<Node>) -> Vec<String> {
    let Node::Table(top) = &technique.value else {
        return Vec::new();
    };
    let Some(Node::Table(passes)) = top.get("passes").map(|e| &e.value.value) else {
        return Vec::new();
    };
    passes
        .values()
        .filter_map(|pass| match &pass.value.value {
            Node::Table(t) => match t.get("writes").map(|e| &e.value.value) {
                Some(Node::Table(w)) => Some(w.values()),
                _ => None,
            },
            _ => None,
        })
        .flatten()
        .filter_map(|e| match &e.value.value {
            Node::Scalar(crate::value::Value::Str(r)) => Some(r.clone()),
            _ => None,
        })
        .collect()
}

/// One error per resource the point promises that no pass of the technique
/// `point/name` writes, at the technique's `[technique]` table.
pub(crate) fn check_writes(
    promise: &PointFile,
    point: &str,
    name: &str,
    technique: &Spanned<Node>,
) -> Vec<crate::Error> {
    let written = written(technique);
    let at = match &technique.value {
        Node::Table(top) => top
            .get("technique")
            .map_or(technique.location.clone(), |e| e.key.clone()),
        _ => technique.location.clone(),
    };
    promise
        .writes
        .iter()
        .filter(|w| !written.contains(&w.value))
        .map(|w| {
            crate::Error::new(
                at.clone(),
                crate::ErrorKind::Schema(format!(
                    "{point} technique `{name}`: no pass writes `{}`, which every {point} technique must write (promised at {})",
                    w.value, w.location
                )),
            )
        })
        .collect()
}

/// `fn NAME(ARGS) -> RET` → (NAME, ARGS, RET).
pub(super) fn split_signature(text: &str) -> Option<(String, String, String)> {
    let rest = text.trim().strip_prefix("fn ")?;
    let (name, rest) = rest.split_once('(')?;
    let (args, ret) = rest.rsplit_once(')')?;
    let ret = ret.trim().strip_prefix("->")?.trim();
    let name = name.trim();
    let ident = |s: &str| {
        !s.is_empty()
            && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !s.starts_with(|c: char| c.is_ascii_digit())
    };
    (ident(name) && !ret.is_empty())
        .then(|| (name.to_owned(), args.trim().to_owned(), ret.to_owned()))
}

/// The WGSL contract of every point file of the library
/// (`techniques/*/point.toml` under `roots` — a pipeline's own folders, then
/// the search path — and then the built-in copies) that has one; the errors
/// of every broken file.
pub fn wgsl_points(roots: &[std::path::PathBuf]) -> Result<Vec<WgslPoint>, Errors> {
    let mut points = Vec::new();
    let mut errors = Vec::new();
    for (key, path) in plait_assets::list_tree_in(roots, super::TECHNIQUES_DIR, "toml") {
        let parts: Vec<&str> = key.split('/').collect();
        let [_, point, file] = parts.as_slice() else {
            continue;
        };
        if *file != POINT_FILE {
            continue;
        }
        let text = match plait_assets::read_to_string(&path) {
            Ok(t) => t,
            Err(e) => {
                errors.push(crate::Error::new(
                    Location::Path { path: path.clone() },
                    crate::ErrorKind::Schema(format!("cannot read file: {e}")),
                ));
                continue;
            }
        };
        match parse(point, &path, &text) {
            Ok(p) => points.extend(p.wgsl),
            Err(e) => errors.extend(e.0),
        }
    }
    if errors.is_empty() {
        Ok(points)
    } else {
        Err(Errors(errors))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A point file with a `[wgsl]` contract (the optional-function tests
    /// extend it).
    pub(crate) const GOOD: &str = r#"
[wgsl]
param = "self_shadow"
providers = "plait::self_shadow"
function = "fn hair_visibility(world: vec3<f32>) -> f32"
module = "plait::self_shadow"
call = "self_shadow"
default = "none"
doc = "Fraction of the light reaching `world`."
"#;

    #[test]
    fn a_point_file_generates_its_selector() {
        let p = parse("self_shadow", Path::new("point.toml"), GOOD)
            .expect("parses")
            .wgsl
            .expect("a [wgsl] table");
        assert_eq!(p.signature(), "fn hair_visibility(world: vec3<f32>) -> f32");
        assert_eq!(p.define("deep_opacity"), "SELF_SHADOW_DEEP_OPACITY");
        let s = p.selector_source(&["deep_opacity".into(), "none".into()], &[]);
        assert!(
            s.contains("#define_import_path plait::self_shadow\n"),
            "{s}"
        );
        assert!(
            s.contains(
                "#ifdef SELF_SHADOW_DEEP_OPACITY\n#import plait::self_shadow::deep_opacity::hair_visibility\n"
            ),
            "{s}"
        );
        assert!(s.contains("#else ifdef SELF_SHADOW_NONE\n"), "{s}");
        assert!(
            s.contains("#else\n#import plait::self_shadow::none::hair_visibility\n#endif\n"),
            "{s}"
        );
        assert!(
            s.contains(
                "fn self_shadow(world: vec3<f32>) -> f32 {\n    return hair_visibility(world);\n}"
            ),
            "{s}"
        );
    }

    #[test]
    fn a_point_file_may_promise_writes_alone() {
        let p = parse(
            "transparency",
            Path::new("point.toml"),
            "[point]\nwrites = [\"final\"]\n",
        )
        .expect("parses");
        assert_eq!(p.wgsl, None);
        assert_eq!(p.writes.len(), 1);
        assert_eq!(p.writes[0].value, "final");
        assert_eq!(p.writes[0].location.to_string(), "point.toml:2:11");
    }

    #[test]
    fn a_point_file_may_join_every_draw_of_a_geometry() {
        let p = parse(
            "geometry",
            Path::new("point.toml"),
            "[point]\ndraws = [\"hair\"]\n",
        )
        .expect("parses");
        assert_eq!(p.draws.len(), 1);
        assert_eq!(p.draws[0].value, "hair");
        let text = parse(
            "geometry",
            Path::new("point.toml"),
            "[point]\ndraws = [\"hairs\"]\n",
        )
        .unwrap_err()
        .to_string();
        assert!(text.contains("point.toml:2:10"), "{text}");
        assert!(
            text.contains("no geometry `hairs`; did you mean `hair`?"),
            "{text}"
        );
    }

    #[test]
    fn a_point_contract_is_read_and_its_mistakes_located() {
        let text = format!(
            "[point]\nbindings = [8, 15]\n{GOOD}\n[inputs.vis_x]\nkind = \"buffer\"\naccess = \"storage_read\"\n\n[params.w]\ntype = \"float\"\ndefault = 0.5\nmin = 0.0\nmax = 1.0\n"
        );
        let p = parse("self_shadow", Path::new("point.toml"), &text)
            .expect("parses")
            .wgsl
            .expect("[wgsl]");
        let c = &p.contract;
        assert_eq!(c.bindings.as_ref().map(|b| b.value), Some((8, 15)));
        assert_eq!(c.inputs.len(), 1);
        assert!(c.inputs[0].optional, "a provider's slot is optional");
        assert_eq!(c.params[0].spec.name, "w");
        let bad = text.replace("bindings = [8, 15]", "bindings = [15, 8]");
        let e = parse("self_shadow", Path::new("point.toml"), &bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains("point.toml:2:12"), "{e}");
        assert!(e.contains("FIRST ≤ LAST"), "{e}");
        let bad = text.replace("access = \"storage_read\"", "acess = \"storage_read\"");
        let e = parse("self_shadow", Path::new("point.toml"), &bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains("did you mean `access`"), "{e}");
    }

    #[test]
    fn a_broken_point_file_names_the_key() {
        let bad = GOOD.replace(
            "fn hair_visibility(world: vec3<f32>) -> f32",
            "hair_visibility",
        );
        let e = parse("self_shadow", Path::new("point.toml"), &bad).unwrap_err();
        let text = e.to_string();
        assert!(text.contains("point.toml:5:"), "{text}");
        assert!(text.contains("fn NAME(ARGUMENTS) -> TYPE"), "{text}");
        let typo = GOOD.replace("call =", "cal =");
        let text = parse("self_shadow", Path::new("point.toml"), &typo)
            .unwrap_err()
            .to_string();
        assert!(text.contains("unknown key `cal`"), "{text}");
        assert!(text.contains("did you mean `call`"), "{text}");
    }
}
