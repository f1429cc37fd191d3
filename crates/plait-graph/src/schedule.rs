//! The compiled form of a pipeline: plain data, free of wgpu, that the GPU
//! crate turns into command buffers (vello's `Recording` → engine split).

use indexmap::IndexMap;
use std::path::{Path, PathBuf};

use crate::error::Location;
use crate::format::Format;
use crate::spec::{Access, Draw, PassShape, ResourceKind, View};
use crate::value::Value;

/// Index into [`Schedule::resources`]. A type of its own, so a pass index,
/// a physical allocation or a binding number cannot be passed for one; the
/// index comes out through [`ResourceId::index`] only where a list is indexed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
#[serde(transparent)]
pub struct ResourceId(usize);

/// Index into [`Schedule::physical`] (see [`ResourceId`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
#[serde(transparent)]
pub struct PhysicalId(usize);

/// Index into the pass types of the [`crate::Registry`] a schedule was
/// compiled with (the pass library's, in the same order): the pass type
/// resolved once at compile, so build takes the type by this handle and
/// never looks its name up again.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
#[serde(transparent)]
pub struct PassTypeId(usize);

/// A slot a pass type declares: its index among the type's inputs, its
/// outputs ([`crate::PassTypeSpec::slot_id`]), or the registry's shared
/// slots (the ones every hair draw takes). Compile gives each binding the
/// handle of its slot, so build and record find a slot by comparing
/// handles, never names; a name that matches no slot is an error at compile
/// with the nearest one. A Rust pass type names its own slots by constant
/// handles (`SlotId::Output(2)`), each checked against its name by a test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum SlotId {
    Input(usize),
    Output(usize),
    Shared(usize),
}

impl PassTypeId {
    /// The pass type at `index` of the registry's types.
    pub const fn new(index: usize) -> Self {
        PassTypeId(index)
    }
    /// Its position in the registry's (and the library's) types.
    pub const fn index(self) -> usize {
        self.0
    }
}

impl ResourceId {
    /// The resource at `index` of [`Schedule::resources`].
    pub const fn new(index: usize) -> Self {
        ResourceId(index)
    }
    /// Its position in [`Schedule::resources`].
    pub const fn index(self) -> usize {
        self.0
    }
}

impl PhysicalId {
    /// The allocation at `index` of [`Schedule::physical`].
    pub const fn new(index: usize) -> Self {
        PhysicalId(index)
    }
    /// Its position in [`Schedule::physical`].
    pub const fn index(self) -> usize {
        self.0
    }
}

impl std::fmt::Display for ResourceId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl std::fmt::Display for PhysicalId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

/// A resource's size and format after every `${param}` and `screen` is resolved.
#[derive(Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ResourceDesc {
    Texture {
        format: Format,
        width: u32,
        height: u32,
        layers: u32,
        samples: u32,
    },
    Buffer {
        size: u64,
    },
    /// The frame's strands for ray queries: sized by the scene's hair when
    /// built, so its memory is the engine's to report.
    AccelerationStructure,
}

impl ResourceDesc {
    pub fn kind(&self) -> ResourceKind {
        match self {
            ResourceDesc::Texture { .. } => ResourceKind::Texture,
            ResourceDesc::Buffer { .. } => ResourceKind::Buffer,
            ResourceDesc::AccelerationStructure => ResourceKind::AccelerationStructure,
        }
    }

    pub fn bytes(&self) -> u64 {
        match *self {
            ResourceDesc::Texture {
                format,
                width,
                height,
                layers,
                samples,
            } => {
                format.bytes_per_texel()
                    * width as u64
                    * height as u64
                    * layers as u64
                    * samples as u64
            }
            ResourceDesc::Buffer { size } => size,
            // The driver's, at build (plait_gpu::strand_structure).
            ResourceDesc::AccelerationStructure => 0,
        }
    }

    /// `rgba16float 1280x720` / `buffer 4194304 B`, for graphs and tables.
    pub fn label(&self) -> String {
        match *self {
            ResourceDesc::Texture {
                format,
                width,
                height,
                layers,
                samples,
            } => {
                let mut s = format!("{format} {width}x{height}");
                if layers > 1 {
                    s += &format!("x{layers}");
                }
                if samples > 1 {
                    s += &format!(" {samples}xMSAA");
                }
                s
            }
            ResourceDesc::Buffer { size } => format!("buffer {size} B"),
            ResourceDesc::AccelerationStructure => "acceleration structure".into(),
        }
    }
}

