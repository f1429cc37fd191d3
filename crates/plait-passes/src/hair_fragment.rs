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
pub fn shading_inputs() -> Vec<SlotSpec> {
    let mut v = vec![texture(
        "shadow_map",
        Access::Sampled,
        DEPTH,
        "opaque shadow map from the light",
    )];
    v.extend(visibility::slots());
    v.extend(shading::slots());
    v.extend(lighting::slots());
    v.extend(occlusion::slots());
    v.extend(shading_space::slots());
    v.extend(multiple_scattering::slots());
    v
}

/// The params of every provider a hair pass composes.
pub fn shading_params() -> Vec<ParamSpec> {
    let mut p = visibility::params();
    p.extend(shading::params());
    p.extend(lighting::params());
    p.extend(occlusion::params());
    p.extend(shading_space::params());
    p.extend(multiple_scattering::params());
    p
}
