//! Visibility providers: every self-shadowing technique answers one WGSL
//! question, `hair_visibility(world) -> f32`, from its own light maps. A
//! shading pass imports `plait::self_shadow` (generated from
//! `techniques/self_shadow/point.toml`), which picks the provider its
//! `self_shadow` param names, and binds the provider's maps under the `vis_*`
//! slots. Adding a provider is a WGSL module in its technique's folder (no
//! shading pass changes, no import line; `plait::self_shadow::tressfx` was
//! added so); maps or params no provider has used yet are declared in the point file
//! (`[inputs]`, `[params]`), which every pass type shading with it reads.

use plait_graph::{ParamSpec, SlotSpec};

/// The providers, by param value: every module `plait::self_shadow::NAME`
/// found (`techniques/self_shadow/tressfx/self_shadow.wgsl` →
/// `self_shadow = "tressfx"`), so a provider that needs no maps or params
/// beyond those below is WGSL alone.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("self_shadow")
}

/// The optional input slots any provider may need
/// (`techniques/self_shadow/point.toml`, `[inputs]`).
pub fn slots(library: &plait_gpu::PassLibrary) -> Vec<SlotSpec> {
    crate::points::slots(library, "self_shadow")
}

/// Params of the providers (filled into `visibility_params` by name;
/// the point file's `[params]`).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    crate::points::params(library, "self_shadow")
}
