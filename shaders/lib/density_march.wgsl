// plait::density_march — the march through the hair density volume
// (plait::density_volume) that the self-shadow provider's per-voxel pass,
// and the ambient occlusion's per-vertex pass, make: the exact integral of
// the voxels' densities along a ray, voxel by voxel.
#define_import_path plait::density_march

#import plait::frame::frame
#import plait::density_volume::{DENSITY_SCALE, DensityBox, density_box_from, density_cell, density_clip, density_index}

@group(1) @binding(9) var<storage, read> vis_density: array<u32>;
@group(1) @binding(10) var<storage, read> vis_box: array<f32, 8>;

fn density_at_voxel(b: DensityBox, v: vec3<i32>) -> f32 {
    if (any(v < vec3<i32>(0)) || any(v >= vec3<i32>(i32(b.res)))) {
        return 0.0;
    }
    return f32(vis_density[density_index(b, vec3<u32>(v))]);
}

// Expected strands crossed from `world` along unit `dir` to the volume's
// edge: the exact integral of the voxels' constant densities, voxel by voxel
// (Amanatides & Woo 1987's traversal, as the splat walks segments): one read
// per voxel crossed. A march in fixed steps reading the voxel at each
// midpoint would alias (parallel rays entering the box at one face put their
// samples at the same depths of each voxel layer, so a thin layer is counted
// once, twice or not at all), and trilinear steps cost 8 reads each.
fn density_strands_along(world: vec3<f32>, dir: vec3<f32>) -> f32 {
    let b = density_box_from(vis_box);
    if (b.res == 0u) {
        return 0.0;
    }
    let cell = density_cell(b);
    let g0 = (world - b.lo) / cell;
    let d = dir / cell;
    let res = f32(b.res);
    let span = density_clip(g0, d, res);
    let t0 = max(span.x, 0.0);
    let t1 = span.y;
    if (t1 <= t0) {
        return 0.0;
    }
    let entry = g0 + d * t0;
    var v = vec3<i32>(clamp(floor(entry + d * 1e-4), vec3<f32>(0.0), vec3<f32>(res - 1.0)));
    let dir_step = vec3<i32>(sign(d));
    let inv = 1.0 / max(abs(d), vec3<f32>(1e-30));
    let next_face = vec3<f32>(v) + select(vec3<f32>(0.0), vec3<f32>(1.0), d > vec3<f32>(0.0));
    var t_max = select(vec3<f32>(3.0e38), t0 + abs(next_face - entry) * inv, abs(d) > vec3<f32>(1e-30));
    var t = t0;
    var q = 0.0;
    for (var i = 0u; i < 3u * b.res + 3u && t < t1; i++) {
        let t_next = min(min(min(t_max.x, t_max.y), t_max.z), t1);
        q += density_at_voxel(b, v) * (t_next - t);
        t = t_next;
        if (t_max.x <= t_max.y && t_max.x <= t_max.z) {
            v.x += dir_step.x;
            t_max.x += inv.x;
        } else if (t_max.y <= t_max.z) {
            v.y += dir_step.y;
            t_max.y += inv.y;
        } else {
            v.z += dir_step.z;
            t_max.z += inv.z;
        }
        if (any(v < vec3<i32>(0)) || any(v >= vec3<i32>(i32(b.res)))) {
            break;
        }
    }
    // t is in world units along dir (|dir| = 1); q / V^(1/3) per unit length.
    return q / (DENSITY_SCALE * pow(cell.x * cell.y * cell.z, 1.0 / 3.0));
}

// World units of the self-shadow bias (light linear depth × the light's depth range).
fn density_bias() -> f32 {
    return frame.conventions.x * (frame.near_far.w - frame.near_far.z);
}

