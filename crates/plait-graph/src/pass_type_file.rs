//! Pass types declared in TOML next to their WGSL (`shaders/passes/*.toml`):
//! a pass type whose Rust would only restate its slots, params and state.
//!
//! ```toml
//! [pass_type]
//! name = "occupancy"
//! shape = "raster"                        # raster | fullscreen | compute
//! source = "Sintorn & Assarsson 2009 §3.1"
//! description = "One bit per depth slice per texel (atomicOr)."
//! shader = "occupancy.wgsl"               # next to this file
//! # depth = { compare = "less" }  blend = { … }  cull = "none"   (defaults a pass may override)
//!
//! [inputs.range]
//! kind = "texture"                        # texture | buffer
//! access = "sampled"                      # sampled | storage_read | storage_write | color_target | depth_target | uniform
//! formats = ["rg32float"]                 # textures; omitted: any
//! doc = "depth range of the same view"
//!
//! [outputs.bits]
//! kind = "buffer"
//! access = "storage_write"
//! doc = "occupancy bits"
//! words_per_texel = { of = "range", max = 32, hint = "one word holds 32 slices" }
//!
//! [params.layer_size]
//! type = "float"                          # float | int | bool | enum | text | vec3
//! default = 0.05
//! min = 1e-6
//! max = 1e6
//! doc = "size of the first layer in world units"
//! ```
//!
//! `words_per_texel` is the size check `plait check` makes of light-map
//! buffers (u32 words per texel of the map slot `of`, a multiple of
//! `multiple`, at most `max`); `binding` names the shader variable of a slot
//! when it is not the slot's name.

use std::path::Path;

use crate::error::{Errors, Location, Spanned};
use crate::format::Format;
use crate::load::{Node, Table, parse_file};
use crate::node_reader::Reader;
use crate::raster_decl::{self, RasterDecl};
use crate::spec::{
    Access, Formats, ParamSpec, ParamType, PassShape, PassTypeSpec, ResourceKind, SlotSpec,
};
use crate::value::Value;

/// A buffer that holds a whole number of u32 words per texel of a map.
#[derive(Clone, Debug, PartialEq)]
pub struct WordsPerTexel {
    /// The buffer's slot.
    pub slot: String,
    /// The texture slot whose texels it follows.
    pub of: String,
    pub multiple: u64,
    pub max: u64,
    /// Why, in the terms of the pass (added to the error message).
    pub hint: Option<String>,
}

/// A pass type read from a TOML file.
#[derive(Clone, Debug)]
pub struct PassTypeFile {
    pub spec: PassTypeSpec,
    /// The WGSL file as written, relative to the pass-type file's folder.
    pub shader: Spanned<String>,
    /// State defaults a pass of this type may override key by key.
    pub raster: RasterDecl,
    pub words_per_texel: Vec<WordsPerTexel>,
}

const TOP_KEYS: &[&str] = &["pass_type", "inputs", "outputs", "params"];
const TYPE_KEYS: &[&str] = &[
    "name",
    "shape",
    "source",
    "description",
    "shader",
    "features",
    "depth",
    "blend",
    "cull",
];
const SLOT_KEYS: &[&str] = &[
    "kind",
    "access",
    "formats",
    "doc",
    "optional",
    "loads",
    "binding",
    "words_per_texel",
];
const WORDS_KEYS: &[&str] = &["of", "multiple", "max", "hint"];
const PARAM_KEYS: &[&str] = &["type", "default", "min", "max", "choices", "doc"];
const SHAPES: &[&str] = &["raster", "fullscreen", "compute"];
const KINDS: &[&str] = &["texture", "buffer", "acceleration_structure"];
/// A pass builds an acceleration structure or traces rays through it.
const STRUCTURE_ACCESS: &[&str] = &["storage_read", "storage_write"];
const TEXTURE_ACCESS: &[&str] = &[
    "sampled",
    "storage_read",
    "storage_write",
    "color_target",
    "depth_target",
];
const BUFFER_ACCESS: &[&str] = &["storage_read", "storage_write", "uniform"];
const PARAM_TYPES: &[&str] = &["float", "int", "bool", "enum", "text", "vec3"];

