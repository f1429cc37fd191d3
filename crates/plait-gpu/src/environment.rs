//! The scene's environment image on the GPU: the `environment_source` scene
//! binding every pass can read (the lighting techniques resample it into a
//! graph resource, `techniques/lighting/environment.toml`).

use plait_hair::EnvironmentImage;
use wgpu::util::DeviceExt;

use crate::geometry::SceneGeometry;

impl SceneGeometry {
    /// Upload `image` (linear RGB, equirectangular) as an rgba32float
    /// texture, bound to shaders that declare `environment_source`.
    pub fn set_environment(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        image: &EnvironmentImage,
    ) {
        let texels = image.rgba();
        let texture = device.create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some("environment source"),
                size: wgpu::Extent3d {
                    width: image.width(),
                    height: image.height(),
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            bytemuck::cast_slice(&texels),
        );
        self.environment = Some(texture.create_view(&Default::default()));
    }
}
