//! Reading typed values out of a located TOML tree ([`crate::load::Node`]),
//! each problem a schema error at the value's `file:line:column`. Shared by
//! the raster state keys and pass-type files.

use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::load::{Node, Table};
use crate::value::Value;

pub(crate) struct Reader<'e> {
    pub(crate) errors: &'e mut Vec<Error>,
}

impl Reader<'_> {
    pub(crate) fn schema(&mut self, location: &Location, message: String) {
        self.errors
            .push(Error::new(location.clone(), ErrorKind::Schema(message)));
    }

    pub(crate) fn table<'t>(
        &mut self,
        node: &'t Spanned<Node>,
        context: &str,
    ) -> Option<&'t Table> {
        match &node.value {
            Node::Table(t) => Some(t),
            _ => {
                self.schema(&node.location, format!("{context} must be a table"));
                None
            }
        }
    }

    /// Reports keys of `table` that are not `accepted`, suggesting the nearest.
    pub(crate) fn keys(&mut self, table: &Table, accepted: &[&str], context: &str) {
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

    pub(crate) fn string(&mut self, node: &Spanned<Node>, context: &str) -> Option<String> {
        match &node.value {
            Node::Scalar(Value::Str(s)) => Some(s.clone()),
            _ => {
                self.schema(&node.location, format!("{context} must be a string"));
                None
            }
        }
    }

    pub(crate) fn bool(&mut self, node: &Spanned<Node>, context: &str) -> Option<bool> {
        match &node.value {
            Node::Scalar(Value::Bool(b)) => Some(*b),
            _ => {
                self.schema(&node.location, format!("{context} must be true or false"));
                None
            }
        }
    }

    pub(crate) fn int(&mut self, node: &Spanned<Node>, context: &str) -> Option<i64> {
        match &node.value {
            Node::Scalar(Value::Int(i)) => Some(*i),
            _ => {
                self.schema(&node.location, format!("{context} must be an integer"));
                None
            }
        }
    }

    pub(crate) fn number(&mut self, node: &Spanned<Node>, context: &str) -> Option<f64> {
        match &node.value {
            Node::Scalar(Value::Int(i)) => Some(*i as f64),
            Node::Scalar(Value::Float(x)) => Some(*x),
            _ => {
                self.schema(&node.location, format!("{context} must be a number"));
                None
            }
        }
    }

    pub(crate) fn strings(&mut self, node: &Spanned<Node>, context: &str) -> Option<Vec<String>> {
        match &node.value {
            Node::List(items) => items
                .iter()
                .map(|i| self.string(i, &format!("{context}[…]")))
                .collect(),
            _ => {
                self.schema(
                    &node.location,
                    format!("{context} must be a list of strings"),
                );
                None
            }
        }
    }

    /// A list of strings, each kept with its own location so an error
    /// about one entry points at that entry, not at the list.
    pub(crate) fn spanned_strings(
        &mut self,
        node: &Spanned<Node>,
        context: &str,
    ) -> Option<Vec<Spanned<String>>> {
        match &node.value {
            Node::List(items) => items
                .iter()
                .map(|i| {
                    self.string(i, &format!("{context}[…]"))
                        .map(|s| Spanned::new(s, i.location.clone()))
                })
                .collect(),
            _ => {
                self.schema(
                    &node.location,
                    format!("{context} must be a list of strings"),
                );
                None
            }
        }
    }

    /// A string that must be one of `accepted`.
    pub(crate) fn named(
        &mut self,
        node: &Spanned<Node>,
        context: &str,
        accepted: &[&str],
    ) -> Option<String> {
        let Node::Scalar(Value::Str(s)) = &node.value else {
            self.schema(
                &node.location,
                format!("{context} must be a string, one of {}", accepted.join(", ")),
            );
            return None;
        };
        if accepted.contains(&s.as_str()) {
            return Some(s.clone());
        }
        self.schema(
            &node.location,
            format!(
                "{context} is `{s}`{} (accepted: {})",
                crate::suggest::did_you_mean(s, accepted.iter().copied()),
                accepted.join(", ")
            ),
        );
        None
    }
}
