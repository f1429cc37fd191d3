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
use super::plan::{BindingPlan, BindingSource, binding_aliases, unguardable};
use super::record::{DrawWhat, ShaderPass, ShaderPassKind};
use super::state::{DepthMode, RasterState, from_decl};
use crate::GpuError;
use crate::depth_guard::{DepthGuard, GUARD_BINDING};
use crate::geometry::{hair_vertex_layout, opaque_vertex_layout};
use crate::pool::texture_format;
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
        let (path, source) =
            shader_source(t, pass).map_err(|(_, message)| pass_error(pass, message))?;
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
    ) -> Result<ShaderDraw, GpuError> {
        let (path, source) =
            crate::shader::library_file(shader).map_err(|e| pass_error(pass, e.message))?;
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

fn pass_error(pass: &ScheduledPass, message: impl Into<String>) -> GpuError {
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
    let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let result = build_inner(draw, pass, ctx);
    let scoped = pollster::block_on(scope.pop());
    let built = result?;
    if let Some(e) = scoped {
        return Err(GpuError::Validation {
            pass: pass.name.clone(),
            message: crate::describe_wgpu_error(&e),
        });
    }
    Ok(built)
}

fn build_inner(
    draw: &ShaderDraw,
    pass: &ScheduledPass,
    ctx: &BuildContext<'_>,
) -> Result<ShaderPass, GpuError> {
    let module = crate::modules::compose(&draw.path, &draw.source, &draw.defines)?;
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
    let is_compute = draw.shape == PassShape::Compute;
    let state = &draw.state;
    let guard = match (&plan.depth, is_compute) {
        (Some(_), false) => DepthGuard::choose(
            Some(state.depth.compare()),
            plan.writes_storage,
            ctx.capabilities.early_depth_test,
        ),
        _ => DepthGuard::Unneeded,
    };
    if !is_compute && unguardable(&plan, state.depth, ctx.capabilities.early_depth_test).is_some() {
        return Err(GpuError::MissingFeature {
            pass: pass.name.clone(),
            feature: "SHADER_EARLY_DEPTH_TEST (storage writes behind a multisampled or written depth target cannot be tested in the shader)".into(),
            adapter: ctx.adapter_name.to_owned(),
        });
    }
    let module = if guard == DepthGuard::Unneeded {
        module
    } else {
        let mut guarded = (*module).clone();
        guard.apply(&mut guarded);
        std::sync::Arc::new(guarded)
    };

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
    // Compiled only when the cache has no pipeline for this shader and state.
    let shader = std::cell::OnceCell::new();
    let shader = || {
        shader.get_or_init(|| {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&pass.name),
                source: wgpu::ShaderSource::Naga(Cow::Owned((*module).clone())),
            })
        })
    };
    // The library modules' digest too: they may be edited while plait runs.
    let library = crate::modules::library_digest();
    let shader_key: [&dyn std::fmt::Debug; 6] = [
        &draw.path,
        &draw.source,
        &library,
        &draw.defines,
        &layout_entries,
        &guard,
    ];

    let kind = if is_compute {
        let entry = module
            .entry_points
            .iter()
            .find(|e| e.stage == naga::ShaderStage::Compute)
            .ok_or_else(|| pass_error(pass, "the shader has no @compute entry point"))?;
        let wg = entry.workgroup_size;
        let workgroups = [0, 1, 2].map(|i| draw.threads[i].div_ceil(wg[i].max(1)));
        let key = crate::cache::key(&[&shader_key, &entry.name]);
        let pipeline = ctx.pipelines.compute(key, || {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&pass.name),
                layout: Some(&layout),
                module: shader(),
                entry_point: Some(entry.name.as_str()),
                compilation_options: Default::default(),
                cache: None,
            })
        });
        ShaderPassKind::Compute {
            pipeline,
            workgroups,
        }
    } else {
        let what = match draw.shape {
            PassShape::Fullscreen => DrawWhat::Fullscreen,
            _ => match pass.draw.as_deref() {
                Some("hair") => DrawWhat::Hair,
                Some("opaque") => DrawWhat::Opaque,
                other => {
                    return Err(pass_error(
                        pass,
                        format!("cannot draw {other:?}: use \"hair\" or \"opaque\""),
                    ));
                }
            },
        };
        let color_states: Vec<Option<wgpu::ColorTargetState>> = plan
            .colors
            .iter()
            .enumerate()
            .map(|(i, c)| {
                Some(wgpu::ColorTargetState {
                    format: texture_format(c.format),
                    blend: state.blend.get(i).copied().flatten(),
                    write_mask: state
                        .write_mask
                        .get(i)
                        .copied()
                        .unwrap_or(wgpu::ColorWrites::ALL),
                })
            })
            .collect();
        let samples = plan
            .depth
            .as_ref()
            .map(|d| d.samples)
            .or_else(|| plan.colors.last().map(|c| c.samples))
            .unwrap_or(1);
        let mut depth = None;
        let depth_stencil = plan.depth.as_ref().map(|d| {
            let (write, compare) = match (state.depth, d.written) {
                (DepthMode::TestWrite(c), true) => (true, c),
                (DepthMode::TestWrite(c), false) | (DepthMode::TestOnly(c), _) => (false, c),
            };
            depth = Some((d.resource, d.loads || !d.written, write));
            wgpu::DepthStencilState {
                format: texture_format(d.format),
                depth_write_enabled: Some(write),
                depth_compare: Some(compare),
                stencil: Default::default(),
                bias: Default::default(),
            }
        });
        let vertex_layouts = match what {
            DrawWhat::Hair => vec![Some(hair_vertex_layout())],
            DrawWhat::Opaque => vec![Some(opaque_vertex_layout())],
            DrawWhat::Fullscreen => vec![],
        };
        let has_fragment = module
            .entry_points
            .iter()
            .any(|e| e.stage == naga::ShaderStage::Fragment);
        let primitive = wgpu::PrimitiveState {
            topology: if what == DrawWhat::Hair {
                wgpu::PrimitiveTopology::LineList
            } else {
                wgpu::PrimitiveTopology::TriangleList
            },
            cull_mode: state.cull_mode,
            front_face: wgpu::FrontFace::Ccw,
            ..Default::default()
        };
        let multisample = wgpu::MultisampleState {
            count: samples,
            mask: !0,
            alpha_to_coverage_enabled: state.alpha_to_coverage,
        };
        let key = crate::cache::key(&[
            &shader_key,
            &primitive,
            &depth_stencil,
            &multisample,
            &color_states,
            &vertex_layouts,
            &has_fragment,
        ]);
        let pipeline = ctx.pipelines.render(key, || {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&pass.name),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: shader(),
                    entry_point: None,
                    compilation_options: Default::default(),
                    buffers: &vertex_layouts,
                },
                primitive,
                depth_stencil: depth_stencil.clone(),
                multisample,
                fragment: has_fragment.then(|| wgpu::FragmentState {
                    module: shader(),
                    entry_point: None,
                    compilation_options: Default::default(),
                    targets: &color_states,
                }),
                multiview_mask: None,
                cache: None,
            })
        });
        ShaderPassKind::Raster {
            pipeline,
            colors: plan
                .colors
                .iter()
                .map(|c| (c.resource, c.loads || state.load_colors))
                .collect(),
            resolves: plan.colors.iter().map(|c| c.resolve).collect(),
            depth,
            state: state.clone(),
            draw: what,
        }
    };
    Ok(ShaderPass {
        name: pass.name.clone(),
        kind,
        bind_group,
        clears: plan.clears,
    })
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
            BindingSource::Slot { resource, .. } => resources.push((b.binding, *resource)),
            BindingSource::Scene(name) if name == "environment_source" => {
                let view = ctx.geometry.environment.as_ref().ok_or_else(|| {
                    pass_error(pass, "the scene's environment image was not uploaded")
                })?;
                scene.push((b.binding, wgpu::BindingResource::TextureView(view)));
            }
            BindingSource::Scene(name) => {
                let (geometry, what) = match name.strip_prefix("opaque_") {
                    Some(_) => (ctx.geometry.opaque.as_ref(), "opaque geometry"),
                    None => (ctx.geometry.hair.as_ref(), "hair"),
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
        let mut entries: Vec<wgpu::BindGroupEntry> = Vec::new();
        for (binding, buf) in &owned {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: buf.as_entire_binding(),
            });
        }
        for (binding, id) in &resources {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: ctx.pool.binding_resource(*id),
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
