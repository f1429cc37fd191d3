// strand_structure — the slots of the pass that puts the frame's strands in
// an acceleration structure (crates/plait-passes/src/strand_structure.rs),
// for `plait check`. The pass records its own work (plait_gpu::
// strand_structure: shaders/passes/strand_boxes.wgsl, then the builds); this
// entry point is never dispatched.
enable wgpu_ray_query;
#import plait::hair_point::HairPoint

@group(1) @binding(0) var<storage, read> hair_vertices: array<HairPoint>;
@group(1) @binding(1) var structure: acceleration_structure;

@compute @workgroup_size(1)
fn main() {
    var rq: ray_query;
    rayQueryInitialize(&rq, structure, RayDesc(0u, 0xFFu, 0.0, 1.0, hair_vertices[0].position, vec3<f32>(0.0, 0.0, 1.0)));
}
