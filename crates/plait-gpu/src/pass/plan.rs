//! The binding plan of a pass: which shader binding each slot feeds, which
//! slots are colour and depth attachments, what the params uniform holds —
//! computed from the schedule and naga's reflection by ONE function,
//! [`BindingPlan::new`], which `plait check` ([`super::check`]) reports on and
//! build ([`super::build`]) lays out and records from. Slots cannot be matched
//! to bindings one way when checking and another when building.

use std::sync::Arc;

use plait_graph::{
    Access, Error as GraphError, ErrorKind, Format, Location, PassShape, ResolvedResource,
    ResourceDesc, ResourceId, ResourceKind, ScheduledPass,
};

use super::pass_type::{PassType, SCENE_BINDINGS, shader_source};
use crate::depth_guard::DepthGuard;
use crate::reflect::{self, BindingKind, ShaderBinding};

/// What feeds one group-1 binding.
#[derive(Clone, Debug, PartialEq)]
pub enum BindingSource {
    /// The resource bound to the slot of the binding's name.
    Slot {
        resource: ResourceId,
        /// Texture format (for the layout's filterable flag), `None` for buffers.
        format: Option<Format>,
    },
    /// A `*params` uniform filled from the pass params by member name.
    Params(Vec<u8>),
    /// A scene buffer (`hair_vertices`, `hair_indices`).
    Scene(String),
}

/// One group-1 binding of the pass's shader and what feeds it.
#[derive(Clone, Debug)]
pub struct PlannedBinding {
    pub binding: u32,
    pub name: String,
    pub kind: BindingKind,
    pub source: BindingSource,
}

impl PlannedBinding {
    /// Whether the shader can write through this binding.
    pub fn writes(&self) -> bool {
        match self.kind {
            BindingKind::Storage { read_only, .. } => !read_only,
            BindingKind::StorageTexture { access_write, .. } => access_write,
            _ => false,
        }
    }
}

/// A colour attachment, in target order.
#[derive(Clone, Debug, PartialEq)]
pub struct ColorTarget {
    pub slot: String,
    pub resource: ResourceId,
    pub format: Format,
    pub samples: u32,
    /// Keep the contents (`loads`), else clear.
    pub loads: bool,
    /// The single-sampled texture the samples resolve into (`X_resolve`).
    pub resolve: Option<ResourceId>,
}

/// The depth attachment.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthTarget {
    pub slot: String,
    pub resource: ResourceId,
    pub format: Format,
    pub samples: u32,
    /// Bound under `writes` (may be written), else only tested.
    pub written: bool,
    pub loads: bool,
}

/// Everything about a pass's bindings that does not need a GPU.
#[derive(Clone, Debug, Default)]
pub struct BindingPlan {
    /// Group 1, in binding order.
    pub bindings: Vec<PlannedBinding>,
    pub colors: Vec<ColorTarget>,
    pub depth: Option<DepthTarget>,
    /// Storage buffers that start the pass zeroed (written, not loaded).
    pub clears: Vec<ResourceId>,
    /// The shader writes storage (what the depth guard protects).
    pub writes_storage: bool,
    /// How the slots of a data-only pass are accessed, as settled from the
    /// shader: `(is_write, index in reads/writes, access)`.
    pub settled: Vec<(bool, usize, Access)>,
}

