//! The pipeline file's schema: known keys, value types, and the typed
//! [`Pipeline`] built from the merged tree.

use indexmap::IndexMap;
use std::path::{Path, PathBuf};

use super::tree::{Entry, Node, Table};
use super::{PassDecl, Pipeline, PreviousOf, ResourceDecl, SizeDecl, file_location, previous_name};
use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::format::Format;
use crate::shader_path::resolve_shader;
use crate::spec::ResourceKind;
use crate::value::Value;

pub(crate) const TOP_KEYS: &[&str] = &["pipeline", "techniques", "params", "resources", "passes"];
pub(crate) const PIPELINE_KEYS: &[&str] = &["name", "description", "extends", "outputs"];
pub(crate) const TEXTURE_KEYS: &[&str] = &[
    "kind",
    "format",
    "size",
    "layers",
    "samples",
    "history",
    "persistent",
    "clear",
];
pub(crate) const BUFFER_KEYS: &[&str] = &["kind", "size", "history", "persistent", "overflow"];
/// An acceleration structure is sized by the scene's hair.
pub(crate) const STRUCTURE_KEYS: &[&str] = &["kind"];
/// The most frames of history a resource may keep (one copy per frame each).
pub const MAX_HISTORY: i64 = 8;
pub(crate) const PASS_KEYS: &[&str] = &[
    "type",
    "view",
    "draw",
    "reads",
    "writes",
    "params",
    "shader",
    "enabled",
    "uses",
    "depth",
    "blend",
    "cull",
    "alpha_to_coverage",
    "loads",
    "run",
];
const VIEWS: &[&str] = crate::spec::View::NAMES;
/// `run = "once"`: a precompute whose outputs are kept across frames.
const RUNS: &[&str] = &["every_frame", "once"];
const DRAWS: &[&str] = crate::spec::Draw::NAMES;

struct Builder<'e> {
    errors: &'e mut Vec<Error>,
}

impl Builder<'_> {
    fn schema(&mut self, location: &Location, message: String) {
        self.errors
            .push(Error::new(location.clone(), ErrorKind::Schema(message)));
    }

    fn check_keys(&mut self, table: &Table, accepted: &[&str], context: &str) {
        for (key, entry) in table {
            if !accepted.contains(&key.as_str()) {
                self.schema(
                    &entry.key,
                    format!(
                        "unknown key `{key}` in {context}{} (accepted: {})",
                        crate::suggest::did_you_mean(key, accepted.iter().copied()),
                        accepted.join(", ")
                    ),
                );
            }
        }
    }

    fn table<'t>(&mut self, entry: &'t Entry, context: &str) -> Option<&'t Table> {
        match &entry.value.value {
            Node::Table(t) => Some(t),
            _ => {
                self.schema(&entry.value.location, format!("{context} must be a table"));
                None
            }
        }
    }

    fn string(&mut self, entry: &Entry, context: &str) -> Option<Spanned<String>> {
        match &entry.value.value {
            Node::Scalar(Value::Str(s)) => {
                Some(Spanned::new(s.clone(), entry.value.location.clone()))
            }
            _ => {
                self.schema(&entry.value.location, format!("{context} must be a string"));
                None
            }
        }
    }

    fn one_of(
        &mut self,
        entry: &Entry,
        context: &str,
        accepted: &[&str],
    ) -> Option<Spanned<String>> {
        let s = self.string(entry, context)?;
        if accepted.contains(&s.value.as_str()) {
            Some(s)
        } else {
            self.schema(
                &s.location,
                format!(
                    "{context} is `{}`{} (accepted: {})",
                    s.value,
                    crate::suggest::did_you_mean(&s.value, accepted.iter().copied()),
                    accepted.join(", ")
                ),
            );
            None
        }
    }

    fn value(&mut self, node: &Spanned<Node>, context: &str) -> Option<Value> {
        match &node.value {
            Node::Scalar(v) => Some(v.clone()),
            Node::List(items) => items
                .iter()
                .map(|i| self.value(i, context))
                .collect::<Option<Vec<_>>>()
                .map(Value::List),
            Node::Table(_) => {
                self.schema(&node.location, format!("{context} cannot be a table"));
                None
            }
        }
    }

    /// `{slot = "resource"}` tables.
    fn string_map(&mut self, entry: &Entry, context: &str) -> IndexMap<String, Spanned<String>> {
        let mut out = IndexMap::new();
        if let Some(t) = self.table(entry, context) {
            for (k, e) in t {
                if let Some(s) = self.string(e, &format!("{context}.{k}")) {
                    out.insert(k.clone(), s);
                }
            }
        }
        out
    }
}

