// sim_interpolate.wgsl — the drawn strands from the guides, every frame, on
// the GPU (Halén & Wester 2007 §2.5, §5.4–5.5): point k of a drawn strand is
//
//   root + scale · (Σᵢ wᵢ gᵢ[k] − Σᵢ wᵢ gᵢ[0])
//
// (the barycentric blend of its three guides, translated to its own root —
// moved with the head — and scaled to its length), exactly as plait-hair
// grows a guided groom (CPU reference: `plait_hair::guides::Guides`).
// Tangents are recomputed as central differences inside the strand,
// one-sided at its ends (plait_hair::Strands::central_tangents): the static
// groom's are the natural spline's directions (Strands::tangents), a
// per-strand solve this per-point pass does not do. One thread per drawn point;
// thickness, alpha, colour and strand id are left as they are.

#import plait::frame::frame

struct HairVertex {
    position: vec3<f32>,
    thickness: f32,
    tangent: vec3<f32>,
    alpha: f32,
    color: vec3<f32>,
    strand_id: u32,
}

struct StrandGuide {
    // guides 0, 1, 2 and the strand's first point
    ids: vec4<u32>,
    // weights and the length scale
    weights: vec4<f32>,
    // rest root and the point count
    root: vec4<f32>,
}

@group(1) @binding(0) var<storage, read> guide_positions: array<vec4<f32>>;
@group(1) @binding(1) var<storage, read> guide_strands: array<vec2<u32>>;
@group(1) @binding(2) var<storage, read> strand_guides: array<StrandGuide>;
@group(1) @binding(3) var<storage, read_write> hair_vertices: array<HairVertex>;

fn guide_point(g: u32, k: u32) -> vec3<f32> {
    let strand = guide_strands[g];
    return guide_positions[strand.x + min(k, max(strand.y, 1u) - 1u)].xyz;
}

fn blended(b: StrandGuide, k: u32) -> vec3<f32> {
    return b.weights.x * guide_point(b.ids.x, k)
        + b.weights.y * guide_point(b.ids.y, k)
        + b.weights.z * guide_point(b.ids.z, k);
}

fn point_of(b: StrandGuide, root: vec3<f32>, start: vec3<f32>, k: u32) -> vec3<f32> {
    return root + (blended(b, k) - start) * b.weights.w;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&hair_vertices)) {
        return;
    }
    let strand = hair_vertices[i].strand_id;
    if (strand >= arrayLength(&strand_guides)) {
        return;
    }
    let b = strand_guides[strand];
    let count = u32(b.root.w);
    let k = i - b.ids.w;
    let root = (frame.head_model * vec4<f32>(b.root.xyz, 1.0)).xyz;
    let start = blended(b, 0u);
    let here = point_of(b, root, start, k);
    let before = point_of(b, root, start, select(k - 1u, 0u, k == 0u));
    let after = point_of(b, root, start, min(k + 1u, count - 1u));
    var tangent = after - before;
    let len = length(tangent);
    if (len > 0.0) {
        tangent = tangent / len;
    } else {
        tangent = vec3<f32>(0.0, 1.0, 0.0);
    }
    hair_vertices[i].position = here;
    hair_vertices[i].tangent = tangent;
}
