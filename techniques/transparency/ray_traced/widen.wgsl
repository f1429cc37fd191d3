// transparency = ray_traced, ray_widen: the hair's vertices as the primary
// rays' structure boxes them. A primary ray through a pixel centre stands
// for the whole pixel, so it must find every strand that covers part of the
// pixel, not only the strands its centre line touches: each vertex is
// copied with its width grown by WIDEN_PIXELS pixels' footprint there (the
// world size of a pixel across the view at the vertex, as
// plait::strand_coverage measures a strand's width in pixels). The trace
// (trace.wgsl) accepts a strand within half its true width + half a pixel of
// the ray — the extra half pixel beyond that is margin, because the
// footprint between two vertices is their boxes' straight interpolation.
// Strands the level of detail (plait::strand_lod) does not draw get a
// strand id of their own per vertex, so no box joins two of their vertices.
// One thread per vertex; a thread past the hair returns. The thickness
// itself stays in hair_vertices, which the trace reads for the coverage.
#import plait::frame::frame
#import plait::hair_point::HairPoint
#import plait::strand_coverage::strand_width_pixels
#import plait::strand_lod::strand_lod_weight

// The scene's vertices, and the copy the structure is built from (words 0..12
// of a vertex: plait::hair_point::HairPoint).
@group(1) @binding(60) var<storage, read> hair_vertices: array<HairPoint>;
@group(1) @binding(61) var<storage, read_write> ray_vertices: array<HairPoint>;
// Word 0: vertices ray_vertices could not hold; 1: the hair's vertices (the
// technique's `overflow`: the frame fails or the session grows
// ray_max_vertices); 2 unused here (the trace's).
@group(1) @binding(62) var<storage, read_write> ray_status: array<atomic<u32>>;

// Pixels the copy's width exceeds the strand's: 1 for the pixel the trace
// accepts (half on each side) and 0.5 margin.
const WIDEN_PIXELS: f32 = 1.5;
const SQRT2: f32 = 1.41421356237;

@compute @workgroup_size(256)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    let vertices = arrayLength(&hair_vertices);
    let capacity = arrayLength(&ray_vertices);
    if (index == 0u) {
        atomicStore(&ray_status[0], vertices - min(vertices, capacity));
        atomicStore(&ray_status[1], vertices);
    }
    if (index >= vertices || index >= capacity) {
        return;
    }
    var v = hair_vertices[index];
    // Pixels per world unit across the view at the vertex: a width small
    // beside its distance, so the projection is linear over it.
    let probe = 1e-3 * max(distance(frame.camera_position.xyz, v.position), 1e-6);
    let pixels = strand_width_pixels(v.position, v.tangent, probe);
    if (pixels > 0.0) {
        v.thickness += WIDEN_PIXELS * probe / pixels;
#ifdef PRIMITIVE_DOTS
        // DOTS: a ray passing ρ from the axis meets one of the two crossed
        // quads of half-width r when ρ ≤ r · max(|cos φ|, |sin φ|) (φ its
        // angle to the quads), at least r / √2: widened √2 more, the quads
        // reach every strand the swept sphere of the width above reaches.
        v.thickness *= SQRT2;
#endif
    }
    if (strand_lod_weight(v.strand) <= 0.0) {
        v.strand = 0x80000000u | index;
    }
    ray_vertices[index] = v;
}
