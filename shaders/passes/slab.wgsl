// slab: the number of hair fragments per slab of slices per texel
// (000_785589f319b01ef5.txt §3.1, Fig. 8), counted exactly with atomicAdd
// (the paper's additive float blending would need FLOAT32_BLENDABLE and loses
// precision past 2048 fragments in 16-bit floats). Slabs per texel = the
// `slabs` buffer's u32 words per texel (4 for the paper's 4 slabs of 32 slices).
#import plait::frame::{view_proj, view_linear_depth}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> slabs: array<atomic<u32>>;

struct VertexIn {
    @location(0) position: vec3<f32>,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = view_proj() * vec4<f32>(v.position, 1.0);
    out.world = v.position;
    return out;
}

@fragment
fn fs_main(in: VertexOut) {
    let size = textureDimensions(range);
    let texel = min(vec2<u32>(in.clip.xy), size - 1u);
    let r = textureLoad(range, vec2<i32>(texel), 0);
    let rel = (view_linear_depth(in.world) - r.x) / max(r.y - r.x, 1e-9);
    let count = arrayLength(&slabs) / (size.x * size.y);
    let slab = min(u32(clamp(rel, 0.0, 1.0) * f32(count)), count - 1u);
    atomicAdd(&slabs[(texel.y * size.x + texel.x) * count + slab], 1u);
}
