//! The opaque shadow's 3×3 PCF as the GPU computes it: `plait::shadow::pcf_3x3`
//! (four `textureGatherCompare` with the nine bilinear taps' weights applied in
//! the shader) must equal nine `textureSampleCompareLevel` taps one texel
//! apart — the filter it replaced for speed (the book's Performance page) — on a
//! noisy depth map, inside it, across its texels' edges and past its border.

mod probe;

use plait_gpu::Gpu;
use probe::Probe;

const SIZE: u32 = 64;

/// Fills the depth map: a hash of the pixel, so neighbouring texels disagree
/// and every weight of the filter matters.
const NOISE: &str = r#"
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

struct Depth {
    @builtin(frag_depth) depth: f32,
}

@fragment
fn fs_main(@builtin(position) p: vec4<f32>) -> Depth {
    var h = u32(p.x) * 0x9E3779B1u ^ u32(p.y) * 0x85EBCA77u;
    h = (h ^ (h >> 15u)) * 0x2C1B3C6Du;
    h = h ^ (h >> 13u);
    return Depth(0.2 + 0.6 * f32(h & 0xFFFFu) / 65535.0);
}
"#;

const PROBE: &str = r#"
#import plait::frame::shadow_sampler
#import plait::shadow::pcf_3x3

@group(1) @binding(0) var depth_map: texture_depth_2d;
// xy: uv, z: the depth compared against.
@group(1) @binding(1) var<storage, read> points: array<vec4<f32>>;
// x: pcf_3x3, y: the nine taps.
@group(1) @binding(2) var<storage, read_write> results: array<vec2<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= arrayLength(&points)) {
        return;
    }
    let p = points[id.x];
    let texel = 1.0 / vec2<f32>(textureDimensions(depth_map));
    var nine = 0.0;
    for (var y = -1; y <= 1; y++) {
        for (var x = -1; x <= 1; x++) {
            nine += textureSampleCompareLevel(depth_map, shadow_sampler, p.xy + vec2<f32>(f32(x), f32(y)) * texel, p.z);
        }
    }
    results[id.x] = vec2<f32>(pcf_3x3(depth_map, p.xy, p.z), nine / 9.0);
}
"#;

#[test]
fn gathered_pcf_equals_the_nine_filtered_taps() {
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("GPU tests need an adapter: {e}"));
    let device = &gpu.device;

    let depth = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("noisy depth"),
        size: wgpu::Extent3d {
            width: SIZE,
            height: SIZE,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Depth32Float,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    let depth_view = depth.create_view(&Default::default());
    let noise = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("noise"),
        source: wgpu::ShaderSource::Wgsl(NOISE.into()),
    });
    let fill = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("noise"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &noise,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Always),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &noise,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[],
        }),
        multiview_mask: None,
        cache: None,
    });

    // Points inside the map, on texel centres and edges, and past its border
    // (the sampler clamps to the edge texels for both filters).
    let mut points: Vec<[f32; 4]> = Vec::new();
    let mut x = 0x2545_f491u32;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        (x % 1_000_000) as f32 / 1_000_000.0
    };
    for _ in 0..4000 {
        let u = -0.05 + 1.1 * next();
        let v = -0.05 + 1.1 * next();
        points.push([u, v, 0.15 + 0.7 * next(), 0.0]);
    }
    for i in 0..=SIZE {
        let edge = i as f32 / SIZE as f32;
        let centre = (i as f32 + 0.5) / SIZE as f32;
        points.push([edge, centre, 0.5, 0.0]);
        points.push([centre, edge, 0.5, 0.0]);
    }
    let bytes: Vec<u8> = points
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let probe = Probe::new(
        &gpu,
        "shadow_filter_probe.wgsl",
        PROBE,
        &bytes,
        points.len() as u64 * 8,
    );
    // plait's shadow sampler (plait_gpu::pass::FrameSamplers): linear,
    // LessEqual, clamped to the edge.
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        compare: Some(wgpu::CompareFunction::LessEqual),
        ..Default::default()
    });
    let samplers = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &probe.pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry {
            binding: 3,
            resource: wgpu::BindingResource::Sampler(&sampler),
        }],
    });
    let resources = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &probe.pipeline.get_bind_group_layout(1),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&depth_view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: probe.input.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: probe.output.as_entire_binding(),
            },
        ],
    });

    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("noise"),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&fill);
        pass.draw(0..3, 0..1);
    }
    let data = probe.run(&gpu, encoder, &[&samplers, &resources], points.len() as u32);
    let results: Vec<[f32; 2]> = data
        .chunks_exact(8)
        .map(|c| {
            [
                f32::from_le_bytes([c[0], c[1], c[2], c[3]]),
                f32::from_le_bytes([c[4], c[5], c[6], c[7]]),
            ]
        })
        .collect();

    let mut worst = 0.0f32;
    for (p, [gathered, nine]) in points.iter().zip(&results) {
        let difference = (gathered - nine).abs();
        // The two differ only in where the bilinear weights are computed:
        // in f32 here, at the sampler's precision there (llvmpipe: f32, worst
        // 3e-7; GPUs quantize to 8 bits, hence 2^-8). One misplaced weight
        // is off by 0.04 here.
        assert!(
            difference <= 1.0 / 256.0,
            "uv ({}, {}), depth {}: gathered {gathered} vs nine taps {nine}",
            p[0],
            p[1],
            p[2]
        );
        worst = worst.max(difference);
    }
    // The map must make the filter work: partly lit points, not all 0 or 1.
    let partial = results
        .iter()
        .filter(|[_, nine]| *nine > 0.05 && *nine < 0.95)
        .count();
    assert!(
        partial > points.len() / 4,
        "only {partial} of {} points are partly lit: the test map is too flat",
        points.len()
    );
    eprintln!(
        "{} points, {partial} partly lit, worst |gathered - nine taps| = {worst}",
        points.len()
    );
}
