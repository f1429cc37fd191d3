// depth_range: nearest and farthest hair depth per texel (Sintorn & Assarsson 2009
// §3.1, Fig. 7), as linear depth of the pass's view in an rg32float target.
// Drawn twice by the pass (near: depth test Less, writing red; far: depth
// test Greater, writing green), the paper's faster choice over one min/max
// blended pass — and one that needs no FLOAT32_BLENDABLE.
#import plait::hair_map::{MapVertex, MapFragment, map_vertex, map_kept}

// Depth of opaque geometry from the same view (the opaque shadow map for the
// light, the camera depth for the camera): hair behind it is not recorded (§3.5).
@group(1) @binding(0) var opaque_depth: texture_depth_2d;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v, textureDimensions(opaque_depth));
}

// True where the fragment lies behind opaque geometry of this view: the
// depth test (`less`) the occupancy and slab passes make with the same
// texture as their depth attachment, at the same texel (the pass type checks
// the two maps have one size), so all three drop the same fragments.
fn behind_opaque(in: MapFragment) -> bool {
    return !(in.clip.z < textureLoad(opaque_depth, vec2<i32>(in.clip.xy), 0));
}

@fragment
fn fs_main(in: MapFragment) -> @location(0) vec4<f32> {
    if (behind_opaque(in) || !map_kept(in)) {
        discard;
    }
    // The pass's colour write mask keeps red (near) or green (far).
    return vec4<f32>(in.depth, in.depth, 0.0, 0.0);
}
