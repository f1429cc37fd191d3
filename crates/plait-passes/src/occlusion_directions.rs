//! `occlusion_directions`: per-vertex ambient occlusion from deep opacity maps
//! rendered from N directions on the sphere (Xing et al. 2012 §4, Fig. 4).
//!
//! The paper's offline loop, on the GPU inside one pass (the graph stays a
//! DAG): a kernel fits an orthographic view per direction around the hair
//! and writes it as a copy of the frame; then, per direction, the
//! self-shadowing kernels run unchanged with that frame bound at group 0 —
//! the depth range (`depth_range.wgsl`, z0 of the maps), the deep opacity
//! layers (`deep_opacity.wgsl`) — and a gather kernel adds each vertex's
//! transmittance through the hair (the `deep_opacity` visibility provider)
//! divided by N. The result is the mean transmittance over the sphere, the
//! ambient visibility of the vertex (1 = unoccluded). Only hair occludes, as
//! in the paper; the head's own occlusion is the cylinders technique's scalp
//! discs (Halén & Wester 2007 §3.3.1).

use plait_gpu::GpuError;
use plait_gpu::frame::FRAME_UNIFORMS_SIZE;
use plait_gpu::pass::{
    BuildContext, DepthMode, FrameSamplers, PassType, PreparedPass, RasterState, RecordContext,
    ShaderDraw, ShaderPass, build_draw, default_defines,
};
use plait_gpu::shader::Define;
use plait_graph::{
    Access, Binding, Format, PassShape, PassTypeSpec, ResolvedResource, ResourceDesc,
    ScheduledPass, SlotId,
};

use crate::depth_range;
use crate::spec_util::{DEPTH, bound, float, int, texture};

pub struct OcclusionDirections;

inventory::submit! { crate::RustPassType(|_| Box::new(OcclusionDirections)) }

const SHADER: &str = "shaders/passes/occlusion_directions.wgsl";
const DEEP_OPACITY: &str = "shaders/passes/deep_opacity.wgsl";

/// Bytes of one direction's frame in `direction_frames` (the WGSL
/// `DirectionFrame`): the frame padded to a multiple of 256, the uniform
/// offset alignment WebGPU guarantees.
pub const DIRECTION_FRAME_BYTES: u64 = 768;

/// The most directions a pass may take (the frames kernel's one workgroup
/// handles any count; this bounds the precompute's time).
pub const MAX_DIRECTIONS: i64 = 1024;

/// Its slots' handles ([`SlotId`]), in `spec`'s order.
pub(crate) const VERTEX_AO: SlotId = SlotId::Output(0);
pub(crate) const DIRECTION_FRAMES: SlotId = SlotId::Output(1);
pub(crate) const RANGE: SlotId = SlotId::Output(2);
pub(crate) const LAYERS: SlotId = SlotId::Output(3);
pub(crate) const SCRATCH: SlotId = SlotId::Output(4);
pub(crate) const NO_OPAQUE: SlotId = SlotId::Output(5);

