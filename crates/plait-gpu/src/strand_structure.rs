//! The frame's strands in an acceleration structure (issue 48), each
//! segment (a pair of consecutive vertices of one strand) as its
//! [`StrandPrimitive`]: one procedural box enclosing its tapered swept
//! sphere (the tapered capsules issue 48 describes for RTX Hair; the radius
//! is half the strand's thickness at each end), or DOTS — two quads crossed
//! along its axis, four triangles of the same half-widths, NVIDIA's
//! representation before linear swept spheres. A compute pass writes the
//! boxes or the triangles' corners from the hair's vertex buffer as it is
//! this frame (after simulation and level of detail), then a bottom-level
//! structure is built from them and a top-level one holding it once. Both
//! are built again every frame ([`StrandStructure::encode`]): the hair
//! moves. Ray-traced techniques trace through [`StrandStructure::tlas`] with
//! the one loop of `shaders/lib/strand_rays.wgsl`, which intersects each
//! candidate box as a capsule (`shaders/lib/strand_capsule.wgsl`) and counts
//! each segment's DOTS triangles once (`shaders/lib/strand_dots.wgsl`).
//!
//! The scene's meshes (head, ground, `[[meshes]]`) are in the top-level
//! structure too, unless left out (a structure whose rays mask them out):
//! one triangle bottom-level structure per mesh, built once (meshes do not
//! deform; [`StrandStructure::build_meshes`]), each an instance whose
//! transform is the frame's `head_model` for the head's meshes (their
//! vertices are at rest, as the opaque passes draw them) and the identity
//! for the rest, set on every build. Instance masks tell them apart:
//! [`STRAND_MASK`] for the strands, [`MESH_MASK`] for the meshes, so a ray
//! asks for either or both (`plait::strand_rays`); a mesh hit is opaque. The
//! strands' instance has custom data 0, the meshes' 1, 2, …: what tells a
//! strand's DOTS triangle from a mesh's.

mod limits;
mod meshes;
mod sizes;

use std::sync::Mutex;

pub use limits::{
    StrandPrimitive, StructureError, check_meshes, check_primitives, check_segments, segment_count,
};
pub use meshes::MeshInput;
pub use sizes::{BuildSize, DriverSizes};

use crate::{Capabilities, Gpu};
use meshes::Meshes;

/// Bytes per box: min.xyz, max.xyz (wgpu's smallest AABB stride).
pub const BOX_STRIDE: u64 = wgpu::AABB_GEOMETRY_MIN_STRIDE;

/// The strands' instance mask (`STRAND_INSTANCES` in `shaders/lib/strand_rays.wgsl`).
pub const STRAND_MASK: u8 = 0x01;
/// The meshes' instance mask (`MESH_INSTANCES` in `shaders/lib/strand_rays.wgsl`).
pub const MESH_MASK: u8 = 0x02;

/// The identity as a 3×4 row-major instance transform.
const IDENTITY: [f32; 12] = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0];

/// The strands' geometry as the bottom-level build takes it.
enum StrandGeometry {
    Boxes(wgpu::BlasAABBGeometrySizeDescriptor),
    Dots(wgpu::BlasTriangleGeometrySizeDescriptor),
}

/// Rebuilt every frame, traced a few times per shaded point: a fast build.
const STRAND_FLAGS: wgpu::AccelerationStructureFlags =
    wgpu::AccelerationStructureFlags::PREFER_FAST_BUILD;
const TOP_FLAGS: wgpu::AccelerationStructureFlags =
    wgpu::AccelerationStructureFlags::PREFER_FAST_BUILD;

/// How a structure is made: its strands' primitive, and whether the
/// scene's meshes are in it.
#[derive(Clone, Copy, Default)]
pub struct StructureOptions<'a> {
    pub primitive: StrandPrimitive,
    /// `None`: no meshes (a scene without any, or a structure whose rays
    /// mask them out).
    pub meshes: Option<MeshInput<'a>>,
}

/// The structure of one hair vertex buffer and the scene's meshes, rebuilt
/// by each [`encode`](StrandStructure::encode).
pub struct StrandStructure {
    primitive: StrandPrimitive,
    /// Boxes (swept spheres) or triangle corners (DOTS), written each frame.
    input: wgpu::Buffer,
    geometry: StrandGeometry,
    blas: wgpu::Blas,
    meshes: Option<Meshes>,
    /// Locked to set the head's instance transforms before each build.
    tlas: Mutex<wgpu::Tlas>,
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    segments: u32,
    driver: Option<DriverSizes>,
}

impl StrandStructure {
    /// A structure of swept spheres for `points` vertices of `hair_vertices`
    /// (48 B each, `plait_hair::StrandVertex`) and `meshes`, refused with the
    /// numbers when the adapter cannot hold it.
    pub fn new(
        gpu: &Gpu,
        hair_vertices: &wgpu::Buffer,
        points: u32,
        meshes: Option<MeshInput<'_>>,
    ) -> Result<Self, StructureError> {
        Self::with(
            gpu,
            (hair_vertices, points),
            StructureOptions {
                primitive: StrandPrimitive::SweptSphere,
                meshes,
            },
        )
    }