impl BindingPlan {
    /// Match `pass`'s slots to `module`'s bindings. `dynamic_slots`: the
    /// pass type takes any slot (data-only), so accesses come from the shader.
    /// Every problem is returned, located where the pipeline file wrote it.
    pub fn new(
        module: &naga::Module,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
        shape: PassShape,
        dynamic_slots: bool,
        aliases: &[(String, String)],
    ) -> (BindingPlan, Vec<GraphError>) {
        // The shader variable a slot feeds: its own name unless the type says.
        let binding_of = |slot: &str| -> String {
            aliases
                .iter()
                .find(|(s, _)| s == slot)
                .map_or(slot, |(_, b)| b.as_str())
                .to_owned()
        };
        let mut errors = Vec::new();
        let err = |loc: &Location, message: String| {
            GraphError::new(
                loc.clone(),
                ErrorKind::Pass {
                    pass: pass.name.clone(),
                    message,
                },
            )
        };
        let mut plan = BindingPlan::default();
        let shader_bindings = reflect::bindings(module);
        for b in shader_bindings.iter().filter(|b| b.group > 1) {
            errors.push(err(&pass.location, format!("shader binding `{}` is in group {}; plait binds only groups 0 (frame) and 1 (slots)", b.name, b.group)));
        }
        let group1: Vec<&ShaderBinding> = shader_bindings.iter().filter(|b| b.group == 1).collect();
        plan.writes_storage = group1.iter().any(|b| b.writes());
        let is_raster = shape != PassShape::Compute;

        // Slots: checked against the binding of their name, or attachments.
        let slots = pass
            .reads
            .iter()
            .enumerate()
            .map(|(i, b)| (false, i, b))
            .chain(pass.writes.iter().enumerate().map(|(i, b)| (true, i, b)));
        let mut access = |is_write: bool, i: usize, a: Access| plan.settled.push((is_write, i, a));
        let mut color_targets = 0;
        for (is_write, index, b) in slots {
            let Some(res) = resources.get(b.resource) else {
                // A culled pass's binding to a resource nothing live uses.
                continue;
            };
            match group1.iter().find(|s| s.name == binding_of(&b.slot)) {
                None if dynamic_slots => {
                    // Not a shader binding: an attachment of a raster pass.
                    let is_depth = matches!(res.desc, ResourceDesc::Texture { format, .. } if format.is_depth());
                    if !is_raster || res.desc.kind() != ResourceKind::Texture {
                        errors.push(err(
                            &b.location,
                            format!("slot `{}` is not a binding of the shader", b.slot),
                        ));
                    } else if is_depth {
                        access(is_write, index, Access::DepthTarget);
                    } else if is_write {
                        access(is_write, index, Access::ColorTarget);
                        color_targets += 1;
                    } else {
                        errors.push(err(
                            &b.location,
                            format!(
                                "slot `{}` is read but the shader declares no binding of that name",
                                b.slot
                            ),
                        ));
                    }
                }
                None => {
                    if !matches!(b.access, Access::ColorTarget | Access::DepthTarget) {
                        errors.push(err(
                            &b.location,
                            format!(
                                "the shader declares no binding named `{}` for this slot",
                                b.slot
                            ),
                        ));
                    }
                }
                Some(sb) => {
                    check_binding(sb, b, res, pass, is_write, &mut errors);
                    if dynamic_slots {
                        access(
                            is_write,
                            index,
                            match sb.kind {
                                BindingKind::Uniform { .. } => Access::Uniform,
                                BindingKind::Texture { .. } => Access::Sampled,
                                _ if sb.writes() => Access::StorageWrite,
                                _ => Access::StorageRead,
                            },
                        );
                    }
                }
            }
        }
        // A depth texture the shader does not bind is the depth test's
        // target; a second one (a shadow map the shader stopped using) would
        // be silently dropped, so it is refused at its slot.
        let depth_slots: Vec<&plait_graph::Binding> = plan
            .settled
            .iter()
            .filter(|s| s.2 == Access::DepthTarget)
            .map(|s| {
                if s.0 {
                    &pass.writes[s.1]
                } else {
                    &pass.reads[s.1]
                }
            })
            .collect();
        if let [first, extra, ..] = depth_slots.as_slice() {
            errors.push(err(
                &extra.location,
                format!(
                    "slot `{}` is a depth texture the shader does not bind, so it would be a second depth target (`{}` is the first): bind it in the shader or drop it",
                    extra.slot, first.slot
                ),
            ));
        }
        // (A culled pass's writes may name resources the schedule dropped.)
        let all_writes_live = pass
            .writes
            .iter()
            .all(|b| resources.get(b.resource).is_some());
        if dynamic_slots
            && is_raster
            && all_writes_live
            && color_targets == 0
            && !plan
                .settled
                .iter()
                .any(|s| s.0 && s.2 == Access::DepthTarget)
            && !plan.writes_storage
        {
            errors.push(err(
                &pass.location,
                format!(
                    "a {} pass must write at least one target",
                    if shape == PassShape::Fullscreen {
                        "fullscreen"
                    } else {
                        "raster"
                    }
                ),
            ));
        }

        // The accesses as settled: attachments and clears follow from them.
        let access_of = |is_write: bool, i: usize, original: Access| {
            plan.settled
                .iter()
                .find(|s| s.0 == is_write && s.1 == i)
                .map_or(original, |s| s.2)
        };
        let writes: Vec<(Access, &plait_graph::Binding)> = pass
            .writes
            .iter()
            .enumerate()
            .map(|(i, b)| (access_of(true, i, b.access), b))
            .collect();
        let reads: Vec<(Access, &plait_graph::Binding)> = pass
            .reads
            .iter()
            .enumerate()
            .map(|(i, b)| (access_of(false, i, b.access), b))
            .collect();
        let texture = |id: ResourceId| match resources.get(id).map(|r| &r.desc) {
            Some(ResourceDesc::Texture {
                format, samples, ..
            }) => Some((*format, *samples)),
            _ => None,
        };
        let color_slots: Vec<&str> = writes
            .iter()
            .filter(|(a, _)| *a == Access::ColorTarget)
            .map(|(_, b)| b.slot.as_str())
            .collect();
        let resolve_of = |slot: &str| {
            slot.strip_suffix("_resolve")
                .is_some_and(|base| color_slots.contains(&base))
        };
        let mut new_colors = Vec::new();
        for (a, b) in &writes {
            match a {
                Access::ColorTarget if !resolve_of(&b.slot) => {
                    let Some((format, samples)) = texture(b.resource) else {
                        if resources.get(b.resource).is_some() {
                            errors.push(err(
                                &b.location,
                                format!("colour target `{}` is not a texture", b.slot),
                            ));
                        }
                        continue;
                    };
                    let resolve = writes
                        .iter()
                        .find(|(_, r)| r.slot == format!("{}_resolve", b.slot))
                        .map(|(_, r)| *r);
                    // wgpu resolves only a multisampled target into a
                    // single-sampled one of the same format: say so at load,
                    // not as a validation error mid-frame.
                    if let Some(r) = resolve
                        && let Some((resolve_format, resolve_samples)) = texture(r.resource)
                    {
                        let name = |i: usize| resources.get(i).map_or("?", |r| r.name.as_str());
                        if samples < 2 || resolve_samples != 1 || resolve_format != format {
                            errors.push(err(
                                &r.location,
                                format!(
                                    "`{}` (slot `{}`, {samples} sample(s), {}) cannot be resolved into `{}` (slot `{}`, {resolve_samples} sample(s), {}): a resolve needs a multisampled colour target (samples 4) and a single-sampled target of the same format",
                                    name(b.resource),
                                    b.slot,
                                    format.name(),
                                    name(r.resource),
                                    r.slot,
                                    resolve_format.name(),
                                ),
                            ));
                        }
                    }
                    new_colors.push(ColorTarget {
                        slot: b.slot.clone(),
                        resource: b.resource,
                        format,
                        samples,
                        loads: b.loads,
                        resolve: resolve.map(|r| r.resource),
                    });
                }
                // Storage textures are not zeroed: clearing one needs
                // CLEAR_TEXTURE, which core WebGPU lacks; their kernels write
                // every texel (the lighting maps, the environment cube).
                Access::StorageWrite if !b.loads && texture(b.resource).is_none() => {
                    plan.clears.push(b.resource)
                }
                _ => {}
            }
        }
        plan.colors = new_colors;
        plan.depth = writes
            .iter()
            .map(|(a, b)| (*a, *b, true))
            .chain(reads.iter().map(|(a, b)| (*a, *b, false)))
            .find(|(a, _, _)| *a == Access::DepthTarget)
            .and_then(|(_, b, written)| {
                let (format, samples) = texture(b.resource)?;
                Some(DepthTarget {
                    slot: b.slot.clone(),
                    resource: b.resource,
                    format,
                    samples,
                    written,
                    loads: b.loads,
                })
            });

        // Group 1: every shader binding needs a slot, a params uniform or a scene buffer.
        for sb in &group1 {
            let slot = pass
                .reads
                .iter()
                .chain(pass.writes.iter())
                .find(|s| binding_of(&s.slot) == sb.name);
            let source = if let Some(s) = slot {
                BindingSource::Slot {
                    resource: s.resource,
                    format: texture(s.resource).map(|(f, _)| f),
                }
            } else if is_params(sb) {
                let packed = reflect::params_layout(module, &sb.name)
                    .ok_or_else(|| format!("`{}` must be a uniform struct", sb.name))
                    .and_then(|(size, members)| reflect::pack_params(size, &members, &pass.params));
                match packed {
                    Ok(bytes) => BindingSource::Params(bytes),
                    Err(message) => {
                        errors.push(err(&pass.location, message));
                        continue;
                    }
                }
            } else if SCENE_BINDINGS.contains(&sb.name.as_str()) {
                if sb.writes() {
                    // Bound by name it is read-only: a writer must say so in
                    // the file, so the graph orders it before the hair draws.
                    errors.push(err(
                        &pass.location,
                        format!(
                            "the shader writes scene resource `{}`; bind it under `writes` (`writes = {{ {0} = \"{0}\" }}`)",
                            sb.name
                        ),
                    ));
                    continue;
                }
                BindingSource::Scene(sb.name.clone())
            } else {
                errors.push(GraphError::new(
                    pass.location.clone(),
                    ErrorKind::MissingBinding {
                        pass: pass.name.clone(),
                        binding: sb.name.clone(),
                        group: sb.group,
                        index: sb.binding,
                    },
                ));
                continue;
            };
            match &sb.kind {
                BindingKind::Sampler { .. } => errors.push(err(
                    &pass.location,
                    format!(
                        "sampler `{}` belongs in group 0 (import plait::frame)",
                        sb.name
                    ),
                )),
                BindingKind::StorageTexture { format: None, .. } => errors.push(err(
                    &pass.location,
                    format!("storage texture `{}` has an unsupported format", sb.name),
                )),
                _ => {}
            }
            plan.bindings.push(PlannedBinding {
                binding: sb.binding,
                name: sb.name.clone(),
                kind: sb.kind.clone(),
                source,
            });
        }
        (plan, errors)
    }
}

