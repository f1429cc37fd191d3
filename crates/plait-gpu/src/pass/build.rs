//! Building the GPU objects of one draw or dispatch of a shader: the bind
//! group laid out from the pass's [`BindingPlan`], the depth guard, and the
//! (cached) pipeline.
//!
//! [`ShaderDraw`] is everything that defines such a draw. A pass type gets
//! one from [`ShaderDraw::of`]; a pass that records several draws (depth
//! range, depth peeling, k-means) adjusts copies of it or builds its own with
//! [`ShaderDraw::library`] — no need to pose as a pass type.

use std::borrow::Cow;
use std::path::PathBuf;

use plait_graph::{PassShape, ScheduledPass};

use super::layout::binding_type;
use super::pass_type::{BuildContext, PassType, shader_source};
use super::pipeline::PipelineParts;
use super::plan::{BindingPlan, BindingSource, binding_aliases, unguardable};
use super::record::ShaderPass;
use super::state::{RasterState, from_decl};
use crate::GpuError;
use crate::depth_guard::{DepthGuard, GUARD_BINDING};
use crate::shader::Define;

/// One draw (or dispatch) of a shader for a pass.
#[derive(Clone, Debug)]
pub struct ShaderDraw {
    /// Names the shader in messages.
    pub path: PathBuf,
    pub source: Cow<'static, str>,
    pub defines: Vec<(String, Define)>,
    pub shape: PassShape,
    /// Slots are the shader's bindings (data-only pass types).
    pub dynamic_slots: bool,
    /// `(slot, shader binding)` where a slot feeds a binding of another name.
    pub aliases: Vec<(String, String)>,
    /// Raster and fullscreen draws.
    pub state: RasterState,
    /// Compute dispatches: threads to cover.
    pub threads: [u32; 3],
    /// Optional GPU features the draw needs (names as in `wgpu::Features`).
    pub required_features: Vec<String>,
}

impl ShaderDraw {
    /// The draw a pass type makes of `pass`: its shader, defines, state.
    pub fn of<T: PassType + ?Sized>(
        t: &T,
        pass: &ScheduledPass,
        ctx: &BuildContext<'_>,
    ) -> Result<ShaderDraw, GpuError> {
        let spec = t.spec();
        let (path, source) = shader_source(t, pass, ctx.shaders)
            .map_err(|(_, message)| pass_error(pass, message))?;
        let state = raster_state_of(t, pass, &ctx.schedule.resources, ctx.capabilities)
            .map_err(|m| pass_error(pass, m))?;
        Ok(ShaderDraw {
            path,
            source,
            defines: t.defines(pass),
            shape: spec.shape,
            dynamic_slots: spec.dynamic_slots,
            aliases: binding_aliases(&spec),
            state,
            threads: t.compute_threads(pass, ctx.schedule),
            required_features: spec.required_features,
        })
    }

    /// A draw of a library shader (`shaders/passes/x.wgsl`, search path
    /// first) with fixed slots (`pass`'s bindings as given).
    pub fn library(
        shader: &str,
        pass: &ScheduledPass,
        shape: PassShape,
        defines: Vec<(String, Define)>,
        state: RasterState,
        ctx: &BuildContext<'_>,
    ) -> Result<ShaderDraw, GpuError> {
        let (path, source) = ctx
            .shaders
            .library_file(shader)
            .map_err(|e| pass_error(pass, e.message))?;
        Ok(ShaderDraw {
            path,
            source,
            defines,
            shape,
            dynamic_slots: false,
            aliases: Vec::new(),
            state,
            threads: [1, 1, 1],
            required_features: Vec::new(),
        })
    }
}

/// The fixed-function state of a pass: from its TOML keys for types with
/// `state_from_data`, else from the type's Rust ([`PassType::raster_state`]).
pub fn raster_state_of<T: PassType + ?Sized>(
    t: &T,
    pass: &ScheduledPass,
    resources: &[plait_graph::ResolvedResource],
    caps: &crate::Capabilities,
) -> Result<RasterState, String> {
    let spec = t.spec();
    if spec.shape == PassShape::Compute {
        Ok(RasterState::default())
    } else if spec.state_from_data {
        from_decl(&t.raster_decl(pass), pass, resources)
            .map_err(|e| e.into_iter().map(|(_, m)| m).collect::<Vec<_>>().join("; "))
    } else {
        t.raster_state(pass, caps)
    }
}

