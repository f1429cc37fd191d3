//! `guide_interpolation`: the drawn strands rebuilt from the guides every
//! frame on the GPU (Halén & Wester 2007 §2.5, §5.4–5.5) — each point the
//! barycentric blend of its strand's three guides, translated to the
//! strand's root and scaled to its length, tangents recomputed
//! (`shaders/passes/sim_interpolate.wgsl`). It writes the scene resource
//! `hair_vertices`, so the graph runs it before every hair draw. When every
//! strand is its own guide (hair without guides), it copies the simulated
//! strands into the drawn ones. CPU reference: `plait_hair::guides::Guides`.

use plait_gpu::pass::{BuildContext, PassType, PreparedPass, ShaderDraw, build_draw};
use plait_gpu::{Define, GpuError};
use plait_graph::{Access, PassShape, PassTypeSpec, ScheduledPass, SlotSpec};

use crate::spec_util::{SlotExt, buffer};

pub struct GuideInterpolation;

inventory::submit! { crate::RustPassType(|_| Box::new(GuideInterpolation)) }

const SHADER: &str = "shaders/passes/sim_interpolate.wgsl";

fn aliased(mut slot: SlotSpec, binding: &str) -> SlotSpec {
    slot.binding = Some(binding.into());
    slot
}

fn spec() -> PassTypeSpec {
    PassTypeSpec {
        inputs: vec![
            aliased(
                buffer(
                    "positions",
                    Access::StorageRead,
                    "guide points now (scene resource guide_positions)",
                ),
                "guide_positions",
            ),
            aliased(
                buffer(
                    "strands",
                    Access::StorageRead,
                    "first point and count per guide (guide_strands)",
                ),
                "guide_strands",
            ),
            aliased(
                buffer(
                    "bindings",
                    Access::StorageRead,
                    "each drawn strand's guides, weights, root, scale (strand_guides)",
                ),
                "strand_guides",
            ),
        ],
        outputs: vec![aliased(
            buffer(
                "vertices",
                Access::StorageWrite,
                "the drawn hair (hair_vertices): positions and tangents",
            )
            .loads(),
            "hair_vertices",
        )],
        ..PassTypeSpec::new(
            "guide_interpolation",
            PassShape::Compute,
            "Halén & Wester 2007 §2.5, §5.4–5.5",
            "Drawn strands from the simulated guides: barycentric blend over scalp triangles, tangents recomputed, every frame.",
        )
    }
}

impl PassType for GuideInterpolation {
    fn spec(&self) -> PassTypeSpec {
        spec()
    }
    fn shader(&self) -> Option<&str> {
        Some(SHADER)
    }
    fn defines(&self, _pass: &ScheduledPass) -> Vec<(String, Define)> {
        Vec::new()
    }
    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let mut draw = ShaderDraw::of(self, pass, ctx)?;
        draw.threads = [ctx.geometry.point_count, 1, 1];
        Ok(Box::new(build_draw(&draw, pass, ctx)?))
    }
}
