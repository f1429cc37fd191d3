//! One GPU texture or buffer per physical resource of the schedule's memory plan.

use plait_graph::{Access, Format, ResourceDesc, ResourceId, Schedule};

/// `plait_graph::Format` as wgpu's texture format (one to one).
pub fn texture_format(f: Format) -> wgpu::TextureFormat {
    use wgpu::TextureFormat as T;
    match f {
        Format::R8Unorm => T::R8Unorm,
        Format::Rgba8Unorm => T::Rgba8Unorm,
        Format::Rgba8UnormSrgb => T::Rgba8UnormSrgb,
        Format::R16Float => T::R16Float,
        Format::Rg16Float => T::Rg16Float,
        Format::Rgba16Float => T::Rgba16Float,
        Format::R32Float => T::R32Float,
        Format::Rg32Float => T::Rg32Float,
        Format::Rgba32Float => T::Rgba32Float,
        Format::R32Uint => T::R32Uint,
        Format::Rg32Uint => T::Rg32Uint,
        Format::Rgba32Uint => T::Rgba32Uint,
        Format::Depth32Float => T::Depth32Float,
    }
}

/// A physical GPU allocation.
pub enum GpuResource {
    Texture {
        texture: wgpu::Texture,
        view: wgpu::TextureView,
    },
    Buffer(wgpu::Buffer),
    /// The strands' acceleration structure: made by the pass that builds
    /// it (`strand_structure`, when it is built, before any pass binding it),
    /// which sizes it by the scene's hair.
    Strands(std::sync::OnceLock<crate::strand_structure::StrandStructure>),
}

/// The allocations of one schedule, indexed by logical resource.
pub struct ResourcePool {
    physical: Vec<GpuResource>,
    /// Logical resource → physical index.
    map: Vec<usize>,
}

impl ResourcePool {
    /// Scene resources are the `geometry`'s buffers (shared, never allocated).
    pub fn new(
        device: &wgpu::Device,
        schedule: &Schedule,
        geometry: &crate::geometry::SceneGeometry,
    ) -> Self {
        // Usage is the union over every pass that touches any user of the allocation.
        let mut tex_usage = vec![
            wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST;
            schedule.physical.len()
        ];
        let mut buf_usage = vec![
            wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::STORAGE;
            schedule.physical.len()
        ];
        // Which allocations a shader samples (multisampled ones are
        // sampleable only then; see below).
        let mut sampled = vec![false; schedule.physical.len()];
        for pass in schedule.passes.iter() {
            for b in pass.reads.iter().chain(pass.writes.iter()) {
                let p = schedule.resources[b.id()].physical.index();
                match b.access {
                    Access::Sampled => {
                        tex_usage[p] |= wgpu::TextureUsages::TEXTURE_BINDING;
                        sampled[p] = true;
                    }
                    Access::StorageRead | Access::StorageWrite => {
                        tex_usage[p] |= wgpu::TextureUsages::STORAGE_BINDING
                    }
                    // Render targets are sampleable too: a pass with a loop of its own
                    // (depth peeling) reads back what it rendered.
                    Access::ColorTarget | Access::DepthTarget => {
                        tex_usage[p] |= wgpu::TextureUsages::RENDER_ATTACHMENT
                            | wgpu::TextureUsages::TEXTURE_BINDING
                    }
                    Access::Uniform => buf_usage[p] |= wgpu::BufferUsages::UNIFORM,
                }
            }
        }
        let physical = schedule
            .physical
            .iter()
            .enumerate()
            .map(|(i, phys)| {
                let scene = phys
                    .users
                    .iter()
                    .map(|&u| &schedule.resources[u])
                    .find(|r| r.scene)
                    .and_then(|r| geometry.scene_buffer(&r.name));
                if let Some(buffer) = scene {
                    return GpuResource::Buffer(buffer.clone());
                }
                let label = phys
                    .users
                    .iter()
                    .map(|&u| schedule.resources[u].name.as_str())
                    .collect::<Vec<_>>()
                    .join("+");
                match phys.desc {
                    ResourceDesc::AccelerationStructure => {
                        GpuResource::Strands(std::sync::OnceLock::new())
                    }
                    ResourceDesc::Texture {
                        format,
                        width,
                        height,
                        layers,
                        samples,
                    } => {
                        let mut usage = tex_usage[i];
                        if samples > 1 {
                            // Multisampled textures can be neither storage nor
                            // copy targets, and are sampleable only when a
                            // shader samples them: wgpu's GL backend makes a
                            // sampleable one a multisample texture, into which
                            // llvmpipe's GL draws nothing (Mesa 22.3.6), where
                            // a render-only one is a renderbuffer that works.
                            usage &= wgpu::TextureUsages::RENDER_ATTACHMENT;
                            if sampled[i] {
                                usage |= wgpu::TextureUsages::TEXTURE_BINDING;
                            }
                        }
                        let texture = device.create_texture(&wgpu::TextureDescriptor {
                            label: Some(&label),
                            size: wgpu::Extent3d {
                                width,
                                height,
                                depth_or_array_layers: layers,
                            },
                            mip_level_count: 1,
                            sample_count: samples,
                            dimension: wgpu::TextureDimension::D2,
                            format: texture_format(format),
                            usage,
                            view_formats: &[],
                        });
                        let view = texture.create_view(&wgpu::TextureViewDescriptor {
                            label: Some(&label),
                            dimension: Some(if layers > 1 {
                                wgpu::TextureViewDimension::D2Array
                            } else {
                                wgpu::TextureViewDimension::D2
                            }),
                            ..Default::default()
                        });
                        GpuResource::Texture { texture, view }
                    }
                    ResourceDesc::Buffer { size } => {
                        GpuResource::Buffer(device.create_buffer(&wgpu::BufferDescriptor {
                            label: Some(&label),
                            // wgpu requires a multiple of 4 for copies and clears.
                            size: size.max(4).next_multiple_of(4),
                            usage: buf_usage[i],
                            mapped_at_creation: false,
                        }))
                    }
                }
            })
            .collect();
        let map = schedule
            .resources
            .iter()
            .map(|r| r.physical.index())
            .collect();
        ResourcePool { physical, map }
    }

