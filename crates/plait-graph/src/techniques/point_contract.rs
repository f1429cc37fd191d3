//! The rest of a WGSL point's contract, beside its function (`[wgsl]`): what
//! its providers may bind and take, written once in `point.toml`.
//!
//! ```toml
//! [point]
//! bindings = [8, 15]        # the group-1 bindings its providers may declare
//!
//! [inputs.vis_range]        # an optional input slot any provider may bind
//! kind = "texture"          # (the keys of a pass-type file's slots)
//! access = "sampled"
//! formats = ["rg32float"]
//! doc = "occupancy: light-view depth range"
//!
//! [params.shadow_weight]    # a param any provider may read, with its default
//! type = "float"            # (the keys of a pass-type file's params)
//! default = 0.05
//! min = 0.0
//! max = 100.0
//! doc = "…"
//!
//! [params_from]             # a pass-type file's params, renamed, as the point's too
//! file = "shaders/passes/marschner_tables.toml"
//! prefix = "marschner_"
//! skip = ["table_size"]
//! ```
//!
//! Every pass type that shades with the point (the Rust ones included)
//! takes these slots and params, so a new slot name is a line here, never
//! Rust. A technique of the point is checked against them when chosen
//! ([`check_technique`]): each param and read it exports must be declared
//! here, and a `[params]` value it exports unchanged must equal the point's
//! default, so the default is one number.

use crate::error::{Error, ErrorKind, Errors, Location, Spanned};
use crate::load::{Node, Table};
use crate::node_reader::Reader;
use crate::pass_type_file::{read_param, read_slot};
use crate::{ParamSpec, SlotSpec};

/// One param of a point, with where it is declared.
#[derive(Clone, Debug, PartialEq)]
pub struct PointParam {
    pub spec: ParamSpec,
    /// Its `[params.NAME]` key.
    pub at: Location,
}

/// `[params_from]`: a pass-type file's params, renamed `<prefix><name>`.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamsFrom {
    /// Its library path (`shaders/passes/marschner_tables.toml`).
    pub file: String,
    pub prefix: String,
    pub skip: Vec<String>,
    pub at: Location,
}

/// What a point's providers may bind and take (see the module docs).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PointContract {
    /// First and last group-1 binding a provider may declare, and where.
    pub bindings: Option<Spanned<(u32, u32)>>,
    /// Optional input slots, in file order.
    pub inputs: Vec<SlotSpec>,
    pub params: Vec<PointParam>,
    pub params_from: Option<ParamsFrom>,
}

impl PointContract {
    /// Every param of the point: its `[params]`, then those of its
    /// `[params_from]` file (read from the search path now). A missing or
    /// broken file is an error at `[params_from]`; the pass library reports
    /// what is wrong inside it.
    pub fn all_params(&self) -> Result<Vec<PointParam>, Errors> {
        let mut out = self.params.clone();
        let Some(from) = &self.params_from else {
            return Ok(out);
        };
        let fail = |why: String| {
            Errors(vec![Error::new(
                from.at.clone(),
                ErrorKind::Schema(format!("[params_from] `{}`: {why}", from.file)),
            )])
        };
        let path = plait_assets::find(&from.file)
            .ok_or_else(|| fail("no such file on the library search path".into()))?;
        let text = plait_assets::read_to_string(&path).map_err(|e| fail(e.to_string()))?;
        let file = crate::pass_type_file::parse(&path, &text)
            .map_err(|e| fail(format!("the file does not read: {e}")))?;
        out.extend(
            file.spec
                .params
                .into_iter()
                .filter(|p| !from.skip.contains(&p.name))
                .map(|mut spec| {
                    spec.name = format!("{}{}", from.prefix, spec.name);
                    PointParam {
                        spec,
                        at: Location::Path { path: path.clone() },
                    }
                }),
        );
        Ok(out)
    }
}

pub(super) const POINT_KEYS: &[&str] = &["bindings"];
const FROM_KEYS: &[&str] = &["file", "prefix", "skip"];

/// Reads `[point] bindings`, `[inputs]`, `[params]` and `[params_from]`.
pub(super) fn read(r: &mut Reader<'_>, top: &Table, point: Option<&Table>) -> PointContract {
    let mut c = PointContract {
        bindings: point.and_then(|t| read_bindings(r, t)),
        ..PointContract::default()
    };
    if let Some(t) = top
        .get("inputs")
        .and_then(|e| r.table(&e.value, "[inputs]"))
    {
        for (name, entry) in t {
            let ctx = format!("inputs.{name}");
            let Some(st) = r.table(&entry.value, &ctx) else {
                continue;
            };
            if let Some((mut slot, _)) = read_slot(r, name, st, &entry.value.location, &ctx, false)
            {
                // A provider's input is bound only when its technique is chosen.
                slot.optional = true;
                c.inputs.push(slot);
            }
        }
    }
    if let Some(t) = top
        .get("params")
        .and_then(|e| r.table(&e.value, "[params]"))
    {
        for (name, entry) in t {
            if let Some(spec) = read_param(r, name, entry, &format!("params.{name}")) {
                c.params.push(PointParam {
                    spec,
                    at: entry.key.clone(),
                });
            }
        }
    }
    if let Some(e) = top.get("params_from") {
        c.params_from = read_from(r, e);
    }
    c
}