pub(super) fn build_pipeline(
    root: Spanned<Node>,
    files: Vec<PathBuf>,
    top_path: &Path,
    errors: &mut Vec<Error>,
) -> Pipeline {
    let mut b = Builder { errors };
    let root_location = file_location(top_path, 1, 1);
    let mut pipeline = Pipeline {
        name: Spanned::new(String::new(), root_location.clone()),
        description: Spanned::new(String::new(), root_location.clone()),
        files,
        techniques: Vec::new(),
        outputs: Vec::new(),
        params: IndexMap::new(),
        resources: IndexMap::new(),
        passes: IndexMap::new(),
        outputs_location: root_location.clone(),
        notes: Vec::new(),
    };
    let Node::Table(top) = &root.value else {
        return pipeline;
    };
    b.check_keys(top, TOP_KEYS, "the pipeline file");

    match top.get("pipeline") {
        None => b.schema(
            &root_location,
            "missing [pipeline] table (name, outputs)".into(),
        ),
        Some(entry) => {
            if let Some(t) = b.table(entry, "[pipeline]") {
                b.check_keys(t, PIPELINE_KEYS, "[pipeline]");
                pipeline.outputs_location = entry.value.location.clone();
                match t.get("name") {
                    Some(e) => {
                        pipeline.name = b.string(e, "pipeline.name").unwrap_or(pipeline.name)
                    }
                    None => b.schema(&entry.key, "[pipeline] needs a `name`".into()),
                }
                if let Some(e) = t.get("description") {
                    pipeline.description = b
                        .string(e, "pipeline.description")
                        .unwrap_or(pipeline.description);
                }
                match t.get("outputs").map(|e| &e.value) {
                    Some(Spanned {
                        value: Node::List(items),
                        location,
                    }) => {
                        pipeline.outputs_location = location.clone();
                        for item in items {
                            match &item.value {
                                Node::Scalar(Value::Str(s)) => pipeline
                                    .outputs
                                    .push(Spanned::new(s.clone(), item.location.clone())),
                                _ => b.schema(
                                    &item.location,
                                    "pipeline.outputs must list resource names".into(),
                                ),
                            }
                        }
                    }
                    Some(other) => b.schema(
                        &other.location,
                        "pipeline.outputs must be a list of resource names".into(),
                    ),
                    None => b.schema(&entry.key, "[pipeline] needs `outputs = [\"…\"]`".into()),
                }
            }
        }
    }

    if let Some(entry) = top.get("params")
        && let Some(t) = b.table(entry, "[params]")
    {
        for (name, e) in t {
            if let Some(v) = b.value(&e.value, &format!("params.{name}")) {
                pipeline
                    .params
                    .insert(name.clone(), Spanned::new(v, e.value.location.clone()));
            }
        }
    }

    if let Some(entry) = top.get("resources")
        && let Some(t) = b.table(entry, "[resources]")
    {
        for (name, e) in t {
            if let Some(r) = build_resource(&mut b, name, e) {
                let previous = previous_versions(&r);
                pipeline.resources.insert(name.clone(), r);
                for p in previous {
                    pipeline.resources.insert(p.name.clone(), p);
                }
            }
        }
    }

    if let Some(entry) = top.get("passes")
        && let Some(t) = b.table(entry, "[passes]")
    {
        for (name, e) in t {
            if let Some(p) = build_pass(&mut b, name, e) {
                pipeline.passes.insert(name.clone(), p);
            }
        }
    }
    pipeline
}