pub(crate) fn spec() -> PassTypeSpec {
    let buffer = crate::spec_util::buffer;
    let aliased = |mut s: plait_graph::SlotSpec, binding: &str| {
        s.binding = Some(binding.into());
        s
    };
    PassTypeSpec {
        inputs: vec![],
        outputs: vec![
            buffer(
                "vertex_ao",
                Access::StorageWrite,
                "ambient visibility per hair vertex (f32, 1 = unoccluded); at least 4 B per vertex",
            ),
            buffer(
                "direction_frames",
                Access::StorageWrite,
                "scratch: one frame per direction, 768 B each",
            ),
            aliased(
                texture(
                    "range",
                    Access::ColorTarget,
                    &[Format::Rg32Float],
                    "scratch: depth range of one direction (z0 of the deep opacity maps)",
                ),
                "vis_range",
            ),
            aliased(
                buffer(
                    "layers",
                    Access::StorageWrite,
                    "scratch: deep opacity layers of one direction, K u32 per texel",
                ),
                "vis_layers",
            ),
            texture(
                "scratch",
                Access::DepthTarget,
                DEPTH,
                "scratch: depth buffer of the depth-range draws",
            ),
            texture(
                "no_opaque",
                Access::DepthTarget,
                DEPTH,
                "scratch: an opaque depth cleared to far (only hair occludes)",
            ),
        ],
        params: vec![
            int(
                "directions",
                100,
                1,
                MAX_DIRECTIONS,
                "directions on the sphere (Xing et al. 2012 §4: 100; Fig. 7: 9, 25, 64)",
            ),
            float(
                "shadow_weight",
                0.15,
                0.0,
                100.0,
                "opacity one hair fragment adds in front of a vertex",
            ),
            float(
                "layer_size",
                0.2,
                1e-6,
                1e6,
                "deep opacity maps: thickness of the first layer, world units",
            ),
        ],
        ..PassTypeSpec::new(
            "occlusion_directions",
            PassShape::Compute,
            "Xing et al. 2012 §4",
            "Per-vertex ambient occlusion: deep opacity maps from N sphere directions, transmittance averaged.",
        )
    }
}

/// A pass like `pass` (of the type whose spec is `spec`) whose slots are the
/// ones a kernel it records expects: `(kernel slot, this pass's slot,
/// access)`. The kernel's slots are its shader's bindings, so they go by
/// name; the pass's own go by handle.
pub(crate) fn kernel_pass(
    pass: &ScheduledPass,
    spec: &PassTypeSpec,
    shape: PassShape,
    reads: &[(&str, SlotId, Access)],
    writes: &[(&str, SlotId, Access)],
) -> Result<ScheduledPass, GpuError> {
    let rebind = |list: &[(&str, SlotId, Access)], loads: bool| {
        list.iter()
            .map(|&(slot, ours, access)| {
                let b = bound(pass, spec, ours)?;
                Ok(Binding {
                    slot: slot.into(),
                    // A slot of the kernel's shader, no longer of the type.
                    slot_id: None,
                    resolves: None,
                    access,
                    loads,
                    ..b.clone()
                })
            })
            .collect::<Result<Vec<_>, GpuError>>()
    };
    let mut sub = pass.clone();
    sub.shape = shape;
    sub.reads = rebind(reads, false)?;
    // The gather kernel adds into `vertex_ao`: it must not be cleared per direction.
    sub.writes = rebind(writes, true)?;
    if shape == PassShape::Raster {
        sub.view = Some(plait_graph::View::Light);
        sub.draw = Some(plait_graph::Draw::Hair);
    }
    Ok(sub)
}

/// Library compute shader `shader` of `pass` built with `defines` for
/// `threads` threads, its slots those of `kernels` (a [`kernel_pass`]).
pub(crate) fn compute_kernel(
    shader: &str,
    pass: &ScheduledPass,
    defines: Vec<(String, Define)>,
    threads: u32,
    kernels: &ScheduledPass,
    ctx: &BuildContext<'_>,
) -> Result<ShaderPass, GpuError> {
    let mut draw = ShaderDraw::library(
        shader,
        pass,
        PassShape::Compute,
        defines,
        RasterState::default(),
        ctx,
    )?;
    draw.threads = [threads, 1, 1];
    build_draw(&draw, kernels, ctx)
}

pub(crate) fn int_param(pass: &ScheduledPass, name: &str) -> i64 {
    pass.params.get(name).and_then(|v| v.as_i64()).unwrap_or(0)
}

