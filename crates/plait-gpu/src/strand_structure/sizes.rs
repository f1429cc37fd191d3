//! The driver's sizes of the structures, as it states them before a build
//! (Vulkan's `vkGetAccelerationStructureBuildSizesKHR`, what wgpu-core
//! allocates each structure with). wgpu 30 keeps them to itself, so they are
//! asked of wgpu-hal's Vulkan device here; on any other backend (GL, a
//! browser's WebGPU) they are not known (`None`).

use super::StrandPrimitive;

/// Bytes of one structure and of the scratch its build takes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BuildSize {
    pub structure: u64,
    pub scratch: u64,
}

impl std::ops::Add for BuildSize {
    type Output = BuildSize;
    fn add(self, o: BuildSize) -> BuildSize {
        BuildSize {
            structure: self.structure + o.structure,
            // Builds of one frame are recorded together: their scratch adds up.
            scratch: self.scratch + o.scratch,
        }
    }
}

/// The driver's sizes of a structure's parts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DriverSizes {
    /// The strands' bottom-level structure.
    pub strands: BuildSize,
    /// The meshes' bottom-level structures, together.
    pub meshes: BuildSize,
    /// The top-level structure.
    pub top: BuildSize,
}

/// What is sized: the strands' geometry, each mesh's (vertices, indices),
/// the top-level instances. Only the Vulkan query reads it: a browser's
/// build (wasm32) has none, and its fields go unread there.
#[cfg_attr(target_arch = "wasm32", allow(dead_code))]
pub(super) struct Sizing<'a> {
    pub primitive: StrandPrimitive,
    pub segments: u32,
    pub strand_flags: wgpu::AccelerationStructureFlags,
    pub mesh_vertices: u32,
    pub mesh_indices: &'a [u32],
    pub mesh_flags: wgpu::AccelerationStructureFlags,
    pub instances: u32,
    pub top_flags: wgpu::AccelerationStructureFlags,
}

/// The driver's sizes on a Vulkan device; `None` on any other backend.
#[cfg(not(target_arch = "wasm32"))]
#[allow(unsafe_code)]
pub(super) fn driver_sizes(device: &wgpu::Device, s: &Sizing<'_>) -> Option<DriverSizes> {
    use wgpu::hal;
    use wgpu::hal::Device as _;
    type Buffer = <hal::api::Vulkan as hal::Api>::Buffer;
    // SAFETY (the one use of wgpu-hal, documented exception to
    // `unsafe_code = "deny"`): `as_hal` hands the Vulkan device wgpu-core
    // made; it is only asked for sizes, which reads no buffer (every
    // address is None: Vulkan ignores them for this query) and creates,
    // destroys and records nothing, so no wgpu-core state can go stale.
    let raw = unsafe { device.as_hal::<hal::api::Vulkan>() }?;
    let size = |entries: &hal::AccelerationStructureEntries<'_, Buffer>, flags| {
        // SAFETY: as above; the descriptor holds no buffer.
        let sizes = unsafe {
            raw.get_acceleration_structure_build_sizes(
                &hal::GetAccelerationStructureBuildSizesDescriptor { entries, flags },
            )
        };
        BuildSize {
            structure: sizes.acceleration_structure_size,
            scratch: sizes.build_scratch_size,
        }
    };
    let strands = match s.primitive {
        StrandPrimitive::SweptSphere => {
            hal::AccelerationStructureEntries::AABBs(vec![hal::AccelerationStructureAABBs {
                buffer: None,
                offset: 0,
                count: s.segments,
                stride: wgpu::AABB_GEOMETRY_MIN_STRIDE,
                flags: wgpu::AccelerationStructureGeometryFlags::NO_DUPLICATE_ANY_HIT_INVOCATION,
            }])
        }
        StrandPrimitive::Dots => hal::AccelerationStructureEntries::Triangles(vec![
            hal::AccelerationStructureTriangles {
                vertex_buffer: None,
                vertex_format: wgpu::VertexFormat::Float32x3,
                first_vertex: 0,
                vertex_count: 12 * s.segments,
                vertex_stride: 12,
                indices: None,
                transform: None,
                flags: wgpu::AccelerationStructureGeometryFlags::NO_DUPLICATE_ANY_HIT_INVOCATION,
            },
        ]),
    };
    let strands = size(&strands, s.strand_flags);
    let meshes = s
        .mesh_indices
        .iter()
        .map(|&count| {
            let entries = hal::AccelerationStructureEntries::Triangles(vec![
                hal::AccelerationStructureTriangles {
                    vertex_buffer: None,
                    vertex_format: wgpu::VertexFormat::Float32x3,
                    first_vertex: 0,
                    vertex_count: s.mesh_vertices,
                    vertex_stride: 12,
                    indices: Some(hal::AccelerationStructureTriangleIndices {
                        format: wgpu::IndexFormat::Uint32,
                        buffer: None,
                        offset: 0,
                        count,
                    }),
                    transform: None,
                    flags: wgpu::AccelerationStructureGeometryFlags::OPAQUE,
                },
            ]);
            size(&entries, s.mesh_flags)
        })
        .fold(BuildSize::default(), |a, b| a + b);
    let top = hal::AccelerationStructureEntries::Instances(hal::AccelerationStructureInstances {
        buffer: None,
        offset: 0,
        count: s.instances,
    });
    let top = size(&top, s.top_flags);
    Some(DriverSizes {
        strands,
        meshes,
        top,
    })
}

#[cfg(target_arch = "wasm32")]
pub(super) fn driver_sizes(_device: &wgpu::Device, _s: &Sizing<'_>) -> Option<DriverSizes> {
    None
}
