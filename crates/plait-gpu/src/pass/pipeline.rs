//! The (cached) wgpu pipeline of one shader draw or dispatch, made from its
//! [`BindingPlan`] and fixed-function state once the module is composed,
//! guarded and laid out ([`super::build`]).

use std::borrow::Cow;
use std::cell::OnceCell;
use std::sync::Arc;

use plait_graph::{Draw, PassShape, ScheduledPass};

use super::build::{ShaderDraw, pass_error};
use super::pass_type::BuildContext;
use super::plan::BindingPlan;
use super::record::{ColorAttachment, DepthAttachment, DrawWhat, ShaderPassKind};
use super::state::{DepthMode, RasterState};
use crate::GpuError;
use crate::geometry::{
    hair_vertex_layout, hair_vertex_layouts, opaque_vertex_layout, reads_next_vertex,
};
use crate::pool::texture_format;

/// What every pipeline of a draw shares: the laid-out module, its layout,
/// and the cache key of the shader.
pub(super) struct PipelineParts<'a> {
    pub draw: &'a ShaderDraw,
    pub pass: &'a ScheduledPass,
    pub ctx: &'a BuildContext<'a>,
    pub module: Arc<naga::Module>,
    pub layout: wgpu::PipelineLayout,
    /// Names the shader, its defines, the library, the layout and the
    /// depth guard: the pipeline cache's key starts with it.
    pub shader_key: u64,
    /// Compiled only when the cache has no pipeline for this shader and state.
    pub shader: OnceCell<wgpu::ShaderModule>,
}

impl PipelineParts<'_> {
    fn shader(&self) -> &wgpu::ShaderModule {
        self.shader.get_or_init(|| {
            self.ctx
                .device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(&self.pass.name),
                    source: wgpu::ShaderSource::Naga(Cow::Owned((*self.module).clone())),
                })
        })
    }

    /// A compute dispatch covering the draw's threads.
    pub fn compute(&self) -> Result<ShaderPassKind, GpuError> {
        let entry = self
            .module
            .entry_points
            .iter()
            .find(|e| e.stage == naga::ShaderStage::Compute)
            .ok_or_else(|| pass_error(self.pass, "the shader has no @compute entry point"))?;
        let wg = entry.workgroup_size;
        let workgroups = [0, 1, 2].map(|i| self.draw.threads[i].div_ceil(wg[i].max(1)));
        let key = crate::cache::key(&[&self.shader_key, &entry.name]);
        let pipeline = self.ctx.pipelines.compute(key, || {
            self.ctx
                .device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(&self.pass.name),
                    layout: Some(&self.layout),
                    module: self.shader(),
                    entry_point: Some(entry.name.as_str()),
                    compilation_options: Default::default(),
                    cache: None,
                })
        });
        Ok(ShaderPassKind::Compute {
            pipeline,
            workgroups,
        })
    }

    /// A raster or fullscreen draw into the plan's attachments. A hair draw
    /// whose vertex stage is `plait::hair_fragment`'s (it reads the next hair
    /// vertex, [`reads_next_vertex`](crate::geometry::reads_next_vertex)) gets a second pipeline: the quad draw
    /// of strands wider than a pixel (`plait::strand_coverage`).
    pub fn raster(&self, plan: &BindingPlan) -> Result<ShaderPassKind, GpuError> {
        let state = &self.draw.state;
        let what = self.draw_what()?;
        let next = what == DrawWhat::Hair && reads_next_vertex(&self.module);
        let vertex_layouts = match what {
            DrawWhat::Hair if next => hair_vertex_layouts(wgpu::VertexStepMode::Vertex)
                .into_iter()
                .map(Some)
                .collect(),
            DrawWhat::Hair => vec![Some(hair_vertex_layout())],
            DrawWhat::Opaque => vec![Some(opaque_vertex_layout())],
            DrawWhat::Fullscreen => vec![],
        };
        let topology = if what == DrawWhat::Hair {
            self.ctx.geometry.hair_draw().1
        } else {
            wgpu::PrimitiveTopology::TriangleList
        };
        let pipeline = self.render_pipeline(plan, topology, state.cull_mode, &vertex_layouts);
        // Only over hair lines: wisps are triangles of their own width.
        let quads = (next && topology == wgpu::PrimitiveTopology::LineList).then(|| {
            let layouts: Vec<_> = hair_vertex_layouts(wgpu::VertexStepMode::Instance)
                .into_iter()
                .map(Some)
                .collect();
            // The corners' winding follows the strand's direction on screen.
            self.render_pipeline(plan, wgpu::PrimitiveTopology::TriangleList, None, &layouts)
        });
        Ok(ShaderPassKind::Raster {
            pipeline,
            quads,
            light_view: self.pass.view == Some(plait_graph::View::Light),
            next,
            colors: color_attachments(plan, state),
            depth: depth_attachment(plan, state),
            state: state.clone(),
            draw: what,
        })
    }

    /// The (cached) render pipeline of the draw for this topology, culling
    /// and vertex buffers.
    fn render_pipeline(
        &self,
        plan: &BindingPlan,
        topology: wgpu::PrimitiveTopology,
        cull_mode: Option<wgpu::Face>,
        vertex_layouts: &[Option<wgpu::VertexBufferLayout<'static>>],
    ) -> wgpu::RenderPipeline {
        let state = &self.draw.state;
        let color_states = color_states(plan, state);
        let depth_stencil = depth_stencil(plan, state);
        let has_fragment = self
            .module
            .entry_points
            .iter()
            .any(|e| e.stage == naga::ShaderStage::Fragment);
        let primitive = wgpu::PrimitiveState {
            topology,
            cull_mode,
            front_face: wgpu::FrontFace::Ccw,
            ..Default::default()
        };
        let multisample = wgpu::MultisampleState {
            count: samples(plan),
            mask: !0,
            alpha_to_coverage_enabled: state.alpha_to_coverage,
        };
        let key = crate::cache::key(&[
            &self.shader_key,
            &primitive,
            &depth_stencil,
            &multisample,
            &color_states,
            &vertex_layouts,
            &has_fragment,
        ]);
        self.ctx.pipelines.render(key, || {
            self.ctx
                .device
                .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some(&self.pass.name),
                    layout: Some(&self.layout),
                    vertex: wgpu::VertexState {
                        module: self.shader(),
                        entry_point: None,
                        compilation_options: Default::default(),
                        buffers: vertex_layouts,
                    },
                    primitive,
                    depth_stencil: depth_stencil.clone(),
                    multisample,
                    fragment: has_fragment.then(|| wgpu::FragmentState {
                        module: self.shader(),
                        entry_point: None,
                        compilation_options: Default::default(),
                        targets: &color_states,
                    }),
                    multiview_mask: None,
                    cache: None,
                })
        })
    }

    /// What a raster draw draws: the pass's `draw` geometry, or a triangle
    /// covering the screen.
    fn draw_what(&self) -> Result<DrawWhat, GpuError> {
        Ok(match self.draw.shape {
            PassShape::Fullscreen => DrawWhat::Fullscreen,
            _ => match self.pass.draw {
                Some(Draw::Hair) => DrawWhat::Hair,
                Some(Draw::Opaque) => DrawWhat::Opaque,
                // Compile requires `draw` of a raster pass; a Rust pass type
                // that records a raster draw of its own may forget it.
                None => {
                    return Err(pass_error(
                        self.pass,
                        "a raster draw needs `draw = \"hair\"` or `\"opaque\"`",
                    ));
                }
            },
        })
    }
}

