// compose: the occupancy-order blended hair image over the scene
// (Sintorn & Assarsson 2009 §3.4). The scene (opaque objects over the
// background) is attenuated by (1-α)^n, n the hair fragments of the pixel
// (the sum of the camera-view slab counts), α the mean fragment alpha of the
// pixel (MEAN_ALPHA_PIXEL: Σα / n of its visible fragments) or of the frame;
// the hair image, whose alpha
// should sum to Λ = 1-(1-α)^n, is rescaled to it: rgb · Λ / a. (The paper
// writes hair.a / Λ; the factor that makes the intensity right is Λ / a.)
#import plait::frame::{frame, fullscreen_position, background_at}

@group(1) @binding(0) var hair: texture_2d<f32>;
@group(1) @binding(1) var scene: texture_2d<f32>;
@group(1) @binding(2) var<storage, read> counts: array<u32>;
@group(1) @binding(3) var alpha_sums: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(index);
}

@fragment
fn fs_main(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let size = textureDimensions(hair);
    let p = min(vec2<u32>(pixel.xy), size - 1u);
    let slabs = arrayLength(&counts) / (size.x * size.y);
    var n = 0u;
    for (var i = 0u; i < slabs; i++) {
        n += counts[(p.y * size.x + p.x) * slabs + i];
    }
    // ᾱ: the mean fragment alpha, the method's constant α — the same the
    // hair pass weighed the fragments with.
#ifdef MEAN_ALPHA_PIXEL
    let sums = textureLoad(alpha_sums, vec2<i32>(p), 0);
    let alpha = clamp(sums.x / max(sums.y, 1.0), 0.0, 0.999);
#else
    let alpha = clamp(frame.hair_stats.x, 0.0, 0.999);
#endif
    let transmit = pow(1.0 - alpha, f32(n));
    let lambda = 1.0 - transmit;
    let h = textureLoad(hair, vec2<i32>(p), 0);
    var hair_rgb = vec3<f32>(0.0);
    if (h.a > 1e-6) {
        hair_rgb = h.rgb * (lambda / h.a);
    }
    let s = textureLoad(scene, vec2<i32>(p), 0);
    let behind = s.rgb + (1.0 - s.a) * background_at(pixel.xy);
    // Alpha: the part of the pixel anything covers (hair over the head and
    // ground; 0 where only the background shows), docs/formats.md.
    return vec4<f32>(behind * transmit + hair_rgb, 1.0 - transmit * (1.0 - s.a));
}
