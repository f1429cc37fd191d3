//! Bind group layouts: group 0 (the frame's standard inputs) and the layout
//! entry of each reflected group-1 binding.

use plait_graph::Format;

use crate::frame::FRAME_UNIFORMS_SIZE;
use crate::pool::texture_format;
use crate::reflect::{BindingKind, TextureSample};

/// The layout type of a reflected binding (`format`: the bound texture's, for
/// the filterable flag); `None` for what group 1 cannot hold (samplers).
pub(crate) fn binding_type(
    kind: &BindingKind,
    format: Option<Format>,
) -> Option<wgpu::BindingType> {
    let dimension = |arrayed: bool| {
        if arrayed {
            wgpu::TextureViewDimension::D2Array
        } else {
            wgpu::TextureViewDimension::D2
        }
    };
    Some(match kind {
        BindingKind::Uniform { .. } => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        BindingKind::Storage { read_only, .. } => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage {
                read_only: *read_only,
            },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        BindingKind::Texture {
            sample,
            multisampled,
            arrayed,
        } => wgpu::BindingType::Texture {
            sample_type: match sample {
                TextureSample::Float => wgpu::TextureSampleType::Float {
                    filterable: format.is_some_and(filterable) && !multisampled,
                },
                TextureSample::Uint => wgpu::TextureSampleType::Uint,
                TextureSample::Sint => wgpu::TextureSampleType::Sint,
                TextureSample::Depth => wgpu::TextureSampleType::Depth,
            },
            view_dimension: dimension(*arrayed),
            multisampled: *multisampled,
        },
        BindingKind::StorageTexture {
            format: f,
            access_write,
            access_read,
            arrayed,
        } => wgpu::BindingType::StorageTexture {
            access: match (access_read, access_write) {
                (true, true) => wgpu::StorageTextureAccess::ReadWrite,
                (false, true) => wgpu::StorageTextureAccess::WriteOnly,
                _ => wgpu::StorageTextureAccess::ReadOnly,
            },
            format: texture_format((*f)?),
            view_dimension: dimension(*arrayed),
        },
        BindingKind::Sampler { .. } => return None,
        BindingKind::AccelerationStructure => wgpu::BindingType::AccelerationStructure {
            vertex_return: false,
        },
    })
}

fn filterable(format: Format) -> bool {
    !matches!(
        format,
        Format::R32Float | Format::Rg32Float | Format::Rgba32Float
    )
}

/// The group 0 layout: frame uniforms, the three samplers, the background image.
pub fn frame_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let all =
        wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE;
    let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: all,
        ty,
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("plait frame"),
        entries: &[
            entry(
                0,
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(FRAME_UNIFORMS_SIZE),
                },
            ),
            entry(
                1,
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            ),
            entry(
                2,
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::NonFiltering),
            ),
            entry(
                3,
                wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
            ),
            entry(
                4,
                wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
            ),
        ],
    })
}

/// Group 0's samplers (`linear_sampler`, `nearest_sampler`, `shadow_sampler`
/// of `plait::frame`), made once and bound with a frame's uniforms and
/// background by [`FrameSamplers::bind`]: the executor's frame and a pass's
/// own frames (one per light direction) bind group 0 the same way.
pub struct FrameSamplers {
    linear: wgpu::Sampler,
    nearest: wgpu::Sampler,
    shadow: wgpu::Sampler,
}

impl FrameSamplers {
    pub fn new(device: &wgpu::Device) -> Self {
        let sampler = |filter, compare| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                mag_filter: filter,
                min_filter: filter,
                compare,
                ..Default::default()
            })
        };
        FrameSamplers {
            linear: sampler(wgpu::FilterMode::Linear, None),
            nearest: sampler(wgpu::FilterMode::Nearest, None),
            shadow: sampler(
                wgpu::FilterMode::Linear,
                Some(wgpu::CompareFunction::LessEqual),
            ),
        }
    }

    /// Group 0 with `frame` (the uniforms) and `background` (the image).
    pub fn bind(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        frame: wgpu::BindingResource<'_>,
        background: &wgpu::TextureView,
        label: &str,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: frame,
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&self.linear),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&self.nearest),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::Sampler(&self.shadow),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::TextureView(background),
                },
            ],
        })
    }
}
