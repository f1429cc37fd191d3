//! Runs a compiled schedule: allocates the memory plan, builds every pass,
//! records one command buffer with per-pass timestamps, reads outputs back.

use std::path::Path;

use plait_graph::{ResourceDesc, Schedule};
use wgpu::util::DeviceExt;

use crate::frame::FrameUniforms;
use crate::geometry::SceneGeometry;
use crate::overflow::{Overflow, OverflowReadback};
use crate::pass::{
    BuildContext, FrameSamplers, PassLibrary, PreparedPass, RecordContext, frame_layout,
};
use crate::pool::ResourcePool;
use crate::readback::{TexelData, map_buffer, read_texture_async};
use crate::timing::Timestamps;
use crate::{Gpu, GpuError};

/// GPU time of one pass.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PassTiming {
    pub name: String,
    pub type_name: String,
    /// `None` where the adapter has no timestamp queries.
    pub gpu_ms: Option<f64>,
    /// What the pass found out while recording ([`PreparedPass::stats`]), e.g. `layers`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub stats: Vec<(String, f64)>,
    /// A `run = "once"` pass not recorded this frame: its outputs are the
    /// first frame's, and `gpu_ms` is that frame's time.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub cached: bool,
}

/// What one frame cost.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FrameReport {
    pub passes: Vec<PassTiming>,
    /// First timestamp to last: the frame on the GPU (not the sum of passes,
    /// which double-counts overlap on pipelined GPUs). Through pass
    /// descriptors ([`crate::timing`]) the first pass's begin to the last
    /// one's end.
    pub total_gpu_ms: Option<f64>,
    /// Every overflow counter the schedule declares, as this frame left it:
    /// what each bounded buffer could not hold ([`Overflow::dropped`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub overflow: Vec<Overflow>,
}

impl FrameReport {
    /// The counters that dropped something this frame.
    pub fn dropped(&self) -> impl Iterator<Item = &Overflow> {
        self.overflow.iter().filter(|o| o.dropped > 0)
    }

    /// The counters whose pass had invocations that could not finish
    /// ([`Overflow::incomplete`]).
    pub fn incomplete(&self) -> impl Iterator<Item = &Overflow> {
        self.overflow.iter().filter(|o| o.incomplete > 0)
    }
}

/// A schedule ready to render on a device.
pub struct Renderer<'g> {
    gpu: &'g Gpu,
    schedule: Schedule,
    pool: ResourcePool,
    geometry: SceneGeometry,
    frame_buffer: wgpu::Buffer,
    frame_group: FrameGroup,
    frame_bind_group: wgpu::BindGroup,
    passes: Vec<Box<dyn PreparedPass>>,
    timestamps: Option<Timestamps>,
    overflow: OverflowReadback,
    notes: Vec<String>,
    /// Frames rendered so far: `run = "once"` passes record on the first.
    frames_rendered: std::sync::atomic::AtomicU64,
    /// GPU time of each pass on the frame it last ran (what a cached
    /// `run = "once"` pass reports).
    last_ms: std::sync::Mutex<Vec<Option<f64>>>,
    /// What recording reads of the last frame ([`Renderer::set_frame`]).
    recorded: std::sync::Mutex<RecordedFrame>,
    /// A pass writes `hair_vertices` (simulation, interpolation): the hair
    /// drawn is the GPU's, not the CPU's the frame measured.
    hair_on_gpu: bool,
    /// Per pass, for a light-view pass, the most texels across of a
    /// texture it reads or writes (its maps: [`light_map_texels`]).
    light_texels: Vec<Option<u32>>,
}

/// What recording a frame reads of its [`FrameUniforms`] on the CPU.
#[derive(Clone, Copy)]
struct RecordedFrame {
    /// For the passes that place the head on the CPU (`RecordContext::head_model`).
    head_model: [[f32; 4]; 4],
    /// `RecordContext::wide_strands`, before `hair_on_gpu`.
    wide_strands: bool,
    /// The frame, for `RecordContext::wide_light_strands`, which each
    /// light-view pass decides in its own maps' texels.
    frame: FrameUniforms,
}

