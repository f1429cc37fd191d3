//! `occlusion_cylinders`: per-vertex ambient occlusion with hair vertices as
//! transparent cylinders and the scalp as oriented discs (Halén & Wester
//! 2007 §3.3.1, §5.7). Two kernels of `occlusion_cylinders.wgsl`: the hair's
//! bounding box (which opaque triangles are scalp), then one thread per
//! receiving vertex summing the shadow of every caster, chunk by chunk, then
//! the visibility from the sum.
//!
//! The chunks exist for lavapipe's loop budget: each group of 8 invocations
//! may run 65,535 loop iterations in all, then every loop silently stops. One
//! loop over the 330,000 casters of the built-in groom would sum only the
//! first ~65,000; so the shadow kernel is dispatched once per chunk of at
//! most `chunk_iterations` casters (or scalp triangles), each dispatch
//! adding its chunk to the vertex's running sum in `vertex_ao`, in the order
//! one loop would (deterministic, no float atomics). The pass runs once, so
//! the extra dispatches cost nothing per frame. A loop that still stops
//! early counts in `ao_status` (the `incomplete` word of its overflow
//! declaration) and fails the frame.

use plait_gpu::GpuError;
use plait_gpu::pass::{
    BuildContext, PassType, PreparedPass, RecordContext, ShaderPass, default_defines,
};
use plait_gpu::shader::Define;
use plait_graph::{Access, PassShape, PassTypeSpec, ResourceDesc, ScheduledPass, SlotId, Value};

use crate::occlusion_directions::{compute_kernel, kernel_pass};
use crate::spec_util::{bound, buffer, choice, int};

pub struct OcclusionCylinders;

inventory::submit! { crate::RustPassType(|_| Box::new(OcclusionCylinders)) }

const SHADER: &str = "shaders/passes/occlusion_cylinders.wgsl";

/// Loop iterations of one shadow dispatch by default (the `chunk_iterations`
/// param): a quarter of lavapipe's 65,535 per group of 8 invocations.
pub const CHUNK_ITERATIONS: i64 = 16_384;

/// Bytes of `hair_box`: the box (two vec4) and the current chunk (4 u32).
const HAIR_BOX_BYTES: u64 = 48;
/// Where the chunk's bounds start in `hair_box` (the WGSL `HairBox`).
const CHUNK_OFFSET: u64 = 32;
const CHUNK_BYTES: u64 = 16;

/// Its slots' handles ([`SlotId`]), in `spec`'s order.
pub(crate) const VERTEX_AO: SlotId = SlotId::Output(0);
pub(crate) const HAIR_BOX: SlotId = SlotId::Output(1);
pub(crate) const AO_STATUS: SlotId = SlotId::Output(2);

pub(crate) fn spec() -> PassTypeSpec {
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
                "scratch: the hair's bounding box and the chunk being summed, 48 B",
            ),
            buffer(
                "ao_status",
                Access::StorageWrite,
                "word 0 counts invocations whose sum was cut short (declare it `overflow = { incomplete = 0 }`), at least 4 B",
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
            int(
                "chunk_iterations",
                CHUNK_ITERATIONS,
                1,
                u32::MAX as i64,
                "loop iterations (casters or scalp triangles) one dispatch sums; lavapipe ends every loop of a group of 8 invocations past 65,535 in all (the frame then fails)",
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
        let spec = spec();
        let vertices =
            crate::occlusion_directions::checked_vertex_count(pass, &spec, VERTEX_AO, ctx)?;
        let mut defines = default_defines(pass);
        if ctx.geometry.opaque.is_none() {
            defines.push(("NO_SCALP".into(), Define::Bool(true)));
        }
        let slots = [
            ("vertex_ao", VERTEX_AO, Access::StorageWrite),
            ("hair_box", HAIR_BOX, Access::StorageWrite),
            ("ao_status", AO_STATUS, Access::StorageWrite),
        ];
        let kernels = kernel_pass(pass, &spec, PassShape::Compute, &[], &slots)?;
        let kernel = |extra: Option<&str>, threads: u32| {
            let mut defines = defines.clone();
            if let Some(name) = extra {
                defines.push((name.into(), Define::Bool(true)));
            }
            compute_kernel(SHADER, pass, defines, threads, &kernels, ctx)
        };
        let bounds = kernel(Some("CYLINDER_BOUNDS"), 1)?;
        let shadow = kernel(None, vertices)?;
        let visibility = kernel(Some("CYLINDER_VISIBILITY"), vertices)?;
        check_scratch(pass, &spec, ctx)?;
        let (chunk_buffer, chunks) = chunk_buffer(pass, ctx, vertices);
        Ok(Box::new(Prepared {
            bounds,
            shadow,
            visibility,
            chunk_buffer,
            chunks,
            vertex_ao: bound(pass, &spec, VERTEX_AO)?.id(),
            hair_box: bound(pass, &spec, HAIR_BOX)?.id(),
        }))
    }
}

