//! Shading providers: every `shading` technique answers one WGSL question,
//! `hair_direct(tangent, to_light, to_eye, base) -> vec3`: the radiance a strand
//! reflects towards the eye per unit key-light colour, before shadowing
//! (the generated `plait::shading` picks the provider the `shading` param
//! names). Its uniform is `shading_params` (binding 20), its resources bind at
//! 21–29 through the optional slots of `techniques/shading/point.toml`.
//!
//! The point file declares the providers' params once: the lobe gain, the
//! Chiang et al. 2016 fibre, and (`[params_from]`) the Marschner model's,
//! which are the `marschner_tables` pass type's own
//! (`shaders/passes/marschner_tables.toml`) prefixed `marschner_`, so their
//! ranges and docs are written once.

use plait_graph::{ParamSpec, SlotSpec};

/// The providers, by param value: every module `plait::shading::NAME` found.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("shading")
}

/// The optional input slots any provider may need (the point file's `[inputs]`).
pub fn slots(library: &plait_gpu::PassLibrary) -> Vec<SlotSpec> {
    crate::points::slots(library, "shading")
}

/// Params of the providers (filled into `shading_params` by member name).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    crate::points::params(library, "shading")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_takes_every_model_param_of_the_table_pass() {
        let library = crate::read_library(&[]);
        let names: Vec<String> = params(&library).into_iter().map(|p| p.name).collect();
        for want in [
            "marschner_shift_r",
            "marschner_shift_tt",
            "marschner_shift_trt",
            "marschner_width_r",
            "marschner_width_tt",
            "marschner_width_trt",
            "marschner_ior",
            "marschner_absorption",
            "marschner_caustic_limit",
            "marschner_specular_gain",
            "chiang_beta_m",
        ] {
            assert!(names.iter().any(|n| n == want), "{want} missing: {names:?}");
        }
        assert!(!names.iter().any(|n| n.ends_with("table_size")));
    }
}
