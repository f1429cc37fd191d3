// strand_dots — DOTS triangles of the frame's hair for the strands'
// acceleration structure when it is built with `primitive = "dots"`
// (crates/plait-gpu/src/strand_structure.rs): segment i (vertex i to vertex
// i + 1) is four triangles, twelve corners of 3 × f32 from corner 12i, two
// quads crossed along its axis of half-width half the strand's thickness at
// each end — plait::strand_dots::dots_corner, which the Rust side prepends
// to this text (the tracers call the same functions). A pair of vertices of
// two different strands, or of one place, is no segment: its corners are
// all vertex i, triangles of no area that no ray's test accepts (the
// tracing shaders check the strand ids too). The import is for the shader
// library's checks (tests/shaders.rs composes this file through it); the
// Rust side drops `#` lines as it prepends the module's text.
#import plait::strand_dots::dots_corner

struct HairPoint {
    position: vec3<f32>,
    thickness: f32,
    tangent: vec3<f32>,
    alpha: f32,
    color: vec3<f32>,
    strand: u32,
}

@group(0) @binding(0) var<storage, read> hair_vertices: array<HairPoint>;
@group(0) @binding(1) var<storage, read_write> corners: array<f32>;

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
    let segment = a.strand == b.strand && any(a.position != b.position);
    for (var j = 0u; j < 12u; j++) {
        var p = a.position;
        if (segment) {
            p = dots_corner(a.position, 0.5 * a.thickness, b.position, 0.5 * b.thickness, j);
        }
        let o = 3u * (12u * i + j);
        corners[o] = p.x;
        corners[o + 1u] = p.y;
        corners[o + 2u] = p.z;
    }
}
