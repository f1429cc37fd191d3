//! Loading pipeline files: TOML with the source location of every value,
//! `extends` chains, `--set key=value` overrides and `${param}` substitution.
//!
//! The steps, in order:
//! 1. parse each file of the `extends` chain into a [`Node`] tree whose every
//!    value carries its `file:line:column`;
//! 2. merge base ← child key by key (tables recursively, everything else
//!    replaced), then apply `--set` flags through the same merge
//!    ([`crate::overrides`]);
//! 3. substitute `${name}` from `[params]`;
//! 4. check the schema (unknown keys, value types) and build a [`Pipeline`].
//!
//! Sizes and integer params may be arithmetic expressions over the screen
//! size, which only [`crate::compile`] knows, so they stay [`Value`]s here.

use indexmap::IndexMap;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::error::{Error, ErrorKind, Errors, Location, Spanned};
use crate::format::Format;
use crate::overrides::apply_override;
use crate::spec::ResourceKind;
use crate::techniques::apply_techniques;
use crate::value::Value;

/// A loaded pipeline file (after `extends`, `--set` and `${param}`), not yet
/// checked against pass types. Every value keeps the place that set it.
#[derive(Clone, Debug)]
pub struct Pipeline {
    pub name: Spanned<String>,
    pub description: Spanned<String>,
    /// The pipeline file, every file it extends, then the technique files.
    pub files: Vec<PathBuf>,
    /// `[techniques]`: the technique chosen for each choice point.
    pub techniques: Vec<crate::schedule::ChosenTechnique>,
    pub outputs: Vec<Spanned<String>>,
    /// `[params]` with every `${…}` resolved.
    pub params: IndexMap<String, Spanned<Value>>,
    /// `[resources]` in file order (base file's first).
    pub resources: IndexMap<String, ResourceDecl>,
    /// `[passes]` in file order, without those with `enabled = false`.
    pub passes: IndexMap<String, PassDecl>,
    /// Where `outputs` was set (or the `[pipeline]` table), for output errors.
    pub outputs_location: Location,
}

/// A `[resources.NAME]` table.
#[derive(Clone, Debug)]
pub struct ResourceDecl {
    pub name: String,
    pub kind: Spanned<ResourceKind>,
    /// Textures only.
    pub format: Option<Spanned<Format>>,
    pub size: SizeDecl,
    /// Textures only; default 1. An integer or an expression string.
    pub layers: Option<Spanned<Value>>,
    /// Textures only; default 1. An integer or an expression string.
    pub samples: Option<Spanned<Value>>,
    /// The `[resources.NAME]` header (or first key) that declared it.
    pub location: Location,
}

/// The `size` of a resource, before the screen size is known.
#[derive(Clone, Debug)]
pub enum SizeDecl {
    /// `"screen"` (divisor 1) or `"screen/N"`.
    Screen { divisor: u32, location: Location },
    /// `[width, height]`, each an integer or an expression string.
    Extent {
        width: Spanned<Value>,
        height: Spanned<Value>,
        location: Location,
    },
    /// A buffer's size in bytes: an integer or an expression string.
    Bytes(Spanned<Value>),
}

impl SizeDecl {
    pub fn location(&self) -> &Location {
        match self {
            SizeDecl::Screen { location, .. } | SizeDecl::Extent { location, .. } => location,
            SizeDecl::Bytes(v) => &v.location,
        }
    }
}

/// A `[passes.NAME]` table.
#[derive(Clone, Debug)]
pub struct PassDecl {
    pub name: String,
    pub type_name: Spanned<String>,
    pub view: Option<Spanned<String>>,
    pub draw: Option<Spanned<String>>,
    /// slot → resource name.
    pub reads: IndexMap<String, Spanned<String>>,
    pub writes: IndexMap<String, Spanned<String>>,
    pub params: IndexMap<String, Spanned<Value>>,
    /// Resolved path (see [`resolve_shader`]); the location is where it was written.
    pub shader: Option<Spanned<PathBuf>>,
    pub location: Location,
}

