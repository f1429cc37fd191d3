//! Resolving one pass: its type looked up in the registry, its params checked
//! and defaulted, the fields that apply to its shape (`view`, `draw`, raster
//! state, `shader`), and its `reads`/`writes` bound to resources with each
//! slot's kind and format checked.

use indexmap::IndexMap;

use crate::error::{Error, ErrorKind, Location};
use crate::load::{PassDecl, Pipeline};
use crate::scene_resources::{SCENE_RESOURCES, scene_resource};
use crate::schedule::*;
use crate::spec::{
    Access, ParamSpec, ParamType, PassShape, PassTypeSpec, Registry, ResourceKind, SlotSpec,
};
use crate::value::Value;

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
    let pass_error = |location: &Location, message: String| {
        Error::new(
            location.clone(),
            ErrorKind::Pass {
                pass: decl.name.clone(),
                message,
            },
        )
    };

    let mut params = IndexMap::new();
    if let Some(spec) = spec {
        for (name, value) in &decl.params {
            let shared = registry.shared_params.iter().find(|p| &p.name == name);
            if spec.dynamic_slots && shared.is_none() {
                // Data-only passes: params are whatever the shader reads (a
                // `params` uniform member or a define), checked against
                // naga's reflection and the shader's text later.
                params.insert(name.clone(), value.value.clone());
                continue;
            }
            let own = spec.params.iter().find(|p| &p.name == name);
            let Some(param) = own.or(shared.filter(|_| spec.dynamic_slots)) else {
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
        // Every param of the type, in the type's order, defaults filled in.
        let mut ordered = IndexMap::new();
        for param in &spec.params {
            if let Some(v) = params.swap_remove(&param.name) {
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
        if !spec.dynamic_slots {
            params = ordered;
        }

        if spec.shape == PassShape::Raster {
            for (field, value) in [("view", &decl.view), ("draw", &decl.draw)] {
                if value.is_none() {
                    let hint = if field == "view" {
                        "light | camera"
                    } else {
                        "hair | opaque"
                    };
                    errors.push(pass_error(
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
                        &v.location,
                        format!(
                            "type `{}` draws no scene geometry, so `{field}` does not apply",
                            spec.name
                        ),
                    ));
                }
            }
        }
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
                    location,
                    format!("type `{}` {why}, so `{key}` does not apply", spec.name),
                ));
            }
        }
        match (&decl.shader, spec.needs_shader) {
            (None, true) => errors.push(pass_error(
                &decl.location,
                format!(
                    "type `{}` runs a shader from the pipeline and needs `shader = \"….wgsl\"`",
                    spec.name
                ),
            )),
            (Some(s), false) => errors.push(pass_error(
                &s.location,
                format!(
                    "type `{}` brings its own shader; `shader` does not apply",
                    spec.name
                ),
            )),
            _ => {}
        }
        for slot in &decl.raster.loads {
            if !decl.writes.contains_key(&slot.value) {
                let written: Vec<&str> = decl.writes.keys().map(String::as_str).collect();
                errors.push(pass_error(
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

    let reads = bind_slots(decl, spec, pipeline, descs, Direction::Read, errors);
    let writes = bind_slots(decl, spec, pipeline, descs, Direction::Write, errors);
    ScheduledPass {
        name: decl.name.clone(),
        type_name: decl.type_name.value.clone(),
        shape: spec.map_or(PassShape::Compute, |s| s.shape),
        view: decl.view.as_ref().map(|v| v.value.clone()),
        draw: decl.draw.as_ref().map(|v| v.value.clone()),
        reads,
        writes,
        params,
        shader: decl.shader.as_ref().map(|s| s.value.clone()),
        shader_location: decl.shader.as_ref().map(|s| s.location.clone()),
        raster: decl.raster.clone(),
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

#[derive(Clone, Copy, PartialEq)]
enum Direction {
    Read,
    Write,
}

impl Direction {
    fn word(self) -> &'static str {
        match self {
            Direction::Read => "input",
            Direction::Write => "output",
        }
    }
}

/// Binds `reads` or `writes`; `Binding::resource` is an index into
/// `pipeline.resources` until [`build_schedule`](super::schedule::build_schedule) renumbers it.
fn bind_slots(
    decl: &PassDecl,
    spec: Option<&PassTypeSpec>,
    pipeline: &Pipeline,
    descs: &[Option<ResourceDesc>],
    direction: Direction,
    errors: &mut Vec<Error>,
) -> Vec<Binding> {
    let (written, slots): (_, &[SlotSpec]) = match direction {
        Direction::Read => (&decl.reads, spec.map_or(&[][..], |s| &s.inputs)),
        Direction::Write => (&decl.writes, spec.map_or(&[][..], |s| &s.outputs)),
    };
    let mut bindings = Vec::new();
    for (slot_name, resource) in written {
        // `slot = ""` unbinds a slot the base file bound: how a variant
        // (`extends`) drops an input it does not need.
        if resource.value.is_empty() {
            continue;
        }
        let scene = scene_resource(&resource.value);
        let index = match (pipeline.resources.get_index_of(&resource.value), scene) {
            (Some(index), _) => index,
            (None, Some((i, scene))) => {
                if direction == Direction::Write && !scene.writable {
                    let writable: Vec<_> = SCENE_RESOURCES
                        .iter()
                        .filter(|r| r.writable)
                        .map(|r| r.name)
                        .collect();
                    errors.push(Error::new(
                        resource.location.clone(),
                        ErrorKind::Pass {
                            pass: decl.name.clone(),
                            message: format!(
                                "scene resource `{}` is read-only ({}); passes may write only {}",
                                scene.name,
                                scene.doc,
                                writable.join(", ")
                            ),
                        },
                    ));
                    continue;
                }
                pipeline.resources.len() + i
            }
            (None, None) => {
                errors.push(crate::history::undeclared(pipeline, resource));
                continue;
            }
        };
        if direction == Direction::Write
            && let Some((_, declared)) = pipeline.resources.get_index(index)
            && let Some(of) = &declared.previous_of
        {
            errors.push(Error::new(
                resource.location.clone(),
                ErrorKind::WritesHistory {
                    pass: decl.name.clone(),
                    previous: resource.value.clone(),
                    resource: of.resource.clone(),
                },
            ));
            continue;
        }
        let declared_kind = pipeline
            .resources
            .get_index(index)
            .map_or(ResourceKind::Buffer, |(_, r)| r.kind.value);
        let slot = slots.iter().find(|s| &s.name == slot_name);
        let (access, loads) = match (slot, spec) {
            (Some(slot), _) => (slot.access, slot.loads),
            // Data-only passes: the shader's bindings decide (checked later by
            // naga reflection); assume the common access for the direction.
            (None, Some(spec)) if spec.dynamic_slots => {
                (dynamic_access(direction, declared_kind), false)
            }
            (None, Some(spec)) => {
                let known: Vec<_> = slots.iter().map(|s| s.name.as_str()).collect();
                errors.push(Error::new(
                    resource.location.clone(),
                    ErrorKind::UnknownSlot {
                        pass: decl.name.clone(),
                        pass_type: spec.name.clone(),
                        direction: direction.word(),
                        slot: slot_name.clone(),
                        known: if known.is_empty() {
                            "none".into()
                        } else {
                            known.join(", ")
                        },
                    },
                ));
                continue;
            }
            // Unknown pass type (already reported): keep the edge so graph
            // errors can still be found.
            (None, None) => (dynamic_access(direction, declared_kind), false),
        };
        if let Some(slot) = slot {
            if slot.kind != declared_kind {
                errors.push(Error::new(
                    resource.location.clone(),
                    ErrorKind::KindMismatch {
                        resource: resource.value.clone(),
                        declared: declared_kind.to_string(),
                        pass: decl.name.clone(),
                        slot: slot_name.clone(),
                        expected: slot.kind.to_string(),
                    },
                ));
            } else if let Some(Some(ResourceDesc::Texture { format, .. })) = descs.get(index)
                && !slot.formats.accepts(*format)
            {
                errors.push(Error::new(
                    resource.location.clone(),
                    ErrorKind::FormatMismatch {
                        resource: resource.value.clone(),
                        declared: format.to_string(),
                        pass: decl.name.clone(),
                        slot: slot_name.clone(),
                        accepted: slot.formats.to_string(),
                    },
                ));
            }
        }
        bindings.push(Binding {
            slot: slot_name.clone(),
            resource: index,
            resource_name: resource.value.clone(),
            access,
            // The scene's contents are there before any pass: never cleared.
            // `loads = [...]`: the pass draws over what the attachment holds.
            loads: loads
                || (direction == Direction::Write
                    && (scene.is_some() || decl.raster.keeps(slot_name))),
            location: resource.location.clone(),
        });
    }
    if spec.is_some() {
        for slot in slots.iter().filter(|s| !s.optional) {
            if !written.contains_key(&slot.name) {
                errors.push(Error::new(
                    decl.location.clone(),
                    ErrorKind::MissingSlot {
                        pass: decl.name.clone(),
                        direction: direction.word(),
                        slot: slot.name.clone(),
                    },
                ));
            }
        }
    }
    bindings
}

fn dynamic_access(direction: Direction, kind: ResourceKind) -> Access {
    match (direction, kind) {
        (Direction::Read, ResourceKind::Texture) => Access::Sampled,
        (Direction::Read, ResourceKind::Buffer) => Access::StorageRead,
        (Direction::Write, _) => Access::StorageWrite,
    }
}
