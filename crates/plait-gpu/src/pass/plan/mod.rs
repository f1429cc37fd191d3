//! The binding plan of a pass: which shader binding each slot feeds, which
//! slots are colour and depth attachments, what the params uniform holds —
//! computed from the schedule and naga's reflection by ONE function,
//! [`BindingPlan::new`], which `plait check` ([`super::check`]) reports on and
//! build ([`super::build`]) lays out and records from. Slots cannot be matched
//! to bindings one way when checking and another when building.

use std::sync::Arc;

use plait_graph::{
    Access, Error as GraphError, ErrorKind, Format, Location, PassShape, ResolvedResource,
    ResourceDesc, ResourceId, ScheduledPass, SlotRef,
};

mod attachments;
mod bindings;
mod slots;

use super::pass_type::{PassType, shader_source};
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
    /// A scene buffer (`hair_vertices`, `wisp_indices`, …: `SCENE_BINDINGS`).
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
    /// The resource's `clear = …`, used instead of the state's clear colour.
    pub clear: Option<[f64; 4]>,
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
    /// The resource's `clear = …` (its first channel is the depth).
    pub clear: Option<[f64; 4]>,
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
    /// shader.
    pub settled: Vec<(SlotRef, Access)>,
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
        let mut planner = Planner::new(module, pass, resources, shape, dynamic_slots, aliases);
        let color_targets = planner.settle_slots();
        planner.check_targets(color_targets);
        planner.attachments();
        planner.group1_sources();
        (planner.plan, planner.errors)
    }
}

/// The state [`BindingPlan::new`]'s phases share: what they read, the plan
/// they fill, the errors they find.
struct Planner<'a> {
    module: &'a naga::Module,
    pass: &'a ScheduledPass,
    resources: &'a [ResolvedResource],
    shape: PassShape,
    dynamic_slots: bool,
    aliases: &'a [(String, String)],
    /// The shader's group-1 bindings, in binding order.
    group1: Vec<ShaderBinding>,
    plan: BindingPlan,
    errors: Vec<GraphError>,
}

impl<'a> Planner<'a> {
    /// Reflect the shader; a binding outside groups 0 and 1 is an error.
    fn new(
        module: &'a naga::Module,
        pass: &'a ScheduledPass,
        resources: &'a [ResolvedResource],
        shape: PassShape,
        dynamic_slots: bool,
        aliases: &'a [(String, String)],
    ) -> Self {
        let mut planner = Planner {
            module,
            pass,
            resources,
            shape,
            dynamic_slots,
            aliases,
            group1: Vec::new(),
            plan: BindingPlan::default(),
            errors: Vec::new(),
        };
        for b in reflect::bindings(module) {
            match b.group {
                0 => {}
                1 => planner.group1.push(b),
                group => planner.error(&pass.location, format!("shader binding `{}` is in group {group}; plait binds only groups 0 (frame) and 1 (slots)", b.name)),
            }
        }
        for (name, group, binding, what) in reflect::unbindable(module) {
            planner.error(&pass.location, format!("shader binding `{name}` (group {group}, binding {binding}) is {what}, which plait cannot bind to a pass"));
        }
        planner.plan.writes_storage = planner.group1.iter().any(|b| b.writes());
        planner
    }

    fn error(&mut self, loc: &Location, message: String) {
        self.errors.push(GraphError::new(
            loc.clone(),
            ErrorKind::Pass {
                pass: self.pass.name.clone(),
                message,
            },
        ));
    }

    /// The shader variable a slot feeds: its own name unless the type says.
    fn binding_of<'s>(&'s self, slot: &'s str) -> &'s str {
        self.aliases
            .iter()
            .find(|(s, _)| s == slot)
            .map_or(slot, |(_, b)| b.as_str())
    }

    fn is_raster(&self) -> bool {
        self.shape != PassShape::Compute
    }

    /// `(format, samples)` of a texture resource; `None` for a buffer or a
    /// resource the schedule dropped.
    fn texture(&self, id: Option<ResourceId>) -> Option<(Format, u32)> {
        match id
            .and_then(|id| self.resources.get(id.index()))
            .map(|r| &r.desc)
        {
            Some(ResourceDesc::Texture {
                format, samples, ..
            }) => Some((*format, *samples)),
            _ => None,
        }
    }

    /// The `clear = …` the resource declares.
    fn clear_of(&self, id: Option<ResourceId>) -> Option<[f64; 4]> {
        id.and_then(|id| self.resources.get(id.index()))?.clear
    }

    /// The access of `slot` as settled, else as the file declared it.
    fn access_of(&self, slot: SlotRef, declared: Access) -> Access {
        self.plan
            .settled
            .iter()
            .find(|(s, _)| *s == slot)
            .map_or(declared, |(_, a)| *a)
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

/// The composed module of a pass (cached), or the error to report.
pub(crate) fn pass_module<T: PassType + ?Sized>(
    t: &T,
    pass: &ScheduledPass,
    shaders: &crate::modules::Shaders,
) -> Result<Arc<naga::Module>, Box<GraphError>> {
    let (path, source) = shader_source(t, pass, shaders).map_err(|(loc, message)| {
        Box::new(GraphError::new(
            loc,
            ErrorKind::Pass {
                pass: pass.name.clone(),
                message,
            },
        ))
    })?;
    shaders
        .compose(&path, &source, &t.defines(pass))
        .map_err(|e| {
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
