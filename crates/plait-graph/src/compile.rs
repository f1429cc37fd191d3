//! Checking a loaded [`Pipeline`] against the pass [`Registry`] and compiling
//! it into a [`Schedule`]: execution order, culling, lifetimes, memory plan.
//!
//! Compile reports as many problems as it can find in one go (sorted by
//! location) rather than stopping at the first, so one edit-run cycle fixes
//! several mistakes.
//!
//! Ordering rules, per resource R:
//! * every writer of R runs before every (other) reader of R;
//! * a "load-writer" of R (its slot has `loads = true`, or the pass also
//!   reads R) runs after every plain writer of R;
//! * all writers of R must then be totally ordered, else the result would
//!   depend on an arbitrary tie-break (`UnorderedWriters`).

use indexmap::IndexMap;
use petgraph::graph::{DiGraph, NodeIndex};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashSet};

use crate::error::{Error, ErrorKind, Errors, Location, Spanned};
use crate::expr;
use crate::load::{PassDecl, Pipeline, ResourceDecl, SizeDecl, location_order};
use crate::scene_resources::{DRAWN_HAIR, SCENE_RESOURCES, scene_resource};
use crate::schedule::*;
use crate::spec::{
    Access, ParamSpec, ParamType, PassShape, PassTypeSpec, Registry, ResourceKind, SlotSpec,
};
use crate::value::Value;

/// Checks `pipeline` and builds its schedule, or returns every problem found.
pub fn compile(
    pipeline: &Pipeline,
    registry: &Registry,
    opts: &CompileOptions,
) -> Result<Schedule, Errors> {
    let mut errors = Vec::new();

    // Resource descriptors, indexed like `pipeline.resources`.
    let mut descs: Vec<Option<ResourceDesc>> = pipeline
        .resources
        .values()
        .map(|r| resolve_resource(r, opts, &mut errors))
        .collect();
    crate::history::check(pipeline, &descs, &mut errors);
    for r in pipeline.resources.values() {
        if scene_resource(&r.name).is_some() {
            errors.push(Error::new(
                r.location.clone(),
                ErrorKind::BadResource {
                    resource: r.name.clone(),
                    reason: "is a scene resource, provided by the scene (sized by its hair); name it in `reads` or `writes` without declaring it".into(),
                },
            ));
        }
    }
    // Scene resources follow the declared ones; their size is the scene's,
    // unknown here (0: they take no memory of the pipeline's).
    descs.extend(
        SCENE_RESOURCES
            .iter()
            .map(|_| Some(ResourceDesc::Buffer { size: 0 })),
    );

    let passes: Vec<ScheduledPass> = pipeline
        .passes
        .values()
        .map(|p| resolve_pass(p, registry, pipeline, &descs, opts, &mut errors))
        .collect();

    let outputs = check_outputs(pipeline, &passes, &mut errors);
    crate::run_once::check_writers(pipeline, &passes, &mut errors);
    let order = order_passes(&passes, pipeline, &mut errors);

    let Some(order) = order.filter(|_| errors.is_empty()) else {
        errors.sort_by(|a, b| location_order(&a.location, &b.location));
        return Err(Errors(errors));
    };
    Ok(build_schedule(pipeline, passes, order, &outputs, descs))
}

// ---------------------------------------------------------------------------
// Values

fn screen_var(opts: &CompileOptions) -> impl Fn(&str) -> Option<f64> {
    let (w, h) = opts.screen;
    move |name| match name {
        "screen_width" => Some(w as f64),
        "screen_height" => Some(h as f64),
        _ => None,
    }
}

/// An integer, a whole float, or an expression string.
fn int_value(v: &Value, opts: &CompileOptions) -> Result<i64, String> {
    match v {
        Value::Int(i) => Ok(*i),
        Value::Float(f) if f.fract() == 0.0 && f.abs() < i64::MAX as f64 => Ok(*f as i64),
        Value::Str(s) => expr::eval_int(s, &screen_var(opts)),
        other => Err(format!(
            "expected an integer or an expression, found {other}"
        )),
    }
}

