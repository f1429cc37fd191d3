//! `${name}` substitution from `[params]`.

use std::collections::HashMap;

use super::tree::{Entry, Node, Table};
use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::value::Value;

struct Substituter {
    raw: Table,
    resolved: HashMap<String, Spanned<Node>>,
    /// Params being resolved, to report loops.
    stack: Vec<String>,
    errors: Vec<Error>,
}

pub(super) fn substitute_params(root: Spanned<Node>, errors: &mut Vec<Error>) -> Spanned<Node> {
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
                    // so a bad value is reported where it is used — unless a
                    // `--set` flag gave x: then the flag is what to fix.
                    match self.param(name, location) {
                        Some(v) if matches!(v.location, Location::Flag { .. }) => return v,
                        Some(v) => v.value,
                        None => node.value.clone(),
                    }
                } else {
                    let (text, flag) = self.interpolate(s, location);
                    // An expression built from a flag's value (`"screen_width
                    // * ${slices} / 8"` with `--set params.slices=0`) is the
                    // flag's to fix, as a whole reference is. Not a path
                    // (`"${dir}/a.wgsl"`): that resolves against its file.
                    match flag.filter(|_| is_expression(&text)) {
                        Some(flag) => return Spanned::new(Node::Scalar(Value::Str(text)), flag),
                        None => Node::Scalar(Value::Str(text)),
                    }
                }
            }
            Node::Scalar(v) => Node::Scalar(v.clone()),
            Node::List(items) => {
                let items: Vec<Spanned<Node>> = items.iter().map(|i| self.node(i)).collect();
                // A list is checked as a whole (`size = ["${light_size}",
                // "${light_size}"]` is 0x0): one made from a flag's value
                // names the flag.
                if let Some(flag) = items.iter().map(|i| &i.location).find(|l| is_flag(l)) {
                    let flag = flag.clone();
                    return Spanned::new(Node::List(items), flag);
                }
                Node::List(items)
            }
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

    /// Replaces each `${x}` inside a longer string by x's text; also the
    /// flag that gave the first x a `--set` flag gave, if any.
    fn interpolate(&mut self, text: &str, location: &Location) -> (String, Option<Location>) {
        let mut out = String::new();
        let mut flag = None;
        let mut rest = text;
        while let Some(start) = rest.find("${") {
            let Some(len) = rest[start + 2..].find('}') else {
                break;
            };
            out.push_str(&rest[..start]);
            let name = &rest[start + 2..start + 2 + len];
            let value = self.param(name, location);
            if let Some(v) = &value
                && flag.is_none()
                && is_flag(&v.location)
            {
                flag = Some(v.location.clone());
            }
            match value.map(|v| v.value) {
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
        (out, flag)
    }
}

fn is_flag(location: &Location) -> bool {
    matches!(location, Location::Flag { .. })
}

/// Whether `text` is arithmetic (`crate::expr`), whatever its names stand for.
fn is_expression(text: &str) -> bool {
    crate::expr::eval(text, &|_| Some(1.0)).is_ok()
}

fn whole_reference(s: &str) -> Option<&str> {
    let name = s.strip_prefix("${")?.strip_suffix('}')?;
    (!name.contains('}') && !name.contains("${")).then_some(name)
}
