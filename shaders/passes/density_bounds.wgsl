// density_bounds — the density volume's box fitted to this frame's strands:
// one workgroup folds every hair vertex into a min/max pair
// (plait::hair_bounds), pads it by `padding` × its largest extent on every
// side (plus one voxel, so a strand on the box's face still has voxels
// either side for trilinear lookups) and writes the box the splat and the
// lookups read (plait::density_volume). Found on the GPU every frame, so
// the volume follows simulated and animated hair with no readback.
#import plait::hair_point::HairPoint
#import plait::hair_bounds::{BOUNDS_GROUP, workgroup_bounds}
#import plait::loop_budget::loop_budget_spent

@group(1) @binding(0) var<storage, read> hair_vertices: array<HairPoint>;
@group(1) @binding(1) var<storage, read_write> box: array<f32, 8>;
@group(1) @binding(2) var<storage, read_write> status: array<atomic<u32>>;

struct BoundsParams {
    resolution: u32,
    padding: f32,
}
@group(1) @binding(3) var<uniform> bounds_params: BoundsParams;

@compute @workgroup_size(256)
fn main(@builtin(local_invocation_index) t: u32) {
    let n = arrayLength(&hair_vertices);
    var lo = vec3<f32>(3.0e38);
    var hi = vec3<f32>(-3.0e38);
    for (var v = t; v < n; v += BOUNDS_GROUP) {
        let p = hair_vertices[v].position;
        lo = min(lo, p);
        hi = max(hi, p);
    }
    // A short last loop (2 or 3 laps, unknown to the compiler) that finishes
    // only while budget is left.
    if (loop_budget_spent(2u + (n & 1u))) {
        atomicAdd(&status[0], 1u);
    }
    let b = workgroup_bounds(t, lo, hi);
    if (t != 0u) {
        return;
    }
    let res = f32(max(bounds_params.resolution, 1u));
    let extent = max(b.hi - b.lo, vec3<f32>(1e-4));
    let pad = vec3<f32>(bounds_params.padding * max(max(extent.x, extent.y), extent.z));
    // One more voxel each side: voxel = size / res, size = extent + 2 pad + 2 voxel.
    let size = (extent + 2.0 * pad) * res / max(res - 2.0, 1.0);
    let lo_out = b.lo - pad - size / res;
    box = array<f32, 8>(lo_out.x, lo_out.y, lo_out.z, res, size.x, size.y, size.z, 0.0);
}
