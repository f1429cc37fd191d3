//! Lighting providers: every `lighting` technique answers
//! `hair_environment(world, tangent, to_eye, base) -> vec3`: the light a strand
//! reflects from everything but the key light (the generated
//! `plait::lighting` picks the provider the `lighting` param names). Its uniform is
//! `lighting_params` (binding 30), its resources bind at 31–39 through the
//! optional slots below.

use plait_graph::{Access, Format, Formats, ParamSpec, ResourceKind, SlotSpec};

use crate::spec_util::choice;

/// The providers, by param value: every module `plait::lighting::NAME` found.
pub fn providers() -> Vec<String> {
    plait_gpu::library::providers("lighting")
}

/// The optional input slots any provider may need.
pub fn slots() -> Vec<SlotSpec> {
    let texture = |name: &str, format: Format, doc: &str| SlotSpec {
        name: name.into(),
        kind: ResourceKind::Texture,
        access: Access::Sampled,
        formats: Formats::OneOf(vec![format]),
        loads: false,
        optional: true,
        doc: doc.into(),
        binding: None,
    };
    vec![
        texture(
            "light_maps",
            Format::Rgba16Float,
            "Kajiya-Kay irradiance maps, diffuse then M+1 specular (lighting = \"irradiance_maps\", Xing et al. 2012 §3)",
        ),
        texture(
            "light_environment",
            Format::Rgba32Float,
            "environment cube atlas: radiance, solid angle (lighting = \"environment_reference\")",
        ),
    ]
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
