// plait::hair_bounds — the bounding box of the hair, found by one workgroup
// of BOUNDS_GROUP threads (the precomputes of ambient occlusion fit their
// views and pick scalp geometry with it). Each thread folds its share of the
// vertices into a min/max pair; `workgroup_bounds` reduces them.
#define_import_path plait::hair_bounds

const BOUNDS_GROUP: u32 = 256u;

var<workgroup> bounds_lo: array<vec3<f32>, 256>;
var<workgroup> bounds_hi: array<vec3<f32>, 256>;

struct Bounds {
    lo: vec3<f32>,
    hi: vec3<f32>,
}

// Called by every thread `t` of a @workgroup_size(256) workgroup with its own
// min `lo` and max `hi`; returns the workgroup's box to every thread.
fn workgroup_bounds(t: u32, lo: vec3<f32>, hi: vec3<f32>) -> Bounds {
    bounds_lo[t] = lo;
    bounds_hi[t] = hi;
    workgroupBarrier();
    for (var stride = BOUNDS_GROUP / 2u; stride > 0u; stride /= 2u) {
        if (t < stride) {
            bounds_lo[t] = min(bounds_lo[t], bounds_lo[t + stride]);
            bounds_hi[t] = max(bounds_hi[t], bounds_hi[t + stride]);
        }
        workgroupBarrier();
    }
    return Bounds(bounds_lo[0], bounds_hi[0]);
}