/// Parse a pass-type file (`path` names it in messages).
pub fn parse(path: &Path, text: &str) -> Result<PassTypeFile, Errors> {
    let root = parse_file(path, text)?;
    let mut errors = Vec::new();
    let parsed = {
        let mut r = Reader {
            errors: &mut errors,
        };
        read_file(&mut r, &root)
    };
    match parsed {
        Some(file) if errors.is_empty() => Ok(file),
        _ => Err(Errors(errors)),
    }
}

fn read_file(r: &mut Reader<'_>, root: &Spanned<Node>) -> Option<PassTypeFile> {
    let top = r.table(root, "a pass-type file")?;
    r.keys(top, TOP_KEYS, "a pass-type file");
    let Some(type_entry) = top.get("pass_type") else {
        r.schema(
            &root.location,
            "a pass-type file needs a [pass_type] table".into(),
        );
        return None;
    };
    let t = r.table(&type_entry.value, "[pass_type]")?;
    r.keys(t, TYPE_KEYS, "[pass_type]");
    let required = |r: &mut Reader<'_>, key: &str| -> Option<Spanned<String>> {
        let Some(e) = t.get(key) else {
            r.schema(&type_entry.key, format!("[pass_type] needs `{key}`"));
            return None;
        };
        let s = r.string(&e.value, &format!("pass_type.{key}"))?;
        Some(Spanned::new(s, e.value.location.clone()))
    };
    let name = required(r, "name");
    let source = required(r, "source");
    let description = required(r, "description");
    let shader = required(r, "shader");
    let shape = match t.get("shape") {
        Some(e) => match r.named(&e.value, "pass_type.shape", SHAPES)?.as_str() {
            "raster" => PassShape::Raster,
            "fullscreen" => PassShape::Fullscreen,
            _ => PassShape::Compute,
        },
        None => {
            r.schema(
                &type_entry.key,
                format!("[pass_type] needs `shape` ({})", SHAPES.join(", ")),
            );
            return None;
        }
    };
    let features = match t.get("features") {
        Some(e) => r.strings(&e.value, "pass_type.features")?,
        None => Vec::new(),
    };
    let raster = raster_decl::parse(t, "pass_type", r.errors);
    let mut words_per_texel = Vec::new();
    let mut slots = |r: &mut Reader<'_>, key: &str, output: bool| -> Vec<SlotSpec> {
        let Some(e) = top.get(key) else {
            return Vec::new();
        };
        let Some(table) = r.table(&e.value, &format!("[{key}]")) else {
            return Vec::new();
        };
        table
            .iter()
            .filter_map(|(slot, entry)| {
                let ctx = format!("{key}.{slot}");
                let st = r.table(&entry.value, &ctx)?;
                let (spec, words) = read_slot(r, slot, st, &entry.value.location, &ctx, output)?;
                words_per_texel.extend(words);
                Some(spec)
            })
            .collect()
    };
    let inputs = slots(r, "inputs", false);
    let outputs = slots(r, "outputs", true);
    let params = match top.get("params") {
        Some(e) => {
            let table = r.table(&e.value, "[params]")?;
            table
                .iter()
                .filter_map(|(p, entry)| read_param(r, p, entry, &format!("params.{p}")))
                .collect()
        }
        None => Vec::new(),
    };
    for w in &words_per_texel {
        let is_texture = |s: &SlotSpec| s.name == w.of && s.kind == ResourceKind::Texture;
        if !inputs.iter().chain(outputs.iter()).any(is_texture) {
            r.schema(
                &type_entry.key,
                format!(
                    "`{}.words_per_texel.of` names `{}`, which is no texture slot of this pass type",
                    w.slot, w.of
                ),
            );
        }
    }
    let (name, source, description, shader) = (name?, source?, description?, shader?);
    Some(PassTypeFile {
        spec: PassTypeSpec {
            inputs,
            outputs,
            params,
            required_features: features,
            state_from_data: shape != PassShape::Compute,
            raster: raster.clone(),
            ..PassTypeSpec::new(&name, shape, &source, &description)
        },
        shader,
        raster,
        words_per_texel,
    })
}

