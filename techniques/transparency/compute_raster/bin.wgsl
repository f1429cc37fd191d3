// compute_raster, strand_bin: one thread per hair segment (the line list's
// vertex pairs) projects it with the camera and appends it (its first vertex) to every
// screen tile it may touch: its screen bounding box grown by one pixel (the
// analytic coverage of tile_blend reaches one pixel either side of the
// line), narrowed to the tiles the line passes within that pixel of.
//
// The `geometry` point's answer is honoured as every hair draw honours it
// (plait::strand_lod): a strand of weight 0 is not binned. A segment is left
// out of a tile whose farthest opaque depth is at or in front of the
// segment's nearest depth (tile_depth): hidden there everywhere; in a tile
// that test keeps, only if some pixel of the tile that tile_blend would draw
// it in (its coverage rule, below) has the segment in front of the opaque
// depth — so hair hidden behind the head takes no capacity, is never
// counted, and the image is the same as without it.
//
// Each tile holds `segments_per_tile` indices; a segment past that is
// dropped and counted: raster_counter[0] counts dropped appends, [1] the
// capacity (in indices of `tile_segments`) that would have held them all —
// the fullest tile's count × tiles — so the engine reports it (the
// technique's `overflow` declaration) and may grow the param;
// raster_counter[3 + tile] counts the tile's segments.
#import plait::frame::frame
#import plait::strand_lod::strand_lod_weight
#import plait::hair_point::{HairPoint, screen_project}


struct Params {
    tile_size: u32,
    segments_per_tile: u32,
}
@group(1) @binding(0) var<uniform> params: Params;
@group(1) @binding(1) var<storage, read> hair_vertices: array<HairPoint>;
@group(1) @binding(2) var<storage, read> hair_indices: array<u32>;
@group(1) @binding(3) var<storage, read> tile_far: array<u32>;
@group(1) @binding(5) var<storage, read_write> tile_segments: array<u32>;
// [0] dropped, [1] needed, [2] tile_blend's, [3 + tile] the tile's count.
@group(1) @binding(6) var<storage, read_write> raster_counter: array<atomic<u32>>;
@group(1) @binding(7) var opaque_depth: texture_depth_2d;

// Whether segment a → b (screen xy, NDC z) is in front of the opaque depth
// at some pixel of the tile from `lo` to `hi` (inclusive) that tile_blend
// draws it in: pixel centres whose major-axis coordinate falls in [0, 1)
// of the segment and whose distance across the line is under one pixel
// (blend.wgsl, line_coverage).
fn visible_in_tile(a: vec4<f32>, b: vec4<f32>, lo: vec2<i32>, hi: vec2<i32>) -> bool {
    let d = b.xy - a.xy;
    let x_major = abs(d.x) >= abs(d.y);
    // Swizzled so that .x is the major axis.
    let a2 = select(a.yx, a.xy, x_major);
    let d2 = select(d.yx, d, x_major);
    let lo2 = select(lo.yx, lo, x_major);
    let hi2 = select(hi.yx, hi, x_major);
    if (abs(d2.x) < 1e-6) {
        return false;
    }
    let cos_theta = abs(d2.x) / length(d2);
    let first = max(lo2.x, i32(floor(min(a2.x, a2.x + d2.x) - 0.5)));
    let last = min(hi2.x, i32(floor(max(a2.x, a2.x + d2.x) + 0.5)));
    for (var i = first; i <= last; i++) {
        let t = (f32(i) + 0.5 - a2.x) / d2.x;
        if (t < 0.0 || t >= 1.0) {
            continue;
        }
        let minor = a2.y + t * d2.y;
        let z = mix(a.z, b.z, t);
        if (z < 0.0) {
            continue;
        }
        let from_j = max(lo2.y, i32(floor(minor - 1.5)));
        let to_j = min(hi2.y, i32(floor(minor + 1.5)));
        for (var j = from_j; j <= to_j; j++) {
            if (abs(f32(j) + 0.5 - minor) * cos_theta >= 1.0) {
                continue;
            }
            let pixel = select(vec2<i32>(j, i), vec2<i32>(i, j), x_major);
            if (z < textureLoad(opaque_depth, pixel, 0)) {
                return true;
            }
        }
    }
    return false;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = id.x;
    if (2u * s + 1u >= arrayLength(&hair_indices)) {
        return;
    }
    let v0 = hair_vertices[hair_indices[2u * s]];
    let v1 = hair_vertices[hair_indices[2u * s + 1u]];
    if (strand_lod_weight(v0.strand) <= 0.0) {
        return;
    }
    let a = screen_project(v0.position);
    let b = screen_project(v1.position);
    // Segments reaching behind the eye are not drawn (the hair is in front
    // of the camera in every scene plait renders; the raster path clips).
    if (a.w <= 0.0 || b.w <= 0.0) {
        return;
    }
    let near_z = min(a.z, b.z);
    if (near_z >= 1.0 || max(a.z, b.z) < 0.0) {
        return;
    }
    let size = vec2<i32>(frame.screen_size.xy);
    let t = i32(params.tile_size);
    let tiles = (size + vec2<i32>(t - 1)) / t;
    let lo = max(vec2<i32>(floor(min(a.xy, b.xy) - 1.0)), vec2<i32>(0));
    let hi = min(vec2<i32>(floor(max(a.xy, b.xy) + 1.0)), size - vec2<i32>(1));
    if (any(lo > hi)) {
        return;
    }
    let d = b.xy - a.xy;
    let len = length(d);
    let normal = select(vec2<f32>(0.0, 1.0), vec2<f32>(-d.y, d.x) / len, len > 1e-6);
    let cap = params.segments_per_tile;
    let allocated = arrayLength(&tile_segments) / cap;
    // Half the tile's diagonal plus the one pixel the coverage reaches.
    let reach = f32(t) * 0.70710678 + 1.5;
    for (var ty = lo.y / t; ty <= hi.y / t; ty++) {
        for (var tx = lo.x / t; tx <= hi.x / t; tx++) {
            let centre = (vec2<f32>(f32(tx), f32(ty)) + 0.5) * f32(t);
            if (abs(dot(centre - a.xy, normal)) > reach) {
                continue;
            }
            let tile = u32(ty * tiles.x + tx);
            if (near_z >= bitcast<f32>(tile_far[tile])) {
                continue;
            }
            let tile_lo = vec2<i32>(tx, ty) * t;
            let tile_hi = min(tile_lo + vec2<i32>(t - 1), size - vec2<i32>(1));
            if (!visible_in_tile(a, b, tile_lo, tile_hi)) {
                continue;
            }
            let slot = atomicAdd(&raster_counter[3u + tile], 1u);
            if (slot < cap) {
                // The segment's first vertex: a strand's segment i joins
                // vertices i and i + 1 (`Strands::line_list`), so tile_blend
                // needs no index buffer (a binding fewer: the WebGPU default
                // of 8 storage buffers per stage holds it with strand space
                // and occupancy's maps).
                tile_segments[tile * cap + slot] = hair_indices[2u * s];
            } else {
                atomicAdd(&raster_counter[0], 1u);
                atomicMax(&raster_counter[1], (slot + 1u) * allocated);
            }
        }
    }
}
