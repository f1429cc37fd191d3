//! Resolving one pass: its type looked up in the registry, its params checked
//! and defaulted, the fields that apply to its shape (`view`, `draw`, raster
//! state, `shader`), and its `reads`/`writes` bound to resources with each
//! slot's kind and format checked (`bind.rs`).

use indexmap::IndexMap;

use crate::error::{Error, ErrorKind, Location};
use crate::load::{PassDecl, Pipeline};
use crate::schedule::*;
use crate::spec::{Draw, ParamSpec, ParamType, PassShape, PassTypeSpec, Registry, SlotSpec, View};
use crate::value::Value;

use super::bind::{Direction, bind_slots};
use super::values::int_value;

/// Checks one param value against its spec, returning the normalised value.
fn check_param(spec: &ParamSpec, value: &Value, opts: &CompileOptions) -> Result<Value, String> {
    match &spec.ty {
        ParamType::Int { min, max } => {
            let n = int_value(value, opts)?;
            if n < *min || n > *max {
                return Err(format!("{n} is out of range {min}..={max}"));
            }
            Ok(Value::Int(n))
        }
        ParamType::Float { min, max } => {
            let x = value
                .as_f64()
                .ok_or_else(|| format!("expected a number, found {value}"))?;
            if x < *min || x > *max || x.is_nan() {
                return Err(format!("{x} is out of range {min}..={max}"));
            }
            Ok(Value::Float(x))
        }
        ParamType::Bool => value
            .as_bool()
            .map(Value::Bool)
            .ok_or_else(|| format!("expected true or false, found {value}")),
        ParamType::Str => value
            .as_str()
            .map(|s| Value::Str(s.to_owned()))
            .ok_or_else(|| format!("expected a string, found {value}")),
        ParamType::Enum(choices) => match value.as_str() {
            Some(s) if choices.iter().any(|c| c == s) => Ok(Value::Str(s.to_owned())),
            _ => Err(format!(
                "{value} is not one of: {}{}",
                choices.join(", "),
                value
                    .as_str()
                    .map(|s| crate::suggest::did_you_mean(s, choices.iter().map(String::as_str)))
                    .unwrap_or_default()
            )),
        },
        ParamType::Vec3 => match value.as_vec3() {
            Some(v) => Ok(Value::List(
                v.iter().map(|&x| Value::Float(x as f64)).collect(),
            )),
            None => Err(format!(
                "expected three numbers like [1.0, 0.5, 0.2], found {value}"
            )),
        },
    }
}

pub(super) fn resolve_pass(
    decl: &PassDecl,
    registry: &Registry,
    pipeline: &Pipeline,
    descs: &[Option<ResourceDesc>],
    opts: &CompileOptions,
    errors: &mut Vec<Error>,
) -> ScheduledPass {
    let spec = registry.get(&decl.type_name.value);
    if spec.is_none() {
        let known = registry.names().join(", ");
        errors.push(Error::new(
            decl.type_name.location.clone(),
            ErrorKind::UnknownPassType {
                name: decl.type_name.value.clone(),
                known,
            },
        ));
    }

    let mut params = IndexMap::new();
    if let Some(spec) = spec {
        params = check_params(decl, spec, registry, opts, errors);
        check_view_and_draw(decl, spec, errors);
        check_raster_keys(decl, spec, errors);
        check_shader_field(decl, spec, errors);
        check_loads(decl, errors);
    }

    // A pass drawing hair also takes the geometry providers' slots.
    let draws_hair = decl
        .draw
        .as_ref()
        .is_some_and(|d| crate::Draw::from_name(&d.value) == Some(crate::Draw::Hair));
    let shared: &[SlotSpec] = if draws_hair {
        &registry.shared_slots
    } else {
        &[]
    };
    let reads = bind_slots(decl, spec, shared, pipeline, descs, Direction::Read, errors);
    let mut writes = bind_slots(decl, spec, &[], pipeline, descs, Direction::Write, errors);
    pair_resolves(&mut writes);
    // The blends of the pass over its type's (the decl build uses,
    // `PassType::raster_decl`), each slot resolved to its write.
    let blend_writes = spec
        .map_or_else(
            || decl.raster.clone(),
            |s| s.raster.overridden_by(&decl.raster),
        )
        .blend
        .keys()
        .map(|slot| writes.iter().position(|b| &b.slot == slot))
        .collect();
    ScheduledPass {
        name: decl.name.clone(),
        type_name: decl.type_name.value.clone(),
        type_id: registry
            .types
            .get_index_of(&decl.type_name.value)
            .map(crate::schedule::PassTypeId::new),
        shape: spec.map_or(PassShape::Compute, |s| s.shape),
        // Their names were checked at load.
        view: decl.view.as_ref().and_then(|v| View::from_name(&v.value)),
        draw: decl.draw.as_ref().and_then(|v| Draw::from_name(&v.value)),
        reads,
        writes,
        params,
        shader: decl.shader.as_ref().map(|s| s.value.clone()),
        shader_location: decl.shader.as_ref().map(|s| s.location.clone()),
        raster: decl.raster.clone(),
        blend_writes,
        run_once: decl.run_once.is_some(),
        location: decl.location.clone(),
        technique: match &decl.location {
            Location::File { path, .. } => pipeline
                .techniques
                .iter()
                .find(|t| t.owns(path))
                .map(|t| t.label()),
            _ => None,
        },
    }
}