/// The default `PassType::build`, boxed: one draw of the type's shader.
pub fn build_shader_pass<T: PassType + ?Sized>(
    t: &T,
    pass: &ScheduledPass,
    ctx: &BuildContext<'_>,
) -> Result<Box<dyn super::PreparedPass>, GpuError> {
    let draw = ShaderDraw::of(t, pass, ctx)?;
    Ok(Box::new(build_draw(&draw, pass, ctx)?))
}

pub(super) fn pass_error(pass: &ScheduledPass, message: impl Into<String>) -> GpuError {
    GpuError::Pass {
        pass: pass.name.clone(),
        message: message.into(),
    }
}

/// Compose (cached), plan, lay out, create the pipeline (cached) of `draw`.
pub fn build_draw(
    draw: &ShaderDraw,
    pass: &ScheduledPass,
    ctx: &BuildContext<'_>,
) -> Result<ShaderPass, GpuError> {
    for feature in &draw.required_features {
        let has =
            wgpu::Features::from_name(feature).is_some_and(|f| ctx.device.features().contains(f));
        if !has {
            return Err(GpuError::MissingFeature {
                pass: pass.name.clone(),
                feature: feature.clone(),
                adapter: ctx.adapter_name.to_owned(),
            });
        }
    }
    // Everything below is checked by wgpu; its errors name this pass.
    let device = ctx.device;
    let (result, scoped) = crate::wait::validated(device, || build_inner(draw, pass, ctx));
    let built = result?;
    if let Some(e) = scoped {
        return Err(GpuError::Validation {
            pass: pass.name.clone(),
            message: crate::describe_wgpu_error(&e),
        });
    }
    Ok(built)
}

/// The phases of [`build_draw`], inside its validation scope.
fn build_inner(
    draw: &ShaderDraw,
    pass: &ScheduledPass,
    ctx: &BuildContext<'_>,
) -> Result<ShaderPass, GpuError> {
    let (plan, guard, module) = plan_and_guard(draw, pass, ctx)?;
    let is_compute = draw.shape == PassShape::Compute;
    let (layout_entries, bind_group) = bind_group(&plan, guard, is_compute, pass, ctx)?;
    let device = ctx.device;
    let group1_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(&pass.name),
        entries: &layout_entries,
    });
    let bind_group = bind_group(&group1_layout);
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(&pass.name),
        bind_group_layouts: &[Some(ctx.frame_layout), Some(&group1_layout)],
        immediate_size: 0,
    });
    // The library modules' digest too: they may be edited while plait runs.
    let library = ctx.shaders.digest();
    let shader_key = crate::cache::key(&[
        &draw.path,
        &draw.source,
        &library,
        &draw.defines,
        &layout_entries,
        &guard,
    ]);
    let parts = PipelineParts {
        draw,
        pass,
        ctx,
        module,
        layout,
        shader_key,
        shader: std::cell::OnceCell::new(),
    };
    let kind = if is_compute {
        parts.compute()?
    } else {
        parts.raster(&plan)?
    };
    Ok(ShaderPass {
        name: pass.name.clone(),
        kind,
        bind_group,
        clears: plan.clears,
    })
}

/// Compose the module, plan its bindings, and guard its storage writes
/// behind the depth test where the hardware cannot ([`DepthGuard`]).
fn plan_and_guard(
    draw: &ShaderDraw,
    pass: &ScheduledPass,
    ctx: &BuildContext<'_>,
) -> Result<(BindingPlan, DepthGuard, std::sync::Arc<naga::Module>), GpuError> {
    let module = ctx
        .shaders
        .compose(&draw.path, &draw.source, &draw.defines)?;
    let (plan, errors) = BindingPlan::new(
        &module,
        pass,
        &ctx.schedule.resources,
        draw.shape,
        draw.dynamic_slots,
        &draw.aliases,
    );
    if let Some(e) = errors.first() {
        // `plait check` reports these with their place; here only the first.
        return Err(pass_error(pass, e.kind.to_string()));
    }
    if draw.shape == PassShape::Compute || plan.depth.is_none() {
        return Ok((plan, DepthGuard::Unneeded, module));
    }
    let depth = draw.state.depth;
    let early = ctx.capabilities.early_depth_test;
    if unguardable(&plan, depth, early).is_some() {
        return Err(GpuError::MissingFeature {
            pass: pass.name.clone(),
            feature: "SHADER_EARLY_DEPTH_TEST (storage writes behind a multisampled or written depth target cannot be tested in the shader)".into(),
            adapter: ctx.adapter_name.to_owned(),
        });
    }
    let guard = DepthGuard::choose(Some(depth.compare()), plan.writes_storage, early);
    if guard == DepthGuard::Unneeded {
        return Ok((plan, guard, module));
    }
    let mut guarded = (*module).clone();
    guard.apply(&mut guarded);
    Ok((plan, guard, std::sync::Arc::new(guarded)))
}

