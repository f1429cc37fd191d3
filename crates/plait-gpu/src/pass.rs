//! How a pass type turns into GPU work.
//!
//! A pass type is a [`PassTypeSpec`] (what it reads, writes and accepts — checked
//! without a GPU) plus a WGSL file plus, where needed, Rust that sets pipeline
//! state or records special loops. The shared machinery here binds resources by
//! name from naga's reflection of the shader (kajiya-rg's "declared accesses +
//! a closure", with the declaration checked against the shader):
//!
//! - group 0: the frame's standard inputs (`#import plait::frame`);
//! - group 1: one binding per slot, the variable named like the slot, plus an
//!   optional `params` uniform whose members are filled from the pass params by
//!   name, plus `hair_vertices` / `hair_indices` storage buffers of the scene;
//! - colour and depth targets are attachments, not bindings.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use plait_graph::{
    Access, Error as GraphError, ErrorKind, Format, Location, PassShape, PassTypeSpec,
    ResourceDesc, ResourceKind, Schedule, ScheduledPass, Value,
};

use crate::depth_guard::{DepthGuard, GUARD_BINDING};
use crate::frame::FRAME_UNIFORMS_SIZE;
use crate::geometry::{SceneGeometry, hair_vertex_layout, opaque_vertex_layout};
use crate::pool::{ResourcePool, texture_format};
use crate::reflect::{self, BindingKind, ShaderBinding, TextureSample};
use crate::shader::{Define, ShaderLibrary};
use crate::{Capabilities, GpuError};

/// Names of scene buffers a shader can bind in group 1 without a slot.
pub const SCENE_BINDINGS: &[&str] = &["hair_vertices", "hair_indices"];

/// Depth test and write of a raster pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DepthMode {
    /// Test and write (the usual opaque pass).
    TestWrite(wgpu::CompareFunction),
    /// Test against a depth target read by the pass, never write it.
    TestOnly(wgpu::CompareFunction),
}

/// Fixed-function state of a raster pass that its Rust module chooses.
#[derive(Clone, Debug, PartialEq)]
pub struct RasterState {
    pub cull_mode: Option<wgpu::Face>,
    /// Used when the pass has a depth attachment.
    pub depth: DepthMode,
    /// Blend per colour target, in target order; missing entries replace.
    pub blend: Vec<Option<wgpu::BlendState>>,
    pub clear_color: wgpu::Color,
    pub clear_depth: f32,
    pub alpha_to_coverage: bool,
    /// Channels written per colour target, in target order; missing entries write all.
    pub write_mask: Vec<wgpu::ColorWrites>,
    /// Keep colour targets' contents even where the schedule says this pass
    /// writes them first (the second draw of a pass that draws twice).
    pub load_colors: bool,
}

impl Default for RasterState {
    fn default() -> Self {
        RasterState {
            cull_mode: None,
            depth: DepthMode::TestWrite(wgpu::CompareFunction::Less),
            blend: Vec::new(),
            clear_color: wgpu::Color::TRANSPARENT,
            clear_depth: 1.0,
            alpha_to_coverage: false,
            write_mask: Vec::new(),
            load_colors: false,
        }
    }
}

/// Additive blending of colour and alpha (accumulation targets).
pub const ADDITIVE: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

/// A WGSL source compiled into the pass library: `(path for messages, text)`.
pub type BuiltinShader = (&'static str, &'static str);

/// One pass type of the library.
pub trait PassType: Send + Sync {
    fn spec(&self) -> PassTypeSpec;

    /// The pass's own WGSL; `None` means the pipeline file's `shader = "…"`.
    fn shader(&self) -> Option<BuiltinShader>;

    /// Shader defines. The default: every int and bool param as its
    /// upper-case name (`slices = 128` → `#if SLICES == 128`).
    fn defines(&self, pass: &ScheduledPass) -> Vec<(String, Define)> {
        default_defines(pass)
    }

    /// Pipeline state of a raster or fullscreen pass.
    fn raster_state(
        &self,
        _pass: &ScheduledPass,
        _caps: &Capabilities,
    ) -> Result<RasterState, String> {
        Ok(RasterState::default())
    }

