// weighted_average_resolve (Bavoil & Myers 2008; Sintorn & Assarsson 2009 §2.2):
// average colour C = Σα·rgb / Σα, average alpha ᾱ = Σα / n over the depth
// complexity n, and the hair as n fragments of (C, ᾱ) blended:
// premultiplied (C · (1 - (1-ᾱ)ⁿ), 1 - (1-ᾱ)ⁿ).
#import plait::frame::fullscreen_position

@group(1) @binding(0) var sums: texture_2d<f32>;
@group(1) @binding(1) var count: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(pixel.xy);
    let s = textureLoad(sums, p, 0);
    let n = textureLoad(count, p, 0).r;
    if (n < 0.5 || s.a <= 1e-6) {
        return vec4<f32>(0.0);
    }
    let colour = s.rgb / s.a;
    let mean_alpha = clamp(s.a / n, 0.0, 1.0);
    let coverage = 1.0 - pow(1.0 - mean_alpha, n);
    return vec4<f32>(colour * coverage, coverage);
}
