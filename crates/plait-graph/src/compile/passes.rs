//! Resolving one pass: its type looked up in the registry, its params checked
//! and defaulted, the fields that apply to its shape (`view`, `draw`, raster
//! state, `shader`), and its `reads`/`writes` bound to resources with each
//! slot's kind and format checked.

use indexmap::IndexMap;

use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::load::{PassDecl, Pipeline};
use crate::scene_resources::{SCENE_RESOURCES, scene_resource};
use crate::schedule::*;
use crate::spec::{
    Access, Draw, ParamSpec, ParamType, PassShape, PassTypeSpec, Registry, ResourceKind, SlotSpec,
    View,
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

/// What binding one direction of one pass's slots shares.
struct Binder<'a> {
    decl: &'a PassDecl,
    spec: Option<&'a PassTypeSpec>,
    /// Slots the pass takes beyond its type's ([`Registry::shared_slots`]).
    shared: &'a [SlotSpec],
    pipeline: &'a Pipeline,
    descs: &'a [Option<ResourceDesc>],
    direction: Direction,
    /// The type's slots for `direction` (none for an unknown type).
    slots: &'a [SlotSpec],
    errors: &'a mut Vec<Error>,
}

/// Binds `reads` or `writes`; `Binding::resource` is an index into
/// `pipeline.resources` until [`build_schedule`](super::schedule::build_schedule) renumbers it.
fn bind_slots(
    decl: &PassDecl,
    spec: Option<&PassTypeSpec>,
    shared: &[SlotSpec],
    pipeline: &Pipeline,
    descs: &[Option<ResourceDesc>],
    direction: Direction,
    errors: &mut Vec<Error>,
) -> Vec<Binding> {
    let (written, slots): (_, &[SlotSpec]) = match direction {
        Direction::Read => (&decl.reads, spec.map_or(&[][..], |s| &s.inputs)),
        Direction::Write => (&decl.writes, spec.map_or(&[][..], |s| &s.outputs)),
    };
    let mut binder = Binder {
        decl,
        spec,
        shared,
        pipeline,
        descs,
        direction,
        slots,
        errors,
    };
    let mut bindings = Vec::new();
    for (slot_name, resource) in written {
        // `slot = ""` unbinds a slot the base file bound: how a variant
        // (`extends`) drops an input it does not need.
        if resource.value.is_empty() {
            continue;
        }
        if let Some(binding) = binder.bind(slot_name, resource) {
            bindings.push(binding);
        }
    }
    if spec.is_some() {
        binder.check_missing(written);
    }
    bindings
}

