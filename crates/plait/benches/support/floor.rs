//! The raster floor of a compiled schedule: the same passes, targets, clears
//! and draw calls over the same geometry, with every shader replaced by a
//! trivial one (position × view-projection; a constant colour per colour
//! target, or no fragment stage at all where the pass has none). Whatever a
//! pipeline spends above its floor is its shaders' work.
//!
//! Derived from the schedule only, so every gallery pipeline has one: the
//! draws per pass come from the pass type (`depth_range` draws twice,
//! `density_clustering` once per k-means stage, everything else once), the
//! state from [`raster_state_of`], the memory from plait's own pool. Compute
//! passes dispatch an empty kernel over the same threads (`strand_shading`:
//! strands × shading points, from the geometry, as its pass type counts them).

use plait::gpu::Gpu;
use plait::gpu::geometry::SceneGeometry;
use plait::gpu::pass::{DepthMode, PassLibrary, raster_state_of};
use plait::gpu::pool::{GpuResource, ResourcePool, texture_format};
use plait::graph::{Access, PassShape, ResourceDesc, ResourceId, Schedule, ScheduledPass, Value};
use wgpu::util::DeviceExt;

use super::timing::Timestamps;

/// Passes whose GPU work depends on what they find at run time (depth
/// peeling's layer count), so no fixed floor exists for them.
pub const NO_FLOOR: &[&str] = &["hair_depth_peel"];

enum Geometry {
    Hair,
    Opaque,
    Fullscreen,
}

enum FloorPass {
    Raster {
        name: String,
        /// One pipeline per draw the real pass makes.
        draws: Vec<wgpu::RenderPipeline>,
        colors: Vec<(ResourceId, bool)>,
        resolves: Vec<Option<ResourceId>>,
        /// (resource, loads, written)
        depth: Option<(ResourceId, bool, bool)>,
        clear_depth: f32,
        light_view: bool,
        geometry: Geometry,
        clears: Vec<ResourceId>,
    },
    Compute {
        name: String,
        pipeline: wgpu::ComputePipeline,
        workgroups: [u32; 3],
        clears: Vec<ResourceId>,
    },
}

/// The floor of one schedule, ready to render.
pub struct Floor<'g> {
    gpu: &'g Gpu,
    pool: ResourcePool,
    geometry: SceneGeometry,
    camera: wgpu::BindGroup,
    light: wgpu::BindGroup,
    passes: Vec<FloorPass>,
    timestamps: Option<Timestamps>,
}

const VERTEX_SHADER: &str = r#"
struct View { view_proj: mat4x4<f32> }
@group(0) @binding(0) var<uniform> view: View;

@vertex
fn vs_geometry(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return view.view_proj * vec4<f32>(position, 1.0);
}

@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@compute @workgroup_size(8, 8, 1)
fn cs_empty() {}

@compute @workgroup_size(64, 1, 1)
fn cs_empty_1d() {}
"#;

/// A fragment stage writing a constant of each target's kind.
fn fragment_shader(targets: &[wgpu::TextureFormat]) -> String {
    let mut fields = String::new();
    let mut body = String::new();
    for (i, format) in targets.iter().enumerate() {
        let (ty, value) = match format.sample_type(None, None) {
            Some(wgpu::TextureSampleType::Uint) => ("vec4<u32>", "vec4<u32>(1u)"),
            Some(wgpu::TextureSampleType::Sint) => ("vec4<i32>", "vec4<i32>(1)"),
            _ => ("vec4<f32>", "vec4<f32>(0.25)"),
        };
        fields.push_str(&format!("@location({i}) c{i}: {ty},\n"));
        body.push_str(&format!("out.c{i} = {value};\n"));
    }
    format!(
        "struct Out {{\n{fields}}}\n@fragment\nfn fs_constant() -> Out {{\nvar out: Out;\n{body}return out;\n}}\n"
    )
}

/// Threads a compute pass runs. Most follow from the schedule (the pass
/// type's `compute_threads`); `strand_shading` runs one per shading point
/// of every strand, which only the geometry knows (as its pass type does).
fn threads_of(
    pass: &ScheduledPass,
    schedule: &Schedule,
    t: &dyn plait::gpu::pass::PassType,
    geometry: &SceneGeometry,
) -> [u32; 3] {
    match pass.type_name.as_str() {
        "strand_shading" => {
            let points = pass
                .params
                .get("shading_points")
                .and_then(Value::as_i64)
                .unwrap_or(1)
                .max(1) as u32;
            [geometry.strand_count.saturating_mul(points), 1, 1]
        }
        _ => t.compute_threads(pass, schedule),
    }
}