/// One slot of a scheduled pass bound to a resource.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Binding {
    /// The slot's name, for messages, graphs and the shader binding it
    /// feeds; code finds a slot by [`Binding::slot_id`].
    pub slot: String,
    /// The slot resolved at compile: `None` for a slot the type does not
    /// declare (a data-only pass's slots are its shader's bindings).
    #[serde(skip)]
    pub slot_id: Option<SlotId>,
    /// For a colour target `X_resolve` of a pass that also writes `X`: the
    /// index in [`ScheduledPass::writes`] of `X`, whose samples it receives
    /// (paired by name once, at compile).
    #[serde(skip)]
    pub resolves: Option<usize>,
    /// `None` only in a culled pass, when its resource was dropped because
    /// only culled passes use it (see [`Binding::resource_name`]). While
    /// compile runs it is the declared index (`[resources]`, then the
    /// scene's); the schedule renumbers it into [`Schedule::resources`].
    pub resource: Option<ResourceId>,
    /// The resource's name as written in the file.
    pub resource_name: String,
    pub access: Access,
    /// Keeps previous contents (see `SlotSpec::loads`). Compile sets it to
    /// `false` on the first writer of a resource even if its slot loads:
    /// with nothing written before, "accumulate" means "clear, then
    /// accumulate", so the GPU side must clear there.
    pub loads: bool,
    #[serde(skip)]
    pub location: Location,
    /// One of the slots every pass drawing hair takes
    /// ([`crate::Registry::shared_slots`]): a shader that does not read it
    /// (a depth-only hair draw) leaves it unbound.
    #[serde(skip)]
    pub shared: bool,
}

impl Binding {
    /// The resource of a live pass's binding: compile gives each one.
    pub fn id(&self) -> ResourceId {
        self.resource
            .expect("a live pass's binding names a live resource")
    }

    /// Its resource among `resources`, `None` if it was dropped.
    pub fn resolved<'r>(&self, resources: &'r [ResolvedResource]) -> Option<&'r ResolvedResource> {
        self.resource.and_then(|id| resources.get(id.index()))
    }
}

/// A technique a pipeline chose for one of its choice points.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ChosenTechnique {
    pub point: String,
    pub name: String,
    pub path: PathBuf,
    /// The params its file defines (its `[params]` keys).
    pub params: Vec<String>,
    /// Its `[param_ranges]`.
    #[serde(skip)]
    pub ranges: Vec<crate::techniques::technique_keys::ParamRange>,
    /// What the engine does for it (`[technique] engine`).
    #[serde(skip)]
    pub engine: Vec<String>,
    /// What it needs of the adapter (`[technique] adapter`, each one of
    /// `techniques::technique_keys::ADAPTER_NEEDS`), where each is written.
    #[serde(skip)]
    pub adapter: Vec<crate::error::Spanned<String>>,
}

impl ChosenTechnique {
    /// `self_shadow/occupancy`.
    pub fn label(&self) -> String {
        format!("{}/{}", self.point, self.name)
    }

    /// Whether `file` belongs to this technique: a file of its folder
    /// (`techniques/<point>/<name>/`), or one it includes from its point's
    /// folder — a fragment, or another technique's file — since a pipeline
    /// chooses one technique per point.
    pub fn owns(&self, file: &Path) -> bool {
        let point_folder = self.path.parent().and_then(Path::parent);
        point_folder.is_some_and(|p| file.starts_with(p))
    }
}

/// A pass, resolved against its type and placed in the schedule.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ScheduledPass {
    pub name: String,
    pub type_name: String,
    /// `type_name` resolved at compile; `None` only in a pass whose type is
    /// unknown, which is a compile error (no schedule is built with one).
    #[serde(skip)]
    pub type_id: Option<PassTypeId>,
    pub shape: PassShape,
    /// Raster passes only.
    pub view: Option<View>,
    /// Raster passes only.
    pub draw: Option<Draw>,
    pub reads: Vec<Binding>,
    pub writes: Vec<Binding>,
    /// Every param of the type, defaults filled in, values checked.
    pub params: IndexMap<String, Value>,
    /// Resolved against the directory of the file that named it.
    pub shader: Option<PathBuf>,
    #[serde(skip)]
    pub shader_location: Option<Location>,
    /// Raster state the pass sets in its file (`depth`, `blend`, `cull`).
    #[serde(skip)]
    pub raster: crate::raster_decl::RasterDecl,
    /// For each blend of the pass over its type's
    /// ([`crate::PassTypeSpec::raster`] overridden by `raster`, the decl
    /// build uses), in order: the index in `writes` of the slot it names,
    /// `None` if the pass writes no such slot. Resolved at compile, so state
    /// is built from indices, not names.
    #[serde(skip)]
    pub blend_writes: Vec<Option<usize>>,
    #[serde(skip)]
    pub location: Location,
    /// The technique that declared the pass (`self_shadow/occupancy`), if any.
    pub technique: Option<String>,
    /// `run = "once"`: a precompute recorded on an executor's first frame
    /// only; what it writes is kept across frames ([`ResolvedResource::kept`]).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub run_once: bool,
}