fn read_bindings(r: &mut Reader<'_>, t: &Table) -> Option<Spanned<(u32, u32)>> {
    let e = t.get("bindings")?;
    let bad = |r: &mut Reader<'_>| {
        r.schema(
            &e.value.location,
            "point.bindings must be [FIRST, LAST], two group-1 binding numbers, FIRST ≤ LAST"
                .into(),
        );
        None
    };
    let Node::List(items) = &e.value.value else {
        return bad(r);
    };
    let numbers: Vec<i64> = items
        .iter()
        .filter_map(|i| r.int(i, "point.bindings"))
        .collect();
    match numbers.as_slice() {
        [first, last] if 0 <= *first && first <= last && *last <= i64::from(u32::MAX) => Some(
            Spanned::new((*first as u32, *last as u32), e.value.location.clone()),
        ),
        _ => bad(r),
    }
}

fn read_from(r: &mut Reader<'_>, e: &crate::load::Entry) -> Option<ParamsFrom> {
    let t = r.table(&e.value, "[params_from]")?;
    r.keys(t, FROM_KEYS, "[params_from]");
    let mut text = |key: &str| match t.get(key) {
        Some(v) => r.string(&v.value, &format!("params_from.{key}")),
        None => {
            r.schema(&e.key, format!("[params_from] needs `{key}`"));
            None
        }
    };
    let (file, prefix) = (text("file"), text("prefix"));
    let skip = match t.get("skip") {
        Some(v) => r.strings(&v.value, "params_from.skip")?,
        None => Vec::new(),
    };
    Some(ParamsFrom {
        file: file?,
        prefix: prefix?,
        skip,
        at: e.key.clone(),
    })
}

/// Technique `name` of `point` against its point's contract: every param it
/// exports is the point's selecting param or one the point declares, every
/// read it exports a declared input slot, and a `[params]` value it exports
/// under the same name (`K = "${K}"`, the point's param tuned by the
/// technique) equals the point's default, so the default is one number.
pub(crate) fn check_technique(
    wgsl: &super::WgslPoint,
    name: &str,
    tree: &Spanned<Node>,
    exports: (Option<&Table>, Option<&Table>),
) -> Vec<Error> {
    let c = &wgsl.contract;
    let mut errors = Vec::new();
    let declared = match c.all_params() {
        Ok(p) => p,
        Err(e) => return e.0,
    };
    let point = &wgsl.point;
    let (reads, params) = exports;
    for (slot, e) in reads.into_iter().flatten() {
        if !c.inputs.iter().any(|s| s.name == *slot) {
            let names = c.inputs.iter().map(|s| s.name.as_str());
            errors.push(Error::new(
                e.key.clone(),
                ErrorKind::Schema(format!(
                    "{point} technique `{name}` exports a read of slot `{slot}`, which {} does not declare{} (its [inputs]: {}); declare it there",
                    wgsl.file,
                    crate::suggest::did_you_mean(slot, names.clone()),
                    names.collect::<Vec<_>>().join(", ")
                )),
            ));
        }
    }
    let own = super::table(tree, "params");
    for (param, e) in params.into_iter().flatten() {
        if *param == wgsl.param {
            continue;
        }
        let Some(decl) = declared.iter().find(|p| p.spec.name == *param) else {
            let names = declared.iter().map(|p| p.spec.name.as_str());
            errors.push(Error::new(
                e.key.clone(),
                ErrorKind::Schema(format!(
                    "{point} technique `{name}` exports param `{param}`, which {} does not declare{} (its params: {}); declare it there with its default and range",
                    wgsl.file,
                    crate::suggest::did_you_mean(param, names.clone()),
                    names.collect::<Vec<_>>().join(", ")
                )),
            ));
            continue;
        };
        let same_name = matches!(&e.value.value, Node::Scalar(crate::value::Value::Str(s)) if *s == format!("${{{param}}}"));
        let own_value = own.and_then(|t| t.get(param.as_str()));
        if let (true, Some(v), Some(default)) = (same_name, own_value, &decl.spec.default)
            && let Node::Scalar(value) = &v.value.value
            && !same_number(value, default)
        {
            errors.push(Error::new(
                v.value.location.clone(),
                ErrorKind::Schema(format!(
                    "{point} technique `{name}`: `{param} = {value}` differs from the point's default {default} ({}): a point param has one default; write {default} here, change the point's, or export a differently named param of the technique's own under `{param}`",
                    decl.at
                )),
            ));
        }
    }
    errors
}

/// Whether two scalars are the same value (an int and a float of equal value are).
fn same_number(a: &crate::value::Value, b: &crate::value::Value) -> bool {
    use crate::value::Value;
    let num = |v: &Value| match v {
        Value::Int(i) => Some(*i as f64),
        Value::Float(f) => Some(*f),
        _ => None,
    };
    match (num(a), num(b)) {
        (Some(x), Some(y)) => x == y,
        _ => a == b,
    }
}
