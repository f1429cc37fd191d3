//! Shading providers: every `shading` technique answers one WGSL question,
//! `hair_direct(tangent, to_light, to_eye, base) -> vec3`: the radiance a strand
//! reflects towards the eye per unit key-light colour, before shadowing
//! (`shaders/lib/hair_direct.wgsl` picks the provider the `shading` param
//! names). Its uniform is `shading_params` (binding 20), its resources bind at
//! 21–29 through the optional slots below.

use plait_graph::{ParamSpec, SlotSpec};

use crate::spec_util::choice;

/// The providers, by param value: every module in `shaders/lib/shading/`.
pub fn providers() -> Vec<String> {
    plait_gpu::shader::ProviderPoint::named("shading")
        .map(|p| p.providers())
        .unwrap_or_default()
}

/// The optional input slots any provider may need.
pub fn slots() -> Vec<SlotSpec> {
    Vec::new()
}

/// Params of the providers (filled into `shading_params` by member name).
pub fn params() -> Vec<ParamSpec> {
    vec![choice(
        "shading",
        "kajiya_kay",
        &providers().iter().map(String::as_str).collect::<Vec<_>>(),
        "key-light shading model (shading provider): the strand's reflection of the light",
    )]
}