impl ScheduledPass {
    /// The binding of the declared slot `slot`, written or read.
    pub fn bound(&self, slot: SlotId) -> Option<&Binding> {
        self.writes
            .iter()
            .chain(self.reads.iter())
            .find(|b| b.slot_id == Some(slot))
    }

    /// Whether write `index` is an `X_resolve` receiving the samples of a
    /// colour target `X` (it is not drawn into).
    pub fn is_resolve(&self, index: usize) -> bool {
        self.writes[index]
            .resolves
            .and_then(|x| self.writes.get(x))
            .is_some_and(|x| x.access == Access::ColorTarget)
    }
}

/// Why a pass does not run.
#[derive(Clone, Debug, serde::Serialize)]
pub struct CulledPass {
    pub pass: ScheduledPass,
    pub reason: String,
}

/// A declared resource with its lifetime in the schedule.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ResolvedResource {
    pub name: String,
    pub desc: ResourceDesc,
    /// Index in `Schedule::passes` of the first and last pass that touch it.
    pub first_use: usize,
    pub last_use: usize,
    pub physical: PhysicalId,
    /// A scene resource ([`crate::scene_resources`]): the scene's buffer,
    /// not allocated by the pipeline (its `desc` is a 0-byte buffer).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub scene: bool,
    /// Whether the contents outlive the frame (`persistent`, `history`).
    #[serde(skip_serializing_if = "Lifetime::is_frame")]
    pub lifetime: Lifetime,
    /// Its contents outlive the frame (written by a `run = "once"` pass), so
    /// it lives from the first pass to the last and shares no allocation.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub kept: bool,
    /// `clear = …`: every clear of this texture (its first pass in the
    /// frame, or a plain write) fills it with this value, not zeros.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub clear: Option<crate::clear::ClearValue>,
    #[serde(skip)]
    pub location: Location,
}

/// How long a resource's contents live. Anything but [`Lifetime::Frame`]
/// spans the whole schedule and has an allocation of its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Lifetime {
    /// Written and read within one frame; its memory may be shared.
    Frame,
    /// `persistent = true`: kept between frames, never cleared by the engine.
    Persistent,
    /// `history = frames`: this frame's version; the engine copies it into
    /// `NAME.previous` after every frame.
    History { frames: u32 },
    /// `NAME.previous…`: the version of `of` from `frames_ago` frames
    /// before, read-only; zero on the first frame.
    Previous { of: ResourceId, frames_ago: u32 },
}

impl Lifetime {
    pub fn is_frame(&self) -> bool {
        *self == Lifetime::Frame
    }
}

/// One copy the engine records after a frame's passes to age a history:
/// `from` (a version) into `to` (the version one frame older). The list runs
/// oldest first, so each version is read before it is overwritten.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct HistoryCopy {
    pub from: ResourceId,
    pub to: ResourceId,
}

/// One GPU allocation; several resources with identical descriptors and
/// disjoint lifetimes share it (wgpu cannot alias memory of different shapes).
#[derive(Clone, Debug, serde::Serialize)]
pub struct PhysicalResource {
    pub desc: ResourceDesc,
    pub users: Vec<ResourceId>,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct MemoryReport {
    /// Bytes of all physical allocations (with sharing).
    pub peak_bytes: u64,
    /// Bytes if every resource had its own allocation.
    pub unpooled_bytes: u64,
}

/// The compiled pipeline.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Schedule {
    pub name: String,
    pub description: String,
    /// The pipeline file, every file it extends, then the technique files.
    pub files: Vec<PathBuf>,
    /// `[techniques]`: the technique chosen for each choice point.
    pub techniques: Vec<ChosenTechnique>,
    /// Resolved `[params]` (after `--set`), for passes that read pipeline-wide values.
    pub params: IndexMap<String, Value>,
    /// Live passes in execution order.
    pub passes: Vec<ScheduledPass>,
    pub culled: Vec<CulledPass>,
    pub resources: Vec<ResolvedResource>,
    /// Declared resources used only by culled passes (or by nothing), not allocated.
    pub dropped_resources: Vec<String>,
    pub physical: Vec<PhysicalResource>,
    pub outputs: Vec<ResourceId>,
    /// Copies that age every history after the frame (oldest first).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub history: Vec<HistoryCopy>,
    pub memory: MemoryReport,
    /// Counters of what bounded buffers could not hold (`overflow = {…}` on a
    /// resource), which the engine reads back after every frame.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub overflow: Vec<OverflowCounter>,
    /// What compile changed to fit the adapter (a format it cannot blend).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

/// A counter buffer declared with `overflow = {…}` ([`crate::overflow`]):
/// word `dropped_word` counts what the buffer `of` could not hold, word
/// `needed_word` the capacity that would have held it all, in items of
/// `of`; `of` holds `value × per` items, `value` being the param `param`.
#[derive(Clone, Debug, serde::Serialize)]
pub struct OverflowCounter {
    pub counter: ResourceId,
    pub counter_name: String,
    /// The bounded buffer.
    pub of: String,
    /// `None` for a counter of incomplete invocations only (no `of`; `of`
    /// and `param` are then empty).
    pub dropped_word: Option<u32>,
    pub needed_word: Option<u32>,
    /// The word counting shader invocations that could not finish their
    /// work (`incomplete`, [`crate::overflow`]); any count fails the frame.
    pub incomplete_word: Option<u32>,
    pub param: String,
    /// The param's value in this schedule.
    pub value: i64,
    pub per: u64,
    /// The param has its technique's default (nobody chose it): the session
    /// may raise it until `of` holds everything. `false` when the user set
    /// it (a `--set` flag or a pipeline file): then drops are reported.
    pub grows: bool,
    /// Where the param's value was set.
    #[serde(skip)]
    pub param_location: Location,
}

impl OverflowCounter {
    /// Items `of` holds.
    pub fn capacity(&self) -> u64 {
        self.value.max(0) as u64 * self.per
    }

