//! Scene geometry on the GPU: hair as a line list, opaque meshes as one
//! triangle list, and the scene resources of simulation
//! (`plait_graph::scene_resources`): guides at rest and now, every drawn
//! strand's guide binding, the head's colliders (ellipsoids and the head
//! mesh's signed distance field).

use glam::Vec3;
use plait_hair::guides::Guides;
use plait_hair::mesh::Mesh;
use plait_hair::sdf::SignedDistanceField;
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

/// The hair vertex attributes again at locations 6–11: the next hair vertex
/// (`plait::hair_fragment`'s `HairVertex.next_*`), read from the hair vertex
/// buffer bound a second time one vertex further on.
pub const NEXT_HAIR_VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 6] = wgpu::vertex_attr_array![
    6 => Float32x3, 7 => Float32, 8 => Float32x3, 9 => Float32, 10 => Float32x3, 11 => Uint32
];

/// The vertex buffers of a hair pass whose vertex stage is
/// `plait::hair_fragment`'s: each hair vertex with the next one. `Vertex`
/// steps for the line draw, `Instance` for the quad draw of strands wider
/// than a pixel (one instance per hair vertex, 6 vertices each).
pub fn hair_vertex_layouts(
    step_mode: wgpu::VertexStepMode,
) -> [wgpu::VertexBufferLayout<'static>; 2] {
    let array_stride = std::mem::size_of::<StrandVertex>() as u64;
    [
        wgpu::VertexBufferLayout {
            array_stride,
            step_mode,
            attributes: &HAIR_VERTEX_ATTRIBUTES,
        },
        wgpu::VertexBufferLayout {
            array_stride,
            step_mode,
            attributes: &NEXT_HAIR_VERTEX_ATTRIBUTES,
        },
    ]
}

/// The first vertex index of the quad draw (`WIDE_FIRST_VERTEX` in
/// `shaders/lib/strand_coverage.wgsl`): above any hair vertex index, so the
/// shared vertex stage tells a quad corner from a line's vertex.
pub const WIDE_FIRST_VERTEX: u32 = 1 << 30;

/// Whether the module's vertex stage reads the next hair vertex (location
/// 11, `HairVertex.next_strand_id` of `plait::hair_fragment`): then its hair
/// draw binds the hair vertices twice and has the quad draw.
pub fn reads_next_vertex(module: &naga::Module) -> bool {
    let reads = |binding: &Option<naga::Binding>| {
        matches!(binding, Some(naga::Binding::Location { location: 11, .. }))
    };
    module
        .entry_points
        .iter()
        .filter(|e| e.stage == naga::ShaderStage::Vertex)
        .flat_map(|e| &e.function.arguments)
        .any(|a| {
            reads(&a.binding)
                || match &module.types[a.ty].inner {
                    naga::TypeInner::Struct { members, .. } => {
                        members.iter().any(|m| reads(&m.binding))
                    }
                    _ => false,
                }
        })
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
    /// `geometry = "wisps"`: the wisps' triangle list, which every hair
    /// draw draws instead of the hair's lines ([`SceneGeometry::set_wisps`]).
    pub wisps: Option<DrawBuffers>,
    pub opaque: Option<DrawBuffers>,
    /// Each mesh's triangles in `opaque`, in the scene's order: what the
    /// strands' acceleration structure holds as one triangle instance per
    /// mesh (`crate::strand_structure`).
    pub opaque_meshes: Vec<OpaqueMesh>,
    /// The hair's vertices as a storage buffer too, for compute passes.
    pub strand_count: u32,
    pub segment_count: u32,
    /// The scene's environment image, the `environment_source` scene binding
    /// ([`SceneGeometry::set_environment`]).
    pub environment: Option<wgpu::TextureView>,
    /// Points of the drawn hair.
    pub point_count: u32,
    /// The scene resources of simulation and guide interpolation.
    pub guides: GuideBuffers,
    /// `opaque_meshes`: per mesh of `opaque_meshes`, vec4<u32>(first index,
    /// index count, head, 0), so a ray query's triangle hit (instance 1 + i,
    /// a primitive of mesh i's stretch) finds its vertices.
    pub opaque_table: wgpu::Buffer,
}