pub(crate) fn read_slot(
    r: &mut Reader<'_>,
    name: &str,
    t: &Table,
    location: &Location,
    ctx: &str,
    output: bool,
) -> Option<(SlotSpec, Option<WordsPerTexel>)> {
    r.keys(t, SLOT_KEYS, ctx);
    let (kind, access) = read_kind_and_access(r, t, location, ctx, output)?;
    let formats = match t.get("formats") {
        None => Formats::Any,
        Some(e) => read_formats(r, e, ctx)?,
    };
    let flag = |r: &mut Reader<'_>, key: &str| match t.get(key) {
        Some(e) => r.bool(&e.value, &format!("{ctx}.{key}")).unwrap_or(false),
        None => false,
    };
    let optional = flag(r, "optional");
    let loads = flag(r, "loads");
    let doc = match t.get("doc") {
        Some(e) => r.string(&e.value, &format!("{ctx}.doc"))?,
        None => String::new(),
    };
    let binding = match t.get("binding") {
        Some(e) => Some(r.string(&e.value, &format!("{ctx}.binding"))?),
        None => None,
    };
    let words = match t.get("words_per_texel") {
        None => None,
        Some(e) => Some(read_words_per_texel(r, name, kind, e, ctx)?),
    };
    Some((
        SlotSpec {
            name: name.to_owned(),
            kind,
            access,
            formats,
            loads,
            optional,
            doc,
            binding,
        },
        words,
    ))
}

/// A slot's `kind` and `access` (one its kind allows); a written access
/// outside [outputs] is reported.
fn read_kind_and_access(
    r: &mut Reader<'_>,
    t: &Table,
    location: &Location,
    ctx: &str,
    output: bool,
) -> Option<(ResourceKind, Access)> {
    let need = |r: &mut Reader<'_>, key: &str| {
        let e = t.get(key);
        if e.is_none() {
            r.schema(location, format!("{ctx} needs `{key}`"));
        }
        e
    };
    let kind_node = &need(r, "kind")?.value;
    let kind = match r.named(kind_node, &format!("{ctx}.kind"), KINDS)?.as_str() {
        "texture" => ResourceKind::Texture,
        "buffer" => ResourceKind::Buffer,
        _ => ResourceKind::AccelerationStructure,
    };
    let accepted = match kind {
        ResourceKind::Texture => TEXTURE_ACCESS,
        ResourceKind::Buffer => BUFFER_ACCESS,
        ResourceKind::AccelerationStructure => STRUCTURE_ACCESS,
    };
    let access_node = &need(r, "access")?.value;
    let access = match r
        .named(access_node, &format!("{ctx}.access"), accepted)?
        .as_str()
    {
        "sampled" => Access::Sampled,
        "storage_read" => Access::StorageRead,
        "storage_write" => Access::StorageWrite,
        "color_target" => Access::ColorTarget,
        "depth_target" => Access::DepthTarget,
        _ => Access::Uniform,
    };
    if access.is_write() && !output && access != Access::DepthTarget {
        r.schema(
            &access_node.location,
            format!("{ctx}: a written slot (`{access}`) belongs under [outputs]"),
        );
    }
    Some((kind, access))
}

/// A slot's `formats` list; unknown names are reported and left out.
fn read_formats(r: &mut Reader<'_>, e: &crate::load::Entry, ctx: &str) -> Option<Formats> {
    let mut list = Vec::new();
    for s in r.strings(&e.value, &format!("{ctx}.formats"))? {
        match s.parse::<Format>() {
            Ok(f) => list.push(f),
            Err(_) => r.schema(
                &e.value.location,
                format!(
                    "{ctx}.formats: unknown format `{s}`{}",
                    crate::suggest::did_you_mean(&s, Format::ALL.iter().map(|f| f.name()))
                ),
            ),
        }
    }
    Some(Formats::OneOf(list))
}