fn resolve_resource(
    r: &ResourceDecl,
    opts: &CompileOptions,
    errors: &mut Vec<Error>,
) -> Option<ResourceDesc> {
    let bad = |location: &Location, reason: String| {
        Error::new(
            location.clone(),
            ErrorKind::BadResource {
                resource: r.name.clone(),
                reason,
            },
        )
    };
    let eval = |v: &Spanned<Value>, what: &str, errors: &mut Vec<Error>| match int_value(v, opts) {
        Ok(n) => Some(n),
        Err(reason) => {
            errors.push(bad(&v.location, format!("{what}: {reason}")));
            None
        }
    };
    match &r.size {
        SizeDecl::Bytes(size) => {
            let bytes = eval(size, "size", errors)?;
            if bytes <= 0 {
                errors.push(bad(
                    &size.location,
                    format!("buffer size is {bytes} bytes; it must be positive"),
                ));
                return None;
            }
            let limit = opts.max_buffer_binding_size;
            if bytes as u64 > limit {
                errors.push(bad(
                    &size.location,
                    format!(
                        "buffer `{}` is {} ({bytes} bytes); a pass can bind at most {} ({limit} bytes) as storage (WebGPU's default limit when checking without a GPU, the adapter's when rendering)",
                        r.name,
                        mib(bytes as u64),
                        mib(limit),
                    ),
                ));
                return None;
            }
            Some(ResourceDesc::Buffer { size: bytes as u64 })
        }
        SizeDecl::Screen { .. } | SizeDecl::Extent { .. } => {
            let (width, height) = match &r.size {
                SizeDecl::Screen { divisor, .. } => {
                    // Rounded down like integer division, never below one texel.
                    (
                        (opts.screen.0 / divisor).max(1) as i64,
                        (opts.screen.1 / divisor).max(1) as i64,
                    )
                }
                SizeDecl::Extent { width, height, .. } => (
                    eval(width, "width", errors)?,
                    eval(height, "height", errors)?,
                ),
                SizeDecl::Bytes(_) => return None,
            };
            let limit = opts.max_texture_dimension;
            if width < 1 || height < 1 || width > limit as i64 || height > limit as i64 {
                errors.push(Error::new(
                    r.size.location().clone(),
                    ErrorKind::TextureSize {
                        resource: r.name.clone(),
                        width,
                        height,
                        limit,
                    },
                ));
                return None;
            }
            let mut count = |field: &Option<Spanned<Value>>, what: &str| -> Option<u32> {
                let Some(v) = field else { return Some(1) };
                let n = eval(v, what, errors)?;
                if !(1..=2048).contains(&n) {
                    errors.push(bad(
                        &v.location,
                        format!("{what} is {n}; it must be between 1 and 2048"),
                    ));
                    return None;
                }
                Some(n as u32)
            };
            let layers = count(&r.layers, "layers")?;
            let samples = count(&r.samples, "samples")?;
            if !crate::schedule::SAMPLE_COUNTS.contains(&samples) {
                let at = r.samples.as_ref().map_or(&r.location, |v| &v.location);
                errors.push(bad(
                    at,
                    format!(
                        "samples is {samples}; no texture format allows it (counts are 1, 2, 4, 8 or 16, and each format allows a subset: rgba16float 1 or 4 on lavapipe)"
                    ),
                ));
                return None;
            }
            let format = r.format.as_ref()?.value;
            Some(ResourceDesc::Texture {
                format,
                width: width as u32,
                height: height as u32,
                layers,
                samples,
            })
        }
    }
}

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

// ---------------------------------------------------------------------------
// Passes