    pub fn get(&self, id: ResourceId) -> &GpuResource {
        &self.physical[self.map[id.index()]]
    }

    pub fn texture(&self, id: ResourceId) -> Option<(&wgpu::Texture, &wgpu::TextureView)> {
        match self.get(id) {
            GpuResource::Texture { texture, view } => Some((texture, view)),
            _ => None,
        }
    }

    pub fn buffer(&self, id: ResourceId) -> Option<&wgpu::Buffer> {
        match self.get(id) {
            GpuResource::Buffer(b) => Some(b),
            _ => None,
        }
    }

    /// The strands' structure slot (set once by its building pass).
    pub fn strands(
        &self,
        id: ResourceId,
    ) -> Option<&std::sync::OnceLock<crate::strand_structure::StrandStructure>> {
        match self.get(id) {
            GpuResource::Strands(s) => Some(s),
            _ => None,
        }
    }

    /// What a bind group binds for `id`; `None` for a structure its pass
    /// has not built (a pass binding it is then ordered before its builder,
    /// which the schedule never does).
    pub fn binding_resource(&self, id: ResourceId) -> Option<Bound<'_>> {
        Some(match self.get(id) {
            GpuResource::Texture { view, .. } => {
                Bound::Resource(wgpu::BindingResource::TextureView(view))
            }
            GpuResource::Buffer(b) => Bound::Resource(b.as_entire_binding()),
            GpuResource::Strands(s) => Bound::Structure(s.get()?.tlas()),
        })
    }
}

/// A resource as a bind group takes it. The structure's top-level part is
/// held locked while the bind group is made: its builds set the head's
/// instance transforms through the same lock.
pub enum Bound<'a> {
    Resource(wgpu::BindingResource<'a>),
    Structure(std::sync::MutexGuard<'a, wgpu::Tlas>),
}

impl Bound<'_> {
    /// The binding resource of a bind group entry.
    pub fn resource(&self) -> wgpu::BindingResource<'_> {
        match self {
            Bound::Resource(r) => r.clone(),
            Bound::Structure(tlas) => tlas.as_binding(),
        }
    }
}
