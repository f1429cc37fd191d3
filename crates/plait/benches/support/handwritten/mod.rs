//! `pipelines/occupancy.toml` written out by hand against wgpu: the same ten
//! passes, shaders and state, with none of plait's executor — no schedule,
//! no memory plan (one allocation per resource), no binding plan (every bind
//! group layout below is written out), no pass library. Shaders are composed
//! from the same WGSL files with the same defines (naga_oil through
//! `plait::gpu::modules`, so both programs compile identical code); the
//! benchmark checks that its image equals plait's.
//!
//! It answers two questions: does plait's executor add GPU work (frame times
//! side by side, `benches/floor.rs`), and does it add CPU time when encoding
//! a frame (`benches/encode.rs`)?

use std::collections::HashMap;
use std::path::Path;

use plait::gpu::Gpu;
use plait::gpu::frame::FrameUniforms;
use plait::gpu::geometry::{
    SceneGeometry, WIDE_FIRST_VERTEX, hair_vertex_layout, hair_vertex_layouts,
    opaque_vertex_layout, reads_next_vertex,
};
use plait::gpu::shader::Define;
use plait::session::{SceneData, repo_root};
use wgpu::util::DeviceExt;

use super::timing::Timestamps;

mod passes;
use passes::{Geometry, PassDesc, passes};

/// `shadow_weight` of `pipelines/occupancy.toml`'s `[params]`.
const SHADOW_WEIGHT: f32 = 0.15;
/// `light_size`, `slices` and `slabs` of the pipeline and its techniques.
const LIGHT_SIZE: u32 = 512;
const WORDS_PER_TEXEL: u64 = 128 / 32;
const SLABS: u64 = 4;

struct BuiltPass {
    desc: PassDesc,
    pipeline: wgpu::RenderPipeline,
    /// The quad draw of hair segments wider than a pixel, for shaders that
    /// read the next hair vertex (`plait_gpu::geometry::reads_next_vertex`).
    quads: Option<wgpu::RenderPipeline>,
    group: wgpu::BindGroup,
}

/// The default pipeline, built by hand for one scene and size.
pub struct HandWritten<'g> {
    gpu: &'g Gpu,
    textures: HashMap<&'static str, (wgpu::Texture, wgpu::TextureView)>,
    buffers: HashMap<&'static str, wgpu::Buffer>,
    geometry: SceneGeometry,
    frame_group: wgpu::BindGroup,
    passes: Vec<BuiltPass>,
    timestamps: Option<Timestamps>,
    /// As plait's executor: the frame has a strand wider than a pixel, and
    /// one wider than a texel of the light maps (LIGHT_SIZE across).
    wide_strands: bool,
    wide_light_strands: bool,
}

