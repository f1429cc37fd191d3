//! What the transparency pass types share: they all shade hair with
//! `hair_shade.wgsl` (Kajiya-Kay × the visibility provider, so the
//! self-shadowing stays the base pipeline's) and differ only in the
//! `plait::transparency::*` WGSL module that turns the shaded colour and alpha
//! into fragment outputs, and in what resolves and composes the result.
//!
//! Methods (Sintorn & Assarsson 2009 §2.2, §3.4, Fig. 2; Halén & Wester 2007
//! §3.1.2, §5.6): depth peeling (`depth_peeling`), per-pixel fragment lists
//! (`linked_list`), weighted-average blending (`weighted_average`), alpha to
//! coverage (`alpha_to_coverage`), none (`opaque_hair`). `compose_hair_over`
//! puts a front-to-back premultiplied hair image over the scene.

use plait_gpu::Define;
use plait_gpu::pass::{BuiltinShader, default_defines};
use plait_graph::{Access, ParamSpec, ScheduledPass, SlotSpec};

use crate::spec_util::{DEPTH, texture};
use crate::{lighting, occlusion, shading, visibility};

pub const HAIR_SHADER: BuiltinShader = plait_gpu::builtin_shader!("passes/hair_shade.wgsl");

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
    v
}

/// The params of every provider a hair pass composes.
pub fn shading_params() -> Vec<ParamSpec> {
    let mut p = visibility::params();
    p.extend(shading::params());
    p.extend(lighting::params());
    p.extend(occlusion::params());
    p
}

/// The shading defines plus the transparency module's (`TRANSPARENCY_<MODULE>`).
pub fn defines(pass: &ScheduledPass, module: &str) -> Vec<(String, Define)> {
    let mut d = default_defines(pass);
    d.push(("TRANSPARENCY_MODULE".into(), Define::Bool(true)));
    d.push((
        format!("TRANSPARENCY_{}", module.to_ascii_uppercase()),
        Define::Bool(true),
    ));
    d
}
