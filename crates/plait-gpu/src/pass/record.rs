//! Recording a built pass: clears, attachments, the draw or dispatch.

use super::pass_type::{PreparedPass, RecordContext};
use super::state::RasterState;
use crate::geometry::WIDE_FIRST_VERTEX;

/// A pass built from one shader with bindings by name.
pub struct ShaderPass {
    pub name: String,
    pub kind: ShaderPassKind,
    pub bind_group: Option<wgpu::BindGroup>,
    /// Storage outputs that start the pass zeroed (written, not loaded).
    pub clears: Vec<plait_graph::ResourceId>,
}

pub enum ShaderPassKind {
    Raster {
        pipeline: wgpu::RenderPipeline,
        /// The quad draw of hair segments wider than a pixel, for a hair
        /// draw through `plait::hair_fragment` (`None` otherwise).
        quads: Option<wgpu::RenderPipeline>,
        /// A light-view pass: its quad draw is decided by the strands' widths
        /// in light texels (`RecordContext::wide_light_strands`), not the
        /// camera's pixels — a strand far narrower than a pixel can be wider
        /// than a texel (issue 47).
        light_view: bool,
        /// The pipeline reads the next hair vertex from vertex buffer 1.
        next: bool,
        colors: Vec<ColorAttachment>,
        depth: Option<DepthAttachment>,
        state: RasterState,
        draw: DrawWhat,
    },
    Compute {
        pipeline: wgpu::ComputePipeline,
        workgroups: [u32; 3],
    },
}

/// A colour target as the render pass attaches it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColorAttachment {
    pub resource: plait_graph::ResourceId,
    /// Keep the contents, else clear to `clear` (the resource's), or
    /// the state's clear colour.
    pub loads: bool,
    pub clear: Option<wgpu::Color>,
    /// The single-sampled texture the samples resolve into.
    pub resolve: Option<plait_graph::ResourceId>,
}

/// The depth target as the render pass attaches it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthAttachment {
    pub resource: plait_graph::ResourceId,
    /// Keep the contents, else clear to `clear` (the resource's), or
    /// the state's clear depth.
    pub loads: bool,
    pub clear: Option<f32>,
    /// The pipeline writes depth.
    pub writes: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DrawWhat {
    Hair,
    Opaque,
    Fullscreen,
}

impl PreparedPass for ShaderPass {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        self.record_with_query(ctx, encoder, None);
    }
}