impl<'g> HandWritten<'g> {
    pub fn new(gpu: &'g Gpu, scene: &SceneData, size: (u32, u32)) -> Result<Self, String> {
        let device = &gpu.device;
        let (w, h) = size;
        let l = LIGHT_SIZE;
        let tex_usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC;
        let mut textures = HashMap::new();
        for (name, format, (tw, th)) in [
            ("opaque_shadow", wgpu::TextureFormat::Depth32Float, (l, l)),
            ("light_range", wgpu::TextureFormat::Rg32Float, (l, l)),
            ("light_scratch", wgpu::TextureFormat::Depth32Float, (l, l)),
            ("scene", wgpu::TextureFormat::Rgba16Float, (w, h)),
            ("depth", wgpu::TextureFormat::Depth32Float, (w, h)),
            ("camera_range", wgpu::TextureFormat::Rg32Float, (w, h)),
            ("camera_scratch", wgpu::TextureFormat::Depth32Float, (w, h)),
            ("camera_alpha", wgpu::TextureFormat::Rg32Float, (w, h)),
            ("hair", wgpu::TextureFormat::Rgba32Float, (w, h)),
            ("final", wgpu::TextureFormat::Rgba8UnormSrgb, (w, h)),
        ] {
            let texture = device.create_texture(&wgpu::TextureDescriptor {
                label: Some(name),
                size: wgpu::Extent3d {
                    width: tw,
                    height: th,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: tex_usage,
                view_formats: &[],
            });
            let view = texture.create_view(&Default::default());
            textures.insert(name, (texture, view));
        }
        let light_texels = (l as u64) * (l as u64);
        let pixels = (w as u64) * (h as u64);
        let mut buffers = HashMap::new();
        for (name, bytes) in [
            ("light_bits", light_texels * WORDS_PER_TEXEL * 4),
            ("light_slabs", light_texels * SLABS * 4),
            ("camera_bits", pixels * WORDS_PER_TEXEL * 4),
            ("camera_slabs", pixels * SLABS * 4),
        ] {
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(name),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            buffers.insert(name, buffer);
        }
        let mut params = [0u8; 16];
        params[..4].copy_from_slice(&SHADOW_WEIGHT.to_le_bytes());
        buffers.insert(
            "visibility_params",
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("visibility_params"),
                contents: &params,
                usage: wgpu::BufferUsages::UNIFORM,
            }),
        );
        let frame: FrameUniforms = scene.frame(size, 0);
        let (frame_layout, frame_group) = frame_group(gpu, &frame);
        let geometry = SceneGeometry::upload(device, &scene.strands, &scene.meshes);
        // The shader library as plait reads it (the search path), once.
        let shaders = plait::gpu::modules::Shaders::read(&[]);
        let mut built = Vec::new();
        for desc in passes() {
            let (pipeline, quads, group) =
                build_pass(gpu, &shaders, &desc, &frame_layout, &textures, &buffers)?;
            built.push(BuiltPass {
                desc,
                pipeline,
                quads,
                group,
            });
        }
        let timestamps = Timestamps::new(gpu, built.len());
        Ok(HandWritten {
            gpu,
            textures,
            buffers,
            geometry,
            frame_group,
            passes: built,
            timestamps,
            wide_strands: frame.draws_wide_strands(),
            wide_light_strands: frame.draws_wide_light_strands(LIGHT_SIZE),
        })
    }

    /// Record one frame with a timestamp after each draw (as plait times
    /// each pass) and finish it, unsubmitted.
    pub fn encode(&self) -> wgpu::CommandBuffer {
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
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
        encoder.finish()
    }

    /// Render one frame and wait: (frame GPU ms, per-draw GPU ms).
    pub fn render(&self) -> Option<(f64, Vec<f64>)> {
        self.gpu.queue.submit([self.encode()]);
        let times = self.timestamps.as_ref().map(|ts| ts.read(self.gpu));
        if times.is_none() {
            let _ = self.gpu.wait();
        }
        times
    }

    /// Draw names in recording order (the depth ranges twice).
    pub fn draw_names(&self) -> Vec<&'static str> {
        self.passes.iter().map(|p| p.desc.name).collect()
    }

    /// The final image, 8-bit sRGB.
    pub fn image(&self) -> Result<image::RgbaImage, String> {
        let (texture, _) = &self.textures["final"];
        plait::gpu::readback::read_texture(
            &self.gpu.device,
            &self.gpu.queue,
            texture,
            plait::graph::Format::Rgba8UnormSrgb,
            "final",
        )
        .map(|t| t.to_image())
        .map_err(|e| e.to_string())
    }

    fn record(&self, pass: &BuiltPass, encoder: &mut wgpu::CommandEncoder) {
        let d = &pass.desc;
        for name in d.clears {
            encoder.clear_buffer(&self.buffers[name], 0, None);
        }
        let colors: Vec<_> = d
            .colors
            .iter()
            .map(|(name, _, _, _, clear)| {
                Some(wgpu::RenderPassColorAttachment {
                    view: &self.textures[name].1,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: clear.map_or(wgpu::LoadOp::Load, wgpu::LoadOp::Clear),
                        store: wgpu::StoreOp::Store,
                    },
                })
            })
            .collect();
        let depth = d.depth.map(
            |(name, _, write, clear)| wgpu::RenderPassDepthStencilAttachment {
                view: &self.textures[name].1,
                // Tested only: attached read-only.
                depth_ops: write.then_some(wgpu::Operations {
                    load: clear.map_or(wgpu::LoadOp::Load, wgpu::LoadOp::Clear),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            },
        );
        let mut rpass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(d.name),
            color_attachments: &colors,
            depth_stencil_attachment: depth,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        rpass.set_pipeline(&pass.pipeline);
        rpass.set_bind_group(0, &self.frame_group, &[]);
        rpass.set_bind_group(1, &pass.group, &[]);
        let buffers = match d.geometry {
            Geometry::Hair => self.geometry.hair.as_ref(),
            Geometry::Opaque => self.geometry.opaque.as_ref(),
            Geometry::Fullscreen => {
                rpass.draw(0..3, 0..1);
                None
            }
        };
        let stride = std::mem::size_of::<plait_hair::StrandVertex>() as u64;
        if let Some(b) = buffers {
            rpass.set_vertex_buffer(0, b.vertices.slice(..));
            if pass.quads.is_some() {
                rpass.set_vertex_buffer(1, b.vertices.slice(stride..));
            }
            rpass.set_index_buffer(b.indices.slice(..), wgpu::IndexFormat::Uint32);
            rpass.draw_indexed(0..b.index_count, 0, 0..1);
        }
        // As plait's executor: each hair vertex's segment as a quad where it
        // is wider than a pixel (a light texel), when the frame has any such.
        let light_view = pass.desc.defines.contains(&"LIGHT_VIEW");
        let wide = if light_view {
            self.wide_light_strands
        } else {
            self.wide_strands
        };
        let quads = pass.quads.as_ref().filter(|_| wide);
        if let (Some(quads), Some((vertices, count))) = (quads, self.geometry.hair_quads()) {
            rpass.set_pipeline(quads);
            rpass.set_vertex_buffer(0, vertices.slice(..));
            rpass.set_vertex_buffer(1, vertices.slice(stride..));
            rpass.draw(WIDE_FIRST_VERTEX..WIDE_FIRST_VERTEX + 6, 0..count - 1);
        }
    }
}