    /// Threads of a compute pass; the default covers the first written
    /// texture (width × height) or buffer (one thread per 4 bytes).
    fn compute_threads(&self, pass: &ScheduledPass, schedule: &Schedule) -> [u32; 3] {
        default_threads(pass, schedule)
    }

    /// Sizes the pass's shaders rely on that a pipeline file can get wrong
    /// (u32 words per texel of a map), checked by `plait check` before any
    /// GPU work; the message says what size would do.
    fn check_sizes(
        &self,
        _pass: &ScheduledPass,
        _resources: &[plait_graph::ResolvedResource],
    ) -> Result<(), String> {
        Ok(())
    }

    /// Build the GPU objects of a pass. Types with loops of their own
    /// (depth peeling, k-means) override this; most use the default.
    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        build_shader_pass(self, pass, ctx)
    }
}

/// GPU objects of one pass, ready to record every frame.
pub trait PreparedPass {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder);

    /// Numbers the last `record` found out (e.g. the layers a depth-peeling
    /// pass needed), reported per pass in the executor's `FrameReport`.
    fn stats(&self) -> Vec<(String, f64)> {
        Vec::new()
    }
}

/// What building a pass can use.
pub struct BuildContext<'a> {
    pub device: &'a wgpu::Device,
    pub pipelines: &'a crate::cache::PipelineCache,
    pub capabilities: &'a Capabilities,
    pub adapter_name: &'a str,
    pub schedule: &'a Schedule,
    pub pool: &'a ResourcePool,
    pub geometry: &'a SceneGeometry,
    pub frame_layout: &'a wgpu::BindGroupLayout,
    pub shaders: &'a mut ShaderLibrary,
    pub base_dir: &'a Path,
}

/// What recording a pass can use.
pub struct RecordContext<'a> {
    /// For passes that must see a GPU result mid-frame (an occlusion query):
    /// they may finish the encoder they were given, submit it, wait, and go on
    /// in a fresh one (`std::mem::replace`); the executor's timestamps stay valid.
    /// The executor wraps each pass in a debug group named after the pass:
    /// pop it before finishing the old encoder and push it on the new one.
    pub device: &'a wgpu::Device,
    pub queue: &'a wgpu::Queue,
    pub frame_bind_group: &'a wgpu::BindGroup,
    pub geometry: &'a SceneGeometry,
    pub pool: &'a ResourcePool,
    pub schedule: &'a Schedule,
}

/// The pass types available to a run, by name.
#[derive(Default)]
pub struct PassLibrary {
    pub types: IndexMap<String, Box<dyn PassType>>,
}

impl PassLibrary {
    pub fn add(&mut self, t: impl PassType + 'static) {
        self.types.insert(t.spec().name.clone(), Box::new(t));
    }

    pub fn get(&self, name: &str) -> Option<&dyn PassType> {
        self.types.get(name).map(|b| b.as_ref())
    }

    /// The specs for the graph crate's checks.
    pub fn registry(&self) -> plait_graph::Registry {
        let mut r = plait_graph::Registry::new();
        for t in self.types.values() {
            r.register(t.spec());
        }
        r
    }
}

/// A uniform filled from the pass params by member name: `params`, or a
/// module's own such as `visibility_params`.
fn is_params(b: &ShaderBinding) -> bool {
    matches!(b.kind, BindingKind::Uniform { .. }) && b.name.ends_with("params")
}

fn upper(name: &str) -> String {
    name.to_ascii_uppercase()
}

pub fn default_defines(pass: &ScheduledPass) -> Vec<(String, Define)> {
    let mut out = Vec::new();
    for (k, v) in &pass.params {
        match v {
            Value::Int(i) if *i >= 0 && *i <= u32::MAX as i64 => {
                out.push((upper(k), Define::UInt(*i as u32)))
            }
            Value::Int(i) => out.push((upper(k), Define::Int(*i as i32))),
            Value::Bool(b) => out.push((upper(k), Define::Bool(*b))),
            // `visibility = "modified_shadow_map"` → `#ifdef VISIBILITY_MODIFIED_SHADOW_MAP`.
            Value::Str(v) => out.push((format!("{}_{}", upper(k), upper(v)), Define::Bool(true))),
            _ => {}
        }
    }
    if pass.view.as_deref() == Some("light") {
        out.push(("LIGHT_VIEW".into(), Define::Bool(true)));
    }
    out
}

