//! What one structure holds, checked against the adapter before anything
//! is created (and at load, `plait::structure_limit`): the strands'
//! primitives (a box or four DOTS triangles per segment) in one bottom-level
//! structure, each mesh's triangles in one, and an instance per mesh beside
//! the strands' in the top-level structure.

use crate::Capabilities;

/// How a strand segment is put in the structure (the `strand_structure`
/// pass's `primitive`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum StrandPrimitive {
    /// One procedural box around the segment's tapered swept sphere,
    /// intersected in WGSL (`shaders/lib/strand_capsule.wgsl`).
    #[default]
    SweptSphere,
    /// DOTS: two quads crossed along the axis, four triangles
    /// (`shaders/lib/strand_dots.wgsl`).
    Dots,
}

impl StrandPrimitive {
    /// The param's values, in the order the pass lists them.
    pub const NAMES: [&'static str; 2] = ["swept_sphere", "dots"];

    /// The primitive the param's value `name` names.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "swept_sphere" => Some(Self::SweptSphere),
            "dots" => Some(Self::Dots),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::SweptSphere => "swept_sphere",
            Self::Dots => "dots",
        }
    }

    /// Bottom-level primitives per segment: one box, or four triangles.
    pub fn per_segment(self) -> u64 {
        match self {
            Self::SweptSphere => 1,
            Self::Dots => 4,
        }
    }

    /// Bytes plait writes per segment for the build: a box (min, max), or
    /// twelve corners of 3 × f32.
    pub fn input_bytes(self) -> u64 {
        match self {
            Self::SweptSphere => wgpu::AABB_GEOMETRY_MIN_STRIDE,
            Self::Dots => 12 * 12,
        }
    }
}

/// Why the strands cannot be put in a structure on this adapter.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StructureError {
    #[error(
        "adapter {adapter} has no ray queries (wgpu's EXPERIMENTAL_RAY_QUERY, Vulkan's VK_KHR_ray_query); {}",
        crate::support::RAY_QUERY_FIX
    )]
    NoRayQueries { adapter: String },
    #[error(
        "the hair has {segments} segments, {primitives} primitives as {} ({} per segment), more than the {limit} primitives one acceleration structure of adapter {adapter} holds (max_blas_primitive_count): draw fewer strands or fewer points per strand{}",
        primitive.name(),
        primitive.per_segment(),
        if *primitive == StrandPrimitive::Dots { ", or primitive = \"swept_sphere\" (one box per segment)" } else { "" }
    )]
    TooManySegments {
        segments: u64,
        primitives: u64,
        primitive: StrandPrimitive,
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

/// Segments (pairs of consecutive vertices) for `points` hair vertices.
pub fn segment_count(points: u32) -> u64 {
    u64::from(points.saturating_sub(1))
}

/// Whether an adapter with `caps` holds `segments` boxes in one structure
/// (swept spheres: [`check_primitives`] with one box per segment).
pub fn check_segments(
    segments: u64,
    caps: &Capabilities,
    adapter: &str,
) -> Result<(), StructureError> {
    check_primitives(segments, StrandPrimitive::SweptSphere, caps, adapter)
}

/// Whether an adapter with `caps` holds `segments` segments as `primitive`
/// ([`StrandPrimitive::per_segment`] primitives each) in one structure.
pub fn check_primitives(
    segments: u64,
    primitive: StrandPrimitive,
    caps: &Capabilities,
    adapter: &str,
) -> Result<(), StructureError> {
    let adapter = adapter.to_owned();
    if !caps.ray_query {
        return Err(StructureError::NoRayQueries { adapter });
    }
    let primitives = segments.saturating_mul(primitive.per_segment());
    if primitives > u64::from(caps.max_blas_primitives) {
        return Err(StructureError::TooManySegments {
            segments,
            primitives,
            primitive,
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