/// Group 0: the frame's standard inputs (`shaders/lib/frame.wgsl`).
fn frame_group(gpu: &Gpu, frame: &FrameUniforms) -> (wgpu::BindGroupLayout, wgpu::BindGroup) {
    let device = &gpu.device;
    let all = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
    let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: all,
        ty,
        count: None,
    };
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("hand-written frame"),
        entries: &[
            entry(
                0,
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
            ),
            entry(
                1,
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            ),
            entry(
                2,
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::NonFiltering),
            ),
            entry(
                3,
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
            ),
            entry(
                4,
                wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
            ),
        ],
    });
    let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("hand-written frame"),
        contents: bytemuck::bytes_of(frame),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let sampler = |filter, compare| {
        device.create_sampler(&wgpu::SamplerDescriptor {
            mag_filter: filter,
            min_filter: filter,
            compare,
            ..Default::default()
        })
    };
    let linear = sampler(wgpu::FilterMode::Linear, None);
    let nearest = sampler(wgpu::FilterMode::Nearest, None);
    let shadow = sampler(
        wgpu::FilterMode::Linear,
        Some(wgpu::CompareFunction::LessEqual),
    );
    let black = device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("no background image"),
            size: wgpu::Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8UnormSrgb,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &[0, 0, 0, 255],
    );
    let black = black.create_view(&Default::default());
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("hand-written frame"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(&linear),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::Sampler(&nearest),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::Sampler(&shadow),
            },
            wgpu::BindGroupEntry {
                binding: 4,
                resource: wgpu::BindingResource::TextureView(&black),
            },
        ],
    });
    (layout, group)
}

fn build_pass(
    gpu: &Gpu,
    shaders: &plait::gpu::modules::Shaders,
    d: &PassDesc,
    frame_layout: &wgpu::BindGroupLayout,
    textures: &HashMap<&'static str, (wgpu::Texture, wgpu::TextureView)>,
    buffers: &HashMap<&'static str, wgpu::Buffer>,
) -> Result<
    (
        wgpu::RenderPipeline,
        Option<wgpu::RenderPipeline>,
        wgpu::BindGroup,
    ),
    String,