/// One mesh's stretch of the opaque index buffer.
#[derive(Clone, Debug, PartialEq)]
pub struct OpaqueMesh {
    /// The mesh's name ("head", "ground", a file's), for messages.
    pub name: String,
    pub first_index: u32,
    pub index_count: u32,
    /// Moves with `frame.head_model` (its vertices are at rest).
    pub head: bool,
}

/// An ellipsoid the hair collides with, at rest (the head moves it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collider {
    pub center: Vec3,
    pub radii: Vec3,
}

/// The guide strands on the GPU (layouts in `plait_graph::scene_resources`).
/// Positions and previous positions start at rest and persist as long as
/// the geometry: they are the simulation's state.
pub struct GuideBuffers {
    pub rest: wgpu::Buffer,
    pub strands: wgpu::Buffer,
    pub positions: wgpu::Buffer,
    pub previous: wgpu::Buffer,
    pub strand_guides: wgpu::Buffer,
    pub colliders: wgpu::Buffer,
    /// The head mesh's signed distance field (`plait_hair::sdf`'s GPU
    /// layout; all zeros, "no field", without a head mesh).
    pub head_sdf: wgpu::Buffer,
    pub guide_count: u32,
    pub point_count: u32,
    pub collider_count: u32,
    /// Every drawn strand is its own guide (no interpolation needed to see motion).
    pub identity: bool,
}

/// One drawn strand's binding as `strand_guides` holds it (48 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct StrandGuide {
    /// Guides 0, 1, 2 and the strand's first point.
    pub ids: [u32; 4],
    /// Weights and the length scale.
    pub weights: [f32; 4],
    /// Rest root and the point count (as f32: exact below 2^24).
    pub root: [f32; 4],
}

fn storage(device: &wgpu::Device, label: &str, bytes: &[u8]) -> wgpu::Buffer {
    // Never empty: wgpu cannot bind a 0-byte buffer, nor one smaller than an
    // element of the shader's array (48 bytes at most: a strand's guides).
    let padded;
    let contents = if bytes.is_empty() {
        padded = [0u8; 48];
        &padded[..]
    } else {
        bytes
    };
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
    })
}

impl GuideBuffers {
    /// `pose`: the head's pose the state starts in (the guides at rest, moved
    /// with the head), so a sequence that starts turned does not jump.
    pub fn upload(
        device: &wgpu::Device,
        guides: &Guides,
        drawn: &Strands,
        colliders: &[Collider],
        head_sdf: Option<&SignedDistanceField>,
        pose: glam::Mat4,
    ) -> Self {
        let g = &guides.strands;
        let mut rest = Vec::with_capacity(g.points.len());
        for r in g.ranges() {
            for i in r.clone() {
                let length = if i == r.start {
                    0.0
                } else {
                    (g.points[i] - g.points[i - 1]).length()
                };
                rest.push(g.points[i].extend(length).to_array());
            }
        }
        let strands: Vec<[u32; 2]> = g
            .ranges()
            .map(|r| [r.start as u32, r.len() as u32])
            .collect();
        let bindings: Vec<StrandGuide> = drawn
            .ranges()
            .zip(&guides.bindings)
            .map(|(r, b)| StrandGuide {
                ids: [b.guides[0], b.guides[1], b.guides[2], r.start as u32],
                weights: [b.weights[0], b.weights[1], b.weights[2], b.scale],
                root: b.root.extend(r.len() as f32).to_array(),
            })
            .collect();
        let shapes: Vec<[[f32; 4]; 2]> = colliders
            .iter()
            .map(|c| {
                [
                    c.center.extend(0.0).to_array(),
                    c.radii.extend(0.0).to_array(),
                ]
            })
            .collect();
        let rest_bytes: &[u8] = bytemuck::cast_slice(&rest);
        let posed: Vec<[f32; 4]> = rest
            .iter()
            .map(|p| {
                pose.transform_point3(Vec3::new(p[0], p[1], p[2]))
                    .extend(0.0)
                    .to_array()
            })
            .collect();
        let posed_bytes: &[u8] = bytemuck::cast_slice(&posed);
        GuideBuffers {
            rest: storage(device, "guide_rest", rest_bytes),
            strands: storage(device, "guide_strands", bytemuck::cast_slice(&strands)),
            positions: storage(device, "guide_positions", posed_bytes),
            previous: storage(device, "guide_previous", posed_bytes),
            strand_guides: storage(device, "strand_guides", bytemuck::cast_slice(&bindings)),
            // No collider: one of radii 0, which nothing is inside.
            colliders: storage(device, "head_colliders", bytemuck::cast_slice(&shapes)),
            // No field: `storage` pads an empty buffer with zeros, whose
            // presence word (7) is 0.
            head_sdf: storage(
                device,
                "head_sdf",
                bytemuck::cast_slice(&head_sdf.map(|f| f.gpu_words()).unwrap_or_default()),
            ),
            guide_count: strands.len() as u32,
            point_count: rest.len() as u32,
            collider_count: colliders.len() as u32,
            identity: guides.is_identity(),
        }
    }
}

