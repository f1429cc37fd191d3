// The path tracer's image (pipelines/physical/path_traced.toml): each pixel's mean
// over its samples (shaders/passes/path_trace.wgsl's `pt_sum`), linear
// radiance; alpha the part of its camera rays that met the hair or a mesh
// (docs/formats.md, "The display transform and linear images": the EXR's
// alpha).
#import plait::frame::frame

@group(1) @binding(0) var<storage, read> pt_sum: array<vec4<f32>>;
@group(1) @binding(1) var radiance: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(radiance);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let i = id.y * u32(frame.screen_size.x) + id.x;
    let sum = pt_sum[2u * i];
    let count = max(pt_sum[2u * i + 1u].x, 1.0);
    textureStore(radiance, id.xy, sum / count);
}
