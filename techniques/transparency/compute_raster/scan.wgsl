// compute_raster, tile_scan: each tile's first slot in the shared pool
// `tile_segments` — the sum of the counts of the tiles before it (an
// exclusive prefix sum; Frostbite's per-tile allocation) — in one workgroup:
// each thread sums a run of tiles, thread 0 sums the runs, each thread then
// writes its run's offsets. The pool holds `binned_segments` slots: what the
// tiles need beyond it is counted (raster_counter[0] dropped, [1] the slots
// that would hold everything), so the engine reports it and may grow the
// param. Run with one workgroup (the pass type's dispatch).

struct Params {
    binned_segments: u32,
}
@group(1) @binding(0) var<uniform> params: Params;
// Per tile: [2 tile] its count (tile_count), [2 tile + 1] its first slot (here).
@group(1) @binding(1) var<storage, read_write> tile_ranges: array<u32>;
// [0] dropped, [1] needed, [2] tile_blend's unfinished invocations (reset
// here, counted there).
@group(1) @binding(2) var<storage, read_write> raster_counter: array<u32>;

const THREADS: u32 = 256u;
var<workgroup> run_start: array<u32, THREADS>;

@compute @workgroup_size(256)
fn main(@builtin(local_invocation_index) lid: u32) {
    let tiles = arrayLength(&tile_ranges) / 2u;
    let per = (tiles + THREADS - 1u) / THREADS;
    let first = min(lid * per, tiles);
    let last = min(first + per, tiles);
    var sum = 0u;
    for (var i = first; i < last; i++) {
        sum += tile_ranges[2u * i];
    }
    run_start[lid] = sum;
    workgroupBarrier();
    if (lid == 0u) {
        var total = 0u;
        for (var k = 0u; k < THREADS; k++) {
            let run = run_start[k];
            run_start[k] = total;
            total += run;
        }
        let cap = params.binned_segments;
        raster_counter[0] = select(0u, total - cap, total > cap);
        raster_counter[1] = total;
        raster_counter[2] = 0u;
    }
    workgroupBarrier();
    var at = run_start[lid];
    for (var i = first; i < last; i++) {
        tile_ranges[2u * i + 1u] = at;
        at += tile_ranges[2u * i];
    }
}
