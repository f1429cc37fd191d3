//! Visibility providers: every self-shadowing technique answers one WGSL
//! question, `hair_visibility(world) -> f32`, from its own light maps. A
//! shading pass imports the provider its `visibility` param names, and binds
//! the provider's maps under the `vis_*` slots; adding a provider is a WGSL
//! module in `shaders/lib/visibility/` plus a line here, with no change to
//! the shading passes.

use plait_graph::{Access, ParamSpec, SlotSpec};

use crate::spec_util::{DEPTH, SlotExt, choice, float, texture};

/// The providers, by param value.
pub const PROVIDERS: &[&str] = &["none", "modified_shadow_map"];

/// The optional input slots any provider may need.
pub fn slots() -> Vec<SlotSpec> {
    vec![
        texture("vis_depth", Access::Sampled, DEPTH, "modified_shadow_map: nearest hair depth from the light").optional(),
    ]
}

/// Params of the providers (filled into `visibility_params` by name).
pub fn params() -> Vec<ParamSpec> {
    vec![
        choice("visibility", "none", PROVIDERS, "self-shadowing technique (visibility provider) used for hair shadows"),
        float("density", 40.0, 0.0, 1e6, "modified_shadow_map: extinction per world unit behind the first strand"),
    ]
}