/// Slot `name`'s `words_per_texel` table.
fn read_words_per_texel(
    r: &mut Reader<'_>,
    name: &str,
    kind: ResourceKind,
    e: &crate::load::Entry,
    ctx: &str,
) -> Option<WordsPerTexel> {
    let wctx = format!("{ctx}.words_per_texel");
    let wt = r.table(&e.value, &wctx)?;
    r.keys(wt, WORDS_KEYS, &wctx);
    if kind != ResourceKind::Buffer {
        r.schema(
            &e.key,
            format!("{wctx}: only a buffer holds words per texel"),
        );
    }
    let Some(of) = wt.get("of") else {
        r.schema(
            &e.value.location,
            format!("{wctx} needs `of` (a texture slot)"),
        );
        return None;
    };
    let positive = |r: &mut Reader<'_>, key: &str, default: u64| match wt.get(key) {
        None => Some(default),
        Some(v) => match r.int(&v.value, &format!("{wctx}.{key}"))? {
            n if n >= 1 => Some(n as u64),
            _ => {
                r.schema(
                    &v.value.location,
                    format!("{wctx}.{key} must be at least 1"),
                );
                None
            }
        },
    };
    Some(WordsPerTexel {
        slot: name.to_owned(),
        of: r.string(&of.value, &format!("{wctx}.of"))?,
        multiple: positive(r, "multiple", 1)?,
        max: positive(r, "max", u64::from(u32::MAX))?,
        hint: match wt.get("hint") {
            Some(h) => Some(r.string(&h.value, &format!("{wctx}.hint"))?),
            None => None,
        },
    })
}

pub(crate) fn read_param(
    r: &mut Reader<'_>,
    name: &str,
    entry: &crate::load::Entry,
    ctx: &str,
) -> Option<ParamSpec> {
    let t = r.table(&entry.value, ctx)?;
    r.keys(t, PARAM_KEYS, ctx);
    let Some(ty_entry) = t.get("type") else {
        r.schema(
            &entry.value.location,
            format!("{ctx} needs `type` ({})", PARAM_TYPES.join(", ")),
        );
        return None;
    };
    let number = |r: &mut Reader<'_>, key: &str, default: f64| match t.get(key) {
        Some(e) => r.number(&e.value, &format!("{ctx}.{key}")),
        None => Some(default),
    };
    let ty = match r
        .named(&ty_entry.value, &format!("{ctx}.type"), PARAM_TYPES)?
        .as_str()
    {
        "float" => ParamType::Float {
            min: number(r, "min", f64::MIN)?,
            max: number(r, "max", f64::MAX)?,
        },
        "int" => ParamType::Int {
            min: number(r, "min", i64::MIN as f64)? as i64,
            max: number(r, "max", i64::MAX as f64)? as i64,
        },
        "bool" => ParamType::Bool,
        "text" => ParamType::Str,
        "vec3" => ParamType::Vec3,
        _ => match t.get("choices") {
            Some(e) => ParamType::Enum(r.strings(&e.value, &format!("{ctx}.choices"))?),
            None => {
                r.schema(
                    &entry.value.location,
                    format!("{ctx}: an enum needs `choices`"),
                );
                return None;
            }
        },
    };
    let default = match t.get("default").map(|e| &e.value) {
        None => None,
        Some(Spanned {
            value: Node::Scalar(v),
            ..
        }) => Some(v.clone()),
        Some(Spanned {
            value: Node::List(items),
            location,
        }) => Some(Value::List(
            items
                .iter()
                .map(|i| match &i.value {
                    Node::Scalar(v) => Some(v.clone()),
                    _ => None,
                })
                .collect::<Option<Vec<_>>>()
                .or_else(|| {
                    r.schema(location, format!("{ctx}.default must be a list of numbers"));
                    None
                })?,
        )),
        Some(other) => {
            r.schema(&other.location, format!("{ctx}.default cannot be a table"));
            return None;
        }
    };
    let doc = match t.get("doc") {
        Some(e) => r.string(&e.value, &format!("{ctx}.doc"))?,
        None => String::new(),
    };
    Some(ParamSpec {
        name: name.to_owned(),
        ty,
        default,
        doc,
    })
}