fn upload<V: bytemuck::Pod>(
    device: &wgpu::Device,
    label: &str,
    vertices: &[V],
    indices: &[u32],
) -> Option<DrawBuffers> {
    upload_as(
        device,
        label,
        vertices,
        indices,
        wgpu::BufferUsages::empty(),
    )
}

/// [`upload`] with `extra` usages on both buffers.
fn upload_as<V: bytemuck::Pod>(
    device: &wgpu::Device,
    label: &str,
    vertices: &[V],
    indices: &[u32],
    extra: wgpu::BufferUsages,
) -> Option<DrawBuffers> {
    if indices.is_empty() {
        return None;
    }
    let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(&format!("{label} vertices")),
        contents: bytemuck::cast_slice(vertices),
        // COPY_SRC: compute passes write the hair and tests read it back;
        // COPY_DST: the hair is rewritten when it follows the head.
        usage: wgpu::BufferUsages::VERTEX
            | wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST
            | extra,
    });
    let index_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(&format!("{label} indices")),
        contents: bytemuck::cast_slice(indices),
        usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::STORAGE | extra,
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

    /// Hair and meshes; every strand its own guide, no colliders.
    pub fn upload(device: &wgpu::Device, strands: &Strands, meshes: &[Mesh]) -> Self {
        Self::upload_with_guides(
            device,
            strands,
            meshes,
            &Guides::identity(strands),
            &[],
            None,
            glam::Mat4::IDENTITY,
        )
    }

    /// Hair and meshes, with the groom's guides and the head's colliders
    /// (ellipsoids, and the head mesh's distance field) for simulation (at rest; its state starts at rest moved by `pose`, the
    /// head's first pose). `guides.bindings` has one entry per strand of `strands`.
    pub fn upload_with_guides(
        device: &wgpu::Device,
        strands: &Strands,
        meshes: &[Mesh],
        guides: &Guides,
        colliders: &[Collider],
        head_sdf: Option<&SignedDistanceField>,
        pose: glam::Mat4,
    ) -> Self {
        // Guides made for other strands (a caller cut the strands after
        // loading): every strand its own guide rather than wrong bindings.
        let identity;
        let guides = if guides.bindings.len() == strands.strand_count() {
            guides
        } else {
            identity = Guides::identity(strands);
            &identity
        };
        let (hair_vertices, hair_indices) = strands.line_list();
        let hair = upload(device, "hair", &hair_vertices, &hair_indices);
        let mut vertices = Vec::new();
        let mut indices = Vec::new();
        let mut opaque_meshes = Vec::new();
        for mesh in meshes {
            let base = vertices.len() as u32;
            if !mesh.indices.is_empty() {
                opaque_meshes.push(OpaqueMesh {
                    name: mesh.name.clone(),
                    first_index: indices.len() as u32,
                    index_count: mesh.indices.len() as u32,
                    head: mesh.head,
                });
            }
            vertices.extend(mesh.vertices.iter().map(|v| OpaqueVertex {
                position: v.position,
                normal: v.normal,
                albedo: mesh.albedo,
                head: if mesh.head { 1.0 } else { 0.0 },
            }));
            indices.extend(mesh.indices.iter().map(|i| i + base));
        }
        // With ray queries the meshes are also the triangle instances of the
        // strands' acceleration structure, built from these buffers (a
        // buffer without BLAS_INPUT cannot be; the usage needs the feature).
        let ray_input = if device
            .features()
            .contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY)
        {
            wgpu::BufferUsages::BLAS_INPUT
        } else {
            wgpu::BufferUsages::empty()
        };
        let opaque = upload_as(device, "opaque", &vertices, &indices, ray_input);
        let table: Vec<[u32; 4]> = opaque_meshes
            .iter()
            .map(|m| [m.first_index, m.index_count, u32::from(m.head), 0])
            .collect();
        let opaque_table = storage(device, "opaque_meshes", bytemuck::cast_slice(&table));
        SceneGeometry {
            hair,
            wisps: None,
            opaque,
            opaque_meshes,
            strand_count: strands.strand_count() as u32,
            segment_count: strands.segment_count() as u32,
            environment: None,
            point_count: strands.point_count() as u32,
            guides: GuideBuffers::upload(device, guides, strands, colliders, head_sdf, pose),
            opaque_table,
        }
    }

    /// Hair draws draw `wisps` (triangles, hair vertex layout:
    /// `plait_hair::wisps::WispMesh`) instead of the hair's lines.
    pub fn set_wisps(&mut self, device: &wgpu::Device, wisps: &plait_hair::wisps::WispMesh) {
        self.wisps = upload(device, "wisps", &wisps.vertices, &wisps.indices);
    }

    /// What a hair draw draws: the wisps' triangles when there are wisps,
    /// the hair's lines otherwise.
    pub fn hair_draw(&self) -> (Option<&DrawBuffers>, wgpu::PrimitiveTopology) {
        match &self.wisps {
            Some(w) => (Some(w), wgpu::PrimitiveTopology::TriangleList),
            None => (self.hair.as_ref(), wgpu::PrimitiveTopology::LineList),
        }
    }

    /// The hair's vertices for the quad draw of strands wider than a pixel,
    /// with how many there are; `None` with wisps (their triangles are drawn
    /// at their width already) or without hair.
    pub fn hair_quads(&self) -> Option<(&wgpu::Buffer, u32)> {
        if self.wisps.is_some() {
            return None;
        }
        let hair = self.hair.as_ref()?;
        let stride = std::mem::size_of::<StrandVertex>() as u64;
        let count = (hair.vertices.size() / stride) as u32;
        (count >= 2).then_some((&hair.vertices, count))
    }

    /// The buffer of scene resource `name` (`plait_graph::scene_resources`);
    /// `None` for the hair's vertices and indices when the scene has no hair.
    pub fn scene_buffer(&self, name: &str) -> Option<&wgpu::Buffer> {
        let g = &self.guides;
        match name {
            "hair_vertices" => self.hair.as_ref().map(|h| &h.vertices),
            "hair_indices" => self.hair.as_ref().map(|h| &h.indices),
            "guide_rest" => Some(&g.rest),
            "guide_strands" => Some(&g.strands),
            "guide_positions" => Some(&g.positions),
            "guide_previous" => Some(&g.previous),
            "strand_guides" => Some(&g.strand_guides),
            "head_colliders" => Some(&g.colliders),
            "head_sdf" => Some(&g.head_sdf),
            "opaque_vertices" => self.opaque.as_ref().map(|o| &o.vertices),
            "opaque_indices" => self.opaque.as_ref().map(|o| &o.indices),
            "opaque_meshes" => Some(&self.opaque_table),
            _ => None,
        }
    }
}