/// The hair's vertex count, checked against the `vertex_ao` buffer bound to
/// `pass` (slot `ao` of the type whose spec is `spec`).
pub(crate) fn checked_vertex_count(
    pass: &ScheduledPass,
    spec: &PassTypeSpec,
    ao: SlotId,
    ctx: &BuildContext<'_>,
) -> Result<u32, GpuError> {
    let error = |message: String| GpuError::Pass {
        pass: pass.name.clone(),
        message,
    };
    let hair = ctx
        .geometry
        .hair
        .as_ref()
        .ok_or_else(|| error("the scene has no hair".into()))?;
    let vertices = hair.vertices.size() / std::mem::size_of::<plait_hair::StrandVertex>() as u64;
    let ao = &ctx.schedule.resources[bound(pass, spec, ao)?.id()];
    if let ResourceDesc::Buffer { size } = ao.desc
        && size < vertices * 4
    {
        return Err(error(format!(
            "`{}` holds {} vertices ({size} bytes) but the hair has {vertices}: raise its size (the technique's `ao_max_vertices` param)",
            ao.name,
            size / 4
        )));
    }
    u32::try_from(vertices).map_err(|_| error(format!("{vertices} hair vertices are too many")))
}

impl PassType for OcclusionDirections {
    fn spec(&self) -> PassTypeSpec {
        spec()
    }

    fn shader(&self) -> Option<&str> {
        Some(SHADER)
    }

    fn check_sizes(
        &self,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
    ) -> Result<(), String> {
        let directions = int_param(pass, "directions") as u64;
        let frames = pass.bound(DIRECTION_FRAMES);
        if let Some(ResourceDesc::Buffer { size }) =
            frames.and_then(|b| b.resolved(resources)).map(|r| &r.desc)
        {
            let need = directions * DIRECTION_FRAME_BYTES;
            if *size < need {
                return Err(format!(
                    "`direction_frames` holds {size} bytes; {directions} directions need {need} (\"${{directions}} * {DIRECTION_FRAME_BYTES}\")"
                ));
            }
        }
        Ok(())
    }

    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let spec = spec();
        let vertices = checked_vertex_count(pass, &spec, VERTEX_AO, ctx)?;
        let ao_id = bound(pass, &spec, VERTEX_AO)?.id();
        let directions = int_param(pass, "directions").clamp(1, MAX_DIRECTIONS) as u32;

        // The frames kernel (one workgroup) and the gather kernel (a thread per vertex).
        let frames_pass = kernel_pass(
            pass,
            &spec,
            PassShape::Compute,
            &[],
            &[
                ("direction_frames", DIRECTION_FRAMES, Access::StorageWrite),
                ("vertex_ao", VERTEX_AO, Access::StorageWrite),
            ],
        )?;
        let mut defines = default_defines(pass);
        defines.push(("AO_FRAMES".into(), Define::Bool(true)));
        let frames = compute_kernel(SHADER, pass, defines, 1, &frames_pass, ctx)?;

        let gather_pass = kernel_pass(
            pass,
            &spec,
            PassShape::Compute,
            &[
                ("vis_range", RANGE, Access::Sampled),
                ("vis_layers", LAYERS, Access::StorageRead),
            ],
            &[
                ("direction_frames", DIRECTION_FRAMES, Access::StorageWrite),
                ("vertex_ao", VERTEX_AO, Access::StorageWrite),
            ],
        )?;
        let gather = compute_kernel(
            SHADER,
            pass,
            default_defines(pass),
            vertices,
            &gather_pass,
            ctx,
        )?;

        // Self-shadowing's own kernels, from each direction's frame.
        let range_pass = kernel_pass(
            pass,
            &spec,
            PassShape::Raster,
            &[("opaque_depth", NO_OPAQUE, Access::Sampled)],
            &[
                ("range", RANGE, Access::ColorTarget),
                ("scratch", SCRATCH, Access::DepthTarget),
            ],
        )?;
        let mut range_draw = ShaderDraw::library(
            depth_range::SHADER,
            pass,
            PassShape::Raster,
            default_defines(&range_pass),
            RasterState::default(),
            ctx,
        )?;
        let [near_state, far_state] = depth_range::draw_states();
        range_draw.state = near_state;
        let near = build_draw(&range_draw, &range_pass, ctx)?;
        range_draw.state = far_state;
        let far = build_draw(&range_draw, &range_pass, ctx)?;