/// The pipeline's colour target states, in target order.
fn color_states(plan: &BindingPlan, state: &RasterState) -> Vec<Option<wgpu::ColorTargetState>> {
    plan.colors
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
        .collect()
}

/// The sample count of the attachments (depth's, else the last colour's).
fn samples(plan: &BindingPlan) -> u32 {
    plan.depth
        .as_ref()
        .map(|d| d.samples)
        .or_else(|| plan.colors.last().map(|c| c.samples))
        .unwrap_or(1)
}

/// Whether the pipeline writes depth, and how it compares: a depth target
/// bound under `reads` is only tested, whatever the state asks.
fn depth_write_compare(state: &RasterState, written: bool) -> (bool, wgpu::CompareFunction) {
    match (state.depth, written) {
        (DepthMode::TestWrite(c), true) => (true, c),
        (DepthMode::TestWrite(c), false) | (DepthMode::TestOnly(c), _) => (false, c),
    }
}

fn depth_stencil(plan: &BindingPlan, state: &RasterState) -> Option<wgpu::DepthStencilState> {
    let d = plan.depth.as_ref()?;
    let (write, compare) = depth_write_compare(state, d.written);
    Some(wgpu::DepthStencilState {
        format: texture_format(d.format),
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    })
}

fn color_attachments(plan: &BindingPlan, state: &RasterState) -> Vec<ColorAttachment> {
    plan.colors
        .iter()
        .map(|c| ColorAttachment {
            resource: c.resource,
            loads: c.loads || state.load_colors,
            clear: c.clear.map(|[r, g, b, a]| wgpu::Color { r, g, b, a }),
            resolve: c.resolve,
        })
        .collect()
}

/// A depth target only tested keeps its contents (it is attached read-only).
fn depth_attachment(plan: &BindingPlan, state: &RasterState) -> Option<DepthAttachment> {
    let d = plan.depth.as_ref()?;
    Some(DepthAttachment {
        resource: d.resource,
        loads: d.loads || !d.written,
        clear: d.clear.map(|c| c[0] as f32),
        writes: depth_write_compare(state, d.written).0,
    })
}
