//! Multiple-scattering providers: every `multiple_scattering` technique
//! answers `hair_multiple_scattering(world, tangent, to_light, to_eye, base,
//! hair_visibility) -> vec3`: the radiance per unit key-light irradiance that
//! single scattering leaves out (`plait::hair_radiance` adds it). Its uniform
//! is `multiple_scattering_params` (binding 70), its resources bind at 71–79
//! through the optional slots below. What a provider needs of the other
//! points (a strand count from self_shadow, a fibre from shading) is in its
//! technique.toml (`[technique.requires]`), not here.

use plait_graph::{Access, Format, ParamSpec, SlotSpec};

use crate::spec_util::{SlotExt, choice, float, texture};

/// The providers, by param value: every module `plait::multiple_scattering::NAME` found.
pub fn providers() -> Vec<String> {
    plait_gpu::library::providers("multiple_scattering")
}

/// The optional input slots any provider may need.
pub fn slots() -> Vec<SlotSpec> {
    vec![
        texture(
            "dual_scattering_a",
            Access::Sampled,
            &[Format::Rgba16Float],
            "dual_scattering: ā_f, ā_b, α_f, α_b at (sin θi, σ_a/(1+σ_a)) (Zinke et al. 2008 §4)",
        )
        .optional(),
        texture(
            "dual_scattering_b",
            Access::Sampled,
            &[Format::Rgba16Float],
            "dual_scattering: β_f², β_b² at (sin θi, σ_a/(1+σ_a)) (Zinke et al. 2008 §4)",
        )
        .optional(),
    ]
}

/// Params of the providers (filled into `multiple_scattering_params` by member name).
pub fn params() -> Vec<ParamSpec> {
    vec![
        choice(
            "multiple_scattering",
            "none",
            &providers().iter().map(String::as_str).collect::<Vec<_>>(),
            "light scattered by more than one strand (multiple_scattering provider)",
        ),
        float(
            "karis_scatter",
            1.0,
            0.0,
            1.0,
            "karis: the material's Scatter, the term's weight (Karis 2016)",
        ),
        float(
            "dual_scattering_front_density",
            0.7,
            0.0,
            1.0,
            "dual_scattering: forward density factor d_f (Zinke et al. 2008 §4)",
        ),
        float(
            "dual_scattering_back_density",
            0.7,
            0.0,
            1.0,
            "dual_scattering: backward density factor d_b (Zinke et al. 2008 §4)",
        ),
    ]
}
