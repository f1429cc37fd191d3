//! Pass type declarations: what a pass type reads, writes and accepts as params.
//!
//! The pass library (a crate with GPU code) registers one [`PassTypeSpec`] per
//! pass type; the graph crate checks pipeline files against these specs without
//! touching a GPU.

use indexmap::IndexMap;

use crate::format::Format;
use crate::value::Value;

/// Texture or buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ResourceKind {
    Texture,
    Buffer,
    /// A ray-tracing acceleration structure of the frame's strands (issue
    /// 48): built by a pass (`strand_structure`), traced by shaders that
    /// bind it as `acceleration_structure`. No size: the hair's.
    AccelerationStructure,
}

impl std::fmt::Display for ResourceKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ResourceKind::Texture => "texture",
            ResourceKind::Buffer => "buffer",
            ResourceKind::AccelerationStructure => "acceleration_structure",
        })
    }
}

/// How a pass touches a resource bound to one of its slots. The GPU crate
/// derives texture/buffer usage flags from this; the scheduler derives order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Access {
    /// Read in a shader through a sampled texture binding.
    Sampled,
    /// Read-only storage buffer or storage texture.
    StorageRead,
    /// Written (and possibly read) as storage, e.g. with atomics.
    StorageWrite,
    /// Rendered into as a colour attachment.
    ColorTarget,
    /// Rendered into as a depth attachment.
    DepthTarget,
    /// Read as a uniform buffer.
    Uniform,
}

/// In words, for listings (`plait passes`): "sampled", "storage, written"…
impl std::fmt::Display for Access {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Access::Sampled => "sampled",
            Access::StorageRead => "storage, read",
            Access::StorageWrite => "storage, written",
            Access::ColorTarget => "colour target",
            Access::DepthTarget => "depth target",
            Access::Uniform => "uniform",
        })
    }
}

impl Access {
    pub fn is_write(self) -> bool {
        matches!(
            self,
            Access::StorageWrite | Access::ColorTarget | Access::DepthTarget
        )
    }
}

/// Which formats a texture slot accepts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Formats {
    Any,
    OneOf(Vec<Format>),
}

impl Formats {
    pub fn accepts(&self, f: Format) -> bool {
        match self {
            Formats::Any => true,
            Formats::OneOf(list) => list.contains(&f),
        }
    }
}

impl std::fmt::Display for Formats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Formats::Any => f.write_str("any format"),
            Formats::OneOf(list) => {
                let names: Vec<_> = list.iter().map(|f| f.name()).collect();
                f.write_str(&names.join(" | "))
            }
        }
    }
}

/// One named input or output of a pass type.
#[derive(Clone, Debug, PartialEq)]
pub struct SlotSpec {
    pub name: String,
    pub kind: ResourceKind,
    pub access: Access,
    /// Texture formats accepted (ignored for buffers).
    pub formats: Formats,
    /// An output slot with `loads = true` keeps and adds to the previous
    /// contents (blending, atomics on a cleared buffer): it must run after
    /// the pass that wrote those contents.
    pub loads: bool,
    pub optional: bool,
    pub doc: String,
    /// The shader variable the slot feeds, when it is not named like the
    /// slot: one kernel can serve pass types whose slots are named for their
    /// papers (`slab`'s `slabs` and `opacity_shadow_maps`' `slices` are both
    /// `counts` of `slice_counts.wgsl`).
    pub binding: Option<String>,
}

impl SlotSpec {
    /// The name of the shader binding this slot feeds.
    pub fn binding_name(&self) -> &str {
        self.binding.as_deref().unwrap_or(&self.name)
    }
}

/// The type of a pass param.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamType {
    Int {
        min: i64,
        max: i64,
    },
    Float {
        min: f64,
        max: f64,
    },
    Bool,
    Str,
    Enum(Vec<String>),
    /// An RGB or XYZ triple of floats.
    Vec3,
}

/// The accepted values in words, for listings and messages:
/// `integer 0 … 8`, `number 1e-6 … 1e6`, `one of frame | pixel`.
impl std::fmt::Display for ParamType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ParamType::Int { min, max } => write!(f, "integer {min} … {max}"),
            ParamType::Float { min, max } => {
                write!(f, "number {} … {}", short_number(*min), short_number(*max))
            }
            ParamType::Bool => f.write_str("true or false"),
            ParamType::Str => f.write_str("text"),
            ParamType::Enum(choices) => write!(f, "one of {}", choices.join(" | ")),
            ParamType::Vec3 => f.write_str("three numbers [x, y, z]"),
        }
    }
}

/// `1e-6`, `0.05`, `100`, `1e6`: plain within 0.001..10000, else a power of ten.
pub fn short_number(x: f64) -> String {
    let magnitude = x.abs();
    if x == 0.0 || (1e-3..1e4).contains(&magnitude) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct ParamSpec {
    pub name: String,
    pub ty: ParamType,
    /// `None` makes the param required.
    pub default: Option<Value>,
    pub doc: String,
}

/// Whether a pass type takes `view = "light" | "camera"` and `draw = "hair" | "opaque"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PassShape {
    /// Rasterizes scene geometry from a view: needs `view` and `draw`.
    Raster,
    /// One triangle covering the target: no `view`/`draw`.
    Fullscreen,
    /// A compute dispatch.
    Compute,
}

/// Where a raster pass looks from (`view = "camera" | "light"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum View {
    Camera,
    Light,
}

