//! `occlusion_cylinders`: per-vertex ambient occlusion with hair vertices as
//! transparent cylinders and the scalp as oriented discs (Halén & Wester
//! 2007 §3.3.1, §5.7). Two kernels of `occlusion_cylinders.wgsl`: the hair's
//! bounding box (which opaque triangles are scalp), then one thread per
//! receiving vertex summing the shadow of every caster.

use plait_gpu::GpuError;
use plait_gpu::pass::{
    BuildContext, PassType, PreparedPass, RasterState, RecordContext, ShaderDraw, ShaderPass,
    build_draw, default_defines,
};
use plait_gpu::shader::Define;
use plait_graph::{Access, PassShape, PassTypeSpec, ResourceDesc, ScheduledPass, Value};

use crate::occlusion_directions::{bound, kernel_pass};
use crate::spec_util::{buffer, choice, int};

pub struct OcclusionCylinders;

inventory::submit! { crate::RustPassType(|| Box::new(OcclusionCylinders)) }

const SHADER: &str = "shaders/passes/occlusion_cylinders.wgsl";

fn spec() -> PassTypeSpec {
    PassTypeSpec {
        outputs: vec![
            buffer(
                "vertex_ao",
                Access::StorageWrite,
                "ambient visibility per hair vertex (f32, 1 = unoccluded); at least 4 B per vertex",
            ),
            buffer(
                "hair_box",
                Access::StorageWrite,
                "scratch: the hair's bounding box, 32 B",
            ),
        ],
        params: vec![
            int(
                "caster_stride",
                1,
                1,
                4096,
                "every k-th hair vertex casts, for k vertices (1 = all: the thesis's O(n²) sum)",
            ),
            plait_graph::ParamSpec {
                name: "scalp_discs".into(),
                ty: plait_graph::ParamType::Bool,
                default: Some(Value::Bool(true)),
                doc: "opaque triangles inside the hair's bounds cast as oriented discs".into(),
            },
            choice(
                "combine",
                "exp",
                &["exp", "sum"],
                "visibility from the summed shadow S: exp(-S) (independent casters) or the thesis's 1 - S, clamped",
            ),
        ],
        ..PassTypeSpec::new(
            "occlusion_cylinders",
            PassShape::Compute,
            "Halén & Wester 2007 §3.3.1",
            "Per-vertex ambient occlusion: hair vertices as transparent cylinders, scalp as discs.",
        )
    }
}

impl PassType for OcclusionCylinders {
    fn spec(&self) -> PassTypeSpec {
        spec()
    }

    fn shader(&self) -> Option<&str> {
        Some(SHADER)
    }

    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let vertices = crate::occlusion_directions::checked_vertex_count(pass, ctx)?;
        let mut defines = default_defines(pass);
        if ctx.geometry.opaque.is_none() {
            defines.push(("NO_SCALP".into(), Define::Bool(true)));
        }
        let slots = [
            ("vertex_ao", "vertex_ao", Access::StorageWrite),
            ("hair_box", "hair_box", Access::StorageWrite),
        ];
        let kernels = kernel_pass(pass, PassShape::Compute, &[], &slots)?;
        let mut bounds_defines = defines.clone();
        bounds_defines.push(("CYLINDER_BOUNDS".into(), Define::Bool(true)));
        let bounds_draw = ShaderDraw::library(
            SHADER,
            pass,
            PassShape::Compute,
            bounds_defines,
            RasterState::default(),
        )?;
        let bounds = build_draw(&bounds_draw, &kernels, ctx)?;
        let mut shadow_draw = ShaderDraw::library(
            SHADER,
            pass,
            PassShape::Compute,
            defines,
            RasterState::default(),
        )?;
        shadow_draw.threads = [vertices, 1, 1];
        let shadow = build_draw(&shadow_draw, &kernels, ctx)?;
        // Bound, so checked to exist; its size is the shader's concern.
        let box_id = bound(pass, "hair_box")?.id();
        if let ResourceDesc::Buffer { size } = ctx.schedule.resources[box_id].desc
            && size < 32
        {
            return Err(GpuError::Pass {
                pass: pass.name.clone(),
                message: format!("`hair_box` holds {size} bytes; it needs 32"),
            });
        }
        Ok(Box::new(Prepared { bounds, shadow }))
    }
}

struct Prepared {
    bounds: ShaderPass,
    shadow: ShaderPass,
}

impl PreparedPass for Prepared {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        self.bounds.record(ctx, encoder);
        self.shadow.record(ctx, encoder);
    }
}
