//! A compiled schedule against an [`AdapterSupport`], without a device: the
//! rules wgpu applies to what the pool and the passes create, each problem
//! named at the pass slot (or resource declaration) that asks for it.

use plait_graph::{Location, PassShape, ResourceId, Schedule, ScheduledPass};
use wgpu::{DownlevelFlags as D, TextureFormatFeatureFlags as F};

use super::{AdapterSupport, Problem, Unsupported};
use crate::Capabilities;
use crate::depth_guard::DepthGuard;
use crate::pass::plan::{BindingPlan, BindingSource, PlannedBinding, binding_aliases, pass_module};
use crate::pass::{PassLibrary, PassType, raster_state_of};
use crate::pool::texture_format;
use crate::reflect::BindingKind;

/// Whether `schedule` runs on the adapter described by `support` and
/// `caps`; every problem when it does not. Compile fits the formats to the
/// adapter it is given (32-bit float targets blended in 16 bits without
/// FLOAT32_BLENDABLE): a schedule compiled for another adapter is refused
/// here rather than fitted.
pub fn check_schedule(
    schedule: &Schedule,
    library: &PassLibrary,
    support: &AdapterSupport,
    caps: &Capabilities,
) -> Result<(), Box<Unsupported>> {
    let found = problems(schedule, library, support, caps);
    if found.is_empty() {
        Ok(())
    } else {
        Err(Box::new(Unsupported::new(support, &schedule.name, found)))
    }
}

/// The problems of a schedule already fitted to the adapter, in pass order,
/// each once.
pub fn problems(
    schedule: &Schedule,
    library: &PassLibrary,
    support: &AdapterSupport,
    caps: &Capabilities,
) -> Vec<Problem> {
    let mut out = Vec::new();
    super::adapter_needs::technique_problems(schedule, caps, &mut out);
    super::adapter_needs::structure_problems(schedule, caps, &mut out);
    super::textures::resource_problems(schedule, support, &mut out);
    for pass in &schedule.passes {
        super::textures::usage_problems(pass, schedule, support, &mut out);
        if let Some(t) = library.pass_type(pass) {
            pass_problems(t, pass, schedule, support, caps, &library.shaders, &mut out);
        }
    }
    let mut unique: Vec<Problem> = Vec::new();
    for p in out {
        if !unique.contains(&p) {
            unique.push(p);
        }
    }
    unique
}

pub(super) fn problem(
    pass: Option<&ScheduledPass>,
    location: &Location,
    resource: Option<&str>,
    what: String,
    missing: String,
) -> Problem {
    Problem {
        location: location.clone(),
        pass: pass.map(|p| p.name.clone()),
        technique: pass.and_then(|p| p.technique.clone()),
        resource: resource.map(str::to_owned),
        what,
        missing,
    }
}

fn lacks(flag: D) -> String {
    format!("the adapter lacks {flag:?}")
}

