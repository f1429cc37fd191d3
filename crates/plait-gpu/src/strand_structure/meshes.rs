//! The scene's meshes in the structure: one triangle bottom-level structure
//! per mesh, built once (meshes do not deform) — by its own submission
//! ([`Meshes::build_on`]) so that "built" means submitted, or else in every
//! frame's encoder until then ([`Meshes::entries`]).

use std::sync::atomic::{AtomicBool, Ordering};

use crate::geometry::{OpaqueMesh, OpaqueVertex, SceneGeometry};

/// The scene's opaque meshes as the structure takes them: the one vertex
/// and index buffer every mesh is drawn from (`SceneGeometry::opaque`,
/// which has `BLAS_INPUT` on a device with ray queries) and each mesh's
/// stretch of it.
#[derive(Clone, Copy)]
pub struct MeshInput<'a> {
    pub vertices: &'a wgpu::Buffer,
    pub indices: &'a wgpu::Buffer,
    pub meshes: &'a [OpaqueMesh],
}

impl<'a> MeshInput<'a> {
    /// The geometry's meshes; `None` without any.
    pub fn of(geometry: &'a SceneGeometry) -> Option<Self> {
        let opaque = geometry.opaque.as_ref()?;
        (!geometry.opaque_meshes.is_empty()).then_some(MeshInput {
            vertices: &opaque.vertices,
            indices: &opaque.indices,
            meshes: &geometry.opaque_meshes,
        })
    }

    /// Vertices of the shared buffer (each mesh's structure takes them all).
    pub(super) fn vertex_count(&self) -> u32 {
        (self.vertices.size() / std::mem::size_of::<OpaqueVertex>() as u64) as u32
    }
}

/// One mesh's bottom-level structure.
pub(super) struct MeshBlas {
    pub blas: wgpu::Blas,
    size: wgpu::BlasTriangleGeometrySizeDescriptor,
    first_index: u32,
    pub head: bool,
}

/// The meshes' structures and the buffers they are built from.
pub(super) struct Meshes {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    pub blas: Vec<MeshBlas>,
    /// Set once a submission holding the builds was made
    /// ([`Meshes::build_on`]); until then every frame's encoder builds them.
    built: AtomicBool,
}

/// Built once and traced by every ray: a fast trace.
pub(super) const MESH_FLAGS: wgpu::AccelerationStructureFlags =
    wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE;

impl Meshes {
    /// One unbuilt triangle bottom-level structure per mesh: every mesh
    /// indexes the one opaque vertex buffer (its indices already offset), so
    /// each structure takes the whole buffer and its own stretch of indices.
    pub fn new(device: &wgpu::Device, input: MeshInput<'_>) -> Self {
        let vertex_count = input.vertex_count();
        let blas = input
            .meshes
            .iter()
            .map(|mesh| {
                let size = wgpu::BlasTriangleGeometrySizeDescriptor {
                    vertex_format: wgpu::VertexFormat::Float32x3,
                    vertex_count,
                    index_format: Some(wgpu::IndexFormat::Uint32),
                    index_count: Some(mesh.index_count),
                    flags: wgpu::AccelerationStructureGeometryFlags::OPAQUE,
                };
                let blas = device.create_blas(
                    &wgpu::CreateBlasDescriptor {
                        label: Some(&mesh.name),
                        flags: MESH_FLAGS,
                        update_mode: wgpu::AccelerationStructureUpdateMode::Build,
                    },
                    wgpu::BlasGeometrySizeDescriptors::Triangles {
                        descriptors: vec![size.clone()],
                    },
                );
                MeshBlas {
                    blas,
                    size,
                    first_index: mesh.first_index,
                    head: mesh.head,
                }
            })
            .collect();
        Meshes {
            vertices: input.vertices.clone(),
            indices: input.indices.clone(),
            blas,
            built: AtomicBool::new(false),
        }
    }

    /// The meshes' builds for an encoder that also builds the top-level
    /// structure: none once a submission built them, else all of them. The
    /// flag is not set here: an encoder may be dropped unsubmitted (a frame
    /// that fails before its submit), and a top-level build over structures
    /// never built is a validation error on every later frame.
    pub fn entries(&self) -> Vec<wgpu::BlasBuildEntry<'_>> {
        if self.built.load(Ordering::Acquire) {
            return Vec::new();
        }
        self.blas
            .iter()
            .map(|b| wgpu::BlasBuildEntry {
                blas: &b.blas,
                geometry: wgpu::BlasGeometries::TriangleGeometries(vec![
                    wgpu::BlasTriangleGeometry {
                        size: &b.size,
                        vertex_buffer: &self.vertices,
                        first_vertex: 0,
                        vertex_stride: std::mem::size_of::<OpaqueVertex>() as u64,
                        index_buffer: Some(&self.indices),
                        first_index: Some(b.first_index),
                        transform_buffer: None,
                        transform_buffer_offset: None,
                    },
                ]),
            })
            .collect()
    }

    /// Builds the meshes' structures in a submission of their own, once:
    /// queued before whatever is submitted after it, so every later frame's
    /// top-level build finds them built, and marked built only once that
    /// submission is made. (A build the device refuses is a validation error
    /// the frame reports, as any other.)
    pub fn build_on(&self, device: &wgpu::Device, queue: &wgpu::Queue) {
        if self.built.load(Ordering::Acquire) {
            return;
        }
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("mesh_structures"),
        });
        let entries = self.entries();
        encoder.build_acceleration_structures(entries.iter(), std::iter::empty());
        queue.submit([encoder.finish()]);
        self.built.store(true, Ordering::Release);
    }
}
