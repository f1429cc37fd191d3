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

use crate::{Capabilities, Gpu};

/// Bytes per box: min.xyz, max.xyz (wgpu's smallest AABB stride).
pub const BOX_STRIDE: u64 = wgpu::AABB_GEOMETRY_MIN_STRIDE;

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

/// The structure of one hair vertex buffer, rebuilt by each [`encode`](Self::encode).
pub struct StrandStructure {
    boxes: wgpu::Buffer,
    size: wgpu::BlasAABBGeometrySizeDescriptor,
    blas: wgpu::Blas,
    tlas: wgpu::Tlas,
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    segments: u32,
}

impl StrandStructure {
    /// A structure for `points` vertices of `hair_vertices` (48 B each,
    /// `plait_hair::StrandVertex`), refused with the numbers when the
    /// adapter cannot hold it.
    pub fn new(
        gpu: &Gpu,
        hair_vertices: &wgpu::Buffer,
        points: u32,
    ) -> Result<Self, StructureError> {
        let adapter = gpu.support.describe();
        Self::on(
            &gpu.device,
            (&gpu.capabilities, &adapter),
            hair_vertices,
            points,
        )
    }

    /// [`StrandStructure::new`] on `device`, whose adapter is described by
    /// its capabilities and name.
    pub fn on(
        device: &wgpu::Device,
        (caps, adapter): (&Capabilities, &str),
        hair_vertices: &wgpu::Buffer,
        points: u32,
    ) -> Result<Self, StructureError> {
        let segments = segment_count(points).max(1);
        check_segments(segments, caps, adapter)?;
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
        let mut tlas = device.create_tlas(&wgpu::CreateTlasDescriptor {
            label: Some("strands"),
            max_instances: 1,
            flags: wgpu::AccelerationStructureFlags::PREFER_FAST_BUILD,
            update_mode: wgpu::AccelerationStructureUpdateMode::Build,
        });
        // The hair's vertices are in world space: the identity, 3×4 row-major.
        let identity = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0];
        tlas[0] = Some(wgpu::TlasInstance::new(&blas, identity, 0, 0xff));
        let (pipeline, bind_group) = box_pass(device, hair_vertices, &boxes);
        Ok(StrandStructure {
            boxes,
            size,
            blas,
            tlas,
            pipeline,
            bind_group,
            segments,
        })
    }

    /// The boxes from this frame's vertices, then both structures built.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) {
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
        let entry = wgpu::BlasBuildEntry {
            blas: &self.blas,
            geometry: wgpu::BlasGeometries::AabbGeometries(vec![wgpu::BlasAabbGeometry {
                size: &self.size,
                stride: BOX_STRIDE,
                aabb_buffer: &self.boxes,
                primitive_offset: 0,
            }]),
        };
        encoder.build_acceleration_structures(std::iter::once(&entry), std::iter::once(&self.tlas));
    }

    /// The top-level structure, for a bind group's acceleration structure.
    pub fn tlas(&self) -> &wgpu::Tlas {
        &self.tlas
    }

    /// Segments (boxes) in the structure.
    pub fn segments(&self) -> u32 {
        self.segments
    }

    /// Bytes of the boxes plait allocates. The structures' own sizes are
    /// the driver's and wgpu 30 does not report them.
    pub fn box_bytes(&self) -> u64 {
        self.boxes.size()
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
