// shortcut, the resolve (AMD TressFX 4.1 ShortCut): the hair is the average
// colour of the k nearest fragments, weighted by their alphas,
// Σα·rgb / Σα, at the coverage of all of them, 1 - Π(1-α) — premultiplied,
// for compose_hair_over.
#import plait::frame::fullscreen_position

@group(1) @binding(0) var sums: texture_2d<f32>;
@group(1) @binding(1) var coverage: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(pixel.xy);
    let s = textureLoad(sums, p, 0);
    let c = clamp(textureLoad(coverage, p, 0).r, 0.0, 1.0);
    if (s.a <= 1e-6) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(s.rgb / s.a * c, c);
}