/// Loads a pipeline file, following `extends` and applying `--set` flags
/// (`overrides` holds the `key=value` texts).
pub fn load(path: &Path, overrides: &[String]) -> Result<Pipeline, Errors> {
    // The file as a whole: a file that cannot be read has no line 1.
    let text = plait_assets::read_to_string(path).map_err(|e| {
        Error::new(
            Location::Path {
                path: path.to_path_buf(),
            },
            ErrorKind::Io(e.to_string()),
        )
    })?;
    load_str(path, &text, overrides)
}

/// Like [`load`], with the top file's text given (tests, editors). `extends`
/// is still read from disk, relative to `path_for_messages`.
pub fn load_str(
    path_for_messages: &Path,
    text: &str,
    overrides: &[String],
) -> Result<Pipeline, Errors> {
    let mut files = Vec::new();
    let mut chain = Vec::new();
    let mut root = load_chain(path_for_messages, text, &mut chain, &mut files)?;
    let mut errors = Vec::new();
    // Technique choices first, so `--set` can reach the params, resources and
    // passes of the technique it chose.
    let (choices, rest): (Vec<&String>, Vec<&String>) = overrides
        .iter()
        .partition(|f| f.trim_start().starts_with("techniques."));
    for flag in choices {
        apply_override(&mut root, flag, &mut errors);
    }
    let mut techniques = Vec::new();
    if errors.is_empty() {
        techniques = apply_techniques(&mut root, path_for_messages, &mut files, &mut errors);
    }
    if !errors.is_empty() {
        errors.sort_by(|a, b| location_order(&a.location, &b.location));
        return Err(Errors(errors));
    }
    for flag in rest {
        apply_override(&mut root, flag, &mut errors);
    }
    if !errors.is_empty() {
        return Err(Errors(errors));
    }
    let root = substitute_params(root, &mut errors);
    let mut pipeline = build_pipeline(root, files, path_for_messages, &mut errors);
    pipeline.techniques = techniques;
    if errors.is_empty() {
        Ok(pipeline)
    } else {
        errors.sort_by(|a, b| location_order(&a.location, &b.location));
        Err(Errors(errors))
    }
}

/// Total order on locations for sorting error lists: files by path then
/// position, then flags, then built-ins.
pub fn location_order(a: &Location, b: &Location) -> std::cmp::Ordering {
    fn key(l: &Location) -> (u8, &Path, u32, u32, &str) {
        match l {
            Location::File { path, line, column } => (0, path.as_path(), *line, *column, ""),
            Location::Path { path } => (0, path.as_path(), 0, 0, ""),
            Location::Flag { flag } => (1, Path::new(""), 0, 0, flag.as_str()),
            Location::Builtin => (2, Path::new(""), 0, 0, ""),
        }
    }
    key(a).cmp(&key(b))
}

fn file_location(path: &Path, line: u32, column: u32) -> Location {
    Location::File {
        path: path.to_path_buf(),
        line,
        column,
    }
}

// ---------------------------------------------------------------------------
// The located value tree.

/// A TOML value with locations on every value and key; what `extends` and
/// `--set` merge.
#[derive(Clone, Debug)]
pub(crate) enum Node {
    Scalar(Value),
    List(Vec<Spanned<Node>>),
    Table(Table),
}

pub(crate) type Table = IndexMap<String, Entry>;

#[derive(Clone, Debug)]
pub(crate) struct Entry {
    pub(crate) key: Location,
    pub(crate) value: Spanned<Node>,
}

/// Maps byte offsets of one file to 1-based line:column (columns in chars).
pub(crate) struct SourceMap<'a> {
    path: &'a Path,
    text: &'a str,
    line_starts: Vec<usize>,
}

impl<'a> SourceMap<'a> {
    pub(crate) fn new(path: &'a Path, text: &'a str) -> Self {
        let mut line_starts = vec![0];
        line_starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        SourceMap {
            path,
            text,
            line_starts,
        }
    }

