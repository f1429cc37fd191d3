//! The located value tree: TOML parsed with the `file:line:column` of every
//! key and value, merged key by key (`extends`, `--set`, techniques).

use indexmap::IndexMap;
use std::path::{Path, PathBuf};

use super::file_location;
use crate::error::{Error, ErrorKind, Errors, Location, Spanned};
use crate::value::Value;

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
        let offset = e.span().map_or(0, |s| s.start);
        // `light_size = 1024 +` is a broken expression, not a string that
        // wants quotes: say what is wrong with the expression.
        if let Some((at, message)) = unquoted_expression(text, offset) {
            return Error::new(map.location(at), ErrorKind::Schema(message));
        }
        Error::new(
            map.location(offset),
            ErrorKind::Syntax(e.message().trim().to_owned()),
        )
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

/// When the line of a syntax error at `offset` is `key = VALUE` with VALUE
/// an unquoted arithmetic expression (`1024 + 2`, `${light_size} * 2`): the
/// value's offset and what is wrong — the expression itself when it is
/// incomplete, else only the missing quotes.
fn unquoted_expression(text: &str, offset: usize) -> Option<(usize, String)> {
    let start = text[..offset.min(text.len())]
        .rfind('\n')
        .map_or(0, |i| i + 1);
    let end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let line = &text[start..end];
    let (key_part, rest) = line.split_once('=')?;
    let key = key_part.trim();
    // Values TOML could parse start with a quote, bracket, brace, digit
    // or sign; an expression also holds an operator or a `${…}` after that.
    let value = rest.split('#').next()?.trim();
    let looks_like_expression = !value.is_empty()
        && !value.starts_with(['"', '\'', '[', '{'])
        && (value.contains("${") || value.chars().skip(1).any(|c| "+-*/()".contains(c)));
    if key.is_empty() || !looks_like_expression {
        return None;
    }
    let at = start + key_part.len() + 1 + rest.find(value).unwrap_or(0);
    // Any name stands for a number here: only the shape is checked.
    let shape = substitute_references(value);
    let quoted = format!("`{key} = \"{value}\"`");
    let message = match crate::expr::eval(&shape, &|_| Some(1.0)) {
        Ok(_) => format!("`{value}` is an expression: write it as a string, {quoted}"),
        Err(why) => format!(
            "`{value}` is not a complete expression ({}); an expression is written as a string, e.g. \"${{light_size}} * 2\"",
            why.replace(&format!(" in expression `{shape}`"), "")
        ),
    };
    Some((at, message))
}

/// `${name}` replaced by `name`, so the expression parser sees its shape.
fn substitute_references(value: &str) -> String {
    let mut out = String::new();
    let mut rest = value;
    while let Some(i) = rest.find("${") {
        out.push_str(&rest[..i]);
        match rest[i + 2..].find('}') {
            Some(len) => {
                out.push_str(&rest[i + 2..i + 2 + len]);
                rest = &rest[i + 3 + len..];
            }
            None => {
                out.push_str(&rest[i..]);
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
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
pub(super) fn load_chain(
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
            ErrorKind::ReadFile {
                path: base_path.clone(),
                reason: e.to_string(),
            },
        )
    })?;
    let mut base = load_chain(&base_path, &base_text, chain, files)?;
    merge(&mut base, child);
    Ok(base)
}