fn draws_of(pass: &ScheduledPass) -> usize {
    match pass.type_name.as_str() {
        "depth_range" => 2,
        "density_clustering" => match pass.params.get("iterations") {
            Some(Value::Int(i)) => *i as usize + 1,
            _ => 2,
        },
        _ => 1,
    }
}

impl<'g> Floor<'g> {
    /// The floor of `schedule` (already checked and built by plait for the
    /// same device, so its state is known to be valid).
    pub fn new(
        gpu: &'g Gpu,
        schedule: &Schedule,
        library: &PassLibrary,
        geometry: SceneGeometry,
        frame: &plait::gpu::frame::FrameUniforms,
    ) -> Result<Self, String> {
        if let Some(p) = schedule
            .passes
            .iter()
            .find(|p| NO_FLOOR.contains(&p.type_name.as_str()))
        {
            return Err(format!(
                "pass `{}` ({}) does a data-dependent amount of work: no fixed floor",
                p.name, p.type_name
            ));
        }
        let device = &gpu.device;
        let pool = ResourcePool::new(device, schedule, &geometry);
        let view_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("floor view"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let bind_view = |matrix: &[[f32; 4]; 4]| {
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("floor view"),
                contents: bytemuck::bytes_of(matrix),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("floor view"),
                layout: &view_layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: buffer.as_entire_binding(),
                }],
            })
        };
        let camera = bind_view(&frame.camera_view_proj);
        let light = bind_view(&frame.light_view_proj);
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("floor"),
            bind_group_layouts: &[Some(&view_layout)],
            immediate_size: 0,
        });
        let vertex_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("floor vertex"),
            source: wgpu::ShaderSource::Wgsl(VERTEX_SHADER.into()),
        });
        let mut passes = Vec::new();
        for pass in &schedule.passes {
            let t = library
                .get(&pass.type_name)
                .ok_or_else(|| format!("no pass type `{}`", pass.type_name))?;
            let clears: Vec<ResourceId> = pass
                .writes
                .iter()
                .filter(|b| b.access == Access::StorageWrite && !b.loads)
                .map(plait_graph::Binding::id)
                .collect();
            if pass.shape == PassShape::Compute {
                let threads = threads_of(pass, schedule, t, &geometry);
                // A row of threads runs in rows of 64 (8 × 8 tiles would
                // run eight times the threads), a grid in 8 × 8 tiles.
                let row = threads[1] <= 1 && threads[2] <= 1;
                let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(&pass.name),
                    layout: Some(&layout),
                    module: &vertex_module,
                    entry_point: Some(if row { "cs_empty_1d" } else { "cs_empty" }),
                    compilation_options: Default::default(),
                    cache: None,
                });
                let workgroups = if row {
                    [threads[0].div_ceil(64), 1, 1]
                } else {
                    [
                        threads[0].div_ceil(8),
                        threads[1].div_ceil(8),
                        threads[2].max(1),
                    ]
                };
                passes.push(FloorPass::Compute {
                    name: pass.name.clone(),
                    pipeline,
                    workgroups,
                    clears,
                });
                continue;
            }
            let state = raster_state_of(t, pass, &schedule.resources, &gpu.capabilities)?;
            let is_resolve = |slot: &str| {
                slot.strip_suffix("_resolve")
                    .is_some_and(|base| pass.writes.iter().any(|b| b.slot == base))
            };
            let colors: Vec<(ResourceId, bool)> = pass
                .writes
                .iter()
                .filter(|b| b.access == Access::ColorTarget && !is_resolve(&b.slot))
                .map(|b| (b.id(), b.loads || state.load_colors))
                .collect();
            let resolves: Vec<Option<ResourceId>> = pass
                .writes
                .iter()
                .filter(|b| b.access == Access::ColorTarget && !is_resolve(&b.slot))
                .map(|b| {
                    let name = format!("{}_resolve", b.slot);
                    pass.writes
                        .iter()
                        .find(|r| r.slot == name)
                        .map(plait_graph::Binding::id)
                })
                .collect();
            let depth = pass
                .writes
                .iter()
                .map(|b| (b, true))
                .chain(pass.reads.iter().map(|b| (b, false)))
                .find(|(b, _)| b.access == Access::DepthTarget)
                .map(|(b, written)| {
                    let write = written && matches!(state.depth, DepthMode::TestWrite(_));
                    (b.id(), !written || b.loads, write)
                });
            let desc_of = |id: ResourceId| match schedule.resources[id].desc {
                ResourceDesc::Texture {
                    format, samples, ..
                } => Ok((texture_format(format), samples)),
                ResourceDesc::Buffer { .. } | ResourceDesc::AccelerationStructure => Err(format!(
                    "pass `{}`: target `{}` is no texture",
                    pass.name, schedule.resources[id].name
                )),
            };
            let mut formats = Vec::new();
            let mut samples = 1;
            for &(id, _) in &colors {
                let (f, s) = desc_of(id)?;
                formats.push(f);
                samples = s;
            }
            let depth_format = match depth {
                Some((id, ..)) => {
                    let (f, s) = desc_of(id)?;
                    samples = s;
                    Some(f)
                }
                None => None,
            };
            let fragment_module = (!formats.is_empty()).then(|| {
                device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("floor fragment"),
                    source: wgpu::ShaderSource::Wgsl(fragment_shader(&formats).into()),
                })
            });
            let targets: Vec<Option<wgpu::ColorTargetState>> = formats
                .iter()
                .enumerate()
                .map(|(i, &format)| {
                    Some(wgpu::ColorTargetState {
                        format,
                        blend: state.blend.get(i).copied().flatten(),
                        write_mask: state
                            .write_mask
                            .get(i)
                            .copied()
                            .unwrap_or(wgpu::ColorWrites::ALL),
                    })
                })
                .collect();
            let geometry = match (pass.shape, pass.draw) {
                (PassShape::Fullscreen, _) => Geometry::Fullscreen,
                (_, Some(plait_graph::Draw::Opaque)) => Geometry::Opaque,
                _ => Geometry::Hair,
            };
            let stride = match geometry {
                Geometry::Hair => std::mem::size_of::<plait::hair::StrandVertex>(),
                _ => std::mem::size_of::<plait::gpu::geometry::OpaqueVertex>(),
            } as u64;
            let position = [wgpu::VertexAttribute {
                format: wgpu::VertexFormat::Float32x3,
                offset: 0,
                shader_location: 0,
            }];
            let buffers = [Some(wgpu::VertexBufferLayout {
                array_stride: stride,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &position,
            })];
            let fullscreen = matches!(geometry, Geometry::Fullscreen);
            let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&pass.name),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &vertex_module,
                    entry_point: Some(if fullscreen {
                        "vs_fullscreen"
                    } else {
                        "vs_geometry"
                    }),
                    compilation_options: Default::default(),
                    buffers: if fullscreen { &[] } else { &buffers },
                },
                primitive: wgpu::PrimitiveState {
                    topology: if matches!(geometry, Geometry::Hair) {
                        wgpu::PrimitiveTopology::LineList
                    } else {
                        wgpu::PrimitiveTopology::TriangleList
                    },
                    cull_mode: state.cull_mode,
                    ..Default::default()
                },
                depth_stencil: depth_format.map(|format| wgpu::DepthStencilState {
                    format,
                    depth_write_enabled: Some(depth.is_some_and(|d| d.2)),
                    depth_compare: Some(state.depth.compare()),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: samples,
                    mask: !0,
                    alpha_to_coverage_enabled: state.alpha_to_coverage,
                },
                fragment: fragment_module.as_ref().map(|module| wgpu::FragmentState {
                    module,
                    entry_point: Some("fs_constant"),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            });
            passes.push(FloorPass::Raster {
                name: pass.name.clone(),
                draws: vec![pipeline; draws_of(pass)],
                colors,
                resolves,
                depth,
                clear_depth: state.clear_depth,
                light_view: pass.view == Some(plait_graph::View::Light),
                geometry,
                clears,
            });
        }
        let timestamps = Timestamps::new(gpu, passes.len());
        Ok(Floor {
            gpu,
            pool,
            geometry,
            camera,
            light,
            passes,
            timestamps,
        })
    }

    /// Render one frame and wait: (frame GPU ms, per-pass GPU ms) when the
    /// adapter has timestamps.
    pub fn render(&self) -> Option<(f64, Vec<f64>)> {
        let device = &self.gpu.device;
        let mut encoder = device.create_command_encoder(&Default::default());
        if let Some(ts) = &self.timestamps {
            ts.write(&mut encoder, 0);
        }
        for (i, pass) in self.passes.iter().enumerate() {
            self.record(pass, &mut encoder);
            if let Some(ts) = &self.timestamps {
                ts.write(&mut encoder, i + 1);
            }
        }
        if let Some(ts) = &self.timestamps {
            ts.resolve(&mut encoder);
        }
        self.gpu.queue.submit([encoder.finish()]);
        self.timestamps.as_ref().map(|ts| ts.read(self.gpu))
    }

    fn clear(&self, ids: &[ResourceId], encoder: &mut wgpu::CommandEncoder) {
        for &id in ids {
            match self.pool.get(id) {
                GpuResource::Buffer(b) => encoder.clear_buffer(b, 0, None),
                GpuResource::Texture { texture, .. } => {
                    encoder.clear_texture(texture, &wgpu::ImageSubresourceRange::default())
                }
                GpuResource::Strands(_) => {}
            }
        }
    }

    fn record(&self, pass: &FloorPass, encoder: &mut wgpu::CommandEncoder) {
        match pass {
            FloorPass::Compute {
                name,
                pipeline,
                workgroups,
                clears,
            } => {
                self.clear(clears, encoder);
                let mut cpass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(name),
                    timestamp_writes: None,
                });
                cpass.set_pipeline(pipeline);
                cpass.set_bind_group(0, &self.camera, &[]);
                cpass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
            }
            FloorPass::Raster {
                name,
                draws,
                colors,
                resolves,
                depth,
                clear_depth,
                light_view,
                geometry,
                clears,
            } => {
                self.clear(clears, encoder);
                for (d, pipeline) in draws.iter().enumerate() {
                    let view = |id: ResourceId| {
                        self.pool
                            .texture(id)
                            .map(|(_, v)| v)
                            .expect("targets are textures (checked in new)")
                    };
                    let color_attachments: Vec<_> = colors
                        .iter()
                        .zip(resolves)
                        .map(|(&(id, loads), resolve)| {
                            Some(wgpu::RenderPassColorAttachment {
                                view: view(id),
                                depth_slice: None,
                                resolve_target: resolve.map(view),
                                ops: wgpu::Operations {
                                    // Later draws of a multi-draw pass add to the first.
                                    load: if loads || d > 0 {
                                        wgpu::LoadOp::Load
                                    } else {
                                        wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)
                                    },
                                    store: wgpu::StoreOp::Store,
                                },
                            })
                        })
                        .collect();
                    let depth_attachment =
                        depth.map(
                            |(id, loads, write)| wgpu::RenderPassDepthStencilAttachment {
                                view: view(id),
                                depth_ops: (write || !loads).then_some(wgpu::Operations {
                                    load: if loads {
                                        wgpu::LoadOp::Load
                                    } else {
                                        wgpu::LoadOp::Clear(*clear_depth)
                                    },
                                    store: wgpu::StoreOp::Store,
                                }),
                                stencil_ops: None,
                            },
                        );
                    let mut rpass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some(name),
                        color_attachments: &color_attachments,
                        depth_stencil_attachment: depth_attachment,
                        timestamp_writes: None,
                        occlusion_query_set: None,
                        multiview_mask: None,
                    });
                    rpass.set_pipeline(pipeline);
                    rpass.set_bind_group(
                        0,
                        if *light_view {
                            &self.light
                        } else {
                            &self.camera
                        },
                        &[],
                    );
                    let buffers = match geometry {
                        Geometry::Hair => self.geometry.hair.as_ref(),
                        Geometry::Opaque => self.geometry.opaque.as_ref(),
                        Geometry::Fullscreen => {
                            rpass.draw(0..3, 0..1);
                            None
                        }
                    };
                    if let Some(b) = buffers {
                        rpass.set_vertex_buffer(0, b.vertices.slice(..));
                        rpass.set_index_buffer(b.indices.slice(..), wgpu::IndexFormat::Uint32);
                        rpass.draw_indexed(0..b.index_count, 0, 0..1);
                    }
                }
            }
        }
    }
}