impl Binder<'_> {
    /// Binds one slot to the resource it names, or reports why it cannot be.
    fn bind(&mut self, slot_name: &String, resource: &Spanned<String>) -> Option<Binding> {
        let scene = scene_resource(&resource.value);
        let index = self.resource_index(resource)?;
        self.check_not_history(index, resource)?;
        let declared_kind = self
            .pipeline
            .resources
            .get_index(index)
            .map_or(ResourceKind::Buffer, |(_, r)| r.kind.value);
        let slot = self
            .slots
            .iter()
            .chain(self.shared)
            .find(|s| &s.name == slot_name);
        let (access, loads) = self.access(slot, slot_name, resource, declared_kind)?;
        if let Some(slot) = slot {
            self.check_fit(slot, slot_name, resource, index, declared_kind);
        }
        Some(Binding {
            slot: slot_name.clone(),
            slot_id: self.slot_id(slot_name),
            resolves: None,
            resource: Some(ResourceId::new(index)),
            resource_name: resource.value.clone(),
            access,
            // The scene's contents are there before any pass: never cleared.
            // `loads = [...]`: the pass draws over what the attachment holds.
            loads: loads
                || (self.direction == Direction::Write
                    && (scene.is_some() || self.decl.raster.keeps(slot_name))),
            location: resource.location.clone(),
            shared: !self.slots.iter().any(|s| &s.name == slot_name)
                && self.shared.iter().any(|s| &s.name == slot_name),
        })
    }

    /// The handle of `slot_name` ([`crate::SlotId`]): one of the type's
    /// slots for this direction, else one of the shared slots.
    fn slot_id(&self, slot_name: &str) -> Option<crate::SlotId> {
        let named = |s: &SlotSpec| s.name == slot_name;
        let own = self.slots.iter().position(named).map(match self.direction {
            Direction::Read => crate::SlotId::Input,
            Direction::Write => crate::SlotId::Output,
        });
        own.or_else(|| {
            self.shared
                .iter()
                .position(named)
                .map(crate::SlotId::Shared)
        })
    }

    /// The index of the resource named, declared or scene (after the
    /// declared ones), or `None` once reported unknown or not writable.
    fn resource_index(&mut self, resource: &Spanned<String>) -> Option<usize> {
        let pipeline = self.pipeline;
        let scene = scene_resource(&resource.value);
        match (pipeline.resources.get_index_of(&resource.value), scene) {
            (Some(index), _) => Some(index),
            (None, Some((i, scene))) => {
                if self.direction == Direction::Write && !scene.writable {
                    let writable: Vec<_> = SCENE_RESOURCES
                        .iter()
                        .filter(|r| r.writable)
                        .map(|r| r.name)
                        .collect();
                    self.errors.push(Error::new(
                        resource.location.clone(),
                        ErrorKind::Pass {
                            pass: self.decl.name.clone(),
                            message: format!(
                                "scene resource `{}` is read-only ({}); passes may write only {}",
                                scene.name,
                                scene.doc,
                                writable.join(", ")
                            ),
                        },
                    ));
                    return None;
                }
                Some(pipeline.resources.len() + i)
            }
            (None, None) => {
                self.errors
                    .push(crate::history::undeclared(pipeline, resource));
                None
            }
        }
    }

    /// Reports a write to a history (`R.previous`), returning `None` then.
    fn check_not_history(&mut self, index: usize, resource: &Spanned<String>) -> Option<()> {
        if self.direction == Direction::Write
            && let Some((_, declared)) = self.pipeline.resources.get_index(index)
            && let Some(of) = &declared.previous_of
        {
            self.errors.push(Error::new(
                resource.location.clone(),
                ErrorKind::WritesHistory {
                    pass: self.decl.name.clone(),
                    previous: resource.value.clone(),
                    resource: of.resource.clone(),
                },
            ));
            return None;
        }
        Some(())
    }

    /// The slot's access and whether it loads, or `None` once the slot is
    /// reported unknown to the type.
    fn access(
        &mut self,
        slot: Option<&SlotSpec>,
        slot_name: &str,
        resource: &Spanned<String>,
        declared_kind: ResourceKind,
    ) -> Option<(Access, bool)> {
        match (slot, self.spec) {
            (Some(slot), _) => Some((slot.access, slot.loads)),
            // Data-only passes: the shader's bindings decide (checked later by
            // naga reflection); assume the common access for the direction.
            (None, Some(spec)) if spec.dynamic_slots => {
                Some((dynamic_access(self.direction, declared_kind), false))
            }
            (None, Some(spec)) => {
                let known: Vec<_> = self.slots.iter().map(|s| s.name.as_str()).collect();
                self.errors.push(Error::new(
                    resource.location.clone(),
                    ErrorKind::UnknownSlot {
                        pass: self.decl.name.clone(),
                        pass_type: spec.name.clone(),
                        direction: self.direction.word(),
                        slot: slot_name.to_owned(),
                        known: if known.is_empty() {
                            "none".into()
                        } else {
                            known.join(", ")
                        },
                    },
                ));
                None
            }
            // Unknown pass type (already reported): keep the edge so graph
            // errors can still be found.
            (None, None) => Some((dynamic_access(self.direction, declared_kind), false)),
        }
    }

    /// Checks the resource's kind, then its texture format, against the slot's.
    fn check_fit(
        &mut self,
        slot: &SlotSpec,
        slot_name: &str,
        resource: &Spanned<String>,
        index: usize,
        declared_kind: ResourceKind,
    ) {
        if slot.kind != declared_kind {
            self.errors.push(Error::new(
                resource.location.clone(),
                ErrorKind::KindMismatch {
                    resource: resource.value.clone(),
                    declared: declared_kind.to_string(),
                    pass: self.decl.name.clone(),
                    slot: slot_name.to_owned(),
                    expected: slot.kind.to_string(),
                },
            ));
        } else if let Some(Some(ResourceDesc::Texture { format, .. })) = self.descs.get(index)
            && !slot.formats.accepts(*format)
        {
            self.errors.push(Error::new(
                resource.location.clone(),
                ErrorKind::FormatMismatch {
                    resource: resource.value.clone(),
                    declared: format.to_string(),
                    pass: self.decl.name.clone(),
                    slot: slot_name.to_owned(),
                    accepted: slot.formats.to_string(),
                },
            ));
        }
    }

    /// Reports each required slot of the type the pass leaves unbound.
    fn check_missing(&mut self, written: &IndexMap<String, Spanned<String>>) {
        for slot in self.slots.iter().filter(|s| !s.optional) {
            if !written.contains_key(&slot.name) {
                self.errors.push(Error::new(
                    self.decl.location.clone(),
                    ErrorKind::MissingSlot {
                        pass: self.decl.name.clone(),
                        direction: self.direction.word(),
                        slot: slot.name.clone(),
                    },
                ));
            }
        }
    }
}

fn dynamic_access(direction: Direction, kind: ResourceKind) -> Access {
    match (direction, kind) {
        (Direction::Read, ResourceKind::Texture) => Access::Sampled,
        (Direction::Read, ResourceKind::Buffer | ResourceKind::AccelerationStructure) => {
            Access::StorageRead
        }
        (Direction::Write, _) => Access::StorageWrite,
    }
}
