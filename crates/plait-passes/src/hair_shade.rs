//! `hair_shade`: Kajiya-Kay hair (004_51cca5cde985008c.txt §3.2.1), shadowed by
//! opaque objects (000_785589f319b01ef5.txt §3.5) and by the hair itself through
//! the visibility provider, blended "over" the colour target.
//!
//! Without a transparency technique the strands are blended in draw order,
//! not depth order: the error the occupancy-order blending of
//! 000_785589f319b01ef5.txt §3.4 removes.

use plait_gpu::pass::{BuiltinShader, DepthMode, PassType, RasterState};
use plait_gpu::Capabilities;
use plait_graph::{Access, PassShape, PassTypeSpec, ScheduledPass};

use crate::spec_util::{DEPTH, HDR, SlotExt, texture};
use crate::visibility;

pub struct HairShade;

/// Premultiplied-alpha "over".
const OVER: wgpu::BlendState = wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING;

impl PassType for HairShade {
    fn spec(&self) -> PassTypeSpec {
        let mut inputs = vec![
            texture("shadow_map", Access::Sampled, DEPTH, "opaque shadow map from the light"),
            texture("depth", Access::DepthTarget, DEPTH, "camera depth of opaque geometry (tested, not written)"),
        ];
        inputs.extend(visibility::slots());
        PassTypeSpec {
            name: "hair_shade".into(),
            description: "Kajiya-Kay hair shading with opaque and self shadows, blended over the target.".into(),
            source: "004_51cca5cde985008c.txt §3.2.1; 000_785589f319b01ef5.txt §3.5".into(),
            shape: PassShape::Raster,
            inputs,
            outputs: vec![texture("color", Access::ColorTarget, HDR, "premultiplied colour, blended over").loads()],
            params: visibility::params(),
            dynamic_slots: false,
            needs_shader: false,
            required_features: vec![],
        }
    }

    fn shader(&self) -> Option<BuiltinShader> {
        Some(("shaders/passes/hair_shade.wgsl", include_str!("../../../shaders/passes/hair_shade.wgsl")))
    }

    fn raster_state(&self, _pass: &ScheduledPass, _caps: &Capabilities) -> Result<RasterState, String> {
        Ok(RasterState {
            depth: DepthMode::TestOnly(wgpu::CompareFunction::Less),
            blend: vec![Some(OVER)],
            ..RasterState::default()
        })
    }
}
