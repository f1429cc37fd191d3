//! The order estimate of Sintorn & Assarsson 2009 §3.2 as the GPU computes it:
//! `order_estimate` from `shaders/lib/occupancy.wgsl`, run in a compute shader
//! on synthetic texels, must equal the CPU mirror
//! `plait_passes::occupancy::order_estimate` — whose accuracy against exact
//! counts is tested in that module (exact at slab boundaries, within F_i inside).

mod probe;

use plait_gpu::Gpu;
use plait_passes::occupancy::{TexelMaps, maps_from_depths, order_estimate};
use probe::Probe;

const PROBE: &str = r#"
#import plait::occupancy::{TexelMaps, order_estimate}

struct Case {
    words: u32,
    slabs: u32,
    rel: f32,
    pad: u32,
    bits: array<u32, 32>,
    counts: array<u32, 32>,
}
@group(0) @binding(0) var<storage, read> cases: array<Case>;
@group(0) @binding(1) var<storage, read_write> results: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= arrayLength(&results)) {
        return;
    }
    let c = cases[id.x];
    var maps: TexelMaps;
    maps.words = c.words;
    maps.slabs = c.slabs;
    maps.bits = c.bits;
    maps.counts = c.counts;
    results[id.x] = order_estimate(&maps, c.rel);
}
"#;

fn gpu() -> Gpu {
    Gpu::new().unwrap_or_else(|e| panic!("GPU tests need an adapter: {e}"))
}

/// Cases: several fragment distributions × slab layouts × query depths.
fn cases() -> Vec<(TexelMaps, f32)> {
    let mut depth_sets: Vec<Vec<f32>> = vec![
        vec![],
        vec![0.5],
        (0..200).map(|i| 0.3 + 0.001 * i as f32).collect(),
    ];
    let mut x = 0x9e37_79b9u32;
    let mut clustered = vec![0.0, 0.02];
    for _ in 0..500 {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        let u = (x % 100_000) as f32 / 100_000.0;
        clustered.push(0.4 + 0.5 * u * u * u);
    }
    depth_sets.push(clustered);
    let mut out = Vec::new();
    for depths in &depth_sets {
        for (words, slabs) in [(4, 4), (4, 1), (8, 4), (8, 8), (1, 1)] {
            let maps = maps_from_depths(depths, words, slabs);
            for i in 0..=64 {
                out.push((maps.clone(), -0.05 + 1.1 * i as f32 / 64.0));
            }
        }
    }
    out
}

#[test]
fn gpu_order_estimate_matches_cpu_mirror() {
    let gpu = gpu();
    let cases = cases();
    let mut bytes: Vec<u8> = Vec::new();
    for (maps, rel) in &cases {
        let mut words = [0u32; 68];
        words[0] = maps.bits.len() as u32;
        words[1] = maps.counts.len() as u32;
        words[2] = rel.to_bits();
        words[4..4 + maps.bits.len()].copy_from_slice(&maps.bits);
        words[36..36 + maps.counts.len()].copy_from_slice(&maps.counts);
        bytes.extend(words.iter().flat_map(|w| w.to_le_bytes()));
    }
    let probe = Probe::new(
        &gpu,
        "order_estimate_probe.wgsl",
        PROBE,
        &bytes,
        cases.len() as u64 * 4,
    );
    let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &probe.pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: probe.input.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: probe.output.as_entire_binding(),
            },
        ],
    });
    let encoder = gpu.device.create_command_encoder(&Default::default());
    let data = probe.run(&gpu, encoder, &[&bind_group], cases.len() as u32);
    let gpu_results: Vec<f32> = data
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let mut worst = 0.0f32;
    for (i, ((maps, rel), got)) in cases.iter().zip(&gpu_results).enumerate() {
        let want = order_estimate(maps, *rel);
        let tolerance = 1e-3 * want.abs().max(1.0);
        assert!(
            (got - want).abs() <= tolerance,
            "case {i} (words {}, slabs {}, rel {rel}): GPU {got} vs CPU {want}",
            maps.bits.len(),
            maps.counts.len()
        );
        worst = worst.max((got - want).abs());
    }
    assert!(
        gpu_results.iter().any(|&v| v > 10.0),
        "the cases must exercise non-trivial orders"
    );
    eprintln!("{} cases, worst |GPU - CPU| = {worst}", cases.len());
}
