//! Strands crossed by rays from given points, traced on the GPU through a
//! strands' acceleration structure built from hand-made vertices
//! (`plait_gpu::strand_structure`) with the loop every ray-traced technique
//! walks (`plait::strand_rays::strands_crossed`, through
//! `tests/fixtures/strand_trace_probe.wgsl`), and whether a path's ray
//! leaving a segment is blocked (`ray_blocked`, through
//! `tests/fixtures/strand_blocked_probe.wgsl`): `tests/ray_traced_strands.rs`
//! and the mutants' tests (`tests/mutants/`).

use glam::Vec3;
use plait_gpu::strand_structure::{StrandPrimitive, StrandStructure, StructureOptions};
use plait_hair::StrandVertex;
use wgpu::util::DeviceExt;

use crate::{open_gpu, repo_root};

/// One strand's vertices: `points` with thickness `width`, strand id `id`.
pub fn strand(points: &[Vec3], width: f32, id: u32) -> Vec<StrandVertex> {
    points
        .iter()
        .map(|p| StrandVertex {
            position: p.to_array(),
            thickness: width,
            tangent: [1.0, 0.0, 0.0],
            alpha: 1.0,
            color: [0.5; 3],
            strand_id: id,
        })
        .collect()
}

/// The HairPoint struct the fixture and plait::strand_rays read (48 B,
/// `plait_hair::StrandVertex`; shaders/lib/hair_point.wgsl).
const HAIR_POINT: &str = "struct HairPoint {\n    position: vec3<f32>,\n    thickness: f32,\n    tangent: vec3<f32>,\n    alpha: f32,\n    color: vec3<f32>,\n    strand: u32,\n}\n";

/// The probe shader: `fixture` after `enable`, HairPoint,
/// plait::strand_capsule, plait::strand_dots and plait::strand_rays, each
/// library file without its directives (the text is one module).
fn probe_shader(fixture: &str) -> String {
    let read = |p: &str| std::fs::read_to_string(repo_root().join(p)).expect(p);
    let library = |p: &str| -> String {
        read(p)
            .lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with("enable "))
            .map(|l| format!("{l}\n"))
            .collect()
    };
    let capsule = library("shaders/lib/strand_capsule.wgsl");
    let dots = library("shaders/lib/strand_dots.wgsl");
    let rays = library("shaders/lib/strand_rays.wgsl");
    let text = read(&format!("tests/fixtures/{fixture}"));
    format!("enable wgpu_ray_query;\n{HAIR_POINT}\n{capsule}\n{dots}\n{rays}\n{text}")
}

/// Strands crossed from each point toward `to_light`, traced on the GPU
/// through a structure of `primitive`s.
pub fn counts(
    primitive: StrandPrimitive,
    vertices: &[StrandVertex],
    points: &[Vec3],
    to_light: Vec3,
    bias: f32,
) -> Vec<f32> {
    let probe = [to_light.x, to_light.y, to_light.z, bias];
    trace(
        "strand_trace_probe.wgsl",
        primitive,
        vertices,
        points,
        probe,
    )
}

/// Whether anything lies along the ray from each point along `dir`, as a
/// path's ray leaving segment `skip` (0xffffffff: none) meets it
/// (`plait::strand_rays::ray_blocked`, through
/// `tests/fixtures/strand_blocked_probe.wgsl`), through a structure of
/// swept spheres (the path tracer's).
pub fn blocked(vertices: &[StrandVertex], points: &[Vec3], dir: Vec3, skip: u32) -> Vec<bool> {
    let probe = [dir.x, dir.y, dir.z, f32::from_bits(skip)];
    let primitive = StrandPrimitive::SweptSphere;
    trace(
        "strand_blocked_probe.wgsl",
        primitive,
        vertices,
        points,
        probe,
    )
    .into_iter()
    .map(|b| b != 0.0)
    .collect()
}

/// One f32 per point from `tests/fixtures/FIXTURE` (after the library, as
/// [`probe_shader`] composes it), its uniform `probe` the four words given,
/// traced through a structure of `primitive`s built from `vertices`.
fn trace(
    fixture: &str,
    primitive: StrandPrimitive,
    vertices: &[StrandVertex],
    points: &[Vec3],
    probe: [f32; 4],
) -> Vec<f32> {
    let (_lock, gpu) = open_gpu();
    assert!(
        gpu.capabilities.ray_query,
        "adapter {} has no ray queries: {}",
        gpu.support.describe(),
        plait_gpu::support::RAY_QUERY_FIX
    );
    let device = &gpu.device;
    let storage = |label: &str, bytes: &[u8], usage: wgpu::BufferUsages| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage: wgpu::BufferUsages::STORAGE | usage,
        })
    };
    let hair = storage(
        "hair",
        bytemuck::cast_slice(vertices),
        wgpu::BufferUsages::empty(),
    );
    let options = StructureOptions {
        primitive,
        meshes: None,
    };
    let structure = StrandStructure::with(&gpu, (&hair, vertices.len() as u32), options)
        .expect("the structure");
    assert_eq!(structure.primitive(), primitive);
    let p4: Vec<[f32; 4]> = points.iter().map(|p| [p.x, p.y, p.z, 0.0]).collect();
    let probe_points = storage(
        "points",
        bytemuck::cast_slice(&p4),
        wgpu::BufferUsages::empty(),
    );
    let out_size = (points.len() * 4) as u64;
    let out = storage(
        "counts",
        &vec![0u8; out_size as usize],
        wgpu::BufferUsages::COPY_SRC,
    );
    let read = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read"),
        size: out_size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("probe"),
        contents: bytemuck::cast_slice(&probe),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("strand_trace_probe"),
        source: wgpu::ShaderSource::Wgsl(probe_shader(fixture).into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("strand_trace_probe"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    // Group 1, as the passes bind them (plait::strand_rays' vis_strands at 8,
    // vis_hair at 9);
    // group 0, the passes' frame, is empty here.
    let empty = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("strand_trace_probe_empty"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[],
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("strand_trace_probe"),
        layout: &pipeline.get_bind_group_layout(1),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 8,
                resource: structure.tlas().as_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 9,
                resource: hair.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: probe_points.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: out.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 4,
                resource: uniform.as_entire_binding(),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    structure.encode(&mut encoder, glam::Mat4::IDENTITY.to_cols_array_2d());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &empty, &[]);
        pass.set_bind_group(1, &bind_group, &[]);
        pass.dispatch_workgroups((points.len() as u32).div_ceil(64), 1, 1);
    }
    encoder.copy_buffer_to_buffer(&out, 0, &read, 0, out_size);
    gpu.queue.submit([encoder.finish()]);
    let bytes = plait_gpu::readback::map_buffer(device, &read).expect("read the counts");
    let errors = gpu.take_uncaptured_errors();
    assert!(errors.is_empty(), "GPU errors: {errors:#?}");
    bytemuck::cast_slice(&bytes).to_vec()
}
