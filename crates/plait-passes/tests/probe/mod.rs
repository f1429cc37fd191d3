//! A compute probe for GPU tests of library WGSL: compose a shader that
//! imports `plait::…` modules, run it over an input storage buffer, read its
//! output buffer back (`order_estimate.rs`, `shadow_filter.rs`).

use std::path::Path;

use plait_gpu::{Gpu, ShaderLibrary};
use wgpu::util::DeviceExt;

/// The probe's pipeline (entry point `main`, layouts from the shader) and
/// its input and output buffers.
pub struct Probe {
    pub pipeline: wgpu::ComputePipeline,
    pub input: wgpu::Buffer,
    pub output: wgpu::Buffer,
}

impl Probe {
    /// `source` composed against plait's library as `name`; `input` uploaded
    /// as a read-only storage buffer; `output_bytes` of read-write storage.
    pub fn new(gpu: &Gpu, name: &str, source: &str, input: &[u8], output_bytes: u64) -> Probe {
        let device = &gpu.device;
        let mut shaders = ShaderLibrary::new(
            &plait_gpu::library::Library::read(&[]).expect("the library is found"),
        )
        .expect("library modules compose");
        let module = shaders
            .compose(Path::new(name), source, &[])
            .unwrap_or_else(|e| panic!("{e}"));
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(name),
            source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(module)),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(name),
            layout: None,
            module: &shader,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("probe input"),
            contents: input,
            usage: wgpu::BufferUsages::STORAGE,
        });
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("probe output"),
            size: output_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Probe {
            pipeline,
            input,
            output,
        }
    }

    /// Dispatches `invocations` threads (workgroups of 64) with `groups`
    /// bound in order after what `encoder` already holds, submits, and
    /// returns the output buffer's bytes.
    pub fn run(
        &self,
        gpu: &Gpu,
        mut encoder: wgpu::CommandEncoder,
        groups: &[&wgpu::BindGroup],
        invocations: u32,
    ) -> Vec<u8> {
        let device = &gpu.device;
        let size = self.output.size();
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("probe readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            for (i, group) in groups.iter().enumerate() {
                pass.set_bind_group(i as u32, *group, &[]);
            }
            pass.dispatch_workgroups(invocations.div_ceil(64), 1, 1);
        }
        encoder.copy_buffer_to_buffer(&self.output, 0, &readback, 0, size);
        gpu.queue.submit([encoder.finish()]);
        plait_gpu::readback::map_buffer(device, &readback).expect("readback")
    }
}