    fn location(&self, offset: usize) -> Location {
        let offset = offset.min(self.text.len());
        let line = self
            .line_starts
            .partition_point(|&start| start <= offset)
            .max(1);
        let start = self.line_starts[line - 1];
        let column = self
            .text
            .get(start..offset)
            .map_or(offset - start, |s| s.chars().count())
            + 1;
        file_location(self.path, line as u32, column as u32)
    }
}

pub(crate) fn parse_file(path: &Path, text: &str) -> Result<Spanned<Node>, Errors> {
    let map = SourceMap::new(path, text);
    let table = toml::de::DeTable::parse(text).map_err(|e| {
        let location = map.location(e.span().map_or(0, |s| s.start));
        Error::new(location, ErrorKind::Syntax(e.message().trim().to_owned()))
    })?;
    let mut errors = Vec::new();
    let span = table.span();
    let node = convert_table(table.get_ref(), &map, &mut errors);
    if errors.is_empty() {
        Ok(Spanned::new(Node::Table(node), map.location(span.start)))
    } else {
        Err(Errors(errors))
    }
}

fn convert_table(
    table: &toml::de::DeTable<'_>,
    map: &SourceMap<'_>,
    errors: &mut Vec<Error>,
) -> Table {
    let mut out = Table::new();
    for (key, value) in table.iter() {
        if let Some(node) = convert_value(value, map, errors) {
            let entry = Entry {
                key: map.location(key.span().start),
                value: node,
            };
            out.insert(key.get_ref().to_string(), entry);
        }
    }
    out
}

pub(crate) fn convert_value(
    value: &toml::Spanned<toml::de::DeValue<'_>>,
    map: &SourceMap<'_>,
    errors: &mut Vec<Error>,
) -> Option<Spanned<Node>> {
    use toml::de::DeValue;
    let location = map.location(value.span().start);
    let node = match value.get_ref() {
        DeValue::String(s) => Node::Scalar(Value::Str(s.to_string())),
        DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
            Ok(n) => Node::Scalar(Value::Int(n)),
            Err(_) => {
                errors.push(Error::new(
                    location,
                    ErrorKind::Schema(format!("integer `{i}` is out of range")),
                ));
                return None;
            }
        },
        DeValue::Float(f) => match f.as_str().parse::<f64>() {
            Ok(x) => Node::Scalar(Value::Float(x)),
            Err(_) => {
                errors.push(Error::new(
                    location,
                    ErrorKind::Schema(format!("float `{f}` is not a number")),
                ));
                return None;
            }
        },
        DeValue::Boolean(b) => Node::Scalar(Value::Bool(*b)),
        DeValue::Datetime(_) => {
            errors.push(Error::new(
                location,
                ErrorKind::Schema("dates are not used in pipeline files".into()),
            ));
            return None;
        }
        DeValue::Array(items) => Node::List(
            items
                .iter()
                .filter_map(|item| convert_value(item, map, errors))
                .collect(),
        ),
        DeValue::Table(t) => Node::Table(convert_table(t, map, errors)),
    };
    Some(Spanned::new(node, location))
}

/// Child wins: tables merge recursively, anything else is replaced along
/// with its location.
pub(crate) fn merge(base: &mut Spanned<Node>, child: Spanned<Node>) {
    match (&mut base.value, child.value) {
        (Node::Table(base_table), Node::Table(child_table)) => {
            for (key, entry) in child_table {
                match base_table.get_mut(&key) {
                    Some(existing) => {
                        existing.key = entry.key;
                        merge(&mut existing.value, entry.value);
                    }
                    None => {
                        base_table.insert(key, entry);
                    }
                }
            }
        }
        (_, other) => *base = Spanned::new(other, child.location),
    }
}

fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

