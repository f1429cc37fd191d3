// shortcut, the second hair draw (AMD TressFX 4.1 ShortCut): the depth test
// against the k-th nearest depth (kth.wgsl) lets only the k nearest
// fragments reach this shader — they alone are shaded, by the shared
// hair-fragment stage, and summed unsorted: α·rgb and α (the pass's additive
// blend). Fragments at exactly the k-th depth all pass.
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

@fragment
fn fs_main(in: HairVaryings) -> @location(0) vec4<f32> {
    let f = shade_hair(in);
    return vec4<f32>(f.rgb * f.alpha, f.alpha);
}