pub fn default_threads(pass: &ScheduledPass, schedule: &Schedule) -> [u32; 3] {
    match pass
        .writes
        .first()
        .map(|b| &schedule.resources[b.resource].desc)
    {
        Some(ResourceDesc::Texture {
            width,
            height,
            layers,
            ..
        }) => [*width, *height, *layers],
        Some(ResourceDesc::Buffer { size }) => [(size / 4).min(u32::MAX as u64) as u32, 1, 1],
        None => [1, 1, 1],
    }
}

/// The shader source of a pass: built in, or the file the pipeline names.
pub fn shader_source(
    t: &dyn PassType,
    pass: &ScheduledPass,
) -> Result<(PathBuf, Cow<'static, str>), (Location, String)> {
    if let Some((name, text)) = t.shader() {
        let loc = pass.location.clone();
        return crate::shader::library_source(name, text).map_err(|e| (loc, e.message));
    }
    let loc = pass
        .shader_location
        .clone()
        .unwrap_or_else(|| pass.location.clone());
    let Some(path) = &pass.shader else {
        return Err((loc, "needs `shader = \"path.wgsl\"`".into()));
    };
    match crate::shader::read_shader_file(path) {
        Ok(text) => Ok((path.clone(), text)),
        Err(e) => Err((loc, format!("cannot read shader {}: {e}", path.display()))),
    }
}