fn build_resource(b: &mut Builder<'_>, name: &str, entry: &Entry) -> Option<ResourceDecl> {
    let context = format!("[resources.{name}]");
    let t = b.table(entry, &context)?;
    if name.contains('.') {
        // `NAME.previous` names a history; a dotted name could collide with one.
        b.schema(
            &entry.key,
            format!("resource name `{name}` contains `.`, which is kept for histories (`NAME.previous`); use `_`"),
        );
        return None;
    }
    let kind = resource_kind(b, name, entry, t, &context)?;
    b.check_keys(
        t,
        match kind.value {
            ResourceKind::Texture => TEXTURE_KEYS,
            ResourceKind::Buffer => BUFFER_KEYS,
            ResourceKind::AccelerationStructure => STRUCTURE_KEYS,
        },
        &format!("{context} ({})", kind.value),
    );
    let size = match (kind.value, t.get("size")) {
        (ResourceKind::AccelerationStructure, _) => SizeDecl::Scene(kind.location.clone()),
        (_, None) => {
            b.schema(&entry.key, format!("{context} needs a `size`"));
            return None;
        }
        (ResourceKind::Buffer, Some(e)) => buffer_size(b, name, &e.value)?,
        (ResourceKind::Texture, Some(e)) => texture_size(b, name, &e.value)?,
    };
    let format = resource_format(b, name, entry, t, &context, kind.value)?;
    let int_field = |key: &str| {
        t.get(key)
            .map(|e| e.value.clone())
            .and_then(|n| match n.value {
                Node::Scalar(v) => Some(Spanned::new(v, n.location)),
                _ => None,
            })
    };
    let history = resource_history(b, name, t);
    let persistent = resource_persistent(b, name, t);
    let clear = resource_clear(b, name, t, format.as_ref(), persistent.as_ref());
    Some(ResourceDecl {
        name: name.to_owned(),
        format,
        size,
        layers: int_field("layers"),
        samples: int_field("samples"),
        location: entry.key.clone(),
        history,
        persistent,
        previous_of: None,
        overflow: match (kind.value, t.get("overflow")) {
            (ResourceKind::Buffer, Some(e)) => crate::overflow::parse(&e.value, name, b.errors),
            _ => None,
        },
        kind,
        clear,
    })
}

/// `clear = …` of a texture, checked against its format. A persistent
/// texture keeps its contents across frames, so it is never cleared.
fn resource_clear(
    b: &mut Builder<'_>,
    name: &str,
    t: &Table,
    format: Option<&Spanned<Format>>,
    persistent: Option<&Location>,
) -> Option<Spanned<crate::clear::ClearValue>> {
    let e = t.get("clear")?;
    if persistent.is_some() {
        b.schema(
            &e.value.location,
            format!("resources.{name} is `persistent`, kept between frames and never cleared, so it cannot declare `clear`"),
        );
        return None;
    }
    crate::clear::parse(&e.value, name, format?.value, b.errors)
}

/// The resource's `kind`, where it is written.
fn resource_kind(
    b: &mut Builder<'_>,
    name: &str,
    entry: &Entry,
    t: &Table,
    context: &str,
) -> Option<Spanned<ResourceKind>> {
    let Some(kind_entry) = t.get("kind") else {
        b.schema(
            &entry.key,
            format!(
                "{context} needs `kind = \"texture\"`, `\"buffer\"` or `\"acceleration_structure\"`"
            ),
        );
        return None;
    };
    let kind_name = b.one_of(
        kind_entry,
        &format!("resources.{name}.kind"),
        &["texture", "buffer", "acceleration_structure"],
    )?;
    let kind = match kind_name.value.as_str() {
        "texture" => ResourceKind::Texture,
        "buffer" => ResourceKind::Buffer,
        _ => ResourceKind::AccelerationStructure,
    };
    Some(Spanned::new(kind, kind_name.location))
}