/// `(slot, shader binding)` for the slots of `spec` that feed a binding of another name.
pub fn binding_aliases(spec: &plait_graph::PassTypeSpec) -> Vec<(String, String)> {
    spec.inputs
        .iter()
        .chain(spec.outputs.iter())
        .filter_map(|s| Some((s.name.clone(), s.binding.clone()?)))
        .collect()
}

/// A uniform filled from the pass params by member name: `params`, or a
/// module's own such as `visibility_params`.
fn is_params(b: &ShaderBinding) -> bool {
    matches!(b.kind, BindingKind::Uniform { .. }) && b.name.ends_with("params")
}

/// A slot bound to shader binding `sb`: resource kind, format, samples,
/// layers, and writes through a slot declared under `reads`.
fn check_binding(
    sb: &ShaderBinding,
    b: &plait_graph::Binding,
    res: &ResolvedResource,
    pass: &ScheduledPass,
    is_write: bool,
    errors: &mut Vec<GraphError>,
) {
    let err = |message: String| {
        GraphError::new(
            b.location.clone(),
            ErrorKind::Pass {
                pass: pass.name.clone(),
                message,
            },
        )
    };
    if sb.resource_kind() != Some(res.desc.kind()) {
        errors.push(err(format!(
            "slot `{}` is bound to {} `{}`, but the shader declares it as {:?}",
            b.slot,
            res.desc.kind(),
            res.name,
            sb.kind
        )));
        return;
    }
    if let ResourceDesc::Texture {
        format,
        samples,
        layers,
        ..
    } = res.desc
    {
        if let Err(why) = sb.accepts_format(format) {
            errors.push(GraphError::new(
                b.location.clone(),
                ErrorKind::FormatMismatch {
                    resource: res.name.clone(),
                    declared: format.to_string(),
                    pass: pass.name.clone(),
                    slot: b.slot.clone(),
                    accepted: why,
                },
            ));
        }
        let (multi, arrayed) = match sb.kind {
            BindingKind::Texture {
                multisampled,
                arrayed,
                ..
            } => (multisampled, arrayed),
            BindingKind::StorageTexture { arrayed, .. } => (false, arrayed),
            _ => (false, false),
        };
        if multi != (samples > 1) {
            errors.push(err(format!(
                "`{}` has {samples} samples but the shader's `{}` is {}multisampled",
                res.name,
                b.slot,
                if multi { "" } else { "not " }
            )));
        }
        if arrayed != (layers > 1) {
            errors.push(err(format!(
                "`{}` has {layers} layers but the shader's `{}` is {}an array texture",
                res.name,
                b.slot,
                if arrayed { "" } else { "not " }
            )));
        }
    }
    if sb.writes() && !is_write {
        errors.push(err(format!(
            "the shader writes `{}`; bind it under `writes`, not `reads`",
            b.slot
        )));
    }
}