/// Check a pass against its shader with naga, and settle how dynamic slots
/// are accessed. No GPU involved: `plait check` runs this.
pub fn check_pass(
    t: &dyn PassType,
    pass: &mut ScheduledPass,
    schedule_resources: &[plait_graph::ResolvedResource],
    shaders: &mut ShaderLibrary,
) -> Vec<GraphError> {
    let mut errors = Vec::new();
    let err = |loc: &Location, message: String| {
        GraphError::new(
            loc.clone(),
            ErrorKind::Pass {
                pass: pass.name.clone(),
                message,
            },
        )
    };
    let (path, source) = match shader_source(t, pass) {
        Ok(s) => s,
        Err((loc, message)) => return vec![err(&loc, message)],
    };
    let defines = t.defines(pass);
    let module = match shaders.compose(&path, &source, &defines) {
        Ok(m) => m,
        Err(e) => {
            let loc = pass
                .shader_location
                .clone()
                .unwrap_or_else(|| pass.location.clone());
            return vec![GraphError::new(
                loc,
                ErrorKind::Shader {
                    path: e.path,
                    message: e.message,
                },
            )];
        }
    };
    let spec = t.spec();
    if let Err(message) = t.check_sizes(pass, schedule_resources) {
        errors.push(err(&pass.location, message));
    }
    let bindings = reflect::bindings(&module);
    let group1: Vec<&ShaderBinding> = bindings.iter().filter(|b| b.group == 1).collect();
    for b in bindings.iter().filter(|b| b.group > 1) {
        errors.push(err(&pass.location, format!("shader binding `{}` is in group {}; plait binds only groups 0 (frame) and 1 (slots)", b.name, b.group)));
    }
    // Every shader binding needs a slot, a params uniform or a scene buffer.
    for b in &group1 {
        let bound = pass
            .reads
            .iter()
            .chain(pass.writes.iter())
            .any(|s| s.slot == b.name);
        if !bound && !is_params(b) && !SCENE_BINDINGS.contains(&b.name.as_str()) {
            errors.push(GraphError::new(
                pass.location.clone(),
                ErrorKind::MissingBinding {
                    pass: pass.name.clone(),
                    binding: b.name.clone(),
                    group: b.group,
                    index: b.binding,
                },
            ));
        }
        if !bound
            && is_params(b)
            && let Some((size, members)) = reflect::params_layout(&module, &b.name)
            && let Err(message) = reflect::pack_params(size, &members, &pass.params)
        {
            errors.push(err(&pass.location, message));
        }
    }
    let is_raster = spec.shape != PassShape::Compute;
    let mut color_targets = 0;
    for (is_write, b) in pass
        .reads
        .iter_mut()
        .map(|b| (false, b))
        .chain(pass.writes.iter_mut().map(|b| (true, b)))
    {
        let Some(res) = schedule_resources.get(b.resource) else {
            // A culled pass's binding to a resource nothing live uses.
            continue;
        };
        let shader_binding = group1.iter().find(|s| s.name == b.slot);
        match shader_binding {
            None if spec.dynamic_slots => {
                // Not a shader binding: an attachment of a fullscreen pass.
                let is_depth =
                    matches!(res.desc, ResourceDesc::Texture { format, .. } if format.is_depth());
                if !is_raster || res.desc.kind() != ResourceKind::Texture {
                    errors.push(err(
                        &b.location,
                        format!("slot `{}` is not a binding of the shader", b.slot),
                    ));
                } else if is_depth {
                    b.access = Access::DepthTarget;
                } else if is_write {
                    b.access = Access::ColorTarget;
                    color_targets += 1;
                } else {
                    errors.push(err(
                        &b.location,
                        format!(
                            "slot `{}` is read but the shader declares no binding of that name",
                            b.slot
                        ),
                    ));
                }
            }
            None => {
                if !matches!(b.access, Access::ColorTarget | Access::DepthTarget) {
                    errors.push(err(
                        &b.location,
                        format!(
                            "the shader declares no binding named `{}` for this slot",
                            b.slot
                        ),
                    ));
                }
            }
            Some(sb) => {
                if sb.resource_kind() != Some(res.desc.kind()) {
                    errors.push(err(
                        &b.location,
                        format!(
                            "slot `{}` is bound to {} `{}`, but the shader declares it as {:?}",
                            b.slot,
                            res.desc.kind(),
                            res.name,
                            sb.kind
                        ),
                    ));
                    continue;
                }
                if let ResourceDesc::Texture {
                    format,
                    samples,
                    layers,
                    ..
                } = res.desc
                {
                    if let Err(why) = sb.accepts_format(format) {
                        errors.push(GraphError::new(
                            b.location.clone(),
                            ErrorKind::FormatMismatch {
                                resource: res.name.clone(),
                                declared: format.to_string(),
                                pass: pass.name.clone(),
                                slot: b.slot.clone(),
                                accepted: why,
                            },
                        ));
                    }
                    let (multi, arrayed) = match sb.kind {
                        BindingKind::Texture {
                            multisampled,
                            arrayed,
                            ..
                        } => (multisampled, arrayed),
                        BindingKind::StorageTexture { arrayed, .. } => (false, arrayed),
                        _ => (false, false),
                    };
                    if multi != (samples > 1) {
                        errors.push(err(&b.location, format!("`{}` has {samples} samples but the shader's `{}` is {}multisampled", res.name, b.slot, if multi { "" } else { "not " })));
                    }
                    if arrayed != (layers > 1) {
                        errors.push(err(&b.location, format!("`{}` has {layers} layers but the shader's `{}` is {}an array texture", res.name, b.slot, if arrayed { "" } else { "not " })));
                    }
                }
                if sb.writes() && !is_write {
                    errors.push(err(
                        &b.location,
                        format!(
                            "the shader writes `{}`; bind it under `writes`, not `reads`",
                            b.slot
                        ),
                    ));
                }
                if spec.dynamic_slots {
                    b.access = match sb.kind {
                        BindingKind::Uniform { .. } => Access::Uniform,
                        BindingKind::Texture { .. } => Access::Sampled,
                        _ if sb.writes() => Access::StorageWrite,
                        _ => Access::StorageRead,
                    };
                }
            }
        }
    }
    if spec.dynamic_slots
        && is_raster
        && color_targets == 0
        && !pass.writes.iter().any(|b| b.access == Access::DepthTarget)
        && pass.writes.iter().all(|b| b.access != Access::StorageWrite)
    {
        errors.push(err(
            &pass.location,
            "a fullscreen pass must write at least one target".into(),
        ));
    }
    errors
}

