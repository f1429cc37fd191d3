// depth_peeling, one layer (Sintorn & Assarsson 2009 §2.2, Fig. 2 "ground
// truth"): keep only fragments strictly behind the previous layer's depth and
// in front of the opaque depth; the pass's depth test (Less) then leaves the
// nearest of them — the layer — shaded by the shared hair-fragment stage,
// premultiplied. The loop over layers (and the occlusion query that ends it)
// is the technique's Rust: crates/plait-passes/src/depth_peeling.rs.
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}

@group(1) @binding(60) var opaque_depth: texture_depth_2d;
@group(1) @binding(61) var peel_prev: texture_depth_2d;

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

@fragment
fn fs_main(in: HairVaryings) -> @location(0) vec4<f32> {
    // Shaded first, in uniform control flow (providers may sample textures
    // with derivatives).
    let f = shade_hair(in);
    let clip = in.clip;
    let p = vec2<i32>(clip.xy);
    if (clip.z >= textureLoad(opaque_depth, p, 0) || clip.z <= textureLoad(peel_prev, p, 0)) {
        discard;
    }
    return vec4<f32>(f.rgb * f.alpha, f.alpha);
}