/// What the pass's shader, bindings and targets need.
fn pass_problems(
    t: &dyn PassType,
    pass: &ScheduledPass,
    schedule: &Schedule,
    support: &AdapterSupport,
    caps: &Capabilities,
    shaders: &crate::modules::Shaders,
    out: &mut Vec<Problem>,
) {
    let spec = t.spec();
    let is_compute = spec.shape == PassShape::Compute;
    if is_compute && !support.downlevel.contains(D::COMPUTE_SHADERS) {
        out.push(problem(
            Some(pass),
            &pass.location,
            None,
            "is a compute pass".into(),
            lacks(D::COMPUTE_SHADERS),
        ));
        return;
    }
    // A shader that does not compose was reported by `plait check`.
    let Ok(module) = pass_module(t, pass, shaders) else {
        return;
    };
    let (plan, _) = BindingPlan::new(
        &module,
        pass,
        &schedule.resources,
        spec.shape,
        spec.dynamic_slots,
        &binding_aliases(&spec),
    );
    let ctx = PassCtx {
        pass,
        schedule,
        support,
    };
    for b in &plan.bindings {
        ctx.binding(b, is_compute, out);
    }
    if !support.depth_values_readable {
        for g in super::depth_values::depth_value_reads(&module) {
            let name = module.global_variables[g].name.as_deref().unwrap_or("?");
            let name = crate::reflect::plain_name(name);
            let b = plan.bindings.iter().find(|b| b.name == name);
            let (location, resource) = ctx.slot_of(b);
            out.push(problem(
                Some(pass),
                &location,
                resource.as_deref(),
                format!(
                    "reads depth texture `{}` as values (textureLoad, or sampling without a comparison)",
                    resource.as_deref().unwrap_or(name)
                ),
                format!(
                    "the {} backend cannot: naga's GLSL output declares depth textures as shadow samplers",
                    support.backend.to_str()
                ),
            ));
        }
    }
    if !support.sample_mask && super::sample_mask::uses_sample_mask(&module) {
        ctx.add(
            out,
            &pass.location,
            None,
            "uses `@builtin(sample_mask)` in its fragment shader (it picks the samples it covers)"
                .into(),
            format!(
                "the {} backend cannot: naga's GLSL output treats gl_SampleMaskIn and gl_SampleMask, int arrays in GLSL, as a uint",
                support.backend.to_str()
            ),
        );
    }
    if is_compute {
        ctx.workgroup(&module, out);
        ctx.stage_limits(&plan, false, true, out);
        return;
    }
    let Ok(state) = raster_state_of(t, pass, &schedule.resources, caps) else {
        return;
    };
    let guard = match &plan.depth {
        Some(_) => DepthGuard::choose(
            Some(state.depth.compare()),
            plan.writes_storage,
            caps.early_depth_test,
        ),
        None => DepthGuard::Unneeded,
    };
    let in_shader = matches!(guard, DepthGuard::InShader(_));
    ctx.stage_limits(&plan, in_shader, false, out);
    ctx.targets(&plan, &state, in_shader, out);
}

struct PassCtx<'a> {
    pass: &'a ScheduledPass,
    schedule: &'a Schedule,
    support: &'a AdapterSupport,
}

