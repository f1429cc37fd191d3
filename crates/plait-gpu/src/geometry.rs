//! Scene geometry on the GPU: hair as a line list, opaque meshes as one triangle list.

use plait_hair::mesh::Mesh;
use plait_hair::{StrandVertex, Strands};
use wgpu::util::DeviceExt;

/// An opaque vertex with its mesh's albedo baked in, so all opaque geometry is one draw.
/// Shaders that read `opaque_vertices` as storage step by its 10 floats
/// (`OPAQUE_STRIDE` in `shaders/passes/occlusion_cylinders.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct OpaqueVertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub albedo: [f32; 3],
    /// 1 for the head's vertices, which move with `frame.head_model`; 0 for
    /// everything else.
    pub head: f32,
}

/// Vertex buffer layout of hair (`StrandVertex`): locations 0–5 =
/// position, thickness, tangent, alpha, color, strand_id.
pub const HAIR_VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 6] = wgpu::vertex_attr_array![
    0 => Float32x3, 1 => Float32, 2 => Float32x3, 3 => Float32, 4 => Float32x3, 5 => Uint32
];
/// Vertex buffer layout of opaque geometry: locations 0–3 = position, normal,
/// albedo, head weight.
pub const OPAQUE_VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3, 3 => Float32];

pub fn hair_vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<StrandVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &HAIR_VERTEX_ATTRIBUTES,
    }
}

pub fn opaque_vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<OpaqueVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &OPAQUE_VERTEX_ATTRIBUTES,
    }
}

/// Indexed geometry ready to draw.
pub struct DrawBuffers {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub index_count: u32,
}

/// Everything a raster pass can draw.
pub struct SceneGeometry {
    pub hair: Option<DrawBuffers>,
    pub opaque: Option<DrawBuffers>,
    /// The hair's vertices as a storage buffer too, for compute passes.
    pub strand_count: u32,
    pub segment_count: u32,
    /// The scene's environment image, the `environment_source` scene binding
    /// ([`SceneGeometry::set_environment`]).
    pub environment: Option<wgpu::TextureView>,
}

fn upload<V: bytemuck::Pod>(
    device: &wgpu::Device,
    label: &str,
    vertices: &[V],
    indices: &[u32],
) -> Option<DrawBuffers> {
    if indices.is_empty() {
        return None;
    }
    let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(&format!("{label} vertices")),
        contents: bytemuck::cast_slice(vertices),
        // COPY_DST: the hair is rewritten when it follows the head.
        usage: wgpu::BufferUsages::VERTEX
            | wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST,
    });
    let index_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(&format!("{label} indices")),
        contents: bytemuck::cast_slice(indices),
        usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::STORAGE,
    });
    Some(DrawBuffers {
        vertices,
        indices: index_buffer,
        index_count: indices.len() as u32,
    })
}

impl SceneGeometry {
    /// Rewrites the hair's vertices with `strands` moved (same strands and
    /// points as uploaded: only positions and tangents change). `false` when
    /// the point count differs and nothing was written.
    pub fn write_hair(&self, queue: &wgpu::Queue, strands: &Strands) -> bool {
        let Some(hair) = &self.hair else {
            return strands.points.is_empty();
        };
        let (vertices, _) = strands.line_list();
        let bytes: &[u8] = bytemuck::cast_slice(&vertices);
        if bytes.len() as u64 != hair.vertices.size() {
            return false;
        }
        queue.write_buffer(&hair.vertices, 0, bytes);
        true
    }

    pub fn upload(device: &wgpu::Device, strands: &Strands, meshes: &[Mesh]) -> Self {
        let (hair_vertices, hair_indices) = strands.line_list();
        let hair = upload(device, "hair", &hair_vertices, &hair_indices);
        let mut vertices = Vec::new();
        let mut indices = Vec::new();
        for mesh in meshes {
            let base = vertices.len() as u32;
            vertices.extend(mesh.vertices.iter().map(|v| OpaqueVertex {
                position: v.position,
                normal: v.normal,
                albedo: mesh.albedo,
                head: if mesh.name == "head" { 1.0 } else { 0.0 },
            }));
            indices.extend(mesh.indices.iter().map(|i| i + base));
        }
        let opaque = upload(device, "opaque", &vertices, &indices);
        SceneGeometry {
            hair,
            opaque,
            strand_count: strands.strand_count() as u32,
            segment_count: strands.segment_count() as u32,
            environment: None,
        }
    }
}
