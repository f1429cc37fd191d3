// strand_boxes — one box per segment of the frame's hair for the strands'
// acceleration structure (crates/plait-gpu/src/strand_structure.rs): box i
// encloses the tapered swept sphere from vertex i to vertex i + 1 (radius
// half the strand's thickness at each end), min.xyz then max.xyz, 24 B. A
// pair of vertices of two different strands is no segment: its box is the
// point at vertex i, which no ray's capsule test accepts (the tracing
// shaders check the strand ids too).
struct HairPoint {
    position: vec3<f32>,
    thickness: f32,
    tangent: vec3<f32>,
    alpha: f32,
    color: vec3<f32>,
    strand: u32,
}

@group(0) @binding(0) var<storage, read> hair_vertices: array<HairPoint>;
@group(0) @binding(1) var<storage, read_write> boxes: array<f32>;

// Rows of the 2D dispatch: one dimension holds at most 65,535 workgroups.
const ROW: u32 = 65535u * 64u;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * ROW;
    let n = arrayLength(&hair_vertices);
    if (i + 1u >= n) {
        return;
    }
    let a = hair_vertices[i];
    let b = hair_vertices[i + 1u];
    var lo = a.position;
    var hi = a.position;
    if (a.strand == b.strand) {
        let ra = vec3<f32>(0.5 * a.thickness);
        let rb = vec3<f32>(0.5 * b.thickness);
        lo = min(a.position - ra, b.position - rb);
        hi = max(a.position + ra, b.position + rb);
    }
    let o = 6u * i;
    boxes[o] = lo.x;
    boxes[o + 1u] = lo.y;
    boxes[o + 2u] = lo.z;
    boxes[o + 3u] = hi.x;
    boxes[o + 4u] = hi.y;
    boxes[o + 5u] = hi.z;
}