impl PassCtx<'_> {
    fn add(
        &self,
        out: &mut Vec<Problem>,
        location: &Location,
        resource: Option<&str>,
        what: String,
        missing: String,
    ) {
        out.push(problem(Some(self.pass), location, resource, what, missing));
    }

    /// The slot feeding a planned binding: its line in the file and its resource.
    fn slot_of(&self, b: Option<&PlannedBinding>) -> (Location, Option<String>) {
        let resource = match b.map(|b| &b.source) {
            Some(BindingSource::Slot { resource, .. }) => Some(*resource),
            _ => None,
        };
        let slot = resource.and_then(|id| {
            self.pass
                .reads
                .iter()
                .chain(&self.pass.writes)
                .find(|s| s.resource == Some(id))
        });
        match slot {
            Some(s) => (
                s.location.clone(),
                s.resolved(&self.schedule.resources).map(|r| r.name.clone()),
            ),
            None => (self.pass.location.clone(), b.map(|b| b.name.clone())),
        }
    }

    /// The layout entry build makes for `b` (visibility by the same rule).
    fn binding(&self, b: &PlannedBinding, is_compute: bool, out: &mut Vec<Problem>) {
        let in_vertex = !is_compute && !b.writes();
        let in_fragment = !is_compute;
        let (location, resource) = self.slot_of(Some(b));
        let name = resource.clone().unwrap_or_else(|| b.name.clone());
        let flags = self.support.downlevel;
        let mut add = |what: String, missing: String| {
            self.add(out, &location, resource.as_deref(), what, missing)
        };
        match &b.kind {
            BindingKind::Storage { min_size, .. } => {
                if in_vertex && !flags.contains(D::VERTEX_STORAGE) {
                    add(
                        format!("binds storage buffer `{name}` to its vertex stage"),
                        lacks(D::VERTEX_STORAGE),
                    );
                }
                self.aligned(*min_size, &name, &mut add);
            }
            BindingKind::Uniform { size } => self.aligned(*size, &name, &mut add),
            BindingKind::StorageTexture {
                format: Some(format),
                access_write,
                access_read,
                ..
            } => {
                let (flag, access) = match (access_read, access_write) {
                    (true, true) => (F::STORAGE_READ_WRITE, "ReadWrite"),
                    (false, true) => (F::STORAGE_WRITE_ONLY, "WriteOnly"),
                    _ => (F::STORAGE_READ_ONLY, "ReadOnly"),
                };
                if !self.support.format(*format).flags.contains(flag) {
                    add(
                        format!("binds `{name}` as a {access} storage texture"),
                        format!(
                            "Storage texture binding access {access} is not supported for format {:?} on this adapter",
                            texture_format(*format)
                        ),
                    );
                }
            }
            // No filtering check: the layout asks for filtering only where
            // the format is filterable in WebGPU, which wgpu always accepts.
            _ => {}
        }
        if b.writes() && in_fragment && !flags.contains(D::FRAGMENT_WRITABLE_STORAGE) {
            add(
                format!("writes `{name}` from its fragment shader"),
                lacks(D::FRAGMENT_WRITABLE_STORAGE),
            );
        }
    }

    fn aligned(&self, size: u64, name: &str, add: &mut impl FnMut(String, String)) {
        let flag = D::BUFFER_BINDINGS_NOT_16_BYTE_ALIGNED;
        if !size.is_multiple_of(16) && !self.support.downlevel.contains(flag) {
            add(
                format!("binds buffer `{name}` whose type is {size} bytes, not a multiple of 16"),
                lacks(flag),
            );
        }
    }

    fn workgroup(&self, module: &naga::Module, out: &mut Vec<Problem>) {
        let l = &self.support.limits;
        let max = [
            l.max_compute_workgroup_size_x,
            l.max_compute_workgroup_size_y,
            l.max_compute_workgroup_size_z,
        ];
        for e in module
            .entry_points
            .iter()
            .filter(|e| e.stage == naga::ShaderStage::Compute)
        {
            let size = e.workgroup_size;
            let total: u32 = size.iter().product();
            let over = (0..3).any(|i| size[i] > max[i]);
            if over || total > l.max_compute_invocations_per_workgroup {
                self.add(
                    out,
                    &self.pass.location,
                    None,
                    format!("runs workgroups of {size:?} ({total} invocations)"),
                    format!(
                        "the adapter's limits are max_compute_workgroup_size {max:?}, max_compute_invocations_per_workgroup {}",
                        l.max_compute_invocations_per_workgroup
                    ),
                );
            }
        }
    }

    /// Bindings per stage, group 0's included, against the per-stage limits.
    fn stage_limits(
        &self,
        plan: &BindingPlan,
        guard_texture: bool,
        compute: bool,
        out: &mut Vec<Problem>,
    ) {
        let stages: &[(&str, bool)] = if compute {
            &[("compute", false)]
        } else {
            &[("vertex", true), ("fragment", false)]
        };
        let l = &self.support.limits;
        for &(stage, vertex) in stages {
            // Group 0: the frame uniforms, three samplers, the background image.
            let mut n = [1u32, 0, 1, 0, 3];
            if guard_texture && !vertex {
                n[2] += 1;
            }
            for b in &plan.bindings {
                if vertex && b.writes() {
                    continue;
                }
                let i = match b.kind {
                    BindingKind::Uniform { .. } => 0,
                    BindingKind::Storage { .. } => 1,
                    BindingKind::Texture { .. } => 2,
                    BindingKind::StorageTexture { .. } => 3,
                    BindingKind::Sampler { .. } => 4,
                    // One structure, far below any adapter's
                    // max_acceleration_structures_per_shader_stage.
                    BindingKind::AccelerationStructure => continue,
                };
                n[i] += 1;
            }
            let limits = [
                (
                    "uniform buffers",
                    "max_uniform_buffers_per_shader_stage",
                    l.max_uniform_buffers_per_shader_stage,
                ),
                (
                    "storage buffers",
                    "max_storage_buffers_per_shader_stage",
                    l.max_storage_buffers_per_shader_stage,
                ),
                (
                    "sampled textures",
                    "max_sampled_textures_per_shader_stage",
                    l.max_sampled_textures_per_shader_stage,
                ),
                (
                    "storage textures",
                    "max_storage_textures_per_shader_stage",
                    l.max_storage_textures_per_shader_stage,
                ),
                (
                    "samplers",
                    "max_samplers_per_shader_stage",
                    l.max_samplers_per_shader_stage,
                ),
            ];
            for (count, (what, name, limit)) in n.iter().zip(limits) {
                if *count > limit {
                    self.add(
                        out,
                        &self.pass.location,
                        None,
                        format!("binds {count} {what} to its {stage} stage"),
                        format!("the adapter's {name} is {limit}"),
                    );
                }
            }
        }
    }

    /// Colour targets (blending, their count) and the depth target's reads.
    fn targets(
        &self,
        plan: &BindingPlan,
        state: &crate::pass::RasterState,
        guard_texture: bool,
        out: &mut Vec<Problem>,
    ) {
        let flags = self.support.downlevel;
        let location_of = |id: ResourceId| {
            self.pass
                .writes
                .iter()
                .chain(&self.pass.reads)
                .find(|b| b.resource == Some(id))
                .map_or(self.pass.location.clone(), |b| b.location.clone())
        };
        let name_of = |id: ResourceId| {
            self.schedule
                .resources
                .get(id.index())
                .map_or("?", |r| r.name.as_str())
        };
        for (i, c) in plan.colors.iter().enumerate() {
            let blended = state.blend.get(i).copied().flatten().is_some();
            if blended && !self.support.format(c.format).flags.contains(F::BLENDABLE) {
                self.add(
                    out,
                    &location_of(c.resource),
                    Some(name_of(c.resource)),
                    format!("blends into `{}` ({})", name_of(c.resource), c.format),
                    format!(
                        "Format {:?} is not blendable on this adapter",
                        texture_format(c.format)
                    ),
                );
            }
        }
        let limit = self.support.limits.max_color_attachments;
        if plan.colors.len() as u32 > limit {
            self.add(
                out,
                &self.pass.location,
                None,
                format!("renders into {} colour targets", plan.colors.len()),
                format!("the adapter's max_color_attachments is {limit}"),
            );
        }
        let mask = |i: usize| {
            state
                .write_mask
                .get(i)
                .copied()
                .unwrap_or(wgpu::ColorWrites::ALL)
        };
        let blend = |i: usize| state.blend.get(i).copied().flatten();
        let independent =
            (1..plan.colors.len()).any(|i| blend(i) != blend(0) || mask(i) != mask(0));
        if independent && !flags.contains(D::INDEPENDENT_BLEND) {
            self.add(
                out,
                &self.pass.location,
                None,
                "blends its colour targets differently".into(),
                lacks(D::INDEPENDENT_BLEND),
            );
        }
        // A depth target the pass also samples (itself, or the engine's
        // in-shader depth test) must be attachable read-only.
        if let Some(d) = &plan.depth
            && !d.written
            && !flags.contains(D::READ_ONLY_DEPTH_STENCIL)
        {
            let sampled = plan.bindings.iter().any(|b| {
                b.source
                    == BindingSource::Slot {
                        resource: d.resource,
                        format: Some(d.format),
                    }
            });
            if sampled || guard_texture {
                self.add(
                    out,
                    &location_of(d.resource),
                    Some(name_of(d.resource)),
                    format!(
                        "samples its depth target `{}` while testing against it",
                        name_of(d.resource)
                    ),
                    lacks(D::READ_ONLY_DEPTH_STENCIL),
                );
            }
        }
    }
}
