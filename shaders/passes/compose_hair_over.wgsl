// compose_hair_over: the hair image (premultiplied, blended front to back by
// depth peeling, sorted fragment lists or weighted averages) over the scene
// over the background: f = hair + (1 - hair.a) · behind
// (Sintorn & Assarsson 2009 §2.2).
#import plait::frame::{frame, fullscreen_position, background_at}

@group(1) @binding(0) var hair: texture_2d<f32>;
@group(1) @binding(1) var scene: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(pixel.xy);
    let h = textureLoad(hair, p, 0);
    let s = textureLoad(scene, p, 0);
    let behind = s.rgb + (1.0 - s.a) * background_at(pixel.xy);
    // Alpha: the part of the pixel anything covers (hair over the head and
    // ground; 0 where only the background shows), docs/formats.md.
    return vec4<f32>(h.rgb + (1.0 - h.a) * behind, 1.0 - (1.0 - h.a) * (1.0 - s.a));
}
