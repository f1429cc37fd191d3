enable wgpu_ray_query;
// ambient_occlusion = ray_traced, the per-vertex pass: from every hair vertex
// `rays` rays over the sphere (a spherical Fibonacci lattice, rotated by a
// per-vertex random rotation about a random axis so neighbouring vertices do
// not share their directions' aliasing), each counting the strands it crosses
// (plait::strand_rays: each segment's tapered swept sphere, a crossing
// owned by one segment); the vertex's ambient visibility is the mean of
// exp(−w · n) (Xing et al. 2012 §4: transmittance averaged over directions).
// A crossing within one strand width of the vertex is its own strand (the
// ray starts on its axis): not counted. A ray that meets one of the scene's
// meshes (head, ground: triangle instances of the same structure) within
// `mesh_distance` of the vertex is occluded (transmittance 0): near a plane
// at height h a share (1 − h/D)/2 of the sphere's rays is lost
// (tests/ray_traced_meshes.rs).

#import plait::strand_rays::{ray_hits, vis_hair}
#import plait::loop_budget::loop_budget_spent

// The strands' structure and the hair's vertices: plait::strand_rays'
// vis_strands and vis_hair (group 1, bindings 8 and 9).
@group(1) @binding(2) var<storage, read_write> vertex_ao: array<f32>;
// Word 0: vertices vertex_ao could not hold; 1: the hair's vertices; 2:
// invocations a loop budget cut short (the frame fails on either, naming
// ao_max_vertices or the pass).
@group(1) @binding(4) var<storage, read_write> status: array<atomic<u32>>;

struct Params {
    rays: u32,
    shadow_weight: f32,
    // How far a mesh occludes (world units; 0: meshes do not).
    mesh_distance: f32,
}
@group(1) @binding(3) var<uniform> params: Params;

const PI: f32 = 3.14159265358979;
const GOLDEN_ANGLE: f32 = 2.39996322972865;

// Direction i of n on the sphere: the spherical Fibonacci lattice (uniform
// in z, the golden angle in azimuth).
fn fibonacci_direction(i: u32, n: u32) -> vec3<f32> {
    let z = 1.0 - (2.0 * f32(i) + 1.0) / f32(n);
    let r = sqrt(max(0.0, 1.0 - z * z));
    let phi = GOLDEN_ANGLE * f32(i);
    return vec3<f32>(r * cos(phi), r * sin(phi), z);
}

// A 32-bit integer hash (PCG's output permutation), for the per-vertex rotation.
fn hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn unit_float(v: u32) -> f32 {
    return f32(hash(v) >> 8u) / 16777216.0;
}

// Rodrigues' rotation of `v` by `angle` about unit `axis`.
fn rotate(v: vec3<f32>, axis: vec3<f32>, angle: f32) -> vec3<f32> {
    let c = cos(angle);
    let s = sin(angle);
    return v * c + cross(axis, v) * s + axis * dot(axis, v) * (1.0 - c);
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    let vertices = arrayLength(&vis_hair);
    if (index == 0u) {
        atomicStore(&status[0], vertices - min(vertices, arrayLength(&vertex_ao)));
        atomicStore(&status[1], vertices);
    }
    if (index >= vertices || index >= arrayLength(&vertex_ao)) {
        return;
    }
    let v = vis_hair[index];
    let axis = fibonacci_direction(hash(index) % 1024u, 1024u);
    let angle = 2.0 * PI * unit_float(index ^ 0x9e3779b9u);
    let own = max(v.thickness, 1e-6);
    var sum = 0.0;
    for (var i = 0u; i < params.rays; i++) {
        let dir = rotate(fibonacci_direction(i, params.rays), axis, angle);
        let hits = ray_hits(v.position, dir, own, 1e30, params.mesh_distance);
        sum += select(exp(-params.shadow_weight * hits.strands), 0.0, hits.blocked);
    }
    vertex_ao[index] = sum / f32(params.rays);
    if (loop_budget_spent(2u + (params.rays & 1u))) {
        atomicAdd(&status[2], 1u);
    }
}