impl ShaderPass {
    /// Record the pass; a raster pass counts the samples that pass the depth
    /// test in occlusion query `index` of `queries` (depth peeling's stop test).
    pub fn record_with_query(
        &self,
        ctx: &RecordContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
        query: Option<(&wgpu::QuerySet, u32)>,
    ) {
        for &id in &self.clears {
            match ctx.pool.get(id) {
                crate::pool::GpuResource::Buffer(b) => encoder.clear_buffer(b, 0, None),
                crate::pool::GpuResource::Texture { texture, .. } => {
                    encoder.clear_texture(texture, &wgpu::ImageSubresourceRange::default())
                }
                // Built whole every frame by its pass: nothing to clear.
                crate::pool::GpuResource::Strands(_) => {}
            }
        }
        match &self.kind {
            ShaderPassKind::Compute {
                pipeline,
                workgroups,
            } => {
                let mut cpass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(&self.name),
                    timestamp_writes: ctx.compute_timestamps(),
                });
                cpass.set_pipeline(pipeline);
                cpass.set_bind_group(0, ctx.frame_bind_group, &[]);
                if let Some(bg) = &self.bind_group {
                    cpass.set_bind_group(1, bg, &[]);
                }
                cpass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
            }
            ShaderPassKind::Raster {
                pipeline,
                quads,
                light_view,
                next,
                colors,
                depth,
                state,
                draw,
            } => {
                let color_attachments: Vec<_> = colors
                    .iter()
                    .map(
                        |&ColorAttachment {
                             resource,
                             loads,
                             clear,
                             resolve,
                         }| {
                            let view = ctx
                                .pool
                                .texture(resource)
                                .map(|(_, v)| v)
                                .expect("colour targets are textures (checked at build)");
                            Some(wgpu::RenderPassColorAttachment {
                                view,
                                depth_slice: None,
                                resolve_target: resolve
                                    .and_then(|r| ctx.pool.texture(r))
                                    .map(|(_, v)| v),
                                ops: wgpu::Operations {
                                    load: if loads {
                                        wgpu::LoadOp::Load
                                    } else {
                                        wgpu::LoadOp::Clear(clear.unwrap_or(state.clear_color))
                                    },
                                    store: wgpu::StoreOp::Store,
                                },
                            })
                        },
                    )
                    .collect();
                let depth_attachment = depth.map(
                    |DepthAttachment {
                         resource,
                         loads,
                         clear,
                         writes,
                     }| {
                        let view = ctx
                            .pool
                            .texture(resource)
                            .map(|(_, v)| v)
                            .expect("depth targets are textures (checked at build)");
                        wgpu::RenderPassDepthStencilAttachment {
                            view,
                            // Only tested, never written: attached read-only, so the
                            // pass may also sample it (fragment lists test it by hand).
                            depth_ops: (writes || !loads).then_some(wgpu::Operations {
                                load: if loads {
                                    wgpu::LoadOp::Load
                                } else {
                                    wgpu::LoadOp::Clear(clear.unwrap_or(state.clear_depth))
                                },
                                store: wgpu::StoreOp::Store,
                            }),
                            stencil_ops: None,
                        }
                    },
                );
                let mut rpass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(&self.name),
                    color_attachments: &color_attachments,
                    depth_stencil_attachment: depth_attachment,
                    timestamp_writes: ctx.render_timestamps(),
                    occlusion_query_set: query.map(|(q, _)| q),
                    multiview_mask: None,
                });
                if let Some((_, index)) = query {
                    rpass.begin_occlusion_query(index);
                }
                rpass.set_pipeline(pipeline);
                rpass.set_bind_group(0, ctx.frame_bind_group, &[]);
                if let Some(bg) = &self.bind_group {
                    rpass.set_bind_group(1, bg, &[]);
                }
                let buffers = match draw {
                    DrawWhat::Hair => ctx.geometry.hair_draw().0,
                    DrawWhat::Opaque => ctx.geometry.opaque.as_ref(),
                    DrawWhat::Fullscreen => {
                        rpass.draw(0..3, 0..1);
                        None
                    }
                };
                if let Some(b) = buffers {
                    rpass.set_vertex_buffer(0, b.vertices.slice(..));
                    if *next {
                        // The next vertex (ignored by wisps, whose vertices are not
                        // the hair's): the buffer one vertex on, or itself when
                        // it holds one vertex (no segment).
                        rpass.set_vertex_buffer(1, next_vertices(&b.vertices));
                    }
                    rpass.set_index_buffer(b.indices.slice(..), wgpu::IndexFormat::Uint32);
                    rpass.draw_indexed(0..b.index_count, 0, 0..1);
                }
                let wide = if *light_view {
                    ctx.wide_light_strands
                } else {
                    ctx.wide_strands
                };
                let quad_draw = quads.as_ref().filter(|_| wide);
                if let (Some(quads), Some((vertices, count))) =
                    (quad_draw, ctx.geometry.hair_quads())
                {
                    // One instance per hair vertex but the last: the segment it
                    // starts (degenerate across strands and for narrow ones).
                    rpass.set_pipeline(quads);
                    rpass.set_vertex_buffer(0, vertices.slice(..));
                    rpass.set_vertex_buffer(1, next_vertices(vertices));
                    rpass.draw(WIDE_FIRST_VERTEX..WIDE_FIRST_VERTEX + 6, 0..count - 1);
                }
                if query.is_some() {
                    rpass.end_occlusion_query();
                }
            }
        }
    }
}

/// The hair vertex buffer one vertex on (the next vertex of each), or whole
/// when it holds no more than one vertex.
fn next_vertices(vertices: &wgpu::Buffer) -> wgpu::BufferSlice<'_> {
    let stride = std::mem::size_of::<plait_hair::StrandVertex>() as u64;
    if vertices.size() > stride {
        vertices.slice(stride..)
    } else {
        vertices.slice(..)
    }
}
