//! How a pass type turns into GPU work.
//!
//! A pass type is a [`PassTypeSpec`](plait_graph::PassTypeSpec) (what it reads,
//! writes and accepts — checked without a GPU) plus a WGSL file plus, where
//! needed, Rust that sets pipeline state or records special loops. The shared
//! machinery binds resources by name from naga's reflection of the shader
//! (kajiya-rg's "declared accesses + a closure", with the declaration checked
//! against the shader):
//!
//! - group 0: the frame's standard inputs (`#import plait::frame`);
//! - group 1: one binding per slot, the variable named like the slot, plus an
//!   optional `params` uniform whose members are filled from the pass params by
//!   name, plus the scene's `hair_vertices` / `hair_indices` / `wisp_vertices` /
//!   `wisp_indices` / `opaque_vertices` / `opaque_indices` storage buffers;
//! - colour and depth targets are attachments, not bindings.
//!
//! By concern: [`pass_type`] (the trait, its contexts, the library),
//! [`defaults`] (defines and thread counts a type gets unless it says
//! otherwise), [`state`] (fixed-function state, from Rust or from TOML),
//! [`layout`] (bind group layouts), `pipeline` (the cached wgpu pipeline of a draw), [`plan`] (which shader binding each slot feeds — computed once per pass
//! from the schedule and naga's reflection, used by `plait check`, build and
//! record), [`build`] (bind groups and pipelines) and [`record`] (commands).

pub mod build;
pub mod check;
pub mod defaults;
pub mod layout;
mod outputs;
pub mod param_use;
pub mod pass_type;
mod pipeline;
pub mod plan;
pub mod record;
pub mod state;
pub(crate) mod storage_format;

pub use build::{ShaderDraw, build_draw, build_shader_pass, raster_state_of};
pub use check::ShaderChecker;
pub use defaults::{default_defines, default_threads};
pub use layout::{FrameSamplers, frame_layout};
pub use pass_type::{
    BuildContext, Finishing, PassLibrary, PassType, PreparedPass, RecordContext, Recording,
    SCENE_BINDINGS, shader_source,
};
pub use plait_graph::raster_decl::BlendPreset;
pub use plan::BindingPlan;
pub use record::{ColorAttachment, DepthAttachment, DrawWhat, ShaderPass, ShaderPassKind};
pub use state::{DepthMode, RasterState, blend_preset};