/// A size check of a `words_per_texel` slot, as `plait check` runs it;
/// the words per texel when both slots are bound.
pub fn check_words_per_texel(
    w: &WordsPerTexel,
    pass: &crate::ScheduledPass,
    resources: &[crate::ResolvedResource],
) -> Result<Option<u64>, String> {
    let desc = |slot: &str| {
        pass.reads
            .iter()
            .chain(pass.writes.iter())
            .find(|b| b.slot == slot)
            // A culled pass may name resources the schedule dropped.
            .and_then(|b| b.resolved(resources))
            .map(|r| (r.name.clone(), r.desc.clone()))
    };
    let (
        Some((buffer_name, crate::ResourceDesc::Buffer { size })),
        Some((_, crate::ResourceDesc::Texture { width, height, .. })),
    ) = (desc(&w.slot), desc(&w.of))
    else {
        return Ok(None);
    };
    let per_texel = 4 * width as u64 * height as u64;
    let words = size / per_texel;
    if size == 0
        || !size.is_multiple_of(per_texel)
        || !words.is_multiple_of(w.multiple)
        || words > w.max
        || words == 0
    {
        let hint = w.hint.as_ref().map_or(String::new(), |h| format!(" ({h})"));
        return Err(format!(
            "buffer `{buffer_name}` (slot `{}`) has {size} bytes; it needs a multiple of {} u32 words (at most {}) per texel of the {width}x{height} map, i.e. a multiple of {} bytes{hint}",
            w.slot,
            w.multiple,
            w.max,
            per_texel * w.multiple
        ));
    }
    Ok(Some(words))
}

#[cfg(test)]
mod tests {
    use super::*;

    const OCCUPANCY: &str = r#"
[pass_type]
name = "occupancy"
shape = "raster"
source = "Sintorn & Assarsson 2009 §3.1"
description = "bits"
shader = "occupancy.wgsl"
depth = { compare = "less" }

[inputs.range]
kind = "texture"
access = "sampled"
formats = ["rg32float"]

[inputs.depth]
kind = "texture"
access = "depth_target"
formats = ["depth32float"]

[outputs.bits]
kind = "buffer"
access = "storage_write"
binding = "words"
words_per_texel = { of = "range", max = 32, hint = "32 slices per word" }

[params.layer_size]
type = "float"
default = 0.05
min = 0.0
"#;

    #[test]
    fn reads_a_pass_type() {
        let f = parse(Path::new("occupancy.toml"), OCCUPANCY).expect("parses");
        assert_eq!(f.spec.name, "occupancy");
        assert_eq!(f.spec.shape, PassShape::Raster);
        assert!(f.spec.state_from_data);
        assert_eq!(f.spec.inputs.len(), 2);
        assert_eq!(f.spec.inputs[1].access, Access::DepthTarget);
        assert_eq!(f.spec.outputs[0].binding_name(), "words");
        assert_eq!(f.shader.value, "occupancy.wgsl");
        assert!(f.raster.depth.is_some());
        assert_eq!(f.words_per_texel[0].max, 32);
        assert_eq!(f.spec.params[0].default, Some(Value::Float(0.05)));
    }

    #[test]
    fn mistakes_are_located() {
        let bad = OCCUPANCY
            .replace("access = \"sampled\"", "access = \"sampeld\"")
            .replace("of = \"range\"", "of = \"rang\"");
        let errors = parse(Path::new("occupancy.toml"), &bad).expect_err("two mistakes");
        let text = errors.to_string();
        assert!(text.contains("occupancy.toml:12:10"), "{text}");
        assert!(text.contains("did you mean `sampled`"), "{text}");
        assert!(
            text.contains("names `rang`, which is no texture slot"),
            "{text}"
        );
    }
}
