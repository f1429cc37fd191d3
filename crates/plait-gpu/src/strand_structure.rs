//! The frame's strands in an acceleration structure (issue 48): one
//! procedural box per segment enclosing its tapered swept sphere (the
//! tapered capsules issue 48 describes for RTX Hair; the radius is half the strand's thickness at each
//! end), written by a compute pass from the hair's vertex buffer as it is
//! this frame (after simulation and level of detail), then a bottom-level
//! structure built from the boxes and a top-level one holding it once.
//! Both are built again every frame ([`StrandStructure::encode`]): the hair
//! moves. Ray-traced techniques trace through [`StrandStructure::tlas`] and
//! intersect each candidate box as a capsule in WGSL, all with the one loop
//! of `shaders/lib/strand_rays.wgsl` (`shaders/lib/strand_capsule.wgsl`).
//!
//! The scene's meshes (head, ground, `[[meshes]]`) are in the top-level
//! structure too: one triangle bottom-level structure per mesh, built once
//! (meshes do not deform), each an instance whose transform is the frame's
//! `head_model` for the head's meshes (their vertices are at rest, as the
//! opaque passes draw them) and the identity for the rest, set on every
//! build. Instance masks tell them apart: [`STRAND_MASK`] for the strands'
//! boxes, [`MESH_MASK`] for the meshes, so a ray asks for either or both
//! (`plait::strand_rays`); a mesh hit is opaque.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::geometry::{OpaqueMesh, OpaqueVertex, SceneGeometry};
use crate::{Capabilities, Gpu};

/// Bytes per box: min.xyz, max.xyz (wgpu's smallest AABB stride).
pub const BOX_STRIDE: u64 = wgpu::AABB_GEOMETRY_MIN_STRIDE;

/// The strands' instance mask (`STRAND_INSTANCES` in `shaders/lib/strand_rays.wgsl`).
pub const STRAND_MASK: u8 = 0x01;
/// The meshes' instance mask (`MESH_INSTANCES` in `shaders/lib/strand_rays.wgsl`).
pub const MESH_MASK: u8 = 0x02;

/// The identity as a 3×4 row-major instance transform.
const IDENTITY: [f32; 12] = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0];

/// Why the strands cannot be put in a structure on this adapter.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StructureError {
    #[error(
        "adapter {adapter} has no ray queries (wgpu's EXPERIMENTAL_RAY_QUERY, Vulkan's VK_KHR_ray_query); {}",
        crate::support::RAY_QUERY_FIX
    )]
    NoRayQueries { adapter: String },
    #[error(
        "the hair has {segments} segments, more than the {limit} primitives one acceleration structure of adapter {adapter} holds (max_blas_primitive_count): draw fewer strands or fewer points per strand"
    )]
    TooManySegments {
        segments: u64,
        limit: u32,
        adapter: String,
    },
    #[error(
        "mesh `{mesh}` has {triangles} triangles, more than the {limit} primitives one acceleration structure of adapter {adapter} holds (max_blas_primitive_count): simplify the mesh"
    )]
    TooManyTriangles {
        mesh: String,
        triangles: u64,
        limit: u32,
        adapter: String,
    },
    #[error(
        "the structure needs {instances} instances (the strands and {} meshes), more than the {limit} one top-level structure of adapter {adapter} holds (max_tlas_instance_count): merge meshes",
        instances - 1
    )]
    TooManyInstances {
        instances: u64,
        limit: u32,
        adapter: String,
    },
}

/// Boxes (one per pair of consecutive vertices) for `points` hair vertices.
pub fn segment_count(points: u32) -> u64 {
    u64::from(points.saturating_sub(1))
}

/// Whether an adapter with `caps` holds `segments` boxes in one structure.
pub fn check_segments(
    segments: u64,
    caps: &Capabilities,
    adapter: &str,
) -> Result<(), StructureError> {
    let adapter = adapter.to_owned();
    if !caps.ray_query {
        return Err(StructureError::NoRayQueries { adapter });
    }
    if segments > u64::from(caps.max_blas_primitives) {
        return Err(StructureError::TooManySegments {
            segments,
            limit: caps.max_blas_primitives,
            adapter,
        });
    }
    Ok(())
}

/// Whether an adapter with `caps` holds the meshes, `(name, triangles)`
/// each, as one bottom-level structure each and one instance each beside
/// the strands' in the top-level structure.
pub fn check_meshes<'a>(
    meshes: impl ExactSizeIterator<Item = (&'a str, u64)>,
    caps: &Capabilities,
    adapter: &str,
) -> Result<(), StructureError> {
    let instances = 1 + meshes.len() as u64;
    for (mesh, triangles) in meshes {
        if triangles > u64::from(caps.max_blas_primitives) {
            return Err(StructureError::TooManyTriangles {
                mesh: mesh.to_owned(),
                triangles,
                limit: caps.max_blas_primitives,
                adapter: adapter.to_owned(),
            });
        }
    }
    if instances > u64::from(caps.max_tlas_instances) {
        return Err(StructureError::TooManyInstances {
            instances,
            limit: caps.max_tlas_instances,
            adapter: adapter.to_owned(),
        });
    }
    Ok(())
}

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
}