    /// [`StrandStructure::new`] with the strands as `options.primitive`.
    pub fn with(
        gpu: &Gpu,
        hair: (&wgpu::Buffer, u32),
        options: StructureOptions<'_>,
    ) -> Result<Self, StructureError> {
        let adapter = gpu.support.describe();
        Self::on_with(&gpu.device, (&gpu.capabilities, &adapter), hair, options)
    }

    /// [`StrandStructure::new`] on `device`, whose adapter is described by
    /// its capabilities and name.
    pub fn on(
        device: &wgpu::Device,
        adapter: (&Capabilities, &str),
        hair: (&wgpu::Buffer, u32),
        meshes: Option<MeshInput<'_>>,
    ) -> Result<Self, StructureError> {
        let options = StructureOptions {
            primitive: StrandPrimitive::SweptSphere,
            meshes,
        };
        Self::on_with(device, adapter, hair, options)
    }

    /// [`StrandStructure::with`] on `device`.
    pub fn on_with(
        device: &wgpu::Device,
        (caps, adapter): (&Capabilities, &str),
        (hair_vertices, points): (&wgpu::Buffer, u32),
        StructureOptions { primitive, meshes }: StructureOptions<'_>,
    ) -> Result<Self, StructureError> {
        let segments = segment_count(points).max(1);
        check_primitives(segments, primitive, caps, adapter)?;
        let mesh_list = meshes.map_or(&[][..], |m| m.meshes);
        check_meshes(
            mesh_list
                .iter()
                .map(|m| (m.name.as_str(), u64::from(m.index_count / 3))),
            caps,
            adapter,
        )?;
        let segments = segments as u32;
        let input = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(match primitive {
                StrandPrimitive::SweptSphere => "strand_boxes",
                StrandPrimitive::Dots => "strand_dots",
            }),
            size: u64::from(segments) * primitive.input_bytes(),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::BLAS_INPUT,
            mapped_at_creation: false,
        });
        // Each primitive is reported to the shader at most once per ray, so
        // a box's crossing is counted once (and a DOTS triangle's report
        // once before plait::strand_dots picks one per segment).
        let flags = wgpu::AccelerationStructureGeometryFlags::NO_DUPLICATE_ANY_HIT_INVOCATION;
        let (geometry, sizes) = match primitive {
            StrandPrimitive::SweptSphere => {
                let size = wgpu::BlasAABBGeometrySizeDescriptor {
                    primitive_count: segments,
                    flags,
                };
                let sizes = wgpu::BlasGeometrySizeDescriptors::AABBs {
                    descriptors: vec![size.clone()],
                };
                (StrandGeometry::Boxes(size), sizes)
            }
            StrandPrimitive::Dots => {
                let size = wgpu::BlasTriangleGeometrySizeDescriptor {
                    vertex_format: wgpu::VertexFormat::Float32x3,
                    vertex_count: 12 * segments,
                    index_format: None,
                    index_count: None,
                    flags,
                };
                let sizes = wgpu::BlasGeometrySizeDescriptors::Triangles {
                    descriptors: vec![size.clone()],
                };
                (StrandGeometry::Dots(size), sizes)
            }
        };
        let blas = device.create_blas(
            &wgpu::CreateBlasDescriptor {
                label: Some("strands"),
                flags: STRAND_FLAGS,
                update_mode: wgpu::AccelerationStructureUpdateMode::Build,
            },
            sizes,
        );
        let mesh_indices: Vec<u32> = mesh_list.iter().map(|m| m.index_count).collect();
        let instances = 1 + mesh_list.len() as u32;
        let driver = sizes::driver_sizes(
            device,
            &sizes::Sizing {
                primitive,
                segments,
                strand_flags: STRAND_FLAGS,
                mesh_vertices: meshes.map_or(0, |m| m.vertex_count()),
                mesh_indices: &mesh_indices,
                mesh_flags: meshes::MESH_FLAGS,
                instances,
                top_flags: TOP_FLAGS,
            },
        );
        let meshes = meshes.map(|m| Meshes::new(device, m));
        let tlas = device.create_tlas(&wgpu::CreateTlasDescriptor {
            label: Some("strands"),
            max_instances: instances,
            flags: TOP_FLAGS,
            update_mode: wgpu::AccelerationStructureUpdateMode::Build,
        });
        let (pipeline, bind_group) = input_pass(device, primitive, hair_vertices, &input);
        let structure = StrandStructure {
            primitive,
            input,
            geometry,
            blas,
            meshes,
            tlas: Mutex::new(tlas),
            pipeline,
            bind_group,
            segments,
            driver,
        };
        structure.place_instances(IDENTITY);
        Ok(structure)
    }

    /// The top-level instances: the strands (their vertices are in world
    /// space: the identity; custom data 0), then each mesh (custom data 1,
    /// 2, …), the head's moved by `head`.
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

    /// The meshes' structures built by a submission of their own on `queue`,
    /// the first time (nothing after): call before the frame's
    /// [`encode`](Self::encode), whose encoder then leaves them out. Without
    /// it every `encode` builds them again, so a frame whose encoder is
    /// dropped unsubmitted never leaves the next one tracing unbuilt meshes.
    pub fn build_meshes(&self, device: &wgpu::Device, queue: &wgpu::Queue) {
        if let Some(m) = &self.meshes {
            m.build_on(device, queue);
        }
    }

    /// The boxes or triangles from this frame's vertices, the meshes'
    /// structures unless [`build_meshes`](Self::build_meshes) submitted them,
    /// the head's instances moved by `head_model` (the frame's, column-major
    /// as `FrameUniforms` holds it), then the strands' and the top-level
    /// structures built.
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
        let geometry = match &self.geometry {
            StrandGeometry::Boxes(size) => {
                wgpu::BlasGeometries::AabbGeometries(vec![wgpu::BlasAabbGeometry {
                    size,
                    stride: BOX_STRIDE,
                    aabb_buffer: &self.input,
                    primitive_offset: 0,
                }])
            }
            StrandGeometry::Dots(size) => {
                wgpu::BlasGeometries::TriangleGeometries(vec![wgpu::BlasTriangleGeometry {
                    size,
                    vertex_buffer: &self.input,
                    first_vertex: 0,
                    vertex_stride: 12,
                    index_buffer: None,
                    first_index: None,
                    transform_buffer: None,
                    transform_buffer_offset: None,
                }])
            }
        };
        let mut entries = vec![wgpu::BlasBuildEntry {
            blas: &self.blas,
            geometry,
        }];
        if let Some(m) = &self.meshes {
            entries.extend(m.entries());
        }
        let tlas = self.tlas.lock().unwrap_or_else(|e| e.into_inner());
        encoder.build_acceleration_structures(entries.iter(), std::iter::once(&*tlas));
    }

    /// The top-level structure, for a bind group's acceleration structure
    /// (locked: each build sets the head's instances first).
    pub fn tlas(&self) -> std::sync::MutexGuard<'_, wgpu::Tlas> {
        self.tlas.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// How the strands' segments are in the structure.
    pub fn primitive(&self) -> StrandPrimitive {
        self.primitive
    }

    /// Segments in the structure.
    pub fn segments(&self) -> u32 {
        self.segments
    }

    /// Meshes (triangle instances) in the structure.
    pub fn mesh_count(&self) -> usize {
        self.meshes.as_ref().map_or(0, |m| m.blas.len())
    }

    /// Bytes plait allocates and writes each frame for the strands' build:
    /// the boxes, or the DOTS triangles' corners.
    pub fn box_bytes(&self) -> u64 {
        self.input.size()
    }

    /// The driver's sizes of the structures (Vulkan's build sizes, what
    /// wgpu allocates them with); `None` on a backend that does not say.
    pub fn driver_sizes(&self) -> Option<DriverSizes> {
        self.driver
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

/// The compute pass that writes the strands' build input: a box per segment
/// (`shaders/passes/strand_boxes.wgsl`) or the DOTS triangles' corners
/// (`shaders/passes/strand_dots.wgsl` after `plait::strand_dots`, the
/// functions the tracers call, so both see the same quads; the builder is
/// not composed by naga_oil, so the library's directives are left out).
fn input_pass(
    device: &wgpu::Device,
    primitive: StrandPrimitive,
    hair_vertices: &wgpu::Buffer,
    input: &wgpu::Buffer,
) -> (wgpu::ComputePipeline, wgpu::BindGroup) {
    let source = match primitive {
        StrandPrimitive::SweptSphere => {
            include_str!("../../../shaders/passes/strand_boxes.wgsl").to_owned()
        }
        StrandPrimitive::Dots => {
            // The module's text, then the pass's, each without its
            // naga_oil directives (`#define_import_path`, the pass's
            // `#import` of this module): plain WGSL for the device.
            let plain = |text: &str| -> String {
                text.lines()
                    .filter(|l| !l.starts_with('#'))
                    .map(|l| format!("{l}\n"))
                    .collect()
            };
            plain(include_str!("../../../shaders/lib/strand_dots.wgsl"))
                + &plain(include_str!("../../../shaders/passes/strand_dots.wgsl"))
        }
    };
    let label = Some(match primitive {
        StrandPrimitive::SweptSphere => "strand_boxes",
        StrandPrimitive::Dots => "strand_dots",
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label,
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label,
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: hair_vertices.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: input.as_entire_binding(),
            },
        ],
    });
    (pipeline, bind_group)
}
