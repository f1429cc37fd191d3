//! Does this driver end long loops early? Mesa 22.3's lavapipe gives each
//! group of 8 invocations one budget of 65,535 loop laps, shared by all their
//! loops, and ends every loop silently once it is spent (docs/design.md,
//! "Invocations that could not finish"); Mesa 25's does not. The tests that
//! show plait counting such invocations need to know which driver they run
//! on, and a version string would only be a guess: so one dispatch measures it.

use crate::GpuError;

/// Laps the probe asks of each invocation: past lavapipe's 65,535.
pub const PROBE_LAPS: u32 = 100_000;

/// Every lap reads the storage buffer, so the compiler cannot replace the
/// loop by its closed form and the driver has to run each lap.
const PROBE: &str = r#"
@group(0) @binding(0) var<storage, read_write> laps: array<u32, 9>;

@compute @workgroup_size(8)
fn main(@builtin(local_invocation_index) i: u32) {
    var n = 0u;
    loop {
        if n >= laps[8] {
            break;
        }
        n += 1u + laps[i] * 0u;
    }
    laps[i] = n;
}
"#;

/// The fewest laps one of 8 invocations ran when asked for [`PROBE_LAPS`]:
/// `Some(laps)` when the driver cut the loop, `None` when every lap ran.
pub fn probe(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Option<u32>, GpuError> {
    use wgpu::util::DeviceExt;
    let fail = |message: String| GpuError::Readback {
        resource: "loop-budget probe".into(),
        message,
    };
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("loop-budget probe"),
        source: wgpu::ShaderSource::Wgsl(PROBE.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("loop-budget probe"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let mut init = [0u32; 9];
    init[8] = PROBE_LAPS;
    let bytes: Vec<u8> = init.iter().flat_map(|v| v.to_le_bytes()).collect();
    let storage = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("loop-budget probe"),
        contents: &bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    });
    let read = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("loop-budget probe readback"),
        size: bytes.len() as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("loop-budget probe"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: storage.as_entire_binding(),
        }],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(1, 1, 1);
    }
    encoder.copy_buffer_to_buffer(&storage, 0, &read, 0, bytes.len() as u64);
    queue.submit([encoder.finish()]);
    let data = crate::readback::map_buffer(device, &read).map_err(fail)?;
    let fewest = data[..32]
        .chunks_exact(4)
        .map(|w| u32::from_le_bytes(w.try_into().expect("4 bytes")))
        .min()
        .expect("8 invocations");
    Ok((fewest < PROBE_LAPS).then_some(fewest))
}
