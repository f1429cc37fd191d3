// compute_raster, strand_bin: one thread per hair segment writes it (its
// first vertex) into every screen tile it lands in
// (plait::compute_raster::tiles, the walk tile_count counted), at the
// tile's next slot from the first tile_scan gave it. Slots past the pool's
// `binned_segments` are not written: tile_scan counted them as dropped, and
// tile_blend blends only the slots the pool holds.

#import plait::compute_raster::tiles::{segment_span, lands_in, tiles_across}
#import plait::loop_budget::loop_budget_spent

struct Params {
    tile_size: u32,
    binned_segments: u32,
}
@group(1) @binding(0) var<uniform> params: Params;
// Per tile: [2 tile] its count, [2 tile + 1] its first slot.
@group(1) @binding(4) var<storage, read> tile_ranges: array<u32>;
// The pool: slot i holds a segment's first vertex (words 0 … binned_segments;
// the words after are tile_blend's).
@group(1) @binding(5) var<storage, read_write> tile_segments: array<u32>;
// Per tile: the slots filled so far.
@group(1) @binding(6) var<storage, read_write> tile_fill: array<atomic<u32>>;
// [0] invocations whose walk lavapipe's loop budget cut short (count.wgsl).
@group(1) @binding(8) var<storage, read_write> bin_status: array<atomic<u32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    atomicAdd(&bin_status[0], 1u);
    let t = i32(params.tile_size);
    let span = segment_span(id.x, t);
    let across = tiles_across(t);
    for (var ty = span.first_tile.y; ty <= span.last_tile.y; ty++) {
        for (var tx = span.first_tile.x; tx <= span.last_tile.x; tx++) {
            if (lands_in(span, tx, ty, t)) {
                let tile = u32(ty * across + tx);
                let slot = tile_ranges[2u * tile + 1u] + atomicAdd(&tile_fill[tile], 1u);
                if (slot < params.binned_segments) {
                    tile_segments[slot] = span.vertex;
                }
            }
        }
    }
    if (!loop_budget_spent(params.tile_size)) {
        atomicSub(&bin_status[0], 1u);
    }
}