impl RecordedFrame {
    fn of(frame: &FrameUniforms) -> Self {
        RecordedFrame {
            head_model: frame.head_model,
            wide_strands: frame.draws_wide_strands(),
            frame: *frame,
        }
    }
}

/// For a light-view pass of `schedule`, the most texels across of a
/// texture it reads or writes — its maps (the per-texel maps' size
/// plait::hair_map's map_view measures a strand in, read from the depth
/// range texture by the passes that write buffers) — `None` for any other
/// pass, or a light-view pass that holds none (its quads then always drawn).
fn light_map_texels(schedule: &Schedule) -> Vec<Option<u32>> {
    schedule
        .passes
        .iter()
        .map(|pass| {
            if pass.view != Some(plait_graph::View::Light) {
                return None;
            }
            pass.reads
                .iter()
                .chain(&pass.writes)
                .filter_map(|b| match b.resolved(&schedule.resources).map(|r| &r.desc) {
                    Some(ResourceDesc::Texture { width, height, .. }) => {
                        Some((*width).max(*height))
                    }
                    _ => None,
                })
                .max()
        })
        .collect()
}

impl<'g> Renderer<'g> {
    /// Allocate and build everything. `schedule` must come from
    /// `plait_graph::compile_with` and [`crate::pass::ShaderChecker`] for
    /// this adapter (accesses settled, formats fitted): it is used as is.
    pub fn new(
        gpu: &'g Gpu,
        schedule: Schedule,
        library: &PassLibrary,
        geometry: SceneGeometry,
        frame: &FrameUniforms,
        base_dir: &Path,
    ) -> Result<Self, GpuError> {
        let device = &gpu.device;
        for r in &schedule.resources {
            if let ResourceDesc::Texture { width, height, .. } = r.desc {
                let max = gpu.capabilities.max_texture_dimension;
                if width > max || height > max {
                    return Err(GpuError::Resource {
                        resource: r.name.clone(),
                        message: format!("{width}x{height} exceeds the adapter's limit of {max}"),
                    });
                }
            }
        }
        // Compile fitted the formats to the adapter; what it changed is said once.
        let notes = schedule.notes.clone();
        // What the adapter cannot do is refused here, whole, before wgpu
        // sees a single call (callers usually checked already: session).
        let unsupported =
            crate::support::problems(&schedule, library, &gpu.support, &gpu.capabilities);
        if !unsupported.is_empty() {
            return Err(GpuError::Unsupported(Box::new(crate::Unsupported::new(
                &gpu.support,
                &schedule.name,
                unsupported,
            ))));
        }
        let (pool, scoped) =
            crate::wait::validated(device, || ResourcePool::new(device, &schedule, &geometry));
        if let Some(e) = scoped {
            return Err(GpuError::Resource {
                resource: "memory plan".into(),
                message: crate::describe_wgpu_error(&e),
            });
        }
        let frame_layout = frame_layout(device);
        let frame_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("plait frame"),
            contents: bytemuck::bytes_of(frame),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let frame_group = FrameGroup {
            layout: frame_layout,
            samplers: FrameSamplers::new(device),
        };
        let frame_bind_group = frame_group.bind(device, &frame_buffer, &background_view(gpu, None));
        let mut passes = Vec::with_capacity(schedule.passes.len());
        for pass in &schedule.passes {
            // The type resolved at compile, by its handle.
            let t = library.pass_type(pass).ok_or_else(|| GpuError::Pass {
                pass: pass.name.clone(),
                message: format!(
                    "pass type `{}` was not resolved against this library at compile",
                    pass.type_name
                ),
            })?;
            let mut ctx = BuildContext {
                device,
                pipelines: &gpu.pipelines,
                capabilities: &gpu.capabilities,
                adapter_name: gpu.adapter_name(),
                schedule: &schedule,
                pool: &pool,
                geometry: &geometry,
                frame_layout: &frame_group.layout,
                base_dir,
                shaders: &library.shaders,
            };
            passes.push(t.build(pass, &mut ctx)?);
            if let Some(message) = gpu.take_uncaptured_errors().into_iter().next() {
                return Err(GpuError::Validation {
                    pass: pass.name.clone(),
                    message,
                });
            }
        }
        let timestamps = gpu
            .timestamp_way()
            .map(|way| Timestamps::new(device, &gpu.queue, way, schedule.passes.len()));
        let overflow = OverflowReadback::new(device, &schedule, &pool);
        let light_texels = light_map_texels(&schedule);
        let hair_on_gpu = schedule
            .passes
            .iter()
            .any(|p| p.writes.iter().any(|w| w.resource_name == "hair_vertices"));
        Ok(Renderer {
            gpu,
            overflow,
            schedule,
            pool,
            geometry,
            frame_buffer,
            frame_group,
            frame_bind_group,
            last_ms: std::sync::Mutex::new(vec![None; passes.len()]),
            recorded: std::sync::Mutex::new(RecordedFrame::of(frame)),
            hair_on_gpu,
            light_texels,
            frames_rendered: std::sync::atomic::AtomicU64::new(0),
            passes,
            timestamps,
            notes,
        })
    }

