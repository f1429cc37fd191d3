//! The [`PassType`] trait, what building and recording a pass can use, and the
//! library of pass types a run knows.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use plait_graph::{Location, PassTypeSpec, RasterDecl, Schedule, ScheduledPass};

use super::build::{ShaderDraw, build_draw};
use super::defaults::{default_defines, default_threads};
use super::state::RasterState;
use crate::geometry::SceneGeometry;
use crate::pool::ResourcePool;
use crate::shader::Define;
use crate::{Capabilities, GpuError};

/// Names of scene inputs a shader can bind in group 1 without a slot: the
/// hair's, the wisps' (`geometry = wisps`: `plait_hair::wisps::WispMesh`'s
/// vertices and triangle-list indices) and the opaque geometry's storage
/// buffers, and the scene's environment image (`texture_2d<f32>`, rgba32float, equirectangular, see
/// `plait_hair::environment`).
pub const SCENE_BINDINGS: &[&str] = &[
    "hair_vertices",
    "hair_indices",
    "wisp_vertices",
    "wisp_indices",
    "opaque_vertices",
    "opaque_indices",
    "environment_source",
];

/// One pass type of the library.
pub trait PassType: Send + Sync {
    fn spec(&self) -> PassTypeSpec;

    /// The pass's own WGSL, by library path (`shaders/passes/occupancy.wgsl`,
    /// read from the search path or the built-in copies); `None` means the
    /// pipeline file's `shader = "…"`.
    fn shader(&self) -> Option<&str>;

    /// Shader defines. The default: every int and bool param as its
    /// upper-case name (`slices = 128` → `#if SLICES == 128`).
    fn defines(&self, pass: &ScheduledPass) -> Vec<(String, Define)> {
        default_defines(pass)
    }

    /// Pipeline state of a raster or fullscreen pass whose type sets it in
    /// Rust. Types with `state_from_data` get theirs from
    /// [`PassType::raster_decl`] instead.
    fn raster_state(
        &self,
        _pass: &ScheduledPass,
        _caps: &Capabilities,
    ) -> Result<RasterState, String> {
        Ok(RasterState::default())
    }

    /// The TOML raster state of a pass of a `state_from_data` type: the
    /// pass's own keys, over the type's defaults where it has some.
    fn raster_decl(&self, pass: &ScheduledPass) -> RasterDecl {
        pass.raster.clone()
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
    /// (depth peeling, k-means) override this; most use the default, one draw
    /// or dispatch of the type's shader.
    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let draw = ShaderDraw::of(self, pass, ctx)?;
        Ok(Box::new(build_draw(&draw, pass, ctx)?))
    }
}

/// A pass's recording, awaited ([`PreparedPass::record_async`]).
pub type Recording<'a> = std::pin::Pin<Box<dyn std::future::Future<Output = ()> + 'a>>;

/// A pass's check after its frame, awaited ([`PreparedPass::finish_async`]).
pub type Finishing<'a> =
    std::pin::Pin<Box<dyn std::future::Future<Output = Result<(), String>> + 'a>>;

/// GPU objects of one pass, ready to record every frame.
pub trait PreparedPass {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder);

    /// What the executor calls: [`PreparedPass::record`], for a pass that
    /// must see a GPU result mid-frame (depth peeling's occlusion queries)
    /// awaiting it. A browser cannot block inside `record`: there the
    /// result arrives through the page's event loop, so the pass awaits it
    /// here. The default records at once.
    fn record_async<'a>(
        &'a self,
        ctx: &'a RecordContext<'a>,
        encoder: &'a mut wgpu::CommandEncoder,
    ) -> Recording<'a> {
        Box::pin(async move { self.record(ctx, encoder) })
    }

    /// Numbers the last `record` found out (e.g. the layers a depth-peeling
    /// pass needed), reported per pass in the executor's `FrameReport`.
    fn stats(&self) -> Vec<(String, f64)> {
        Vec::new()
    }

    /// Called once the frame's commands have finished on the GPU: a pass
    /// that reads back a status of its own (a simulation that went unstable)
    /// fails the frame here, so its image is never returned.
    fn finish(&self, _device: &wgpu::Device) -> Result<(), String> {
        Ok(())
    }

    /// What the executor calls: [`PreparedPass::finish`], for a pass whose
    /// status is read back awaited (a browser cannot block on the mapping).
    /// The default calls `finish`.
    fn finish_async<'a>(&'a self, device: &'a wgpu::Device) -> Finishing<'a> {
        Box::pin(async move { self.finish(device) })
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
    pub base_dir: &'a Path,
    /// The session's shaders: every module is composed from their texts.
    pub shaders: &'a crate::modules::Shaders,
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
    /// The frame's timestamps: a pass that begins wgpu render or compute
    /// passes itself gives each [`RecordContext::render_timestamps`] or
    /// [`RecordContext::compute_timestamps`] as its `timestamp_writes`, which
    /// is how a browser (WebGPU: no timestamps inside encoders) times it.
    pub timestamps: Option<&'a crate::timing::Timestamps>,
    /// The frame's `head_model` (`FrameUniforms`, column-major): where the
    /// head's meshes are, for a structure's instance transforms
    /// (`strand_structure`), which are the CPU's, not a shader's.
    pub head_model: [[f32; 4]; 4],
    /// Camera hair draws draw their quads of strands wider than a pixel:
    /// some may be ([`crate::frame::FrameUniforms::draws_wide_strands`], or the
    /// hair is moved on the GPU). Without, the quad draw — six vertices per
    /// hair vertex, every one degenerate — would cost a camera pass its
    /// vertex work several times over for nothing.
    pub wide_strands: bool,
    /// [`RecordContext::wide_strands`] for light-view hair draws, in the
    /// light maps' texels ([`crate::frame::FrameUniforms::draws_wide_light_strands`]).
    pub wide_light_strands: bool,
}

