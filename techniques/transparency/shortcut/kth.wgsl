// shortcut, the k-th depth (AMD TressFX 4.1 ShortCut): the pixel's k-th
// nearest hair depth, from the first draw's k-buffer, written as the depth
// the second draw tests against (`less_equal`), so only the k nearest
// fragments are shaded. Where the pixel has fewer than k fragments, the
// opaque depth, one float step nearer: `less_equal` against it is then the
// opaque pass's `less`.
#import plait::frame::{frame, fullscreen_position}

// Inverted depth bits, nearest first (see depths.wgsl); 0 = empty.
@group(1) @binding(0) var<storage, read> nearest_depths: array<u32>;
@group(1) @binding(1) var opaque_depth: texture_depth_2d;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @builtin(frag_depth) f32 {
    let p = vec2<u32>(pixel.xy);
    let base = (p.y * u32(frame.screen_size.x) + p.x) * #{NEAREST}u;
    let kth = nearest_depths[base + #{NEAREST}u - 1u];
    if (kth != 0u) {
        return bitcast<f32>(~kth);
    }
    let opaque = textureLoad(opaque_depth, vec2<i32>(p), 0);
    return bitcast<f32>(max(bitcast<u32>(opaque), 1u) - 1u);
}
