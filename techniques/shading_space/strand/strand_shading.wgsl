// Strand-space shading (Tafuri 2019, Frostbite): one thread per shading point
// of every drawn strand evaluates the radiance the per-fragment path computes
// (`plait::hair_radiance`: the chosen shading, self_shadow and lighting
// providers, the opaque shadow map, the chosen ambient occlusion), with the
// camera of this frame, at shading point k of K: point index
// k·(n-1)/(K-1) along the strand of n points (the middle when K = 1), its
// position, tangent, colour and occlusion interpolated between the two hair
// vertices either side — as the rasterizer interpolates them for a fragment.
// `plait::shading_space::strand` reads the result back in the hair passes.

#import plait::hair_radiance::hair_radiance
#import plait::ambient_occlusion::occlusion_at
#import plait::hair_point::HairPoint
#import plait::strand_curve::strand_curve_tangent


// One drawn strand of `strand_guides` (48 B): ids.w = first vertex, root.w = point count.
struct Strand {
    ids: vec4<u32>,
    weights: vec4<f32>,
    root: vec4<f32>,
}

struct ShadingSpaceParams {
    shading_points: u32,
}
@group(1) @binding(0) var shadow_map: texture_depth_2d;
@group(1) @binding(60) var<uniform> shading_space_params: ShadingSpaceParams;
@group(1) @binding(61) var<storage, read_write> strand_radiance: array<vec4<f32>>;
@group(1) @binding(62) var<storage, read> strands: array<Strand>;
@group(1) @binding(63) var<storage, read> hair_vertices: array<HairPoint>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k_count = shading_space_params.shading_points;
    let strand = id.x / k_count;
    let k = id.x % k_count;
    if (strand >= arrayLength(&strands) || id.x >= arrayLength(&strand_radiance)) {
        return;
    }
    let s = strands[strand];
    let first = s.ids.w;
    let last = max(u32(s.root.w), 1u) - 1u;
    var at = f32(last) * 0.5;
    if (k_count > 1u) {
        at = f32(k) * (f32(last) / f32(k_count - 1u));
    }
    let i0 = min(u32(floor(at)), last);
    let i1 = min(i0 + 1u, last);
    let f = at - f32(i0);
    let a = hair_vertices[first + i0];
    let b = hair_vertices[first + i1];
    let world = mix(a.position, b.position, f);
    // The smooth curve's tangent there, as the fragment path shades about.
    let tangent = strand_curve_tangent(a.position, b.position, a.tangent, b.tangent, f);
    let color = mix(a.color, b.color, f);
    let occlusion = mix(occlusion_at(first + i0), occlusion_at(first + i1), f);
    strand_radiance[id.x] = vec4<f32>(hair_radiance(shadow_map, world, tangent, color, occlusion), 1.0);
}