impl<'a> RecordContext<'a> {
    /// The `timestamp_writes` of a render pass this pass begins.
    pub fn render_timestamps(&self) -> Option<wgpu::RenderPassTimestampWrites<'a>> {
        self.timestamps.and_then(|t| t.render_writes())
    }

    /// The `timestamp_writes` of a compute pass this pass begins.
    pub fn compute_timestamps(&self) -> Option<wgpu::ComputePassTimestampWrites<'a>> {
        self.timestamps.and_then(|t| t.compute_writes())
    }
}

/// The library of one session: the pass types available to it, by name,
/// and its shaders (the WGSL library, the composer, every shader text it
/// read). A value read once and passed to compile and build; a front end
/// that reloads reads a new one.
#[derive(Default)]
pub struct PassLibrary {
    pub types: IndexMap<String, Box<dyn PassType>>,
    /// The shader side: WGSL modules, points and their providers, composed
    /// modules and shader texts ([`crate::modules::Shaders`]).
    pub shaders: std::sync::Arc<crate::modules::Shaders>,
    /// See [`plait_graph::Registry::shared_params`].
    pub shared_params: Vec<plait_graph::ParamSpec>,
    /// See [`plait_graph::Registry::shared_slots`].
    pub shared_slots: Vec<plait_graph::SlotSpec>,
    /// Pass-type files found but not loadable (file:line:col each): every
    /// compile with this library reports them.
    pub problems: Vec<plait_graph::Error>,
    /// Checks of what a shared provider needs, run on every pass like
    /// [`PassType::check_sizes`] (a provider's loop bounded by a texture's
    /// size, whichever pass imports it).
    pub shared_checks: Vec<SharedCheck>,
}

/// A check [`PassLibrary::shared_checks`] runs on every pass: the message
/// names what to change.
pub type SharedCheck =
    fn(&plait_graph::ScheduledPass, &[plait_graph::ResolvedResource]) -> Result<(), String>;

impl PassLibrary {
    pub fn add(&mut self, t: impl PassType + 'static) {
        self.insert(Box::new(t));
    }

    pub fn insert(&mut self, t: Box<dyn PassType>) {
        self.types.insert(t.spec().name.clone(), t);
    }

    pub fn get(&self, name: &str) -> Option<&dyn PassType> {
        self.types.get(name).map(|b| b.as_ref())
    }

    /// The type a scheduled pass was resolved to at compile, by its handle
    /// ([`plait_graph::PassTypeId`], an index into [`Self::registry`]'s
    /// types, which are this library's in order): no lookup by name. `None`
    /// for a pass whose type was unknown (a compile error) or a schedule
    /// compiled with another library (the handle names another type).
    pub fn pass_type(&self, pass: &ScheduledPass) -> Option<&dyn PassType> {
        let (name, t) = self.types.get_index(pass.type_id?.index())?;
        (*name == pass.type_name).then_some(t.as_ref())
    }

    /// The specs for the graph crate's checks.
    pub fn registry(&self) -> plait_graph::Registry {
        let mut r = plait_graph::Registry::new();
        for t in self.types.values() {
            r.register(t.spec());
        }
        r.shared_params = self.shared_params.clone();
        r.shared_slots = self.shared_slots.clone();
        r
    }
}

/// The shader source of a pass: built in, or the file the pipeline names,
/// as `shaders` read it (the first time, from disk: compile; then the same
/// text: build). An error says where the pipeline named it (or should have).
pub fn shader_source<T: PassType + ?Sized>(
    t: &T,
    pass: &ScheduledPass,
    shaders: &crate::modules::Shaders,
) -> Result<(PathBuf, Cow<'static, str>), (Location, String)> {
    if let Some(name) = t.shader() {
        // The copy on the search path when there is one (edits apply without
        // a rebuild), else the built-in text.
        return shaders
            .library_file(name)
            .map_err(|e| (pass.location.clone(), e.message));
    }
    let loc = pass
        .shader_location
        .clone()
        .unwrap_or_else(|| pass.location.clone());
    let Some(path) = &pass.shader else {
        return Err((loc, "needs `shader = \"path.wgsl\"`".into()));
    };
    match shaders.shader_file(path) {
        Ok(text) => Ok((path.clone(), text)),
        Err(e) => Err((loc, format!("{}: cannot read file: {e}", path.display()))),
    }
}