/// The scratch buffers the shader indexes: `hair_box` holds the box and the
/// chunk, `ao_status` its one word.
fn check_scratch(
    pass: &ScheduledPass,
    spec: &PassTypeSpec,
    ctx: &BuildContext<'_>,
) -> Result<(), GpuError> {
    for (slot, need) in [(HAIR_BOX, HAIR_BOX_BYTES), (AO_STATUS, 4)] {
        let binding = bound(pass, spec, slot)?;
        let (id, slot) = (binding.id(), &binding.slot);
        if let ResourceDesc::Buffer { size } = ctx.schedule.resources[id].desc
            && size < need
        {
            return Err(GpuError::Pass {
                pass: pass.name.clone(),
                message: format!("`{slot}` holds {size} bytes; it needs {need}"),
            });
        }
    }
    Ok(())
}

/// Every chunk's bounds ([`chunks`]) in a buffer the pass copies from, and
/// how many there are.
fn chunk_buffer(
    pass: &ScheduledPass,
    ctx: &BuildContext<'_>,
    vertices: u32,
) -> (wgpu::Buffer, u64) {
    let int = |name| crate::occlusion_directions::int_param(pass, name);
    let stride = int("caster_stride").clamp(1, u32::MAX as i64) as u32;
    let per_chunk = int("chunk_iterations").clamp(1, u32::MAX as i64) as u32;
    let triangles = match &ctx.geometry.opaque {
        Some(opaque) if pass.params.get("scalp_discs") != Some(&Value::Bool(false)) => {
            opaque.index_count / 3
        }
        _ => 0,
    };
    let chunks = chunks(vertices, stride, triangles, per_chunk);
    // One empty chunk when there is nothing: a buffer is never 0 bytes.
    let bytes: Vec<u8> = chunks
        .iter()
        .chain(chunks.is_empty().then_some(&[0u32; 4]))
        .flat_map(|c| c.iter().flat_map(|w| w.to_le_bytes()))
        .collect();
    let buffer = wgpu::util::DeviceExt::create_buffer_init(
        ctx.device,
        &wgpu::util::BufferInitDescriptor {
            label: Some(&format!("{} chunks", pass.name)),
            contents: &bytes,
            usage: wgpu::BufferUsages::COPY_SRC,
        },
    );
    (buffer, chunks.len() as u64)
}

/// The shadow dispatches' bounds, `[caster_first, caster_end, triangle_first,
/// triangle_end]` each: the casters `0, k, 2k, … < vertices` (k = `stride`)
/// and then the `triangles`, at most `per_chunk` loop iterations a dispatch.
pub fn chunks(vertices: u32, stride: u32, triangles: u32, per_chunk: u32) -> Vec<[u32; 4]> {
    let stride = stride.max(1);
    let per_chunk = per_chunk.max(1);
    let casters = vertices.div_ceil(stride);
    let mut out = Vec::new();
    let mut first = 0;
    while first < casters {
        let end = first.saturating_add(per_chunk).min(casters);
        out.push([
            first * stride,
            (end as u64 * stride as u64).min(vertices as u64) as u32,
            0,
            0,
        ]);
        first = end;
    }
    let mut first = 0;
    while first < triangles {
        let end = first.saturating_add(per_chunk).min(triangles);
        out.push([0, 0, first, end]);
        first = end;
    }
    out
}

struct Prepared {
    bounds: ShaderPass,
    shadow: ShaderPass,
    visibility: ShaderPass,
    /// Every chunk's bounds, [`CHUNK_BYTES`] each, copied into `hair_box` in turn.
    chunk_buffer: wgpu::Buffer,
    chunks: u64,
    vertex_ao: plait_graph::ResourceId,
    hair_box: plait_graph::ResourceId,
}

impl PreparedPass for Prepared {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        // The running sums start at zero.
        if let Some(b) = ctx.pool.buffer(self.vertex_ao) {
            encoder.clear_buffer(b, 0, None);
        }
        self.bounds.record(ctx, encoder);
        let Some(hair_box) = ctx.pool.buffer(self.hair_box) else {
            return;
        };
        for k in 0..self.chunks {
            encoder.copy_buffer_to_buffer(
                &self.chunk_buffer,
                k * CHUNK_BYTES,
                hair_box,
                CHUNK_OFFSET,
                CHUNK_BYTES,
            );
            self.shadow.record(ctx, encoder);
        }
        self.visibility.record(ctx, encoder);
    }

    fn stats(&self) -> Vec<(String, f64)> {
        vec![("chunks".into(), self.chunks as f64)]
    }
}

#[cfg(test)]
mod tests {
    use super::chunks;

    #[test]
    fn chunks_cover_every_caster_and_triangle_once_in_order() {
        // 10 vertices at stride 3 cast from 0, 3, 6, 9; 2 iterations a chunk.
        assert_eq!(
            chunks(10, 3, 5, 2),
            vec![
                [0, 6, 0, 0],
                [6, 10, 0, 0],
                [0, 0, 0, 2],
                [0, 0, 2, 4],
                [0, 0, 4, 5]
            ]
        );
        assert!(chunks(0, 1, 0, 16).is_empty());
        // One chunk of everything, whatever the param allows.
        assert_eq!(
            chunks(10, 1, 3, u32::MAX),
            vec![[0, 10, 0, 0], [0, 0, 0, 3]]
        );
        // The built-in groom: 330,000 casters in 21 chunks, the head in 1.
        assert_eq!(chunks(330_000, 1, 3_970, 16_384).len(), 22);
    }
}