/// The group 0 layout: frame uniforms, the three samplers, the background image.
pub fn frame_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let all =
        wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE;
    let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: all,
        ty,
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("plait frame"),
        entries: &[
            entry(
                0,
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(FRAME_UNIFORMS_SIZE),
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
    })
}

fn filterable(format: Format) -> bool {
    !matches!(
        format,
        Format::R32Float | Format::Rg32Float | Format::Rgba32Float
    )
}

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
        colors: Vec<(plait_graph::ResourceId, bool)>,
        /// Per colour target: the single-sampled texture its samples resolve into.
        resolves: Vec<Option<plait_graph::ResourceId>>,
        depth: Option<(plait_graph::ResourceId, bool, bool)>,
        state: RasterState,
        draw: DrawWhat,
    },
    Compute {
        pipeline: wgpu::ComputePipeline,
        workgroups: [u32; 3],
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DrawWhat {
    Hair,
    Opaque,
    Fullscreen,
}

fn pass_error(pass: &ScheduledPass, message: impl Into<String>) -> GpuError {
    GpuError::Pass {
        pass: pass.name.clone(),
        message: message.into(),
    }
}

/// The default `PassType::build`: compose, reflect, lay out, create the pipeline.
pub fn build_shader_pass<T: PassType + ?Sized>(
    t: &T,
    pass: &ScheduledPass,
    ctx: &mut BuildContext<'_>,
) -> Result<Box<dyn PreparedPass>, GpuError> {
    Ok(Box::new(build_shader_pass_typed(t, pass, ctx)?))
}

/// [`build_shader_pass`] without the box, for passes that record it their own
/// way (e.g. [`ShaderPass::record_with_query`]).
pub fn build_shader_pass_typed<T: PassType + ?Sized>(
    t: &T,
    pass: &ScheduledPass,
    ctx: &mut BuildContext<'_>,
) -> Result<ShaderPass, GpuError> {
    let spec = t.spec();
    for feature in &spec.required_features {
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
    let (path, source) = shader_source_for_build(t, pass)?;
    // Everything below is checked by wgpu; its errors name this pass.
    let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let result = build_shader_pass_inner(t, pass, ctx, &spec, &path, &source);
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

fn build_shader_pass_inner<T: PassType + ?Sized>(
    t: &T,
    pass: &ScheduledPass,
    ctx: &mut BuildContext<'_>,
    spec: &PassTypeSpec,
    path: &Path,
    source: &str,
) -> Result<ShaderPass, GpuError> {
    let defines = t.defines(pass);
    let mut module = ctx.shaders.compose(path, source, &defines)?;
    let bindings = reflect::bindings(&module);
    let is_compute = spec.shape == PassShape::Compute;
    let device = ctx.device;
    let raster_state = if is_compute {
        None
    } else {
        Some(
            t.raster_state(pass, ctx.capabilities)
                .map_err(|m| pass_error(pass, m))?,
        )
    };
    // The depth attachment: written by the pass, or only tested (read).
    let depth_binding = pass
        .writes
        .iter()
        .map(|b| (b, true))
        .chain(pass.reads.iter().map(|b| (b, false)))
        .find(|(b, _)| b.access == Access::DepthTarget);
    let guard = match (&raster_state, depth_binding) {
        (Some(state), Some(_)) => DepthGuard::choose(
            Some(match state.depth {
                DepthMode::TestWrite(c) | DepthMode::TestOnly(c) => c,
            }),
            bindings.iter().any(|b| b.group == 1 && b.writes()),
            ctx.capabilities.early_depth_test,
        ),
        _ => DepthGuard::Unneeded,
    };
    if let (DepthGuard::InShader(_), Some((b, written))) = (guard, depth_binding) {
        let multisampled = matches!(
            ctx.schedule.resources[b.resource].desc,
            ResourceDesc::Texture { samples, .. } if samples > 1
        );
        let writes_depth = written
            && matches!(
                raster_state.as_ref().map(|s| s.depth),
                Some(DepthMode::TestWrite(_))
            );
        if multisampled || writes_depth {
            return Err(GpuError::MissingFeature {
                pass: pass.name.clone(),
                feature: "SHADER_EARLY_DEPTH_TEST (storage writes behind a multisampled or written depth target cannot be tested in the shader)".into(),
                adapter: ctx.adapter_name.to_owned(),
            });
        }
    }
    guard.apply(&mut module);

    // Group 1 from reflection.
    let mut layout_entries = Vec::new();
    let mut owned_buffers: Vec<(u32, wgpu::Buffer)> = Vec::new();
    let mut resource_entries: Vec<(u32, plait_graph::ResourceId)> = Vec::new();
    let mut scene_entries: Vec<(u32, &wgpu::Buffer)> = Vec::new();
    for b in bindings.iter().filter(|b| b.group == 1) {
        let visibility = if is_compute {
            wgpu::ShaderStages::COMPUTE
        } else if b.writes() {
            wgpu::ShaderStages::FRAGMENT
        } else {
            wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT
        };
        let slot = pass
            .reads
            .iter()
            .chain(pass.writes.iter())
            .find(|s| s.slot == b.name);
        let format = slot.and_then(|s| match ctx.schedule.resources[s.resource].desc {
            ResourceDesc::Texture { format, .. } => Some(format),
            _ => None,
        });
        let ty = match &b.kind {
            BindingKind::Uniform { .. } => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            BindingKind::Storage { read_only, .. } => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage {
                    read_only: *read_only,
                },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            BindingKind::Texture {
                sample,
                multisampled,
                arrayed,
            } => wgpu::BindingType::Texture {
                sample_type: match sample {
                    TextureSample::Float => wgpu::TextureSampleType::Float {
                        filterable: format.is_some_and(filterable) && !multisampled,
                    },
                    TextureSample::Uint => wgpu::TextureSampleType::Uint,
                    TextureSample::Sint => wgpu::TextureSampleType::Sint,
                    TextureSample::Depth => wgpu::TextureSampleType::Depth,
                },
                view_dimension: if *arrayed {
                    wgpu::TextureViewDimension::D2Array
                } else {
                    wgpu::TextureViewDimension::D2
                },
                multisampled: *multisampled,
            },
            BindingKind::StorageTexture {
                format: f,
                access_write,
                access_read,
                arrayed,
            } => wgpu::BindingType::StorageTexture {
                access: match (access_read, access_write) {
                    (true, true) => wgpu::StorageTextureAccess::ReadWrite,
                    (false, true) => wgpu::StorageTextureAccess::WriteOnly,
                    _ => wgpu::StorageTextureAccess::ReadOnly,
                },
                format: texture_format(f.ok_or_else(|| {
                    pass_error(
                        pass,
                        format!("storage texture `{}` has an unsupported format", b.name),
                    )
                })?),
                view_dimension: if *arrayed {
                    wgpu::TextureViewDimension::D2Array
                } else {
                    wgpu::TextureViewDimension::D2
                },
            },
            BindingKind::Sampler { .. } => {
                return Err(pass_error(
                    pass,
                    format!(
                        "sampler `{}` belongs in group 0 (import plait::frame)",
                        b.name
                    ),
                ));
            }
        };
        layout_entries.push(wgpu::BindGroupLayoutEntry {
            binding: b.binding,
            visibility,
            ty,
            count: None,
        });
        if slot.is_none() && is_params(b) {
            let (size, members) = reflect::params_layout(&module, &b.name).ok_or_else(|| {
                pass_error(pass, format!("`{}` must be a uniform struct", b.name))
            })?;
            let bytes = reflect::pack_params(size, &members, &pass.params)
                .map_err(|m| pass_error(pass, m))?;
            let buffer = wgpu::util::DeviceExt::create_buffer_init(
                device,
                &wgpu::util::BufferInitDescriptor {
                    label: Some(&format!("{} params", pass.name)),
                    contents: &bytes,
                    usage: wgpu::BufferUsages::UNIFORM,
                },
            );
            owned_buffers.push((b.binding, buffer));
        } else if let Some(s) = slot {
            resource_entries.push((b.binding, s.resource));
        } else {
            let hair = ctx
                .geometry
                .hair
                .as_ref()
                .ok_or_else(|| pass_error(pass, "the scene has no hair to bind"))?;
            let buf = if b.name == "hair_vertices" {
                &hair.vertices
            } else {
                &hair.indices
            };
            scene_entries.push((b.binding, buf));
        }
    }
    if let (DepthGuard::InShader(_), Some((b, _))) = (guard, depth_binding) {
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
        resource_entries.push((GUARD_BINDING, b.resource));
    }
    let group1_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(&pass.name),
        entries: &layout_entries,
    });
    let bind_group = if layout_entries.is_empty() {
        None
    } else {
        let mut entries: Vec<wgpu::BindGroupEntry> = Vec::new();
        for (binding, buf) in &owned_buffers {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: buf.as_entire_binding(),
            });
        }
        for (binding, id) in &resource_entries {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: ctx.pool.binding_resource(*id),
            });
        }
        for (binding, buf) in &scene_entries {
            entries.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource: buf.as_entire_binding(),
            });
        }
        Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&pass.name),
            layout: &group1_layout,
            entries: &entries,
        }))
    };
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
                source: wgpu::ShaderSource::Naga(Cow::Owned(module.clone())),
            })
        })
    };
    // The library modules' digest too: they may be edited while plait runs.
    let library = ctx.shaders.library_digest();
    let shader_key: [&dyn std::fmt::Debug; 6] =
        [&path, &source, &library, &defines, &layout_entries, &guard];
    let clears: Vec<_> = pass
        .writes
        .iter()
        .filter(|b| b.access == Access::StorageWrite && !b.loads)
        .map(|b| b.resource)
        .collect();

    let kind = if is_compute {
        let entry = module
            .entry_points
            .iter()
            .find(|e| e.stage == naga::ShaderStage::Compute)
            .ok_or_else(|| pass_error(pass, "the shader has no @compute entry point"))?;
        let wg = entry.workgroup_size;
        let threads = t.compute_threads(pass, ctx.schedule);
        let workgroups = [0, 1, 2].map(|i| threads[i].div_ceil(wg[i].max(1)));
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
        let state = raster_state.expect("raster passes have a raster state");
        let draw = match spec.shape {
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
        let mut colors = Vec::new();
        let mut color_states = Vec::new();
        let mut samples = 1;
        // A colour target `X` with a written slot `X_resolve` resolves its
        // samples into that resource at the end of the pass (MSAA).
        let is_resolve = |slot: &str| {
            slot.strip_suffix("_resolve").is_some_and(|base| {
                pass.writes
                    .iter()
                    .any(|o| o.slot == base && o.access == Access::ColorTarget)
            })
        };
        let mut resolves = Vec::new();
        for b in pass
            .writes
            .iter()
            .filter(|b| b.access == Access::ColorTarget && !is_resolve(&b.slot))
        {
            resolves.push(
                pass.writes
                    .iter()
                    .find(|r| r.slot == format!("{}_resolve", b.slot))
                    .map(|r| r.resource),
            );
            let ResourceDesc::Texture {
                format, samples: s, ..
            } = ctx.schedule.resources[b.resource].desc
            else {
                return Err(pass_error(
                    pass,
                    format!("colour target `{}` is not a texture", b.slot),
                ));
            };
            samples = s;
            let blend = state.blend.get(colors.len()).copied().flatten();
            let write_mask = state
                .write_mask
                .get(colors.len())
                .copied()
                .unwrap_or(wgpu::ColorWrites::ALL);
            color_states.push(Some(wgpu::ColorTargetState {
                format: texture_format(format),
                blend,
                write_mask,
            }));
            colors.push((b.resource, b.loads || state.load_colors));
        }
        let mut depth = None;
        let depth_stencil = match depth_binding {
            Some((b, written)) => {
                let ResourceDesc::Texture {
                    format, samples: s, ..
                } = ctx.schedule.resources[b.resource].desc
                else {
                    return Err(pass_error(pass, "depth target is not a texture"));
                };
                samples = s;
                let (write, compare) = match (state.depth, written) {
                    (DepthMode::TestWrite(c), true) => (true, c),
                    (DepthMode::TestWrite(c), false) | (DepthMode::TestOnly(c), _) => (false, c),
                };
                depth = Some((b.resource, b.loads || !written, write));
                Some(wgpu::DepthStencilState {
                    format: texture_format(format),
                    depth_write_enabled: Some(write),
                    depth_compare: Some(compare),
                    stencil: Default::default(),
                    bias: Default::default(),
                })
            }
            None => None,
        };
        let vertex_layouts = match draw {
            DrawWhat::Hair => vec![Some(hair_vertex_layout())],
            DrawWhat::Opaque => vec![Some(opaque_vertex_layout())],
            DrawWhat::Fullscreen => vec![],
        };
        let has_fragment = module
            .entry_points
            .iter()
            .any(|e| e.stage == naga::ShaderStage::Fragment);
        let primitive = wgpu::PrimitiveState {
            topology: if draw == DrawWhat::Hair {
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
            colors,
            resolves,
            depth,
            state,
            draw,
        }
    };
    Ok(ShaderPass {
        name: pass.name.clone(),
        kind,
        bind_group,
        clears,
    })
}

fn shader_source_for_build<T: PassType + ?Sized>(
    t: &T,
    pass: &ScheduledPass,
) -> Result<(PathBuf, Cow<'static, str>), GpuError> {
    if let Some((name, text)) = t.shader() {
        return Ok(crate::shader::library_source(name, text)?);
    }
    let path = pass
        .shader
        .clone()
        .ok_or_else(|| pass_error(pass, "needs `shader = \"path.wgsl\"`"))?;
    let text = crate::shader::read_shader_file(&path)
        .map_err(|e| pass_error(pass, format!("cannot read shader {}: {e}", path.display())))?;
    Ok((path, text))
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
            }
        }
        match &self.kind {
            ShaderPassKind::Compute {
                pipeline,
                workgroups,
            } => {
                let mut cpass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(&self.name),
                    timestamp_writes: None,
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
                colors,
                resolves,
                depth,
                state,
                draw,
            } => {
                let color_attachments: Vec<_> = colors
                    .iter()
                    .zip(resolves)
                    .map(|(&(id, loads), resolve)| {
                        let view = ctx
                            .pool
                            .texture(id)
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
                                    wgpu::LoadOp::Clear(state.clear_color)
                                },
                                store: wgpu::StoreOp::Store,
                            },
                        })
                    })
                    .collect();
                let depth_attachment = depth.map(|(id, loads, write)| {
                    let view = ctx
                        .pool
                        .texture(id)
                        .map(|(_, v)| v)
                        .expect("depth targets are textures (checked at build)");
                    wgpu::RenderPassDepthStencilAttachment {
                        view,
                        // Only tested, never written: attached read-only, so the
                        // pass may also sample it (fragment lists test it by hand).
                        depth_ops: (write || !loads).then_some(wgpu::Operations {
                            load: if loads {
                                wgpu::LoadOp::Load
                            } else {
                                wgpu::LoadOp::Clear(state.clear_depth)
                            },
                            store: wgpu::StoreOp::Store,
                        }),
                        stencil_ops: None,
                    }
                });
                let mut rpass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(&self.name),
                    color_attachments: &color_attachments,
                    depth_stencil_attachment: depth_attachment,
                    timestamp_writes: None,
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
                    DrawWhat::Hair => ctx.geometry.hair.as_ref(),
                    DrawWhat::Opaque => ctx.geometry.opaque.as_ref(),
                    DrawWhat::Fullscreen => {
                        rpass.draw(0..3, 0..1);
                        None
                    }
                };
                if let Some(b) = buffers {
                    rpass.set_vertex_buffer(0, b.vertices.slice(..));
                    rpass.set_index_buffer(b.indices.slice(..), wgpu::IndexFormat::Uint32);
                    rpass.draw_indexed(0..b.index_count, 0, 0..1);
                }
                if query.is_some() {
                    rpass.end_occlusion_query();
                }
            }
        }
    }
}
