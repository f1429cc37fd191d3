//! plait: real-time strand-hair render pipelines as data.
//!
//! This crate ties the pieces together for programs (the `plait` CLI, the
//! test suite, the A/B runner): load and check a pipeline, build it on a
//! device for a scene, render frames, read images back.
//!
//! - [`graph`]: pipeline files, checks, schedule, memory plan (no GPU);
//! - [`hair`]: strands, `.hair` files, grooms, scenes;
//! - [`gpu`]: the wgpu executor;
//! - [`passes`]: the pass library;
//! - [`overflow`]: bounded buffers sized to hold every frame's data;
//! - [`size_limit`]: a `--size` too large for the adapter, named as the flag;
//! - [`structure_limit`]: more strand segments than the adapter's acceleration structure holds;
//! - [`frames`]: sequences of frames (time, head animation, medians);
//! - [`mitsuba`]: a scene exported for the Mitsuba 3 path tracer;
//! - [`linear`]: the linear radiance image before the display transform, as OpenEXR;
//! - [`ab`]: A/B runs, several pipelines against a reference, as one report.

pub use plait_gpu as gpu;
pub use plait_graph as graph;
pub use plait_hair as hair;
pub use plait_passes as passes;

#[cfg(not(target_arch = "wasm32"))]
pub mod ab;
pub mod adapter;
pub mod frames;
pub mod linear;
pub mod mitsuba;
pub mod overflow;
#[cfg(not(target_arch = "wasm32"))]
pub mod probe;
pub mod scene_fit;
pub mod session;
pub mod size_limit;
pub mod source;
pub mod strand_lod;
pub mod structure_limit;
pub mod wisps;