fn resolve_pass(
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
            if spec.dynamic_slots {
                // Data-only passes: params are whatever the shader's `params`
                // uniform declares, checked against naga's reflection later.
                params.insert(name.clone(), value.value.clone());
                continue;
            }
            let Some(param) = spec.params.iter().find(|p| &p.name == name) else {
                let known: Vec<_> = spec.params.iter().map(|p| p.name.as_str()).collect();
                errors.push(Error::new(
                    value.location.clone(),
                    ErrorKind::UnknownParam {
                        pass: decl.name.clone(),
                        pass_type: spec.name.clone(),
                        param: name.clone(),
                        known: if known.is_empty() {
                            "no params".into()
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
            let applies =
                spec.state_from_data && (key == "blend" || spec.shape == PassShape::Raster);
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
/// `pipeline.resources` until [`build_schedule`] renumbers it.
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
            loads: loads || (scene.is_some() && direction == Direction::Write),
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

// ---------------------------------------------------------------------------
// Graph

fn writes_to(pass: &ScheduledPass, resource: usize) -> Option<&Binding> {
    pass.writes.iter().find(|b| b.resource == resource)
}

fn reads_from(pass: &ScheduledPass, resource: usize) -> bool {
    pass.reads.iter().any(|b| b.resource == resource)
}

/// Scene resource ids (after the `declared` ones) a pass reads without naming
/// them: a hair draw reads the hair's vertices and indices.
fn implicit_reads(pass: &ScheduledPass, declared: usize) -> Vec<usize> {
    if pass.draw.as_deref() != Some("hair") {
        return Vec::new();
    }
    DRAWN_HAIR
        .iter()
        .filter_map(|name| scene_resource(name).map(|(i, _)| declared + i))
        .collect()
}

/// The name of resource id `resource`: declared, or a scene resource.
fn resource_name(pipeline: &Pipeline, resource: usize) -> String {
    match pipeline.resources.get_index(resource) {
        Some((name, _)) => name.clone(),
        None => SCENE_RESOURCES[resource - pipeline.resources.len()]
            .name
            .to_owned(),
    }
}

/// Output resource indices (into `pipeline.resources`); reports unknown or
/// unwritten outputs.
fn check_outputs(
    pipeline: &Pipeline,
    passes: &[ScheduledPass],
    errors: &mut Vec<Error>,
) -> Vec<usize> {
    if pipeline.outputs.is_empty() {
        errors.push(Error::new(
            pipeline.outputs_location.clone(),
            ErrorKind::Schema("`outputs` is empty: every pass would be culled".into()),
        ));
    }
    let mut outputs = Vec::new();
    for output in &pipeline.outputs {
        match pipeline.resources.get_index_of(&output.value) {
            None => errors.push(Error::new(
                output.location.clone(),
                ErrorKind::UnknownOutput {
                    name: output.value.clone(),
                    hint: crate::suggest::did_you_mean(
                        &output.value,
                        pipeline.resources.keys().map(String::as_str),
                    ),
                },
            )),
            Some(i) if !passes.iter().any(|p| writes_to(p, i).is_some()) => {
                errors.push(Error::new(
                    output.location.clone(),
                    ErrorKind::OutputNeverWritten(output.value.clone()),
                ))
            }
            Some(i) if !outputs.contains(&i) => outputs.push(i),
            Some(_) => {}
        }
    }
    outputs
}

/// Builds the dependency graph and returns pass indices in execution order,
/// or `None` if it has a cycle. Reports never-written reads, cycles and
/// unordered writers.
fn order_passes(
    passes: &[ScheduledPass],
    pipeline: &Pipeline,
    errors: &mut Vec<Error>,
) -> Option<Vec<usize>> {
    let mut graph: DiGraph<usize, ()> = DiGraph::new();
    let nodes: Vec<NodeIndex> = (0..passes.len()).map(|i| graph.add_node(i)).collect();
    let mut add_edge = |from: usize, to: usize| {
        if from != to {
            graph.update_edge(nodes[from], nodes[to], ());
        }
    };

    let declared = pipeline.resources.len();
    let reads = |p: usize, resource: usize| {
        reads_from(&passes[p], resource) || implicit_reads(&passes[p], declared).contains(&resource)
    };
    for resource in 0..declared + SCENE_RESOURCES.len() {
        let writers: Vec<usize> = (0..passes.len())
            .filter(|&p| writes_to(&passes[p], resource).is_some())
            .collect();
        let readers: Vec<usize> = (0..passes.len()).filter(|&p| reads(p, resource)).collect();
        // An earlier frame's version is written by the engine (a copy of the
        // resource after each frame): it needs a writer of the resource. The
        // scene writes its resources before any pass.
        let previous_of = pipeline
            .resources
            .get_index(resource)
            .and_then(|(_, r)| r.previous_of.as_ref());
        let written_by_someone = match previous_of {
            Some(of) => pipeline
                .resources
                .get_index_of(&of.resource)
                .is_some_and(|base| passes.iter().any(|p| writes_to(p, base).is_some())),
            None => !writers.is_empty() || resource >= declared,
        };
        if !written_by_someone {
            for &r in &readers {
                for b in passes[r].reads.iter().filter(|b| b.resource == resource) {
                    let kind = match previous_of {
                        Some(of) => ErrorKind::HistoryNeverWritten {
                            previous: b.resource_name.clone(),
                            resource: of.resource.clone(),
                            reader: passes[r].name.clone(),
                        },
                        None => ErrorKind::NeverWritten {
                            resource: b.resource_name.clone(),
                            reader: passes[r].name.clone(),
                        },
                    };
                    errors.push(Error::new(b.location.clone(), kind));
                }
            }
        }
        for &w in &writers {
            for &r in &readers {
                add_edge(w, r);
            }
        }
        let is_load_writer = |p: usize| {
            writes_to(&passes[p], resource).is_some_and(|b| b.loads) || reads(p, resource)
        };
        for &plain in writers.iter().filter(|&&w| !is_load_writer(w)) {
            for &load in writers.iter().filter(|&&w| is_load_writer(w)) {
                add_edge(plain, load);
            }
        }
    }

    let mut has_cycle = false;
    for scc in petgraph::algo::tarjan_scc(&graph) {
        if scc.len() > 1 {
            has_cycle = true;
            let members: HashSet<NodeIndex> = scc.iter().copied().collect();
            let cycle = cycle_through(&graph, &members);
            let first = cycle.iter().copied().min().unwrap_or(0);
            let names = cycle
                .iter()
                .chain(cycle.first())
                .map(|&i| passes[i].name.clone())
                .collect();
            errors.push(Error::new(
                passes[first].location.clone(),
                ErrorKind::Cycle(names),
            ));
        }
    }
    if has_cycle {
        return None;
    }

    // reach[a][b]: b runs after a along edges.
    let reach: Vec<Vec<bool>> = nodes
        .iter()
        .map(|&start| {
            let mut row = vec![false; passes.len()];
            let mut dfs = petgraph::visit::Dfs::new(&graph, start);
            while let Some(n) = dfs.next(&graph) {
                row[graph[n]] = true;
            }
            row
        })
        .collect();
    for resource in 0..declared + SCENE_RESOURCES.len() {
        let writers: Vec<usize> = (0..passes.len())
            .filter(|&p| writes_to(&passes[p], resource).is_some())
            .collect();
        'pairs: for (i, &a) in writers.iter().enumerate() {
            for &b in &writers[i + 1..] {
                if !reach[a][b] && !reach[b][a] {
                    let location = writes_to(&passes[b], resource)
                        .map_or(passes[b].location.clone(), |x| x.location.clone());
                    errors.push(Error::new(
                        location,
                        ErrorKind::UnorderedWriters {
                            resource: resource_name(pipeline, resource),
                            first: passes[a].name.clone(),
                            second: passes[b].name.clone(),
                        },
                    ));
                    break 'pairs;
                }
            }
        }
    }

    // Kahn's algorithm; among ready passes the earliest in the file goes first.
    let mut indegree: Vec<usize> = nodes
        .iter()
        .map(|&n| graph.neighbors_directed(n, petgraph::Incoming).count())
        .collect();
    let mut ready: BinaryHeap<Reverse<usize>> = (0..passes.len())
        .filter(|&i| indegree[i] == 0)
        .map(Reverse)
        .collect();
    let mut order = Vec::with_capacity(passes.len());
    while let Some(Reverse(p)) = ready.pop() {
        order.push(p);
        for next in graph.neighbors(nodes[p]) {
            let q = graph[next];
            indegree[q] -= 1;
            if indegree[q] == 0 {
                ready.push(Reverse(q));
            }
        }
    }
    Some(order)
}

/// One cycle inside a strongly connected component, as pass indices,
/// starting at its earliest pass in file order.
fn cycle_through(graph: &DiGraph<usize, ()>, members: &HashSet<NodeIndex>) -> Vec<usize> {
    let Some(&start) = members.iter().min_by_key(|n| graph[**n]) else {
        return Vec::new();
    };
    // Breadth-first search back to `start`, remembering parents.
    let mut parent: std::collections::HashMap<NodeIndex, NodeIndex> = Default::default();
    let mut queue = std::collections::VecDeque::from([start]);
    while let Some(n) = queue.pop_front() {
        let mut successors: Vec<NodeIndex> =
            graph.neighbors(n).filter(|s| members.contains(s)).collect();
        successors.sort_by_key(|s| graph[*s]);
        for s in successors {
            if s == start {
                let mut path = vec![graph[n]];
                let mut cur = n;
                while cur != start {
                    let Some(&p) = parent.get(&cur) else { break };
                    path.push(graph[p]);
                    cur = p;
                }
                path.reverse();
                return path;
            }
            if let std::collections::hash_map::Entry::Vacant(e) = parent.entry(s) {
                e.insert(n);
                queue.push_back(s);
            }
        }
    }
    vec![graph[start]]
}

// ---------------------------------------------------------------------------
// Culling, lifetimes, memory

fn build_schedule(
    pipeline: &Pipeline,
    mut passes: Vec<ScheduledPass>,
    order: Vec<usize>,
    outputs: &[usize],
    descs: Vec<Option<ResourceDesc>>,
) -> Schedule {
    // Live passes: writers of outputs and everything they depend on. Walking
    // the execution order backwards sees every consumer before its producers.
    let declared = pipeline.resources.len();
    // A history makes a read of `R.previous` need `R` (and the younger
    // versions it is copied through), whose writers may come later in the
    // order: walk again until nothing new is needed.
    // Scene resources have no history.
    let history_chain = |r: usize| {
        if r < declared {
            crate::history::chain(pipeline, r)
        } else {
            Vec::new()
        }
    };
    let mut needed: HashSet<usize> = outputs.iter().copied().collect();
    let mut live = vec![false; passes.len()];
    loop {
        let before = needed.len();
        for &p in order.iter().rev() {
            if !live[p]
                && passes[p]
                    .writes
                    .iter()
                    .any(|b| needed.contains(&b.resource))
            {
                live[p] = true;
                needed.extend(passes[p].reads.iter().map(|b| b.resource));
                needed.extend(implicit_reads(&passes[p], declared));
                // A load-writer keeps earlier contents: their writers are needed too.
                needed.extend(
                    passes[p]
                        .writes
                        .iter()
                        .filter(|b| b.loads)
                        .map(|b| b.resource),
                );
            }
        }
        let chained: Vec<usize> = needed.iter().flat_map(|&r| history_chain(r)).collect();
        needed.extend(chained);
        if needed.len() == before {
            break;
        }
    }

    // Renumber resources: keep those a live pass touches, in declaration order.
    let total = declared + SCENE_RESOURCES.len();
    let mut used = vec![false; total];
    for (p, pass) in passes.iter().enumerate() {
        if live[p] {
            for b in pass.reads.iter().chain(&pass.writes) {
                used[b.resource] = true;
                for r in history_chain(b.resource) {
                    used[r] = true;
                }
            }
        }
    }
    let mut new_id = vec![DROPPED_RESOURCE; total];
    let mut resources = Vec::new();
    let mut dropped_resources = Vec::new();
    for (i, decl) in pipeline.resources.values().enumerate() {
        match (&descs[i], used[i]) {
            (Some(desc), true) => {
                new_id[i] = resources.len();
                resources.push(ResolvedResource {
                    name: decl.name.clone(),
                    desc: desc.clone(),
                    first_use: usize::MAX,
                    last_use: 0,
                    physical: 0,
                    scene: false,
                    // A history's versions come after it in declaration
                    // order, so `of` is already renumbered.
                    lifetime: crate::history::declared_lifetime(decl, pipeline, &new_id),
                    kept: false,
                    location: decl.location.clone(),
                });
            }
            _ => dropped_resources.push(decl.name.clone()),
        }
    }
    // Scene resources a live pass names: after the declared ones, never dropped.
    for (i, scene) in SCENE_RESOURCES.iter().enumerate() {
        if used[declared + i] {
            new_id[declared + i] = resources.len();
            resources.push(ResolvedResource {
                name: scene.name.to_owned(),
                desc: ResourceDesc::Buffer { size: 0 },
                first_use: usize::MAX,
                last_use: 0,
                physical: 0,
                scene: true,
                // The scene's buffers outlive every frame, like `persistent`.
                lifetime: Lifetime::Persistent,
                kept: false,
                location: Location::Builtin,
            });
        }
    }
    for pass in &mut passes {
        for b in pass.reads.iter_mut().chain(pass.writes.iter_mut()) {
            b.resource = new_id[b.resource];
        }
    }
    let history = crate::history::copies(&resources);

    let mut slots: Vec<Option<ScheduledPass>> = passes.into_iter().map(Some).collect();
    let mut scheduled = Vec::new();
    let mut culled = Vec::new();
    for &p in &order {
        let Some(pass) = slots[p].take() else {
            continue;
        };
        if live[p] {
            scheduled.push(pass);
        } else {
            let reason = cull_reason(&pass);
            culled.push((p, CulledPass { pass, reason }));
        }
    }
    // Culled passes in file order: they have no execution order to follow.
    culled.sort_by_key(|(p, _)| *p);
    let culled = culled.into_iter().map(|(_, c)| c).collect();

    // The first writer of a resource has nothing to load: it clears. A
    // persistent resource is never cleared by the engine: every writer loads.
    let mut written = vec![false; resources.len()];
    for pass in &mut scheduled {
        for b in &mut pass.writes {
            if resources[b.resource].lifetime == Lifetime::Persistent {
                b.loads = true;
            } else if !written[b.resource] {
                let also_read = pass.reads.iter().any(|r| r.resource == b.resource);
                if !also_read {
                    b.loads = false;
                }
            }
        }
        for b in &pass.writes {
            written[b.resource] = true;
        }
    }

    for (index, pass) in scheduled.iter().enumerate() {
        for b in pass.reads.iter().chain(&pass.writes) {
            let r = &mut resources[b.resource];
            r.first_use = r.first_use.min(index);
            r.last_use = r.last_use.max(index);
        }
    }
    let output_ids: Vec<ResourceId> = outputs
        .iter()
        .map(|&o| new_id[o])
        .filter(|&id| id != DROPPED_RESOURCE)
        .collect();
    let end = scheduled.len().saturating_sub(1);
    for &o in &output_ids {
        resources[o].last_use = end;
    }
    // Contents that outlive the frame span all of it, so the memory plan
    // never lends their allocation to another resource.
    for r in resources.iter_mut().filter(|r| !r.lifetime.is_frame()) {
        r.first_use = 0;
        r.last_use = end;
    }
    crate::run_once::keep_across_frames(&scheduled, &mut resources);

    let (physical, memory) = plan_memory(&mut resources);
    Schedule {
        name: pipeline.name.value.clone(),
        description: pipeline.description.value.clone(),
        files: pipeline.files.clone(),
        techniques: pipeline.techniques.clone(),
        params: pipeline
            .params
            .iter()
            .map(|(k, v)| (k.clone(), v.value.clone()))
            .collect(),
        passes: scheduled,
        culled,
        resources,
        dropped_resources,
        physical,
        outputs: output_ids,
        history,
        memory,
    }
}

fn cull_reason(pass: &ScheduledPass) -> String {
    if pass.writes.is_empty() {
        return "writes nothing".to_owned();
    }
    let mut names: Vec<String> = pass
        .writes
        .iter()
        .map(|b| format!("`{}`", b.resource_name))
        .collect();
    names.dedup();
    let which = if names.len() == 1 {
        "which"
    } else {
        "which none of"
    };
    format!(
        "writes only {}, {which} no output depends on",
        names.join(", ")
    )
}

/// Greedy sharing: in order of first use, each resource takes the first
/// physical allocation with an identical descriptor whose users all ended
/// strictly before it starts (wgpu cannot alias different shapes).
fn plan_memory(resources: &mut [ResolvedResource]) -> (Vec<PhysicalResource>, MemoryReport) {
    let mut by_start: Vec<ResourceId> = (0..resources.len()).collect();
    by_start.sort_by_key(|&r| (resources[r].first_use, r));
    let mut physical: Vec<PhysicalResource> = Vec::new();
    for r in by_start {
        let (desc, first_use) = (resources[r].desc.clone(), resources[r].first_use);
        // The scene's buffers are its own: never shared.
        let reusable = physical.iter().position(|p| {
            !resources[r].scene
                && p.desc == desc
                && p.users
                    .iter()
                    .all(|&u| !resources[u].scene && resources[u].last_use < first_use)
        });
        let id = match reusable {
            Some(id) => id,
            None => {
                physical.push(PhysicalResource {
                    desc,
                    users: Vec::new(),
                });
                physical.len() - 1
            }
        };
        physical[id].users.push(r);
        resources[r].physical = id;
    }
    let memory = MemoryReport {
        peak_bytes: physical.iter().map(|p| p.desc.bytes()).sum(),
        unpooled_bytes: resources.iter().map(|r| r.desc.bytes()).sum(),
    };
    (physical, memory)
}

/// `1.5 MiB`, `1 GiB`: a byte count for messages.
fn mib(bytes: u64) -> String {
    if bytes >= 1 << 30 && bytes.is_multiple_of(1 << 30) {
        format!("{} GiB", bytes >> 30)
    } else {
        format!("{:.1} MiB", bytes as f64 / (1u64 << 20) as f64)
    }
}