/// One mesh's bottom-level structure.
struct MeshBlas {
    blas: wgpu::Blas,
    size: wgpu::BlasTriangleGeometrySizeDescriptor,
    first_index: u32,
    head: bool,
}

/// The meshes' structures and the buffers they are built from.
struct Meshes {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    blas: Vec<MeshBlas>,
    /// Whether `blas` are built (once, by the first [`StrandStructure::encode`]).
    built: AtomicBool,
}

/// The structure of one hair vertex buffer and the scene's meshes, rebuilt
/// by each [`encode`](StrandStructure::encode).
pub struct StrandStructure {
    boxes: wgpu::Buffer,
    size: wgpu::BlasAABBGeometrySizeDescriptor,
    blas: wgpu::Blas,
    meshes: Option<Meshes>,
    /// Locked to set the head's instance transforms before each build.
    tlas: Mutex<wgpu::Tlas>,
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    segments: u32,
}

impl StrandStructure {
    /// A structure for `points` vertices of `hair_vertices` (48 B each,
    /// `plait_hair::StrandVertex`) and `meshes`, refused with the numbers
    /// when the adapter cannot hold it.
    pub fn new(
        gpu: &Gpu,
        hair_vertices: &wgpu::Buffer,
        points: u32,
        meshes: Option<MeshInput<'_>>,
    ) -> Result<Self, StructureError> {
        let adapter = gpu.support.describe();
        Self::on(
            &gpu.device,
            (&gpu.capabilities, &adapter),
            (hair_vertices, points),
            meshes,
        )
    }