/// Parses `text` and, if it `extends` a base, loads the base first and
/// merges this file over it.
fn load_chain(
    path: &Path,
    text: &str,
    chain: &mut Vec<PathBuf>,
    files: &mut Vec<PathBuf>,
) -> Result<Spanned<Node>, Errors> {
    chain.push(canonical(path));
    files.push(path.to_path_buf());
    let child = parse_file(path, text)?;
    let extends = match &child.value {
        Node::Table(t) => t.get("pipeline").and_then(|p| match &p.value.value {
            Node::Table(pt) => pt.get("extends").map(|e| e.value.clone()),
            _ => None,
        }),
        _ => None,
    };
    let Some(extends) = extends else {
        return Ok(child);
    };
    let Node::Scalar(Value::Str(base_name)) = &extends.value else {
        return Err(Error::new(
            extends.location,
            ErrorKind::Schema("`extends` must be a file path string".into()),
        )
        .into());
    };
    let next_to_file = path.parent().unwrap_or(Path::new("")).join(base_name);
    // A pipeline copied out of the library still finds the file it extends.
    let base_path = if plait_assets::exists(&next_to_file) {
        next_to_file
    } else {
        plait_assets::find_named(base_name, "pipelines").unwrap_or(next_to_file)
    };
    if chain.contains(&canonical(&base_path)) {
        return Err(Error::new(extends.location, ErrorKind::ExtendsCycle(base_path)).into());
    }
    let base_text = plait_assets::read_to_string(&base_path).map_err(|e| {
        Error::new(
            extends.location.clone(),
            ErrorKind::Io(format!("{}: {e}", base_path.display())),
        )
    })?;
    let mut base = load_chain(&base_path, &base_text, chain, files)?;
    merge(&mut base, child);
    Ok(base)
}

// ---------------------------------------------------------------------------
// ${param}

struct Substituter {
    raw: Table,
    resolved: HashMap<String, Spanned<Node>>,
    /// Params being resolved, to report loops.
    stack: Vec<String>,
    errors: Vec<Error>,
}

fn substitute_params(root: Spanned<Node>, errors: &mut Vec<Error>) -> Spanned<Node> {
    let Node::Table(mut table) = root.value else {
        return root;
    };
    let raw = match table.get("params").map(|e| &e.value.value) {
        Some(Node::Table(t)) => t.clone(),
        _ => Table::new(),
    };
    let mut sub = Substituter {
        raw,
        resolved: HashMap::new(),
        stack: Vec::new(),
        errors: Vec::new(),
    };
    for (key, entry) in table.iter_mut() {
        if key == "params" {
            if let Node::Table(params) = &mut entry.value.value {
                for (name, param) in params.iter_mut() {
                    if let Some(v) = sub.param(name, &param.value.location) {
                        param.value = v;
                    }
                }
            }
        } else {
            entry.value = sub.node(&entry.value);
        }
    }
    errors.append(&mut sub.errors);
    Spanned::new(Node::Table(table), root.location)
}

impl Substituter {
    fn param(&mut self, name: &str, used_at: &Location) -> Option<Spanned<Node>> {
        if let Some(v) = self.resolved.get(name) {
            return Some(v.clone());
        }
        if let Some(pos) = self.stack.iter().position(|n| n == name) {
            let mut cycle = self.stack[pos..].to_vec();
            cycle.push(name.to_owned());
            self.errors
                .push(Error::new(used_at.clone(), ErrorKind::ParamCycle(cycle)));
            return None;
        }
        let Some(raw) = self.raw.get(name).map(|e| e.value.clone()) else {
            self.errors.push(Error::new(
                used_at.clone(),
                ErrorKind::UndefinedParam(name.to_owned()),
            ));
            return None;
        };
        self.stack.push(name.to_owned());
        let value = self.node(&raw);
        self.stack.pop();
        self.resolved.insert(name.to_owned(), value.clone());
        Some(value)
    }