type MakeBindGroup<'a> = Box<dyn FnOnce(&wgpu::BindGroupLayout) -> Option<wgpu::BindGroup> + 'a>;

/// Group 1's layout entries from the plan, and the bind group to make once
/// the layout exists.
fn bind_group<'a>(
    plan: &BindingPlan,
    guard: DepthGuard,
    is_compute: bool,
    pass: &'a ScheduledPass,
    ctx: &'a BuildContext<'_>,
) -> Result<(Vec<wgpu::BindGroupLayoutEntry>, MakeBindGroup<'a>), GpuError> {
    let mut layout_entries = Vec::new();
    let mut owned: Vec<(u32, wgpu::Buffer)> = Vec::new();
    let mut resources: Vec<(u32, plait_graph::ResourceId)> = Vec::new();
    let mut scene: Vec<(u32, wgpu::BindingResource<'a>)> = Vec::new();
    for b in &plan.bindings {
        let visibility = if is_compute {
            wgpu::ShaderStages::COMPUTE
        } else if b.writes() {
            wgpu::ShaderStages::FRAGMENT
        } else {
            wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT
        };
        let format = match b.source {
            BindingSource::Slot { format, .. } => format,
            _ => None,
        };
        layout_entries.push(wgpu::BindGroupLayoutEntry {
            binding: b.binding,
            visibility,
            ty: binding_type(&b.kind, format).ok_or_else(|| {
                pass_error(pass, format!("`{}` cannot be bound in group 1", b.name))
            })?,
            count: None,
        });
        match &b.source {
            BindingSource::Params(bytes) => owned.push((
                b.binding,
                wgpu::util::DeviceExt::create_buffer_init(
                    ctx.device,
                    &wgpu::util::BufferInitDescriptor {
                        label: Some(&format!("{} params", pass.name)),
                        contents: bytes,
                        usage: wgpu::BufferUsages::UNIFORM,
                    },
                ),
            )),
            BindingSource::Slot { resource, .. } => {
                if ctx.pool.binding_resource(*resource).is_none() {
                    let message = format!(
                        "`{}`: the strands' structure is bound before the pass that builds it",
                        b.name
                    );
                    return Err(pass_error(pass, message));
                }
                resources.push((b.binding, *resource))
            }
            BindingSource::Scene(name) if name == "environment_source" => {
                let view = ctx.geometry.environment.as_ref().ok_or_else(|| {
                    pass_error(pass, "the scene's environment image was not uploaded")
                })?;
                scene.push((b.binding, wgpu::BindingResource::TextureView(view)));
            }
            BindingSource::Scene(name) => {
                let (geometry, what) = if name.starts_with("opaque_") {
                    (ctx.geometry.opaque.as_ref(), "opaque geometry")
                } else if name.starts_with("wisp_") {
                    (ctx.geometry.wisps.as_ref(), "wisps (geometry = wisps)")
                } else {
                    (ctx.geometry.hair.as_ref(), "hair")
                };
                let buffers = geometry.ok_or_else(|| {
                    pass_error(pass, format!("the scene has no {what} to bind as `{name}`"))
                })?;
                let buf = if name.ends_with("_vertices") {
                    &buffers.vertices
                } else {
                    &buffers.indices
                };
                scene.push((b.binding, buf.as_entire_binding()));
            }
        }
    }
    if let (DepthGuard::InShader(_), Some(d)) = (guard, &plan.depth) {
        layout_entries.push(wgpu::BindGroupLayoutEntry {
            binding: GUARD_BINDING,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Depth,
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        });
        resources.push((GUARD_BINDING, d.resource));
    }
    let empty = layout_entries.is_empty();
    let make: MakeBindGroup<'a> = Box::new(move |layout| {
        if empty {
            return None;
        }
        // Checked above when the plan was read.
        let bound = resources
            .iter()
            .map(|(binding, id)| Some((*binding, ctx.pool.binding_resource(*id)?)))
            .collect::<Option<Vec<_>>>()?;
        let mut entries: Vec<wgpu::BindGroupEntry> = Vec::new();
        for (binding, buf) in &owned {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: buf.as_entire_binding(),
            });
        }
        for (binding, resource) in &bound {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: resource.resource(),
            });
        }
        for (binding, resource) in &scene {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: resource.clone(),
            });
        }
        Some(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&pass.name),
            layout,
            entries: &entries,
        }))
    });
    Ok((layout_entries, make))
}
