// plait::shadow — opaque objects' shadow map lookups (Sintorn & Assarsson 2009 §3.5).
#define_import_path plait::shadow

#import plait::frame::{light_uv_depth, shadow_sampler}

// Fraction of light reaching `world` past opaque geometry: the 3×3 PCF of
// nine bilinear comparison taps one texel apart; outside the map counts as lit.
//
// Nine bilinear taps at offsets -1, 0, 1 around the point weigh the 4×4
// texels b-1 … b+2 (b = floor(uv · size - 0.5), f the fraction past it) by
// (1-f, 1, 1, f) along each axis, / 9. Four `textureGatherCompare`s read
// those 16 comparisons once where nine filtered taps read 36, and the weights
// are applied here: the same filter (every gallery image bit-identical at 8
// bits), 8–10% off the `forward` frame on lavapipe (README, Performance).
fn opaque_shadow(shadow_map: texture_depth_2d, world: vec3<f32>, bias: f32) -> f32 {
    let p = light_uv_depth(world);
    if (any(p.xy < vec2<f32>(0.0)) || any(p.xy > vec2<f32>(1.0)) || p.z > 1.0) {
        return 1.0;
    }
    return pcf_3x3(shadow_map, p.xy, p.z - bias);
}

// The 3×3 PCF at `uv` of comparisons against `depth` (crates/plait-passes/
// tests/shadow_filter.rs checks it against the nine filtered taps).
fn pcf_3x3(shadow_map: texture_depth_2d, uv: vec2<f32>, depth: f32) -> f32 {
    let size = vec2<f32>(textureDimensions(shadow_map));
    let t = uv * size - 0.5;
    let b = floor(t);
    let f = t - b;
    let rest = vec2<f32>(1.0) - f;
    // A gather at the texel corner c reads texels c-1 and c on each axis.
    let g00 = textureGatherCompare(shadow_map, shadow_sampler, b / size, depth);
    let g10 = textureGatherCompare(shadow_map, shadow_sampler, (b + vec2<f32>(2.0, 0.0)) / size, depth);
    let g01 = textureGatherCompare(shadow_map, shadow_sampler, (b + vec2<f32>(0.0, 2.0)) / size, depth);
    let g11 = textureGatherCompare(shadow_map, shadow_sampler, (b + vec2<f32>(2.0)) / size, depth);
    let lit = weighted_gather(g00, vec2<f32>(rest.x, 1.0), vec2<f32>(rest.y, 1.0))
        + weighted_gather(g10, vec2<f32>(1.0, f.x), vec2<f32>(rest.y, 1.0))
        + weighted_gather(g01, vec2<f32>(rest.x, 1.0), vec2<f32>(1.0, f.y))
        + weighted_gather(g11, vec2<f32>(1.0, f.x), vec2<f32>(1.0, f.y));
    return lit / 9.0;
}

// A gather's four comparisons weighed by their texels' column weights (wx:
// lower, upper) and row weights (wy: lower, upper). WGSL's gather order:
// x = (u0, v1), y = (u1, v1), z = (u1, v0), w = (u0, v0).
fn weighted_gather(g: vec4<f32>, wx: vec2<f32>, wy: vec2<f32>) -> f32 {
    return dot(g, vec4<f32>(wx.x * wy.y, wx.y * wy.y, wx.y * wy.x, wx.x * wy.x));
}
