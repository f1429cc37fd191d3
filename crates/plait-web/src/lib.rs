//! plait in a browser: the engine on the page's WebGPU (wgpu's `webgpu`
//! backend), with the built-in library alone — a page has no file system, so
//! pipelines, techniques, shaders and scenes are the copies `plait-assets`
//! embeds (`<built-in>/…`), and messages name those paths.
//!
//! [`engine`] is the part that does not depend on the browser (it builds
//! natively too); [`bindings`] are the functions the page calls
//! (`scripts/web.sh` builds them with wasm-bindgen).

pub mod engine;
pub mod orbit;
pub mod timings;

#[cfg(target_arch = "wasm32")]
pub mod bindings;
#[cfg(target_arch = "wasm32")]
mod occlusion_shim;

pub use engine::{Engine, Frame, Request};
