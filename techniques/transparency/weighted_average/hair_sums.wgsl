// weighted_average, the hair pass (Bavoil & Myers 2008, as Sintorn &
// Assarsson 2009 §2.2 describes it): one unsorted additive draw sums α·rgb
// and α into `color` and the depth complexity n into `count`; the
// weighted_average_resolve pass averages them. Additive blending (the pass's
// `blend`), so the draw order does not matter.
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}

struct Sums {
    @location(0) color: vec4<f32>,
    @location(1) count: vec4<f32>,
}

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

@fragment
fn fs_main(in: HairVaryings) -> Sums {
    let f = shade_hair(in);
    return Sums(vec4<f32>(f.rgb * f.alpha, f.alpha), vec4<f32>(1.0, 0.0, 0.0, 0.0));
}
