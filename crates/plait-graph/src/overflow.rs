//! Overflow counters: a buffer that counts what a bounded buffer could not
//! hold, declared on the counter's resource so the engine can read it back
//! and the session can size the bounded buffer to hold everything.
//!
//! ```toml
//! [resources.list_counter]
//! kind = "buffer"
//! size = "8"
//! overflow = { of = "list_nodes", dropped = 1, needed = 0,
//!              param = "nodes_per_pixel", per = "screen_width * screen_height" }
//! ```
//!
//! Word `dropped` of the counter counts the items `of` could not hold; word
//! `needed` the capacity that would have held them all (read only when
//! something was dropped). `of` holds `param × per` items, so
//! `ceil(needed / per)` is the value of `param` that holds everything.
//!
//! `incomplete = W` (optional) names a word counting shader invocations that
//! could not finish their work — a shader's own check, for limits no load-time
//! check can see (lavapipe stops every loop of an invocation once the
//! invocation has run 65,535 loop iterations in total). Any non-zero count
//! fails the frame: its output is missing data, and no param holds it.
//! A counter that only counts such invocations (no bounded buffer behind it)
//! declares `incomplete` alone: `overflow = { incomplete = 0 }`.
//!
//! Why the param's origin matters: a param the user set (a `--set` flag or a
//! pipeline file) is a cap to respect and report; one that still has its
//! technique file's default is only a starting size, which the session may
//! raise ([`OverflowCounter::grows`]).

use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::load::{Node, Pipeline, Table};
use crate::node_reader::Reader;
use crate::schedule::ResourceId;
use crate::schedule::{CompileOptions, OverflowCounter, ResolvedResource};
use crate::value::Value;

const KEYS: &[&str] = &["of", "dropped", "needed", "param", "per", "incomplete"];
/// Counters are small: a word index past this is a mistake, not a layout.
const MAX_WORD: i64 = 63;

/// An `overflow = {…}` table as written (see the module docs).
#[derive(Clone, Debug)]
pub struct OverflowDecl {
    /// What the counter counts for a bounded buffer; `None` for a counter of
    /// `incomplete` invocations only.
    pub bounded: Option<BoundedDecl>,
    /// The word counting invocations that could not finish (module docs).
    pub incomplete: Option<Spanned<u32>>,
    pub location: Location,
}

/// The bounded-buffer part of an `overflow = {…}` table.
#[derive(Clone, Debug)]
pub struct BoundedDecl {
    pub of: Spanned<String>,
    pub dropped: Spanned<u32>,
    pub needed: Spanned<u32>,
    pub param: Spanned<String>,
    /// Items of `of` per unit of `param`: an integer or an expression.
    pub per: Spanned<Value>,
}

/// The keys of the bounded-buffer part.
const BOUNDED_KEYS: &[&str] = &["of", "dropped", "needed", "param", "per"];

/// Reads `resources.NAME.overflow`, each problem a schema error at its key.
pub(crate) fn parse(
    node: &Spanned<Node>,
    resource: &str,
    errors: &mut Vec<Error>,
) -> Option<OverflowDecl> {
    let context = format!("resources.{resource}.overflow");
    let mut r = Reader { errors };
    let t: &Table = r.table(node, &context)?;
    r.keys(t, KEYS, &context);
    let word = |r: &mut Reader, e: &crate::load::Entry, key: &str| {
        let n = r.int(&e.value, &format!("{context}.{key}"))?;
        if !(0..=MAX_WORD).contains(&n) {
            r.schema(
                &e.value.location,
                format!(
                    "{context}.{key} is a u32 word index of the counter, 0 … {MAX_WORD}; found {n}"
                ),
            );
            return None;
        }
        Some(Spanned::new(n as u32, e.value.location.clone()))
    };
    let incomplete = match t.get("incomplete") {
        Some(e) => Some(word(&mut r, e, "incomplete")?),
        None => None,
    };
    // A pure counter of incomplete invocations: no bounded buffer behind it.
    if incomplete.is_some() && BOUNDED_KEYS.iter().all(|k| t.get(*k).is_none()) {
        return Some(OverflowDecl {
            bounded: None,
            incomplete,
            location: node.location.clone(),
        });
    }
    let mut missing = Vec::new();
    let mut get = |key: &str| {
        let e = t.get(key);
        if e.is_none() {
            missing.push(key.to_owned());
        }
        e
    };
    let (of, dropped, needed, param) = (get("of"), get("dropped"), get("needed"), get("param"));
    if !missing.is_empty() {
        r.schema(
            &node.location,
            format!(
                "{context} needs {} (it has: {})",
                missing.join(", "),
                t.keys().cloned().collect::<Vec<_>>().join(", ")
            ),
        );
        return None;
    }
    let string = |r: &mut Reader, e: &crate::load::Entry, key: &str| {
        r.string(&e.value, &format!("{context}.{key}"))
            .map(|s| Spanned::new(s, e.value.location.clone()))
    };
    let per = match t.get("per") {
        None => Spanned::new(Value::Int(1), node.location.clone()),
        Some(e) => match &e.value.value {
            Node::Scalar(v @ (Value::Int(_) | Value::Str(_))) => {
                Spanned::new(v.clone(), e.value.location.clone())
            }
            _ => {
                r.schema(
                    &e.value.location,
                    format!("{context}.per is an integer or an expression (`screen_width * screen_height`)"),
                );
                return None;
            }
        },
    };
    let (of, dropped, needed, param) = (of?, dropped?, needed?, param?);
    let bounded = BoundedDecl {
        of: string(&mut r, of, "of")?,
        dropped: word(&mut r, dropped, "dropped")?,
        needed: word(&mut r, needed, "needed")?,
        param: string(&mut r, param, "param")?,
        per,
    };
    Some(OverflowDecl {
        bounded: Some(bounded),
        incomplete,
        location: node.location.clone(),
    })
}