        let layers_pass = kernel_pass(
            pass,
            &spec,
            PassShape::Raster,
            &[
                ("range", RANGE, Access::Sampled),
                ("depth", NO_OPAQUE, Access::DepthTarget),
            ],
            &[("layers", LAYERS, Access::StorageWrite)],
        )?;
        let mut layers_pass = layers_pass;
        // Zeroed before every direction's draw.
        layers_pass.writes[0].loads = false;
        let layers_draw = ShaderDraw::library(
            DEEP_OPACITY,
            pass,
            PassShape::Raster,
            default_defines(&layers_pass),
            RasterState {
                depth: DepthMode::TestOnly(wgpu::CompareFunction::Less),
                ..RasterState::default()
            },
            ctx,
        )?;
        let layers = build_draw(&layers_draw, &layers_pass, ctx)?;

        // Each direction's frame, bound at group 0 like the executor's.
        let uniforms = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{} frames", pass.name)),
            size: directions as u64 * DIRECTION_FRAME_BYTES,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let groups = FrameGroups::new(ctx, &uniforms, directions, &pass.name);
        Ok(Box::new(Prepared {
            frames,
            gather,
            near,
            far,
            layers,
            uniforms,
            groups,
            frames_buffer: bound(pass, &spec, DIRECTION_FRAMES)?.id(),
            vertex_ao: ao_id,
            no_opaque: bound(pass, &spec, NO_OPAQUE)?.id(),
            directions,
        }))
    }
}

/// Group 0 bind groups, one per direction: the frame at its offset in the
/// uniform copy of `direction_frames`, samplers as the executor's.
struct FrameGroups {
    groups: Vec<wgpu::BindGroup>,
}

impl FrameGroups {
    fn new(ctx: &BuildContext<'_>, uniforms: &wgpu::Buffer, directions: u32, label: &str) -> Self {
        let device = ctx.device;
        let samplers = FrameSamplers::new(device);
        let background = device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: 1,
                    height: 1,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba8Unorm,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
            .create_view(&Default::default());
        let groups = (0..directions as u64)
            .map(|d| {
                let frame = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: uniforms,
                    offset: d * DIRECTION_FRAME_BYTES,
                    size: wgpu::BufferSize::new(FRAME_UNIFORMS_SIZE),
                });
                samplers.bind(device, ctx.frame_layout, frame, &background, label)
            })
            .collect();
        FrameGroups { groups }
    }
}

struct Prepared {
    frames: ShaderPass,
    gather: ShaderPass,
    near: ShaderPass,
    far: ShaderPass,
    layers: ShaderPass,
    uniforms: wgpu::Buffer,
    groups: FrameGroups,
    frames_buffer: plait_graph::ResourceId,
    vertex_ao: plait_graph::ResourceId,
    no_opaque: plait_graph::ResourceId,
    directions: u32,
}

impl PreparedPass for Prepared {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        // Zero the sums and write every direction's frame.
        if let Some(b) = ctx.pool.buffer(self.vertex_ao) {
            encoder.clear_buffer(b, 0, None);
        }
        self.frames.record(ctx, encoder);
        if let Some(frames) = ctx.pool.buffer(self.frames_buffer) {
            encoder.copy_buffer_to_buffer(frames, 0, &self.uniforms, 0, self.uniforms.size());
        }
        // Nothing opaque: the depth the hair kernels test against is far everywhere.
        if let Some((_, view)) = ctx.pool.texture(self.no_opaque) {
            encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("occlusion: no opaque"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
        }
        for group in &self.groups.groups {
            let direction = RecordContext {
                frame_bind_group: group,
                // The directions' frames are made on the GPU: the CPU's
                // measure of the camera's widths says nothing of theirs.
                wide_strands: true,
                wide_light_strands: true,
                ..*ctx
            };
            self.near.record(&direction, encoder);
            self.far.record(&direction, encoder);
            self.layers.record(&direction, encoder);
            self.gather.record(&direction, encoder);
        }
    }

    fn stats(&self) -> Vec<(String, f64)> {
        vec![("directions".into(), self.directions as f64)]
    }
}