/// Pairs each written `X_resolve` with the written `X` whose samples it
/// receives: by name here, once, so build pairs them by index.
fn pair_resolves(writes: &mut [Binding]) {
    for i in 0..writes.len() {
        let base = writes[i].slot.strip_suffix("_resolve");
        writes[i].resolves = base.and_then(|base| writes.iter().position(|b| b.slot == base));
    }
}

/// An error about pass `decl` at `location`.
fn pass_error(decl: &PassDecl, location: &Location, message: String) -> Error {
    Error::new(
        location.clone(),
        ErrorKind::Pass {
            pass: decl.name.clone(),
            message,
        },
    )
}

/// Checks the pass's params against its type, returning them normalised
/// (and, unless the type's slots are dynamic, in the type's order with
/// defaults filled in).
fn check_params(
    decl: &PassDecl,
    spec: &PassTypeSpec,
    registry: &Registry,
    opts: &CompileOptions,
    errors: &mut Vec<Error>,
) -> IndexMap<String, Value> {
    let mut params = IndexMap::new();
    // A pass that draws hair takes the providers' params whatever its type:
    // the `geometry` point joins every hair draw (its point file's `draws`),
    // and its provider runs in the vertex stage they all share.
    let draws_hair = decl
        .draw
        .as_ref()
        .is_some_and(|d| crate::Draw::from_name(&d.value) == Some(crate::Draw::Hair));
    let takes_shared = spec.dynamic_slots || draws_hair;
    for (name, value) in &decl.params {
        let shared = registry.shared_params.iter().find(|p| &p.name == name);
        let declared = spec.params.iter().any(|p| &p.name == name);
        if spec.dynamic_slots && shared.is_none() && !declared {
            // Data-only passes: params are whatever the shader reads (a
            // `params` uniform member or a define), checked against
            // naga's reflection and the shader's text later; one the type
            // declares (`path_trace`'s spp) is held to its range below.
            params.insert(name.clone(), value.value.clone());
            continue;
        }
        let own = spec.params.iter().find(|p| &p.name == name);
        let Some(param) = own.or(shared.filter(|_| takes_shared)) else {
            let known: Vec<_> = spec.params.iter().map(|p| p.name.as_str()).collect();
            errors.push(Error::new(
                value.location.clone(),
                ErrorKind::UnknownParam {
                    pass: decl.name.clone(),
                    pass_type: spec.name.clone(),
                    param: name.clone(),
                    known: if known.is_empty() {
                        "none".into()
                    } else {
                        known.join(", ")
                    },
                },
            ));
            continue;
        };
        match check_param(param, value, opts) {
            Ok(v) => {
                params.insert(name.clone(), v);
            }
            Err(reason) => errors.push(Error::new(
                value.location.clone(),
                ErrorKind::BadParam {
                    pass: decl.name.clone(),
                    param: name.clone(),
                    reason,
                },
            )),
        }
    }
    let mut ordered = order_params(decl, spec, &mut params, errors);
    if takes_shared {
        // A data-only pass also takes params its type does not declare (its
        // shader's, checked against the shader), and a hair draw the
        // providers' params: after the declared ones.
        ordered.extend(params);
    }
    ordered
}

