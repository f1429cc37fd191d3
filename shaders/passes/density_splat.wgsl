// density_splat — the hair voxelized into the density volume
// (plait::density_volume): every segment (consecutive vertices of one
// strand) is walked voxel by voxel (Amanatides & Woo 1987's traversal) and
// adds to each voxel it crosses its projected area toward the key light,
// w · l · |sin(t, L)|, over V^(2/3), in fixed point (atomicAdd). One thread
// per voxel of the grid (the dispatch), each taking every R³-th segment.
// Status word 0 counts adds that would have wrapped a voxel's u32 and
// threads lavapipe's loop budget cut short: either fails the frame.
#import plait::frame::frame
#import plait::hair_point::HairPoint
#import plait::density_volume::{DENSITY_SCALE, DensityBox, density_box_from, density_cell, density_clip, density_index, density_to_light}
#import plait::loop_budget::loop_budget_spent

@group(1) @binding(0) var<storage, read> hair_vertices: array<HairPoint>;
@group(1) @binding(1) var<storage, read> box: array<f32, 8>;
@group(1) @binding(2) var<storage, read_write> grid: array<atomic<u32>>;
@group(1) @binding(3) var<storage, read_write> status: array<atomic<u32>>;

// Adds `q` (in units of voxel faces) to voxel `v`, counting a wrap.
fn deposit(b: DensityBox, v: vec3<u32>, q: f32) {
    let add = u32(round(q * DENSITY_SCALE));
    if (add == 0u) {
        return;
    }
    let old = atomicAdd(&grid[density_index(b, v)], add);
    if (old > 0xFFFFFFFFu - add) {
        atomicAdd(&status[0], 1u);
    }
}

// Walks the segment p0 → p1 through the grid, depositing w · l · |sin|
// piece by piece. Returns the voxels visited.
fn splat_segment(b: DensityBox, p0: vec3<f32>, p1: vec3<f32>, area_per_length: f32) -> u32 {
    let cell = density_cell(b);
    let face = pow(cell.x * cell.y * cell.z, 2.0 / 3.0);
    let seg_len = length(p1 - p0);
    let g0 = (p0 - b.lo) / cell;
    let d = (p1 - p0) / cell;
    let res = f32(b.res);
    let span = density_clip(g0, d, res);
    let t_start = max(span.x, 0.0);
    let t_end = min(span.y, 1.0);
    if (t_start >= t_end || seg_len <= 0.0) {
        return 0u;
    }
    let entry = g0 + d * t_start;
    var v = vec3<i32>(clamp(floor(entry + d * 1e-6), vec3<f32>(0.0), vec3<f32>(res - 1.0)));
    let dir_step = vec3<i32>(sign(d));
    let inv = 1.0 / max(abs(d), vec3<f32>(1e-30));
    // t of the next voxel boundary along each axis, and between boundaries.
    let next_face = vec3<f32>(v) + select(vec3<f32>(0.0), vec3<f32>(1.0), d > vec3<f32>(0.0));
    var t_max = select(vec3<f32>(3.0e38), t_start + abs(next_face - entry) * inv, abs(d) > vec3<f32>(1e-30));
    let t_delta = inv;
    var t = t_start;
    var visited = 0u;
    // At most 3 R voxels on a segment through the whole grid.
    for (var i = 0u; i < 3u * b.res + 3u && t < t_end; i++) {
        let t_next = min(min(min(t_max.x, t_max.y), t_max.z), t_end);
        deposit(b, vec3<u32>(v), (t_next - t) * seg_len * area_per_length / face);
        visited += 1u;
        t = t_next;
        if (t_max.x <= t_max.y && t_max.x <= t_max.z) {
            v.x += dir_step.x;
            t_max.x += t_delta.x;
        } else if (t_max.y <= t_max.z) {
            v.y += dir_step.y;
            t_max.y += t_delta.y;
        } else {
            v.z += dir_step.z;
            t_max.z += t_delta.z;
        }
        if (any(v < vec3<i32>(0)) || any(v >= vec3<i32>(i32(b.res)))) {
            break;
        }
    }
    return visited;
}

@compute @workgroup_size(256)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let b = density_box_from(box);
    let threads = arrayLength(&grid);
    let n = arrayLength(&hair_vertices);
    let first = id.x;
    if (first >= threads || b.res == 0u) {
        return;
    }
    var laps = 0u;
    for (var s = first; s + 1u < n; s += threads) {
        let a = hair_vertices[s];
        let c = hair_vertices[s + 1u];
        if (a.strand != c.strand) {
            continue;
        }
        let mid = 0.5 * (a.position + c.position);
        let tangent = c.position - a.position;
        let to_light = density_to_light(mid, frame.light_direction, frame.light_position);
        let sin_l = length(cross(normalize(tangent), to_light));
        let width = 0.5 * (a.thickness + c.thickness);
        laps += splat_segment(b, a.position, c.position, width * sin_l);
    }
    if (loop_budget_spent(2u + (laps & 1u))) {
        atomicAdd(&status[0], 1u);
    }
}
