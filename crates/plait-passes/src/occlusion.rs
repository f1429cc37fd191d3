//! Occlusion providers: every `ambient_occlusion` technique answers
//! `vertex_occlusion(vertex_index) -> f32` in the hair vertex shader: the
//! fraction of the environment's light reaching the vertex
//! (the generated `plait::ambient_occlusion` picks the provider the
//! `ambient_occlusion` param names). Its uniform is `occlusion_params` (binding 40), its per-vertex
//! resources bind at 41–44 through the optional slots below.
//!
//! The precomputes that fill them are passes of their techniques
//! (`run = "once"`): `occlusion_directions` (deep opacity maps from N
//! directions, Xing et al. 2012 §4) and `occlusion_cylinders` (cylinders and
//! scalp discs, Halén & Wester 2007 §3.3.1).

use plait_graph::{ParamSpec, SlotSpec};

/// The providers, by param value: every module `plait::ambient_occlusion::NAME`
/// found.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("ambient_occlusion")
}

/// The optional input slots any provider may need
/// (`techniques/ambient_occlusion/point.toml`, `[inputs]`).
pub fn slots(library: &plait_gpu::PassLibrary) -> Vec<SlotSpec> {
    crate::points::slots(library, "ambient_occlusion")
}

/// Params of the providers (filled into `occlusion_params` by member name).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    crate::points::params(library, "ambient_occlusion")
}
