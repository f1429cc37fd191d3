// compute_raster, tile_count: one thread per hair segment counts it into
// every screen tile it lands in (plait::compute_raster::tiles), so
// tile_scan can give each tile exactly the slots it needs.

#import plait::compute_raster::tiles::{segment_span, lands_in, tiles_across}
#import plait::loop_budget::loop_budget_spent

struct Params {
    tile_size: u32,
}
@group(1) @binding(0) var<uniform> params: Params;
// Per tile: [2 tile] the segments landing in it (counted here), [2 tile + 1]
// its first slot in tile_segments (tile_scan).
@group(1) @binding(4) var<storage, read_write> tile_ranges: array<atomic<u32>>;
// [0] invocations of tile_count and strand_bin whose walk lavapipe's loop
// budget cut short (a long segment's many tiles): the frame fails.
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
                atomicAdd(&tile_ranges[2u * u32(ty * across + tx)], 1u);
            }
        }
    }
    if (!loop_budget_spent(params.tile_size)) {
        atomicSub(&bin_status[0], 1u);
    }
}