/// A buffer's `size`: a byte count, an integer or an expression.
fn buffer_size(b: &mut Builder<'_>, name: &str, size_node: &Spanned<Node>) -> Option<SizeDecl> {
    match &size_node.value {
        Node::Scalar(v @ (Value::Int(_) | Value::Str(_))) => Some(SizeDecl::Bytes(Spanned::new(
            v.clone(),
            size_node.location.clone(),
        ))),
        _ => {
            b.schema(
                &size_node.location,
                format!(
                    "resources.{name}.size of a buffer is a byte count (integer or expression)"
                ),
            );
            None
        }
    }
}

/// A texture's `size`: `[width, height]`, `"screen"` or `"screen/N"`.
fn texture_size(b: &mut Builder<'_>, name: &str, size_node: &Spanned<Node>) -> Option<SizeDecl> {
    match &size_node.value {
        Node::Scalar(Value::Str(s)) => match parse_screen_size(s) {
            Some(divisor) => Some(SizeDecl::Screen {
                divisor,
                location: size_node.location.clone(),
            }),
            None => {
                b.schema(&size_node.location, format!("resources.{name}.size is `{s}`; accepted: [width, height], \"screen\", \"screen/N\""));
                None
            }
        },
        Node::List(items) if items.len() == 2 => {
            let dim = |n: &Spanned<Node>| match &n.value {
                Node::Scalar(v @ (Value::Int(_) | Value::Str(_))) => {
                    Some(Spanned::new(v.clone(), n.location.clone()))
                }
                _ => None,
            };
            match (dim(&items[0]), dim(&items[1])) {
                (Some(width), Some(height)) => Some(SizeDecl::Extent {
                    width,
                    height,
                    location: size_node.location.clone(),
                }),
                _ => {
                    b.schema(
                        &size_node.location,
                        format!("resources.{name}.size must hold two integers or expressions"),
                    );
                    None
                }
            }
        }
        _ => {
            b.schema(
                &size_node.location,
                format!(
                    "resources.{name}.size must be [width, height], \"screen\" or \"screen/N\""
                ),
            );
            None
        }
    }
}

/// A texture's `format` (required; buffers have none). The outer `None`
/// means an error was reported.
fn resource_format(
    b: &mut Builder<'_>,
    name: &str,
    entry: &Entry,
    t: &Table,
    context: &str,
    kind: ResourceKind,
) -> Option<Option<Spanned<Format>>> {
    match (kind, t.get("format")) {
        (ResourceKind::Texture, Some(e)) => {
            let s = b.string(e, &format!("resources.{name}.format"))?;
            match s.value.parse::<Format>() {
                Ok(f) => Some(Some(Spanned::new(f, s.location))),
                Err(err) => {
                    b.schema(&s.location, err.to_string());
                    None
                }
            }
        }
        (ResourceKind::Texture, None) => {
            b.schema(
                &entry.key,
                format!("{context} is a texture and needs a `format`"),
            );
            None
        }
        _ => Some(None),
    }
}

/// `history = N`: how many past frames are kept, if any.
fn resource_history(b: &mut Builder<'_>, name: &str, t: &Table) -> Option<Spanned<u32>> {
    t.get("history").and_then(|e| match &e.value.value {
        Node::Scalar(Value::Int(n)) if (1..=MAX_HISTORY).contains(n) => {
            Some(Spanned::new(*n as u32, e.value.location.clone()))
        }
        _ => {
            b.schema(
                &e.value.location,
                format!(
                    "resources.{name}.history is the number of past frames kept, an integer 1 … {MAX_HISTORY} (`history = 1` gives `{name}.previous`)"
                ),
            );
            None
        }
    })
}

