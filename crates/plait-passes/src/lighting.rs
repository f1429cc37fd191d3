//! Lighting providers: every `lighting` technique answers
//! `hair_environment(world, tangent, to_eye, base) -> vec3`: the light a strand
//! reflects from everything but the key light (the generated
//! `plait::lighting` picks the provider the `lighting` param names). Its uniform is
//! `lighting_params` (binding 30), its resources bind at 31–39 through the
//! optional slots below.

use plait_graph::{
    Access, Format, Formats, ParamSpec, ResolvedResource, ResourceDesc, ResourceKind,
    ScheduledPass, SlotSpec, Value,
};

use crate::spec_util::choice;

/// The providers, by param value: every module `plait::lighting::NAME` found.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("lighting")
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
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    vec![choice(
        "lighting",
        "ambient",
        &providers(library)
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
        "light from everything but the key light (lighting provider), darkened by occlusion",
    )]
}

/// The largest environment cube face `environment_reference` sums per
/// fragment: s · (6s + 1) + s + 1 loop laps (24,705 at 64). lavapipe ends
/// every loop of a group of 8 fragments after 65,535 laps in all (docs/
/// design.md, "Loop budgets"; measured: s = 105 cut), and the fragment's
/// other providers loop too, so the cap leaves them ~40,000.
pub const MAX_REFERENCE_ENVIRONMENT: u32 = 64;

/// `lighting = "environment_reference"` on a pass whose `light_environment`
/// cube is larger than [`MAX_REFERENCE_ENVIRONMENT`]: refused at load, since
/// the brute-force sum would stop early, silently, on lavapipe.
pub fn check_environment_size(
    pass: &ScheduledPass,
    resources: &[ResolvedResource],
) -> Result<(), String> {
    if pass.params.get("lighting") != Some(&Value::Str("environment_reference".into())) {
        return Ok(());
    }
    let cube = pass
        .reads
        .iter()
        .find(|b| b.slot == "light_environment")
        .and_then(|b| b.resolved(resources));
    match cube.map(|r| &r.desc) {
        Some(ResourceDesc::Texture { height, .. }) if *height > MAX_REFERENCE_ENVIRONMENT => {
            let s = *height as u64;
            let laps = s * (6 * s + 1) + s + 1;
            Err(format!(
                "lighting = \"environment_reference\" sums all 6 · {s}² texels of `light_environment` in every fragment ({laps} loop laps), and lavapipe ends every loop of a group of 8 fragments after 65,535 laps, shared with the other providers; with this lighting environment_size is at most {MAX_REFERENCE_ENVIRONMENT} (--set params.environment_size={MAX_REFERENCE_ENVIRONMENT})"
            ))
        }
        _ => Ok(()),
    }
}