    fn node(&mut self, node: &Spanned<Node>) -> Spanned<Node> {
        let location = &node.location;
        let value = match &node.value {
            Node::Scalar(Value::Str(s)) => {
                if let Some(name) = whole_reference(s) {
                    // `"${x}"` alone takes x's type; the use site keeps its location
                    // so a bad value is reported where it is used.
                    match self.param(name, location) {
                        Some(v) => v.value,
                        None => node.value.clone(),
                    }
                } else {
                    Node::Scalar(Value::Str(self.interpolate(s, location)))
                }
            }
            Node::Scalar(v) => Node::Scalar(v.clone()),
            Node::List(items) => Node::List(items.iter().map(|i| self.node(i)).collect()),
            Node::Table(t) => Node::Table(
                t.iter()
                    .map(|(k, e)| {
                        (
                            k.clone(),
                            Entry {
                                key: e.key.clone(),
                                value: self.node(&e.value),
                            },
                        )
                    })
                    .collect(),
            ),
        };
        Spanned::new(value, location.clone())
    }

    /// Replaces each `${x}` inside a longer string by x's text.
    fn interpolate(&mut self, text: &str, location: &Location) -> String {
        let mut out = String::new();
        let mut rest = text;
        while let Some(start) = rest.find("${") {
            let Some(len) = rest[start + 2..].find('}') else {
                break;
            };
            out.push_str(&rest[..start]);
            let name = &rest[start + 2..start + 2 + len];
            match self.param(name, location).map(|v| v.value) {
                Some(Node::Scalar(Value::Str(s))) => out.push_str(&s),
                Some(Node::Scalar(v)) => out.push_str(&v.to_string()),
                Some(_) => self.errors.push(Error::new(
                    location.clone(),
                    ErrorKind::Schema(format!(
                        "`${{{name}}}` is a list or table and cannot be part of a string"
                    )),
                )),
                None => {}
            }
            rest = &rest[start + 3 + len..];
        }
        out.push_str(rest);
        out
    }
}

fn whole_reference(s: &str) -> Option<&str> {
    let name = s.strip_prefix("${")?.strip_suffix('}')?;
    (!name.contains('}') && !name.contains("${")).then_some(name)
}

// ---------------------------------------------------------------------------
// Schema

pub(crate) const TOP_KEYS: &[&str] = &["pipeline", "techniques", "params", "resources", "passes"];
pub(crate) const PIPELINE_KEYS: &[&str] = &["name", "description", "extends", "outputs"];
pub(crate) const TEXTURE_KEYS: &[&str] = &["kind", "format", "size", "layers", "samples"];
pub(crate) const BUFFER_KEYS: &[&str] = &["kind", "size"];
pub(crate) const PASS_KEYS: &[&str] = &[
    "type", "view", "draw", "reads", "writes", "params", "shader", "enabled", "uses",
];
const VIEWS: &[&str] = &["light", "camera"];
const DRAWS: &[&str] = &["hair", "opaque"];

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
                    "{context} is `{}`{}; accepted: {}",
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