    pub fn schedule(&self) -> &Schedule {
        &self.schedule
    }

    /// What the renderer changed to fit the adapter (e.g. a 32-bit float
    /// target blended in 16 bits), one sentence each.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The scene's background image (sRGB), shown where `frame.background.w`
    /// says the background is an image.
    pub fn set_background_image(&mut self, image: &image::RgbaImage) {
        let view = background_view(self.gpu, Some(image));
        self.frame_bind_group = self
            .frame_group
            .bind(&self.gpu.device, &self.frame_buffer, &view);
    }

    /// Replace the hair's vertices with `strands` moved (the hair following
    /// the head), before `render`. Fails when `strands` is not the uploaded
    /// hair's shape.
    pub fn set_hair(&self, strands: &plait_hair::Strands) -> Result<(), GpuError> {
        if self.geometry.write_hair(&self.gpu.queue, strands) {
            Ok(())
        } else {
            Err(GpuError::Resource {
                resource: "hair vertices".into(),
                message: format!(
                    "{} points given, but the uploaded hair has a different count",
                    strands.point_count()
                ),
            })
        }
    }

    /// Replace the frame's standard inputs (e.g. a new jitter) before `render`.
    pub fn set_frame(&self, frame: &FrameUniforms) {
        *self.recorded.lock().unwrap_or_else(|e| e.into_inner()) = RecordedFrame::of(frame);
        self.gpu
            .queue
            .write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(frame));
    }

    /// Whether the next frame is the first (`run = "once"` passes record on it).
    fn first_frame(&self) -> bool {
        self.frames_rendered
            .load(std::sync::atomic::Ordering::Relaxed)
            == 0
    }

    /// Record the next frame's commands — every pass, its debug group and
    /// timestamps — and finish them, without submitting: what `render`
    /// submits, and what the encode benchmark (`crates/plait/benches/encode.rs`)
    /// times against wgpu written by hand.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn encode(&self) -> wgpu::CommandBuffer {
        pollster::block_on(self.encode_async())
    }

    /// [`Renderer::encode`], awaiting the passes that read a GPU result
    /// mid-frame ([`PreparedPass::record_async`]): what `render_async` submits.
    async fn encode_async(&self) -> wgpu::CommandBuffer {
        let device = &self.gpu.device;
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some(&self.schedule.name),
        });
        let recorded = *self.recorded.lock().unwrap_or_else(|e| e.into_inner());
        let ctx = RecordContext {
            device,
            queue: &self.gpu.queue,
            frame_bind_group: &self.frame_bind_group,
            geometry: &self.geometry,
            pool: &self.pool,
            schedule: &self.schedule,
            timestamps: self.timestamps.as_ref(),
            head_model: recorded.head_model,
            wide_strands: self.hair_on_gpu || recorded.wide_strands,
            // Decided per pass below, in its own maps' texels.
            wide_light_strands: true,
        };
        if let Some(ts) = &self.timestamps {
            ts.frame_start(&mut encoder);
        }
        let first_frame = self.first_frame();
        let skipped = |i: usize| self.schedule.passes[i].run_once && !first_frame;
        for (i, pass) in self.passes.iter().enumerate() {
            if let Some(ts) = &self.timestamps {
                ts.pass_start(i);
            }
            if !skipped(i) {
                encoder.push_debug_group(&self.schedule.passes[i].name);
                let ctx = RecordContext {
                    wide_light_strands: self.hair_on_gpu
                        || self.light_texels[i]
                            .is_none_or(|t| recorded.frame.draws_wide_light_strands(t)),
                    ..ctx
                };
                pass.record_async(&ctx, &mut encoder).await;
                encoder.pop_debug_group();
                self.overflow.record(i, &self.pool, &mut encoder);
            }
            // The frame's last timestamp also covers aging the histories.
            if i + 1 == self.passes.len() {
                self.record_history(&mut encoder);
            }
            if let Some(ts) = &self.timestamps {
                ts.pass_end(i, &mut encoder);
            }
        }
        if let Some(ts) = &self.timestamps {
            ts.resolve(&mut encoder);
        }
        encoder.finish()
    }

    /// Render one frame and wait for it; per-pass GPU times when the adapter has timestamps.
    pub fn render(&self) -> Result<FrameReport, GpuError> {
        crate::wait::wait_for(self.render_async()).map_err(GpuError::Device)?
    }

    /// Render one frame and await it: [`Renderer::render`] in a browser,
    /// where the GPU's results arrive through the page's event loop.
    pub async fn render_async(&self) -> Result<FrameReport, GpuError> {
        let device = &self.gpu.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let first_frame = self.first_frame();
        let skipped = |i: usize| self.schedule.passes[i].run_once && !first_frame;
        let commands = self.encode_async().await;
        self.gpu.queue.submit([commands]);
        self.gpu.wait()?;
        if let Some(e) = scope.pop().await {
            return Err(GpuError::Validation {
                pass: self.schedule.name.clone(),
                message: crate::describe_wgpu_error(&e),
            });
        }
        // The timestamps' and counters' readbacks come before the check of
        // errors raised outside a scope: in a browser those arrive with them.
        let mut times = None;
        if let Some(ts) = &self.timestamps {
            times = Some(
                ts.read(device)
                    .await
                    .map_err(|message| GpuError::Readback {
                        resource: "timestamps".into(),
                        message,
                    })?,
            );
        }
        let overflow = self.overflow.read(device, &self.schedule).await?;
        if let Some(message) = self.gpu.take_uncaptured_errors().into_iter().next() {
            return Err(GpuError::Validation {
                pass: self.schedule.name.clone(),
                message,
            });
        }
        for (i, pass) in self.passes.iter().enumerate() {
            pass.finish_async(device)
                .await
                .map_err(|message| GpuError::Pass {
                    pass: self.schedule.passes[i].name.clone(),
                    message,
                })?;
        }
        let mut last_ms = self.last_ms.lock().unwrap_or_else(|e| e.into_inner());
        let passes = self
            .schedule
            .passes
            .iter()
            .enumerate()
            .map(|(i, p)| {
                if !skipped(i) {
                    last_ms[i] = times.as_ref().and_then(|t| t.passes[i]);
                }
                PassTiming {
                    name: p.name.clone(),
                    type_name: p.type_name.clone(),
                    gpu_ms: last_ms[i],
                    stats: self.passes[i].stats(),
                    cached: skipped(i),
                }
            })
            .collect();
        self.frames_rendered
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let total_gpu_ms = times.as_ref().and_then(|t| t.total);
        Ok(FrameReport {
            passes,
            total_gpu_ms,
            overflow,
        })
    }

    /// Ages every history after the frame's passes: each version is copied
    /// into the one a frame older, oldest first (`Schedule::history`). Copies
    /// rather than swaps: bind groups are built once per pass, so swapping
    /// two allocations would need a second set of them for every pass.
    fn record_history(&self, encoder: &mut wgpu::CommandEncoder) {
        use crate::pool::GpuResource;
        for copy in &self.schedule.history {
            match (self.pool.get(copy.from), self.pool.get(copy.to)) {
                (GpuResource::Buffer(from), GpuResource::Buffer(to)) => {
                    encoder.copy_buffer_to_buffer(from, 0, to, 0, from.size().min(to.size()))
                }
                (
                    GpuResource::Texture { texture: from, .. },
                    GpuResource::Texture { texture: to, .. },
                ) => encoder.copy_texture_to_texture(
                    from.as_image_copy(),
                    to.as_image_copy(),
                    from.size(),
                ),
                // Cannot happen: compile gives a history's versions the
                // resource's own descriptor.
                _ => {}
            }
        }
    }

    /// Read a texture resource back (layer 0; multisampled textures cannot be read).
    pub fn read_resource(&self, name: &str) -> Result<TexelData, GpuError> {
        crate::wait::wait_for(self.read_resource_async(name)).map_err(|message| {
            GpuError::Readback {
                resource: name.into(),
                message,
            }
        })?
    }

    /// [`Renderer::read_resource`], awaited (in a browser).
    pub async fn read_resource_async(&self, name: &str) -> Result<TexelData, GpuError> {
        let id = self
            .schedule
            .resource(name)
            .ok_or_else(|| GpuError::Readback {
                resource: name.into(),
                message: "no such resource".into(),
            })?;
        let ResourceDesc::Texture {
            format, samples, ..
        } = self.schedule.resources[id].desc
        else {
            return Err(GpuError::Readback {
                resource: name.into(),
                message: "only textures can be read back as images".into(),
            });
        };
        if samples > 1 {
            return Err(GpuError::Readback {
                resource: name.into(),
                message: "a multisampled texture must be resolved first".into(),
            });
        }
        let (texture, _) = self.pool.texture(id).ok_or_else(|| GpuError::Readback {
            resource: name.into(),
            message: "not a texture".into(),
        })?;
        read_texture_async(&self.gpu.device, &self.gpu.queue, texture, format, name).await
    }

    /// Read a buffer resource back as bytes.
    pub fn read_buffer(&self, name: &str) -> Result<Vec<u8>, GpuError> {
        let id = self
            .schedule
            .resource(name)
            .ok_or_else(|| GpuError::Readback {
                resource: name.into(),
                message: "no such resource".into(),
            })?;
        let buffer = self.pool.buffer(id).ok_or_else(|| GpuError::Readback {
            resource: name.into(),
            message: "not a buffer".into(),
        })?;
        let device = &self.gpu.device;
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("buffer readback"),
            size: buffer.size(),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
        self.gpu.queue.submit([encoder.finish()]);
        map_buffer(device, &staging).map_err(|message| GpuError::Readback {
            resource: name.into(),
            message,
        })
    }
}

/// Group 0's fixed parts, kept to rebind when the background image changes.
struct FrameGroup {
    layout: wgpu::BindGroupLayout,
    samplers: FrameSamplers,
}

impl FrameGroup {
    fn bind(
        &self,
        device: &wgpu::Device,
        frame: &wgpu::Buffer,
        background: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        self.samplers.bind(
            device,
            &self.layout,
            frame.as_entire_binding(),
            background,
            "plait frame",
        )
    }
}

/// The background image as an sRGB texture (sampling decodes it to linear);
/// a 1×1 black texture when there is none.
fn background_view(gpu: &Gpu, image: Option<&image::RgbaImage>) -> wgpu::TextureView {
    let black = image::RgbaImage::from_pixel(1, 1, image::Rgba([0, 0, 0, 255]));
    let image = image.unwrap_or(&black);
    let texture = gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("background image"),
            size: wgpu::Extent3d {
                width: image.width(),
                height: image.height(),
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
        image.as_raw(),
    );
    texture.create_view(&Default::default())
}
