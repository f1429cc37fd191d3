// opaque: no transparency — the strands drawn like opaque geometry with depth
// test and write, alpha 1 (Sintorn & Assarsson 2009 Fig. 2, right: "using no
// transparency"). The shaded colour of the shared hair-fragment stage, its
// alpha ignored.
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

@fragment
fn fs_main(in: HairVaryings) -> @location(0) vec4<f32> {
    return vec4<f32>(shade_hair(in).rgb, 1.0);
}
