//! `strand_structure`: the frame's strands in an acceleration structure for
//! ray queries (issue 48; `plait_gpu::strand_structure`): each segment as
//! its `primitive` — `swept_sphere`, one box enclosing its tapered swept
//! sphere, or `dots`, two crossed quads (four triangles) — from the scene's
//! `hair_vertices` as they are when the pass runs (after simulation and
//! interpolation, which write them), then the bottom- and top-level
//! structures, rebuilt every frame; the scene's meshes as triangle
//! instances beside them (built once, by a submission of their own before
//! the first frame's; the head's instances moved by the frame's
//! `head_model`), unless `meshes = false` (a structure whose rays mask them
//! out builds none). `hair_vertices` may be bound to a technique's
//! buffer of the same layout instead of the scene's (a widened copy,
//! `techniques/transparency/ray_traced`). Its output slot is the resource a
//! ray-traced technique binds (`kind = "acceleration_structure"`). The
//! pass's shader declares the slots for `plait check`; the boxes are
//! written by the structure's own compute pass
//! (`shaders/passes/strand_boxes.wgsl`).

use plait_gpu::pass::{BuildContext, PassType, PreparedPass, RecordContext};
use plait_gpu::strand_structure::{MeshInput, StrandPrimitive, StrandStructure, StructureOptions};
use plait_gpu::{Define, GpuError};
use plait_graph::{
    Access, Formats, PassShape, PassTypeSpec, ResourceKind, ScheduledPass, SlotSpec,
};

use crate::spec_util::{buffer, choice};

pub struct StrandStructurePass;

inventory::submit! { crate::RustPassType(|_| Box::new(StrandStructurePass)) }

const SHADER: &str = "shaders/passes/strand_structure.wgsl";

fn spec() -> PassTypeSpec {
    let structure = SlotSpec {
        name: "structure".into(),
        kind: ResourceKind::AccelerationStructure,
        access: Access::StorageWrite,
        formats: Formats::Any,
        loads: false,
        optional: false,
        doc: "the strands' acceleration structure (declare `kind = \"acceleration_structure\"`)"
            .into(),
        binding: None,
    };
    PassTypeSpec {
        inputs: vec![buffer(
            "hair_vertices",
            Access::StorageRead,
            "the scene's hair vertices (this frame's)",
        )],
        outputs: vec![structure],
        params: vec![
            choice(
                "primitive",
                "swept_sphere",
                &StrandPrimitive::NAMES,
                "a strand segment in the structure: swept_sphere (a box, intersected as a tapered capsule) or dots (two crossed quads, 4 triangles)",
            ),
            plait_graph::ParamSpec {
                name: "meshes".into(),
                ty: plait_graph::ParamType::Bool,
                default: Some(plait_graph::Value::Bool(true)),
                doc: "the scene's meshes in the structure (false: a structure whose rays mask them out builds none)".into(),
            },
        ],
        ..PassTypeSpec::new(
            "strand_structure",
            PassShape::Compute,
            "issue 48 (RTX Hair's tapered capsules as procedural boxes; DOTS, its earlier crossed quads)",
            "The strands in an acceleration structure: per segment a box around its tapered swept sphere or DOTS' two crossed quads (primitive), BLAS + TLAS rebuilt every frame; the scene's meshes as triangle instances (built once, the head moved by head_model; meshes = false leaves them out).",
        )
    }
}

impl PassType for StrandStructurePass {
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
        let fail = |message: String| GpuError::Pass {
            pass: pass.name.clone(),
            message,
        };
        let hair = ctx
            .geometry
            .hair
            .as_ref()
            .ok_or_else(|| fail("the scene has no hair to put in a structure".into()))?;
        let slot = pass.writes.iter().find(|b| b.slot == "structure");
        let (id, name) = slot
            .and_then(|b| Some((b.resource?, b.resource_name.as_str())))
            .ok_or_else(|| fail("no resource bound to `structure`".into()))?;
        let cell = ctx
            .pool
            .strands(id)
            .ok_or_else(|| fail(format!("`{name}` is no acceleration structure")))?;
        // The buffer bound to `hair_vertices`: the scene's, or a technique's
        // copy of it (transparency = ray_traced widens each vertex to the
        // pixel's footprint there, so a primary ray through a pixel centre
        // finds every strand covering part of the pixel). Only its first
        // point_count vertices are boxed; a copy too small for them counts
        // that in its own overflow counter (the boxes past it stay empty).
        let vertices = pass
            .reads
            .iter()
            .find(|b| b.slot == "hair_vertices")
            .and_then(|b| b.resource)
            .and_then(|id| ctx.pool.buffer(id))
            .unwrap_or(&hair.vertices);
        let primitive = match pass.params.get("primitive") {
            Some(plait_graph::Value::Str(name)) => StrandPrimitive::from_name(name)
                .ok_or_else(|| fail(format!("unknown primitive `{name}`")))?,
            _ => StrandPrimitive::default(),
        };
        let meshes = !matches!(
            pass.params.get("meshes"),
            Some(plait_graph::Value::Bool(false))
        );
        let structure = StrandStructure::on_with(
            ctx.device,
            (ctx.capabilities, ctx.adapter_name),
            (vertices, ctx.geometry.point_count),
            StructureOptions {
                primitive,
                meshes: MeshInput::of(ctx.geometry).filter(|_| meshes),
            },
        )
        .map_err(|e| fail(e.to_string()))?;
        let stats = structure_stats(&structure);
        if cell.set(structure).is_err() {
            return Err(fail(format!("`{name}` is built by two passes")));
        }
        Ok(Box::new(Prepared { id, stats }))
    }
}

struct Prepared {
    id: plait_graph::ResourceId,
    stats: Vec<(String, f64)>,
}

/// The structure's memory, in the run's pass stats (`plait render`'s
/// table, `--json`, `plait ab`): the build input plait writes each frame
/// and, where the driver states them, its structures and build scratch.
fn structure_stats(s: &StrandStructure) -> Vec<(String, f64)> {
    let mut out = vec![
        ("segments".into(), f64::from(s.segments())),
        ("input_bytes".into(), s.box_bytes() as f64),
    ];
    if let Some(d) = s.driver_sizes() {
        out.push(("strands_bytes".into(), d.strands.structure as f64));
        out.push(("meshes_bytes".into(), d.meshes.structure as f64));
        out.push(("top_bytes".into(), d.top.structure as f64));
        let scratch = d.strands.scratch + d.meshes.scratch + d.top.scratch;
        out.push(("scratch_bytes".into(), scratch as f64));
    }
    out
}

impl PreparedPass for Prepared {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        if let Some(s) = ctx.pool.strands(self.id).and_then(|c| c.get()) {
            s.build_meshes(ctx.device, ctx.queue);
            s.encode(encoder, ctx.head_model);
        }
    }

    fn stats(&self) -> Vec<(String, f64)> {
        self.stats.clone()
    }
}