> {
    let device = &gpu.device;
    // The copy plait itself would read (the library search path, `PLAIT_PATH`
    // first), so a shader variant there applies to both programs alike.
    let relative = if d.shader.contains('/') {
        d.shader.to_owned()
    } else {
        format!("shaders/passes/{}", d.shader)
    };
    let path = plait_assets::find_on_disk(&relative).unwrap_or_else(|| repo_root().join(&relative));
    let source = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let defines: Vec<(String, Define)> = d
        .defines
        .iter()
        .map(|n| (n.to_string(), Define::Bool(true)))
        .collect();
    let module = shaders
        .compose(Path::new(d.shader), &source, &defines)
        .map_err(|e| format!("{}: {}", d.shader, e.message))?;
    let mut module = (*module).clone();
    let next = matches!(d.geometry, Geometry::Hair) && reads_next_vertex(&module);
    if d.early_depth_test {
        for ep in module
            .entry_points
            .iter_mut()
            .filter(|e| e.stage == naga::ShaderStage::Fragment)
        {
            ep.early_depth_test = Some(naga::EarlyDepthTest::Force);
        }
    }
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(d.name),
        source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(module)),
    });
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(d.name),
        entries: &d
            .binds
            .iter()
            .map(|b| wgpu::BindGroupLayoutEntry {
                binding: b.binding,
                // Writable storage is a fragment-stage binding only.
                visibility: match b.ty {
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: false },
                        ..
                    } => wgpu::ShaderStages::FRAGMENT,
                    _ => wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                },
                ty: b.ty,
                count: None,
            })
            .collect::<Vec<_>>(),
    });
    let entries: Vec<wgpu::BindGroupEntry> = d
        .binds
        .iter()
        .map(|b| wgpu::BindGroupEntry {
            binding: b.binding,
            resource: match b.ty {
                wgpu::BindingType::Texture { .. } => {
                    wgpu::BindingResource::TextureView(&textures[b.resource].1)
                }
                _ => buffers[b.resource].as_entire_binding(),
            },
        })
        .collect();
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(d.name),
        layout: &layout,
        entries: &entries,
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(d.name),
        bind_group_layouts: &[Some(frame_layout), Some(&layout)],
        immediate_size: 0,
    });
    let vertex_buffers: Vec<_> = match d.geometry {
        Geometry::Hair if next => hair_vertex_layouts(wgpu::VertexStepMode::Vertex)
            .into_iter()
            .map(Some)
            .collect(),
        Geometry::Hair => vec![Some(hair_vertex_layout())],
        Geometry::Opaque => vec![Some(opaque_vertex_layout())],
        Geometry::Fullscreen => vec![],
    };
    let targets: Vec<Option<wgpu::ColorTargetState>> = d
        .colors
        .iter()
        .map(|&(_, format, blend, write_mask, _)| {
            Some(wgpu::ColorTargetState {
                format,
                blend,
                write_mask,
            })
        })
        .collect();
    let has_fragment = !d.colors.is_empty() || d.early_depth_test;
    let make = |topology, vertex_buffers: &[Option<wgpu::VertexBufferLayout<'static>>]| {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(d.name),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: vertex_buffers,
            },
            primitive: wgpu::PrimitiveState {
                topology,
                ..Default::default()
            },
            depth_stencil: d
                .depth
                .map(|(_, compare, write, _)| wgpu::DepthStencilState {
                    format: wgpu::TextureFormat::Depth32Float,
                    depth_write_enabled: Some(write),
                    depth_compare: Some(compare),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
            multisample: Default::default(),
            fragment: has_fragment.then(|| wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    };
    let topology = match d.geometry {
        Geometry::Hair => wgpu::PrimitiveTopology::LineList,
        _ => wgpu::PrimitiveTopology::TriangleList,
    };
    let pipeline = make(topology, &vertex_buffers);
    let quads = next.then(|| {
        let layouts: Vec<_> = hair_vertex_layouts(wgpu::VertexStepMode::Instance)
            .into_iter()
            .map(Some)
            .collect();
        make(wgpu::PrimitiveTopology::TriangleList, &layouts)
    });
    Ok((pipeline, quads, group))
}