/// The composed module of a pass (cached), or the error to report.
pub(crate) fn pass_module<T: PassType + ?Sized>(
    t: &T,
    pass: &ScheduledPass,
) -> Result<Arc<naga::Module>, Box<GraphError>> {
    let (path, source) = shader_source(t, pass).map_err(|(loc, message)| {
        Box::new(GraphError::new(
            loc,
            ErrorKind::Pass {
                pass: pass.name.clone(),
                message,
            },
        ))
    })?;
    crate::modules::compose(&path, &source, &t.defines(pass)).map_err(|e| {
        Box::new(GraphError::new(
            pass.shader_location
                .clone()
                .unwrap_or_else(|| pass.location.clone()),
            ErrorKind::Shader {
                path: e.path,
                message: e.message,
            },
        ))
    })
}

/// Why the engine cannot keep this pass's storage writes to fragments that
/// pass its depth test (`depth_guard`), when it cannot: an in-shader test
/// reads the depth target as a texture, which is impossible for a
/// multisampled target and wrong for one the pass writes. Data-only passes
/// are held to it at check time whatever the adapter (`early_depth_test`
/// false), so a pipeline that checks renders everywhere.
pub fn unguardable(
    plan: &BindingPlan,
    depth: super::state::DepthMode,
    early_depth_test: bool,
) -> Option<String> {
    let target = plan.depth.as_ref()?;
    let guard = DepthGuard::choose(Some(depth.compare()), plan.writes_storage, early_depth_test);
    if !matches!(guard, DepthGuard::InShader(_)) {
        return None;
    }
    let writes_depth = target.written && matches!(depth, super::state::DepthMode::TestWrite(_));
    let why = if target.samples > 1 {
        format!("its depth target `{}` is multisampled", target.slot)
    } else if writes_depth {
        format!("it writes its depth target `{}`", target.slot)
    } else {
        return None;
    };
    Some(format!(
        "the shader writes storage behind a depth test, and {why}: without SHADER_EARLY_DEPTH_TEST (WebGPU, Metal, DX12) the engine tests depth in the shader, which needs a single-sampled depth target the pass only reads. Test against a depth target under `reads` with `depth = {{ compare = …, write = false }}` (write depth in a pass of its own)"
    ))
}
