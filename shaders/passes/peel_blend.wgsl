// peel_blend: one peeled layer (premultiplied) goes UNDER the layers peeled
// before it — front-to-back "under" blending, dst += (1 - dst.a) · layer, set
// in the blend state (Sintorn & Assarsson 2009 §2.2; depth_peeling.rs).
#import plait::frame::fullscreen_position

@group(1) @binding(0) var layer: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    return textureLoad(layer, vec2<i32>(pixel.xy), 0);
}
