//! The slots and params of the shared hair-fragment stage
//! (`shaders/lib/hair_fragment.wgsl`, `plait::hair_fragment`) for the pass
//! types written in Rust that shade hair (`hair_shade`, `hair_depth_peel`):
//! the opaque shadow map and what the self_shadow, shading, lighting,
//! ambient_occlusion and shading_space providers bind and take. Data-only raster passes that
//! import the stage need none of this: their slots come from the shader's
//! bindings and their params from the providers' exports (`uses`).
//!
//! The transparency techniques themselves are folders of data
//! (`techniques/transparency/`); only depth peeling keeps Rust, for its loop.

use plait_graph::{Access, ParamSpec, SlotSpec};

use crate::spec_util::{DEPTH, texture};
use crate::{lighting, multiple_scattering, occlusion, shading, shading_space, visibility};

/// The shading inputs of every hair pass: the opaque shadow map, the
/// visibility provider's light maps, and what the shading, lighting and
/// occlusion providers bind.
pub fn shading_inputs(library: &plait_gpu::PassLibrary) -> Vec<SlotSpec> {
    let mut v = vec![texture(
        "shadow_map",
        Access::Sampled,
        DEPTH,
        "opaque shadow map from the light",
    )];
    v.extend(visibility::slots(library));
    v.extend(shading::slots(library));
    v.extend(lighting::slots(library));
    v.extend(occlusion::slots(library));
    v.extend(shading_space::slots(library));
    v.extend(multiple_scattering::slots(library));
    v
}

/// The params of every provider a hair pass composes: the providers of
/// `library` are their choices.
pub fn shading_params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    let mut p = visibility::params(library);
    p.extend(shading::params(library));
    p.extend(lighting::params(library));
    p.extend(occlusion::params(library));
    p.extend(shading_space::params(library));
    p.extend(multiple_scattering::params(library));
    p
}