/// The scene geometry a raster pass draws (`draw = "hair" | "opaque"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Draw {
    Hair,
    Opaque,
}

impl View {
    /// The names a pipeline file may write, in the order errors list them.
    pub const NAMES: &[&str] = &["light", "camera"];

    pub fn from_name(name: &str) -> Option<View> {
        match name {
            "camera" => Some(View::Camera),
            "light" => Some(View::Light),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            View::Camera => "camera",
            View::Light => "light",
        }
    }
}

impl Draw {
    /// The names a pipeline file may write, in the order errors list them.
    pub const NAMES: &[&str] = &["hair", "opaque"];

    pub fn from_name(name: &str) -> Option<Draw> {
        match name {
            "hair" => Some(Draw::Hair),
            "opaque" => Some(Draw::Opaque),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Draw::Hair => "hair",
            Draw::Opaque => "opaque",
        }
    }
}

/// The declaration of a pass type. Registered by the pass library.
#[derive(Clone, Debug)]
pub struct PassTypeSpec {
    pub name: String,
    pub description: String,
    /// Paper and section the pass implements, e.g. Sintorn & Assarsson 2009 §3.1`.
    pub source: String,
    pub shape: PassShape,
    pub inputs: Vec<SlotSpec>,
    pub outputs: Vec<SlotSpec>,
    pub params: Vec<ParamSpec>,
    /// Data-only pass types (`fullscreen`, `compute`) take any slot names:
    /// their slots are the shader's bindings, checked by naga reflection.
    pub dynamic_slots: bool,
    /// Data-only pass types need `shader = "…"`.
    pub needs_shader: bool,
    /// Optional GPU features the pass needs (names as in `wgpu::Features`).
    pub required_features: Vec<String>,
    /// Passes of this type may set `depth`, `blend` and `cull`
    /// ([`crate::raster_decl`]); other types choose their state in Rust.
    pub state_from_data: bool,
    /// The raster keys the type sets for every pass of it (a pass-type
    /// file's `depth`, `blend`, …); a pass's own keys override them, and
    /// compile merges the two into [`crate::ScheduledPass::raster`].
    pub raster: crate::raster_decl::RasterDecl,
}

impl PassTypeSpec {
    /// A pass type with no slots or params yet; fill them with struct update
    /// syntax: `PassTypeSpec { inputs, outputs, ..PassTypeSpec::new(…) }`.
    pub fn new(name: &str, shape: PassShape, source: &str, description: &str) -> Self {
        PassTypeSpec {
            name: name.into(),
            description: description.into(),
            source: source.into(),
            shape,
            inputs: Vec::new(),
            outputs: Vec::new(),
            params: Vec::new(),
            dynamic_slots: false,
            needs_shader: false,
            required_features: Vec::new(),
            state_from_data: false,
            raster: crate::raster_decl::RasterDecl::default(),
        }
    }

    /// The declared slot `id` names (`None` for a shared slot, which the
    /// registry holds, or an index past the type's slots).
    pub fn slot(&self, id: crate::SlotId) -> Option<&SlotSpec> {
        match id {
            crate::SlotId::Input(i) => self.inputs.get(i),
            crate::SlotId::Output(i) => self.outputs.get(i),
            crate::SlotId::Shared(_) => None,
        }
    }

    /// The handle of the slot named `name` among the type's declared slots,
    /// the one compile gives the bindings of it ([`crate::Binding::slot_id`]).
    pub fn slot_id(&self, name: &str) -> Option<crate::SlotId> {
        let named = |s: &SlotSpec| s.name == name;
        (self.inputs.iter().position(named).map(crate::SlotId::Input)).or_else(|| {
            self.outputs
                .iter()
                .position(named)
                .map(crate::SlotId::Output)
        })
    }

    /// A data-only pass type: any slot names (the shader's bindings), params
    /// from the shader's `params` uniform, `shader = "…"` from the pipeline.
    pub fn data_only(name: &str, shape: PassShape, description: &str) -> Self {
        PassTypeSpec {
            dynamic_slots: true,
            needs_shader: true,
            state_from_data: shape != PassShape::Compute,
            ..PassTypeSpec::new(name, shape, "plait", description)
        }
    }
}

/// All pass types known to a run, by name.
#[derive(Clone, Debug, Default)]
pub struct Registry {
    pub types: IndexMap<String, PassTypeSpec>,
    /// Params with one meaning in every pass that takes them: those of the
    /// shader providers (`shadow_weight`, `marschner_specular_gain`, …). A
    /// data-only pass takes any param its shader reads, but one of these
    /// names is held to its spec (range, choices) as a typed pass would be.
    pub shared_params: Vec<ParamSpec>,
    /// Optional input slots every pass drawing hair takes whatever its type:
    /// the `geometry` providers' (`wisp_texture`), given to every hair draw
    /// by the point's `draws`, and the `shading_space` providers' (the tip
    /// fading every hair draw's coverage reads); a pass whose shader binds
    /// none leaves it unbound.
    pub shared_slots: Vec<SlotSpec>,
}

impl Registry {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn register(&mut self, spec: PassTypeSpec) {
        self.types.insert(spec.name.clone(), spec);
    }

    pub fn get(&self, name: &str) -> Option<&PassTypeSpec> {
        self.types.get(name)
    }

    pub fn names(&self) -> Vec<&str> {
        self.types.keys().map(String::as_str).collect()
    }
}