/// Checks every declaration against the pipeline: `of` a declared buffer,
/// both words inside the counter, `param` an integer param, `per` positive.
pub(crate) fn check(pipeline: &Pipeline, opts: &CompileOptions, errors: &mut Vec<Error>) {
    for r in pipeline.resources.values() {
        if let Some(d) = &r.overflow {
            let _ = resolve_one(pipeline, &r.name, d, opts, errors);
        }
    }
}

/// The schedule's counters: the declarations whose counter is allocated
/// (a counter only culled passes write is not read).
pub(crate) fn counters(
    pipeline: &Pipeline,
    resources: &[ResolvedResource],
    opts: &CompileOptions,
) -> Vec<OverflowCounter> {
    let mut ignored = Vec::new();
    pipeline
        .resources
        .values()
        .filter_map(|r| {
            let d = r.overflow.as_ref()?;
            let counter = ResourceId::new(resources.iter().position(|x| x.name == r.name)?);
            let resolved = resolve_one(pipeline, &r.name, d, opts, &mut ignored)?;
            let incomplete_word = d.incomplete.as_ref().map(|w| w.value);
            let (Some(b), Some((value, per))) = (&d.bounded, resolved) else {
                // Only incomplete invocations: nothing to size or grow.
                return Some(OverflowCounter {
                    counter,
                    counter_name: r.name.clone(),
                    of: String::new(),
                    dropped_word: None,
                    needed_word: None,
                    incomplete_word,
                    param: String::new(),
                    value: 0,
                    per: 1,
                    grows: false,
                    param_location: d.location.clone(),
                });
            };
            let location = pipeline.params.get(&b.param.value)?.location.clone();
            Some(OverflowCounter {
                counter,
                counter_name: r.name.clone(),
                of: b.of.value.clone(),
                dropped_word: Some(b.dropped.value),
                needed_word: Some(b.needed.value),
                incomplete_word,
                param: b.param.value.clone(),
                value,
                per,
                grows: is_technique_default(pipeline, &location),
                param_location: location,
            })
        })
        .collect()
}

/// A param keeps its technique's default when its value was written in a
/// chosen technique's file; a flag or a pipeline file sets it.
fn is_technique_default(pipeline: &Pipeline, location: &Location) -> bool {
    match location {
        Location::File { path, .. } => pipeline.techniques.iter().any(|t| t.owns(path)),
        _ => false,
    }
}

/// (param value, per) of one declaration (`Some(None)` for a counter of
/// incomplete invocations only), or the errors that stop it.
fn resolve_one(
    pipeline: &Pipeline,
    counter: &str,
    d: &OverflowDecl,
    opts: &CompileOptions,
    errors: &mut Vec<Error>,
) -> Option<Option<(i64, u64)>> {
    let bad = |location: &Location, reason: String| {
        Error::new(
            location.clone(),
            ErrorKind::BadResource {
                resource: counter.to_owned(),
                reason,
            },
        )
    };
    let mut ok = true;
    if let Some(r) = pipeline.resources.get(counter)
        && let Some(Ok(bytes)) = match &r.size {
            crate::load::SizeDecl::Bytes(v) => Some(crate::compile::int_of(v, opts)),
            _ => None,
        }
    {
        let bounded = d.bounded.iter().flat_map(|b| [&b.dropped, &b.needed]);
        for w in bounded.chain(d.incomplete.as_ref()) {
            if (w.value as i64 + 1) * 4 > bytes {
                errors.push(bad(
                    &w.location,
                    format!(
                        "word {} is past the end of the counter ({bytes} bytes = {} words)",
                        w.value,
                        bytes / 4
                    ),
                ));
                ok = false;
            }
        }
    }
    let Some(d) = &d.bounded else {
        return ok.then_some(None);
    };
    match pipeline.resources.get(&d.of.value) {
        Some(r) if r.kind.value == crate::spec::ResourceKind::Buffer => {}
        Some(_) => {
            errors.push(bad(
                &d.of.location,
                format!(
                    "overflow.of `{}` is a texture; a bounded buffer is counted",
                    d.of.value
                ),
            ));
            ok = false;
        }
        None => {
            let hint = crate::suggest::did_you_mean(
                &d.of.value,
                pipeline.resources.keys().map(String::as_str),
            );
            errors.push(bad(
                &d.of.location,
                format!(
                    "overflow.of `{}` is not a declared resource{hint}",
                    d.of.value
                ),
            ));
            ok = false;
        }
    }
    let value = match pipeline.params.get(&d.param.value) {
        Some(p) => match p.value {
            Value::Int(n) if n >= 1 => Some(n),
            ref other => {
                errors.push(bad(&d.param.location, format!("overflow.param `{}` is {other} (at {}); it must be a positive integer, the bounded buffer's size", d.param.value, p.location)));
                None
            }
        },
        None => {
            let hint = crate::suggest::did_you_mean(
                &d.param.value,
                pipeline.params.keys().map(String::as_str),
            );
            errors.push(bad(
                &d.param.location,
                format!(
                    "overflow.param `{}` is not in [params]{hint}",
                    d.param.value
                ),
            ));
            None
        }
    };
    let per = match crate::compile::int_of(&d.per, opts) {
        Ok(n) if n >= 1 => Some(n as u64),
        Ok(n) => {
            errors.push(bad(
                &d.per.location,
                format!("overflow.per is {n}; it must be positive"),
            ));
            None
        }
        Err(reason) => {
            errors.push(bad(&d.per.location, format!("overflow.per: {reason}")));
            None
        }
    };
    match (ok, value, per) {
        (true, Some(v), Some(p)) => Some(Some((v, p))),
        _ => None,
    }
}