fn build_pipeline(
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
                pipeline.resources.insert(name.clone(), r);
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
    let Some(kind_entry) = t.get("kind") else {
        b.schema(
            &entry.key,
            format!("{context} needs `kind = \"texture\"` or `\"buffer\"`"),
        );
        return None;
    };
    let kind_name = b.one_of(
        kind_entry,
        &format!("resources.{name}.kind"),
        &["texture", "buffer"],
    )?;
    let kind = if kind_name.value == "texture" {
        ResourceKind::Texture
    } else {
        ResourceKind::Buffer
    };
    b.check_keys(
        t,
        if kind == ResourceKind::Texture {
            TEXTURE_KEYS
        } else {
            BUFFER_KEYS
        },
        &format!("{context} ({kind})"),
    );
    let Some(size_entry) = t.get("size") else {
        b.schema(&entry.key, format!("{context} needs a `size`"));
        return None;
    };
    let size_node = &size_entry.value;
    let size = match kind {
        ResourceKind::Buffer => {
            match &size_node.value {
                Node::Scalar(v @ (Value::Int(_) | Value::Str(_))) => {
                    SizeDecl::Bytes(Spanned::new(v.clone(), size_node.location.clone()))
                }
                _ => {
                    b.schema(&size_node.location, format!("resources.{name}.size of a buffer is a byte count (integer or expression)"));
                    return None;
                }
            }
        }
        ResourceKind::Texture => {
            match &size_node.value {
                Node::Scalar(Value::Str(s)) => match parse_screen_size(s) {
                    Some(divisor) => SizeDecl::Screen {
                        divisor,
                        location: size_node.location.clone(),
                    },
                    None => {
                        b.schema(&size_node.location, format!("resources.{name}.size is `{s}`; accepted: [width, height], \"screen\", \"screen/N\""));
                        return None;
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
                        (Some(width), Some(height)) => SizeDecl::Extent {
                            width,
                            height,
                            location: size_node.location.clone(),
                        },
                        _ => {
                            b.schema(
                                &size_node.location,
                                format!(
                                    "resources.{name}.size must hold two integers or expressions"
                                ),
                            );
                            return None;
                        }
                    }
                }
                _ => {
                    b.schema(&size_node.location, format!("resources.{name}.size must be [width, height], \"screen\" or \"screen/N\""));
                    return None;
                }
            }
        }
    };
    let format = match (kind, t.get("format")) {
        (ResourceKind::Texture, Some(e)) => {
            let s = b.string(e, &format!("resources.{name}.format"))?;
            match s.value.parse::<Format>() {
                Ok(f) => Some(Spanned::new(f, s.location)),
                Err(err) => {
                    b.schema(&s.location, err.to_string());
                    return None;
                }
            }
        }
        (ResourceKind::Texture, None) => {
            b.schema(
                &entry.key,
                format!("{context} is a texture and needs a `format`"),
            );
            return None;
        }
        _ => None,
    };
    let int_field = |key: &str| {
        t.get(key)
            .map(|e| e.value.clone())
            .and_then(|n| match n.value {
                Node::Scalar(v) => Some(Spanned::new(v, n.location)),
                _ => None,
            })
    };
    Some(ResourceDecl {
        name: name.to_owned(),
        kind: Spanned::new(kind, kind_name.location),
        format,
        size,
        layers: int_field("layers"),
        samples: int_field("samples"),
        location: entry.key.clone(),
    })
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
    Some(PassDecl {
        name: name.to_owned(),
        type_name,
        view,
        draw,
        reads,
        writes,
        params,
        shader,
        location: entry.key.clone(),
    })
}

/// A shader path is relative to the file that wrote it; failing that, to the
/// repository root (the first ancestor holding `shaders/`), so pipelines can
/// say `shader = "shaders/x.wgsl"`; failing that, on the library search path
/// (`plait_assets::find_named`), so a pipeline copied out of the repository
/// still finds the library's shaders. The first candidate that exists wins; if
/// none does, the file-relative path is kept for the error message of
/// whoever opens it.
pub fn resolve_shader(written: &str, location: &Location) -> PathBuf {
    let base_dir = match location {
        Location::File { path, .. } => path.parent().map(Path::to_path_buf).unwrap_or_default(),
        _ => std::env::current_dir().unwrap_or_default(),
    };
    let next_to_file = base_dir.join(written);
    if plait_assets::exists(&next_to_file) {
        return next_to_file;
    }
    // Lexical ancestors first, so relative inputs give relative (stable,
    // snapshot-friendly) paths; then the canonical ones, for `x.toml` run
    // from inside `pipelines/`.
    let absolute_base = std::fs::canonicalize(&base_dir).unwrap_or_else(|_| base_dir.clone());
    // A built-in copy has no disk ancestors (its last lexical one, "", would
    // be the working directory).
    let ancestors = if plait_assets::is_builtin(&base_dir) {
        vec![]
    } else {
        vec![&base_dir, &absolute_base]
    };
    for base in ancestors {
        let root = base.ancestors().find(|a| a.join("shaders").is_dir());
        if let Some(root) = root {
            let candidate = root.join(written);
            if candidate.exists() {
                return candidate;
            }
        }
    }
    plait_assets::find_named(written, "shaders").unwrap_or(next_to_file)
}
