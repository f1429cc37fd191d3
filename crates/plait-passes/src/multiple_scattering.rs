//! Multiple-scattering providers: every `multiple_scattering` technique
//! answers `hair_multiple_scattering(world, tangent, to_light, to_eye, base,
//! hair_visibility) -> vec3`: the radiance per unit key-light irradiance that
//! single scattering leaves out (`plait::hair_radiance` adds it). Its uniform
//! is `multiple_scattering_params` (binding 70), its resources bind at 71–79
//! through the optional slots of
//! `techniques/multiple_scattering/point.toml`, which also declares its params. What a provider needs of the other
//! points (a strand count from self_shadow, a fibre from shading) is in its
//! technique.toml (`[technique.requires]`), not here.

use plait_graph::{ParamSpec, SlotSpec};

/// The providers, by param value: every module `plait::multiple_scattering::NAME` found.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("multiple_scattering")
}

/// The optional input slots any provider may need (the point file's `[inputs]`).
pub fn slots(library: &plait_gpu::PassLibrary) -> Vec<SlotSpec> {
    crate::points::slots(library, "multiple_scattering")
}

/// Params of the providers (filled into `multiple_scattering_params` by
/// member name; the point file's `[params]`).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    crate::points::params(library, "multiple_scattering")
}
