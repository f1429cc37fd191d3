// density_occlusion — per-vertex ambient occlusion from the hair density
// volume: each vertex's transmittance exp(−w · n) averaged over N
// directions of a spherical Fibonacci lattice, n the strands crossed from
// the vertex to the volume's edge (the march the self-shadow technique
// makes from every voxel, plait::density_march). Xing et al. 2012 §4 average
// transmittance over directions on the sphere from deep opacity maps
// (hair only occludes, as there); here every direction marches the one
// volume built this frame. The volume weighs strands by their area across
// the key light, so another direction sees the groom's strands as if
// crossing it the same way (exact for strands across every direction, an
// over-estimate along the strands' own direction).
#import plait::hair_point::HairPoint
#import plait::density_march::{density_strands_along, density_bias}

@group(1) @binding(0) var<storage, read> hair_vertices: array<HairPoint>;
@group(1) @binding(1) var<storage, read_write> vertex_ao: array<f32>;
// [0] vertices the buffer could not hold, [1] the vertices there are.
@group(1) @binding(3) var<storage, read_write> status: array<u32>;

struct OcclusionParams {
    directions: u32,
    // opacity of one strand crossed
    occlusion_weight: f32,
}
@group(1) @binding(2) var<uniform> occlusion_params: OcclusionParams;

// Direction i of n on a spherical Fibonacci lattice.
fn lattice(i: u32, n: u32) -> vec3<f32> {
    let z = 1.0 - (2.0 * f32(i) + 1.0) / f32(n);
    let r = sqrt(max(1.0 - z * z, 0.0));
    let phi = f32(i) * 2.39996323;
    return vec3<f32>(r * cos(phi), r * sin(phi), z);
}

@compute @workgroup_size(256)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let v = id.x;
    let vertices = arrayLength(&hair_vertices);
    if (v == 0u) {
        status[0] = vertices - min(vertices, arrayLength(&vertex_ao));
        status[1] = vertices;
    }
    if (v >= vertices || v >= arrayLength(&vertex_ao)) {
        return;
    }
    let p = hair_vertices[v].position;
    let n = max(occlusion_params.directions, 1u);
    var sum = 0.0;
    for (var i = 0u; i < n; i++) {
        let d = lattice(i, n);
        sum += exp(-occlusion_params.occlusion_weight * density_strands_along(p + d * density_bias(), d));
    }
    vertex_ao[v] = sum / f32(n);
}
