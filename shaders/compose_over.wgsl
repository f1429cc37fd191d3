// compose_over: a data-only fullscreen pass (no Rust). The premultiplied scene
// colour goes over the background colour, in linear radiance (a float target:
// nothing clips; the display transform, techniques/tone_mapping/, follows).
// Bindings are matched by name to the pass's `reads`; the output is the pass's
// one colour target in `writes`.
#import plait::frame::{frame, fullscreen_position, background_at}

@group(1) @binding(0) var scene: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let c = textureLoad(scene, vec2<i32>(pixel.xy), 0);
    // Alpha: the part of the pixel the scene (hair drawn into it included)
    // covers, 0 where only the background shows (docs/formats.md).
    return vec4<f32>(c.rgb + (1.0 - c.a) * background_at(pixel.xy), c.a);
}
