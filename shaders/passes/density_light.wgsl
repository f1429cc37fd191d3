// density_light — per voxel of the hair density volume, the expected number
// of strands between the voxel's centre and the key light: the exact
// voxel-by-voxel integral of the self-shadow provider
// (plait::density_march::density_strands_along), once a frame
// for R³ centres, so that shading a point reads 8 of them (trilinear)
// instead of marching up to 3 R voxels per fragment. One thread per voxel.
#import plait::frame::frame
#import plait::density_volume::{density_box_from, density_cell, density_to_light}
#import plait::density_march::{density_strands_along, vis_box}

@group(1) @binding(0) var<storage, read_write> toward: array<f32>;

@compute @workgroup_size(256)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let b = density_box_from(vis_box);
    let r = b.res;
    if (id.x >= arrayLength(&toward) || id.x >= r * r * r) {
        return;
    }
    let v = vec3<u32>(id.x % r, (id.x / r) % r, id.x / (r * r));
    let centre = b.lo + (vec3<f32>(v) + 0.5) * density_cell(b);
    let to_light = density_to_light(centre, frame.light_direction, frame.light_position);
    toward[id.x] = density_strands_along(centre, to_light);
}