/// `persistent = true`: where it is written.
fn resource_persistent(b: &mut Builder<'_>, name: &str, t: &Table) -> Option<Location> {
    t.get("persistent").and_then(|e| match &e.value.value {
        Node::Scalar(Value::Bool(true)) => Some(e.value.location.clone()),
        Node::Scalar(Value::Bool(false)) => None,
        _ => {
            b.schema(
                &e.value.location,
                format!("resources.{name}.persistent must be true or false"),
            );
            None
        }
    })
}

/// The read-only resources a history adds: `NAME.previous` … `NAME.previous.N`,
/// shaped like `NAME` and declared where `history` is written.
fn previous_versions(r: &ResourceDecl) -> Vec<ResourceDecl> {
    let Some(history) = &r.history else {
        return Vec::new();
    };
    (1..=history.value)
        .map(|frames_ago| ResourceDecl {
            name: previous_name(&r.name, frames_ago),
            location: history.location.clone(),
            history: None,
            persistent: None,
            overflow: None,
            // A past frame's version is read-only: what it holds was written.
            clear: None,
            previous_of: Some(PreviousOf {
                resource: r.name.clone(),
                frames_ago,
            }),
            ..r.clone()
        })
        .collect()
}

/// `"screen"` → 1, `"screen/4"` → 4.
fn parse_screen_size(s: &str) -> Option<u32> {
    let s = s.trim();
    if s == "screen" {
        return Some(1);
    }
    let divisor: u32 = s
        .strip_prefix("screen")?
        .trim()
        .strip_prefix('/')?
        .trim()
        .parse()
        .ok()?;
    (divisor > 0).then_some(divisor)
}

fn build_pass(b: &mut Builder<'_>, name: &str, entry: &Entry) -> Option<PassDecl> {
    let context = format!("[passes.{name}]");
    let t = b.table(entry, &context)?;
    b.check_keys(t, PASS_KEYS, &context);
    if let Some(e) = t.get("enabled") {
        match &e.value.value {
            Node::Scalar(Value::Bool(false)) => return None,
            Node::Scalar(Value::Bool(true)) => {}
            _ => b.schema(
                &e.value.location,
                format!("passes.{name}.enabled must be true or false"),
            ),
        }
    }
    let Some(type_entry) = t.get("type") else {
        b.schema(&entry.key, format!("{context} needs a `type`"));
        return None;
    };
    let type_name = b.string(type_entry, &format!("passes.{name}.type"))?;
    let view = t
        .get("view")
        .and_then(|e| b.one_of(e, &format!("passes.{name}.view"), VIEWS));
    let draw = t
        .get("draw")
        .and_then(|e| b.one_of(e, &format!("passes.{name}.draw"), DRAWS));
    let reads = t
        .get("reads")
        .map(|e| b.string_map(e, &format!("passes.{name}.reads")))
        .unwrap_or_default();
    let writes = t
        .get("writes")
        .map(|e| b.string_map(e, &format!("passes.{name}.writes")))
        .unwrap_or_default();
    let mut params = IndexMap::new();
    if let Some(e) = t.get("params")
        && let Some(pt) = b.table(e, &format!("passes.{name}.params"))
    {
        for (k, pe) in pt {
            if let Some(v) = b.value(&pe.value, &format!("passes.{name}.params.{k}")) {
                params.insert(k.clone(), Spanned::new(v, pe.value.location.clone()));
            }
        }
    }
    let shader = t
        .get("shader")
        .and_then(|e| b.string(e, &format!("passes.{name}.shader")))
        .map(|s| Spanned::new(resolve_shader(&s.value, &s.location), s.location));
    let run_once = t
        .get("run")
        .and_then(|e| b.one_of(e, &format!("passes.{name}.run"), RUNS))
        .filter(|r| r.value == "once")
        .map(|r| r.location);
    Some(PassDecl {
        name: name.to_owned(),
        type_name,
        view,
        draw,
        reads,
        writes,
        params,
        shader,
        raster: crate::raster_decl::parse(t, &format!("passes.{name}"), b.errors),
        run_once,
        location: entry.key.clone(),
    })
}