/// Every param of the type, in the type's order, defaults filled in, taken
/// out of `params`; reports the missing ones.
fn order_params(
    decl: &PassDecl,
    spec: &PassTypeSpec,
    params: &mut IndexMap<String, Value>,
    errors: &mut Vec<Error>,
) -> IndexMap<String, Value> {
    let mut ordered = IndexMap::new();
    for param in &spec.params {
        if let Some(v) = params.shift_remove(&param.name) {
            ordered.insert(param.name.clone(), v);
        } else if decl.params.contains_key(&param.name) {
            // Already reported as a bad value.
        } else if let Some(default) = &param.default {
            ordered.insert(param.name.clone(), default.clone());
        } else {
            errors.push(Error::new(
                decl.location.clone(),
                ErrorKind::MissingParam {
                    pass: decl.name.clone(),
                    param: param.name.clone(),
                },
            ));
        }
    }
    ordered
}

/// `view` and `draw`: required of a raster pass, not applicable otherwise.
fn check_view_and_draw(decl: &PassDecl, spec: &PassTypeSpec, errors: &mut Vec<Error>) {
    if spec.shape == PassShape::Raster {
        for (field, value) in [("view", &decl.view), ("draw", &decl.draw)] {
            if value.is_none() {
                let names = if field == "view" {
                    View::NAMES
                } else {
                    Draw::NAMES
                };
                let hint = names.join(" | ");
                errors.push(pass_error(
                    decl,
                    &decl.location,
                    format!(
                        "type `{}` rasterizes geometry and needs `{field} = ` {hint}",
                        spec.name
                    ),
                ));
            }
        }
    } else {
        for (field, value) in [("view", &decl.view), ("draw", &decl.draw)] {
            if let Some(v) = value {
                errors.push(pass_error(
                    decl,
                    &v.location,
                    format!(
                        "type `{}` draws no scene geometry, so `{field}` does not apply",
                        spec.name
                    ),
                ));
            }
        }
    }
}

/// Reports each raster state key that does not apply to the pass's type.
fn check_raster_keys(decl: &PassDecl, spec: &PassTypeSpec, errors: &mut Vec<Error>) {
    for (key, location) in decl.raster.keys() {
        // A fullscreen pass has colour targets (blend, loads) and may
        // write a depth target through `@builtin(frag_depth)` (depth);
        // culling and alpha to coverage need geometry.
        let applies = spec.state_from_data
            && (matches!(key, "blend" | "loads" | "depth") || spec.shape == PassShape::Raster);
        if !applies {
            let why = if spec.state_from_data {
                "draws no scene geometry".to_owned()
            } else {
                "sets its raster state in Rust (`depth`, `blend` and `cull` are for `type = \"raster\"`, `fullscreen` and pass types declared in TOML)".to_owned()
            };
            errors.push(pass_error(
                decl,
                location,
                format!("type `{}` {why}, so `{key}` does not apply", spec.name),
            ));
        }
    }
}

/// `shader`: required when the type runs the pipeline's shader, not
/// applicable when it brings its own.
fn check_shader_field(decl: &PassDecl, spec: &PassTypeSpec, errors: &mut Vec<Error>) {
    match (&decl.shader, spec.needs_shader) {
        (None, true) => errors.push(pass_error(
            decl,
            &decl.location,
            format!(
                "type `{}` runs a shader from the pipeline and needs `shader = \"….wgsl\"`",
                spec.name
            ),
        )),
        (Some(s), false) => errors.push(pass_error(
            decl,
            &s.location,
            format!(
                "type `{}` brings its own shader; `shader` does not apply",
                spec.name
            ),
        )),
        _ => {}
    }
}

/// Reports each slot `loads` names that the pass does not write.
fn check_loads(decl: &PassDecl, errors: &mut Vec<Error>) {
    for slot in &decl.raster.loads {
        if !decl.writes.contains_key(&slot.value) {
            let written: Vec<&str> = decl.writes.keys().map(String::as_str).collect();
            errors.push(pass_error(
                decl,
                &slot.location,
                format!(
                    "`loads` names `{}`, which this pass does not write{} (written: {})",
                    slot.value,
                    crate::suggest::did_you_mean(&slot.value, written.iter().copied()),
                    if written.is_empty() {
                        "none".into()
                    } else {
                        written.join(", ")
                    }
                ),
            ));
        }
    }
}
