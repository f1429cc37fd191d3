//! Lighting providers: every `lighting` technique answers
//! `hair_environment(world, tangent, to_eye, base) -> vec3`: the light a strand
//! reflects from everything but the key light (the generated
//! `plait::lighting` picks the provider the `lighting` param names). Its uniform is
//! `lighting_params` (binding 30), its resources bind at 31–39 through the
//! optional slots below.

use plait_graph::{ParamSpec, ResolvedResource, ResourceDesc, ScheduledPass, SlotSpec, Value};

/// The slot of the cube a provider sums in every fragment (the point
/// file's `[inputs.light_environment]`).
const SUMMED_CUBE: &str = "light_environment";

/// The providers, by param value: every module `plait::lighting::NAME` found.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("lighting")
}

/// The optional input slots any provider may need
/// (`techniques/lighting/point.toml`, `[inputs]`).
pub fn slots(library: &plait_gpu::PassLibrary) -> Vec<SlotSpec> {
    crate::points::slots(library, "lighting")
}

/// Params of the providers (filled into `lighting_params` by member name).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    crate::points::params(library, "lighting")
}

/// The largest environment cube face `environment_reference` sums per
/// fragment: s · (6s + 1) + s + 1 loop laps (24,705 at 64). lavapipe ends
/// every loop of a group of 8 fragments after 65,535 laps in all (docs/
/// design.md, "Loop budgets"; measured: s = 105 cut), and the fragment's
/// other providers loop too, so the cap leaves them ~40,000. Each lap
/// evaluates the chosen fibre's response to one texel (issue 47): counted
/// as one lap, which holds for `kajiya_kay` and `marschner` (closed form,
/// tables) but not for `chiang` (a 64-lap mean over the width per texel) or
/// `marschner_reference` (bisections): on a lavapipe with the budget (Mesa
/// 22.3) those sums would be cut from small sizes on. Mesa 25.0.7, the
/// driver the scripts install, has none (`Gpu::loop_budget`); a check by
/// the fibre is not made here.
pub const MAX_REFERENCE_ENVIRONMENT: u32 = 64;

/// A pass binding a `light_environment` cube larger than
/// [`MAX_REFERENCE_ENVIRONMENT`]: refused at load, since the brute-force sum
/// would stop early, silently, on lavapipe. Decided by the slot, not by
/// which provider is chosen: the point file documents the slot as summed in
/// every fragment, and a technique binds it only to be summed.
pub fn check_environment_size(
    pass: &ScheduledPass,
    resources: &[ResolvedResource],
) -> Result<(), String> {
    let cube = pass
        .reads
        .iter()
        .find(|b| b.slot == SUMMED_CUBE)
        .and_then(|b| b.resolved(resources));
    match cube.map(|r| &r.desc) {
        Some(ResourceDesc::Texture { height, .. }) if *height > MAX_REFERENCE_ENVIRONMENT => {
            let s = *height as u64;
            let laps = s * (6 * s + 1) + s + 1;
            // The provider chosen, as the pass's param names it.
            let provider = match pass.params.get("lighting") {
                Some(Value::Str(p)) => format!("lighting = \"{p}\""),
                _ => "the lighting provider".to_owned(),
            };
            Err(format!(
                "{provider} sums all 6 · {s}² texels of `{SUMMED_CUBE}` in every fragment ({laps} loop laps), and lavapipe ends every loop of a group of 8 fragments after 65,535 laps, shared with the other providers; with it environment_size is at most {MAX_REFERENCE_ENVIRONMENT} (--set params.environment_size={MAX_REFERENCE_ENVIRONMENT})"
            ))
        }
        _ => Ok(()),
    }
}