    /// The smallest value of `param` that holds `needed` items.
    pub fn value_for(&self, needed: u64) -> u64 {
        needed.div_ceil(self.per).max(1)
    }
}

impl Schedule {
    pub fn resource(&self, name: &str) -> Option<ResourceId> {
        self.resources
            .iter()
            .position(|r| r.name == name)
            .map(ResourceId::new)
    }

    /// Names of other resources sharing `id`'s physical allocation.
    pub fn shares_memory_with(&self, id: ResourceId) -> Vec<&str> {
        let phys = &self.physical[self.resource_at(id).physical.index()];
        phys.users
            .iter()
            .filter(|&&u| u != id)
            .map(|&u| self.resource_at(u).name.as_str())
            .collect()
    }

    /// The resource `id` names.
    pub fn resource_at(&self, id: ResourceId) -> &ResolvedResource {
        &self.resources[id.index()]
    }
}

/// What compile needs to know about the run that is not in the file.
#[derive(Clone, Debug)]
pub struct CompileOptions {
    /// Render size, what `size = "screen"` means.
    pub screen: (u32, u32),
    /// The adapter's `max_texture_dimension_2d` (8192 when checking without a GPU, WebGPU's default).
    pub max_texture_dimension: u32,
    /// The largest buffer a pass can bind as storage: the adapter's
    /// `max_storage_buffer_binding_size`, or WebGPU's default (128 MiB) when
    /// checking without a GPU — a pipeline that passes runs on any adapter.
    pub max_buffer_binding_size: u64,
    /// What the adapter can do that changes the schedule (formats).
    pub capabilities: crate::compile::fit::Capabilities,
}

/// WebGPU's default `max_storage_buffer_binding_size`.
pub const DEFAULT_MAX_BUFFER_BINDING_SIZE: u64 = 128 << 20;

/// Sample counts a texture may have; each format allows a subset.
pub const SAMPLE_COUNTS: [u32; 5] = [1, 2, 4, 8, 16];

impl Default for CompileOptions {
    fn default() -> Self {
        CompileOptions {
            screen: (960, 720),
            max_texture_dimension: 8192,
            max_buffer_binding_size: DEFAULT_MAX_BUFFER_BINDING_SIZE,
            capabilities: Default::default(),
        }
    }
}

/// `resources[id]`: a list of resources is indexed by a [`ResourceId`] only,
/// so an id of another list (a pass index, an allocation) does not compile.
macro_rules! typed_index {
    ($id:ty => $item:ty) => {
        impl std::ops::Index<$id> for [$item] {
            type Output = $item;
            fn index(&self, id: $id) -> &$item {
                &self[id.index()]
            }
        }
        impl std::ops::IndexMut<$id> for [$item] {
            fn index_mut(&mut self, id: $id) -> &mut $item {
                &mut self[id.index()]
            }
        }
        impl std::ops::Index<$id> for Vec<$item> {
            type Output = $item;
            fn index(&self, id: $id) -> &$item {
                &self.as_slice()[id]
            }
        }
        impl std::ops::IndexMut<$id> for Vec<$item> {
            fn index_mut(&mut self, id: $id) -> &mut $item {
                &mut self.as_mut_slice()[id]
            }
        }
    };
}

typed_index!(ResourceId => ResolvedResource);
typed_index!(PhysicalId => PhysicalResource);
