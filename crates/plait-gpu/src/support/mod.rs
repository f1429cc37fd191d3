//! What the opened adapter can do that plait relies on, probed once when the
//! device opens ([`AdapterSupport`]), and the check of a compiled schedule
//! against it ([`check_schedule`]) that runs before any resource is created.
//!
//! wgpu validates each call when it is made, so an adapter that cannot run a
//! pipeline would otherwise fail on the first texture or pipeline it refuses
//! (on llvmpipe's OpenGL: `rg32float` is not renderable), with a raw message
//! naming neither the pass nor what to do. The check mirrors the rules wgpu
//! applies to what plait creates — texture usages per format, sample counts,
//! storage access, blending, downlevel flags, per-stage binding limits — and
//! reports every problem at once, each at the line of the pipeline file that
//! asked for it.

mod adapter_needs;
mod check;
mod depth_values;
mod message;
mod sample_mask;
mod textures;

pub use adapter_needs::RAY_QUERY_FIX;
pub use check::{check_schedule, problems};
pub use message::{Problem, Unsupported};

use plait_graph::Format;

use crate::pool::texture_format;

/// The adapter's support, as plain data (tests build one by hand).
#[derive(Clone, Debug)]
pub struct AdapterSupport {
    /// `llvmpipe (LLVM 15.0.6, 256 bits)`.
    pub adapter: String,
    pub backend: wgpu::Backend,
    /// The driver and its version, as the adapter reports them (may be empty).
    pub driver: String,
    /// What each format allows, as wgpu validates textures on this device.
    pub formats: Vec<(Format, wgpu::TextureFormatFeatures)>,
    pub downlevel: wgpu::DownlevelFlags,
    pub limits: wgpu::Limits,
    /// Whether shaders can read a depth texture as a value (`textureLoad`,
    /// or sampling without a comparison). wgpu's GL backend cannot: naga's
    /// GLSL output declares every depth texture a `sampler2DShadow`, and
    /// GLSL has no such call on one, so the pipeline fails to compile.
    pub depth_values_readable: bool,
    /// Whether fragment shaders can use `@builtin(sample_mask)`. wgpu's GL
    /// backend cannot: naga's GLSL output (naga 30) reads `gl_SampleMaskIn`
    /// and writes `gl_SampleMask` as a `uint`, where GLSL declares both
    /// `int[]`, so the shader fails to compile (gfx-rs/wgpu issue 6085,
    /// open).
    pub sample_mask: bool,
}

impl AdapterSupport {
    /// Probe `adapter` as `device` (opened on it with `features`) validates.
    pub fn probe(adapter: &wgpu::Adapter, device: &wgpu::Device) -> Self {
        let info = adapter.get_info();
        let features = device.features();
        let downlevel = adapter.get_downlevel_capabilities().flags;
        // wgpu checks textures against the adapter's own table when the device
        // has TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES or is a downlevel one,
        // else against WebGPU's guarantees (wgpu-core `describe_format_features`).
        let adapter_table = features
            .contains(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES)
            || !downlevel.contains(wgpu::DownlevelFlags::WEBGPU_TEXTURE_FORMAT_SUPPORT);
        let formats = Format::ALL
            .iter()
            .map(|&format| {
                let tf = texture_format(format);
                let mut f = if adapter_table {
                    adapter.get_texture_format_features(tf)
                } else {
                    tf.guaranteed_format_features(features)
                };
                let float32 = matches!(
                    format,
                    Format::R32Float | Format::Rg32Float | Format::Rgba32Float
                );
                if float32 && !features.contains(wgpu::Features::FLOAT32_FILTERABLE) {
                    f.flags.remove(wgpu::TextureFormatFeatureFlags::FILTERABLE);
                }
                (format, f)
            })
            .collect();
        let driver = [info.driver.trim(), info.driver_info.trim()]
            .into_iter()
            .filter(|s| !s.is_empty())
            .collect::<Vec<_>>()
            .join(" ");
        AdapterSupport {
            adapter: info.name.clone(),
            backend: info.backend,
            driver,
            formats,
            downlevel,
            limits: device.limits(),
            depth_values_readable: info.backend != wgpu::Backend::Gl,
            sample_mask: info.backend != wgpu::Backend::Gl,
        }
    }

    /// What `format` allows (nothing for a format the probe did not list).
    pub fn format(&self, format: Format) -> wgpu::TextureFormatFeatures {
        self.formats
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, f)| *f)
            .unwrap_or(wgpu::TextureFormatFeatures {
                allowed_usages: wgpu::TextureUsages::empty(),
                flags: wgpu::TextureFormatFeatureFlags::empty(),
            })
    }

    /// `llvmpipe (LLVM 15.0.6, 256 bits)` (gl backend, Mesa 22.3.6).
    pub fn describe(&self) -> String {
        let backend = self.backend.to_str();
        if self.driver.is_empty() {
            format!("`{}` ({backend} backend)", self.adapter)
        } else {
            format!("`{}` ({backend} backend, {})", self.adapter, self.driver)
        }
    }
}