    /// [`StrandStructure::new`] on `device`, whose adapter is described by
    /// its capabilities and name.
    pub fn on(
        device: &wgpu::Device,
        (caps, adapter): (&Capabilities, &str),
        (hair_vertices, points): (&wgpu::Buffer, u32),
        meshes: Option<MeshInput<'_>>,
    ) -> Result<Self, StructureError> {
        let segments = segment_count(points).max(1);
        check_segments(segments, caps, adapter)?;
        let mesh_list = meshes.map_or(&[][..], |m| m.meshes);
        check_meshes(
            mesh_list
                .iter()
                .map(|m| (m.name.as_str(), u64::from(m.index_count / 3))),
            caps,
            adapter,
        )?;
        let segments = segments as u32;
        let boxes = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("strand_boxes"),
            size: u64::from(segments) * BOX_STRIDE,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::BLAS_INPUT,
            mapped_at_creation: false,
        });
        // Rebuilt every frame, traced a few times per shaded point: a fast
        // build. Each box is reported to the shader at most once per ray, so
        // a crossing is counted once.
        let size = wgpu::BlasAABBGeometrySizeDescriptor {
            primitive_count: segments,
            flags: wgpu::AccelerationStructureGeometryFlags::NO_DUPLICATE_ANY_HIT_INVOCATION,
        };
        let blas = device.create_blas(
            &wgpu::CreateBlasDescriptor {
                label: Some("strands"),
                flags: wgpu::AccelerationStructureFlags::PREFER_FAST_BUILD,
                update_mode: wgpu::AccelerationStructureUpdateMode::Build,
            },
            wgpu::BlasGeometrySizeDescriptors::AABBs {
                descriptors: vec![size.clone()],
            },
        );
        let meshes = meshes.map(|m| mesh_structures(device, m));
        let instances = 1 + meshes.as_ref().map_or(0, |m| m.blas.len());
        let tlas = device.create_tlas(&wgpu::CreateTlasDescriptor {
            label: Some("strands"),
            max_instances: instances as u32,
            flags: wgpu::AccelerationStructureFlags::PREFER_FAST_BUILD,
            update_mode: wgpu::AccelerationStructureUpdateMode::Build,
        });
        let (pipeline, bind_group) = box_pass(device, hair_vertices, &boxes);
        let structure = StrandStructure {
            boxes,
            size,
            blas,
            meshes,
            tlas: Mutex::new(tlas),
            pipeline,
            bind_group,
            segments,
        };
        structure.place_instances(IDENTITY);
        Ok(structure)
    }

    /// The top-level instances: the strands (their vertices are in world
    /// space: the identity), then each mesh, the head's moved by `head`.
    fn place_instances(&self, head: [f32; 12]) {
        let mut tlas = self.tlas.lock().unwrap_or_else(|e| e.into_inner());
        tlas[0] = Some(wgpu::TlasInstance::new(
            &self.blas,
            IDENTITY,
            0,
            STRAND_MASK,
        ));
        let meshes = self.meshes.iter().flat_map(|m| &m.blas);
        for (i, mesh) in meshes.enumerate() {
            let transform = if mesh.head { head } else { IDENTITY };
            tlas[1 + i] = Some(wgpu::TlasInstance::new(
                &mesh.blas,
                transform,
                1 + i as u32,
                MESH_MASK,
            ));
        }
    }

    /// The boxes from this frame's vertices, the meshes' structures the
    /// first time, the head's instances moved by `head_model` (the frame's,
    /// column-major as `FrameUniforms` holds it), then the strands' and the
    /// top-level structures built.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, head_model: [[f32; 4]; 4]) {
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("strand_boxes"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.bind_group, &[]);
            let groups = self.segments.div_ceil(64);
            let (x, y) = (groups.min(65_535), groups.div_ceil(65_535));
            pass.dispatch_workgroups(x, y, 1);
        }
        self.place_instances(row_major_3x4(head_model));
        let mut entries = vec![wgpu::BlasBuildEntry {
            blas: &self.blas,
            geometry: wgpu::BlasGeometries::AabbGeometries(vec![wgpu::BlasAabbGeometry {
                size: &self.size,
                stride: BOX_STRIDE,
                aabb_buffer: &self.boxes,
                primitive_offset: 0,
            }]),
        }];
        if let Some(m) = &self.meshes
            && !m.built.swap(true, Ordering::Relaxed)
        {
            entries.extend(m.blas.iter().map(|b| wgpu::BlasBuildEntry {
                blas: &b.blas,
                geometry: wgpu::BlasGeometries::TriangleGeometries(vec![
                    wgpu::BlasTriangleGeometry {
                        size: &b.size,
                        vertex_buffer: &m.vertices,
                        first_vertex: 0,
                        vertex_stride: std::mem::size_of::<OpaqueVertex>() as u64,
                        index_buffer: Some(&m.indices),
                        first_index: Some(b.first_index),
                        transform_buffer: None,
                        transform_buffer_offset: None,
                    },
                ]),
            }));
        }
        let tlas = self.tlas.lock().unwrap_or_else(|e| e.into_inner());
        encoder.build_acceleration_structures(entries.iter(), std::iter::once(&*tlas));
    }

    /// The top-level structure, for a bind group's acceleration structure
    /// (locked: each build sets the head's instances first).
    pub fn tlas(&self) -> std::sync::MutexGuard<'_, wgpu::Tlas> {
        self.tlas.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Segments (boxes) in the structure.
    pub fn segments(&self) -> u32 {
        self.segments
    }

    /// Meshes (triangle instances) in the structure.
    pub fn mesh_count(&self) -> usize {
        self.meshes.as_ref().map_or(0, |m| m.blas.len())
    }

    /// Bytes of the boxes plait allocates. The structures' own sizes are
    /// the driver's and wgpu 30 does not report them.
    pub fn box_bytes(&self) -> u64 {
        self.boxes.size()
    }
}

/// A column-major 4×4 matrix's top three rows, row-major (an instance's
/// transform).
fn row_major_3x4(m: [[f32; 4]; 4]) -> [f32; 12] {
    let mut out = [0.0; 12];
    for row in 0..3 {
        for col in 0..4 {
            out[4 * row + col] = m[col][row];
        }
    }
    out
}

/// One triangle bottom-level structure per mesh, unbuilt: every mesh
/// indexes the one opaque vertex buffer (its indices already offset), so
/// each structure takes the whole buffer and its own stretch of indices.
fn mesh_structures(device: &wgpu::Device, input: MeshInput<'_>) -> Meshes {
    let stride = std::mem::size_of::<OpaqueVertex>() as u64;
    let vertex_count = (input.vertices.size() / stride) as u32;
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
            // Built once and traced by every ray: a fast trace.
            let blas = device.create_blas(
                &wgpu::CreateBlasDescriptor {
                    label: Some(&mesh.name),
                    flags: wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE,
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

fn box_pass(
    device: &wgpu::Device,
    hair_vertices: &wgpu::Buffer,
    boxes: &wgpu::Buffer,
) -> (wgpu::ComputePipeline, wgpu::BindGroup) {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("strand_boxes"),
        source: wgpu::ShaderSource::Wgsl(
            include_str!("../../../shaders/passes/strand_boxes.wgsl").into(),
        ),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("strand_boxes"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("strand_boxes"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: hair_vertices.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: boxes.as_entire_binding(),
            },
        ],
    });
    (pipeline, bind_group)
}
