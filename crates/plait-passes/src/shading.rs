//! Shading providers: every `shading` technique answers one WGSL question,
//! `hair_direct(tangent, to_light, to_eye, base) -> vec3`: the radiance a strand
//! reflects towards the eye per unit key-light colour, before shadowing
//! (the generated `plait::shading` picks the provider the `shading` param
//! names). Its uniform is `shading_params` (binding 20), its resources bind at
//! 21–29 through the optional slots below.
//!
//! Marschner (Halén & Wester 2007 §3.2.2, §5.8): `marschner` reads the M and N
//! lookup tables the `marschner_tables` pass draws (slots `marschner_m`,
//! `marschner_n`) and needs only `marschner_specular_gain`;
//! `marschner_reference` evaluates the model per fragment and takes the
//! model's params. Those are the `marschner_tables` pass type's own
//! (`shaders/passes/marschner_tables.toml`), read from it and prefixed
//! `marschner_` (the names of the technique's params), so their ranges and
//! docs are written once.

use plait_graph::{Access, Format, ParamSpec, SlotSpec};

use crate::spec_util::{SlotExt, choice, float, texture};

/// The providers, by param value: every module `plait::shading::NAME` found.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("shading")
}

/// The optional input slots any provider may need.
pub fn slots() -> Vec<SlotSpec> {
    vec![
        texture(
            "marschner_m",
            Access::Sampled,
            &[Format::Rgba16Float],
            "marschner: M_R, M_TT, M_TRT and cos θd at (sin θi, sin θr) (Halén & Wester 2007 §5.8)",
        )
        .optional(),
        texture(
            "marschner_n",
            Access::Sampled,
            &[Format::Rgba16Float],
            "marschner: N_R, N_TT, N_TRT at (cos φ, cos θd) (Halén & Wester 2007 §5.8)",
        )
        .optional(),
    ]
}

/// Params of the providers (filled into `shading_params` by member name).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    let mut p = vec![
        choice(
            "shading",
            "kajiya_kay",
            &providers(library)
                .iter()
                .map(String::as_str)
                .collect::<Vec<_>>(),
            "key-light shading model (shading provider): the strand's reflection of the light",
        ),
        float(
            "marschner_specular_gain",
            8.0,
            0.0,
            1e4,
            "marschner, marschner_reference: gain of the R, TT and TRT lobes against Kajiya-Kay's diffuse term",
        ),
    ];
    p.extend(marschner_model_params(library));
    p.extend(chiang_params());
    p
}

/// The pass type whose params the Marschner model's are
/// (`shaders/passes/marschner_tables.toml`).
const TABLES_TYPE: &str = "marschner_tables";

/// Chiang et al. 2016's fibre at its standard values (§4, the ones issue
/// 47's Mitsuba measurement uses): β_m, β_n, tilt α (degrees), η. One
/// description: the `chiang` technique's param defaults and
/// `plait::mitsuba::Fibre::default()` both read it.
pub const CHIANG_FIBRE: [f64; 4] = [0.3, 0.3, 2.0, 1.55];

/// The `chiang` technique's params. Ranges: β below 0.02 leaves f32's M_p
/// (1/v > 4000) and β_n below 0.15 the 64-point mean over h (its logistic
/// then narrower than the points' spacing; 6.4 % from 512 points at 0.15,
/// measured by tests/fibre.rs); 1 is the papers' top. The tilt within ±10° (Chiang 2016 §4: 2–4°
/// for human hair), η within 1.1–2 (hair 1.55).
fn chiang_params() -> Vec<ParamSpec> {
    let [beta_m, beta_n, tilt, eta] = CHIANG_FIBRE;
    vec![
        float(
            "chiang_beta_m",
            beta_m,
            0.02,
            1.0,
            "chiang: longitudinal roughness β_m (Chiang et al. 2016 §4.1)",
        ),
        float(
            "chiang_beta_n",
            beta_n,
            0.15,
            1.0,
            "chiang: azimuthal roughness β_n (Chiang et al. 2016 §4.1; also in σ_a's mapping, §4.2)",
        ),
        float(
            "chiang_tilt",
            tilt,
            -10.0,
            10.0,
            "chiang: cuticle scale tilt α, degrees (Chiang et al. 2016 §4)",
        ),
        float(
            "chiang_eta",
            eta,
            1.1,
            2.0,
            "chiang: index of refraction η of the fibre",
        ),
    ]
}

/// The Marschner model's params (lobe shifts and widths, index of
/// refraction, absorption, caustic limit): those of the `marschner_tables`
/// pass type of `library` but its table size.
///
/// A missing or broken file gives none here, never a panic: the pass
/// library reports what is wrong at its file, line and column
/// (`data_pass::discover`), so `plait check` fails there.
fn marschner_model_params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    let Some(tables) = library.get(TABLES_TYPE) else {
        return Vec::new();
    };
    tables
        .spec()
        .params
        .into_iter()
        .filter(|p| p.name != "table_size")
        .map(|mut p| {
            p.name = format!("marschner_{}", p.name);
            p.doc = format!("marschner_reference: {}", p.doc);
            p
        })
        .collect()
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
        ] {
            assert!(names.iter().any(|n| n == want), "{want} missing: {names:?}");
        }
        assert!(!names.iter().any(|n| n.ends_with("table_size")));
    }
}
