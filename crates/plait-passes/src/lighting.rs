//! Lighting providers: every `lighting` technique answers
//! `hair_environment(world, tangent, to_eye, base) -> vec3`: the light a strand
//! reflects from everything but the key light (`shaders/lib/hair_environment.wgsl`
//! picks the provider the `lighting` param names). Its uniform is
//! `lighting_params` (binding 30), its resources bind at 31–39 through the
//! optional slots below.

use plait_graph::{ParamSpec, SlotSpec};

use crate::spec_util::choice;

/// The providers, by param value: every module in `shaders/lib/lighting/`.
pub fn providers() -> Vec<String> {
    plait_gpu::shader::ProviderPoint::named("lighting")
        .map(|p| p.providers())
        .unwrap_or_default()
}

/// The optional input slots any provider may need.
pub fn slots() -> Vec<SlotSpec> {
    Vec::new()
}

/// Params of the providers (filled into `lighting_params` by member name).
pub fn params() -> Vec<ParamSpec> {
    vec![choice(
        "lighting",
        "ambient",
        &providers().iter().map(String::as_str).collect::<Vec<_>>(),
        "light from everything but the key light (lighting provider), darkened by occlusion",
    )]
}
