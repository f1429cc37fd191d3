// depth_range: nearest and farthest hair depth per texel (Sintorn & Assarsson 2009
// §3.1, Fig. 7), as linear depth of the pass's view in an rg32float target.
// Drawn twice by the pass (near: depth test Less, writing red; far: depth
// test Greater, writing green), the paper's faster choice over one min/max
// blended pass — and one that needs no FLOAT32_BLENDABLE.
#import plait::frame::{view_proj, view_linear_depth, shadow_sampler}
#import plait::hair_map::{MapVertex, MapFragment, map_vertex}

// Depth of opaque geometry from the same view (the opaque shadow map for the
// light, the camera depth for the camera): hair behind it is not recorded (§3.5).
@group(1) @binding(0) var opaque_depth: texture_depth_2d;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v);
}

// True where the fragment at `world` lies behind opaque geometry of this view.
fn behind_opaque(world: vec3<f32>) -> bool {
    let clip = view_proj() * vec4<f32>(world, 1.0);
    let ndc = clip.xyz / clip.w;
    let uv = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    return textureSampleCompareLevel(opaque_depth, shadow_sampler, uv, ndc.z) < 0.5;
}

@fragment
fn fs_main(in: MapFragment) -> @location(0) vec4<f32> {
    if (behind_opaque(in.world)) {
        discard;
    }
    let d = view_linear_depth(in.world);
    // The pass's colour write mask keeps red (near) or green (far).
    return vec4<f32>(d, d, 0.0, 0.0);
}
