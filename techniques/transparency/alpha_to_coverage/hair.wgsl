// alpha_to_coverage: the strands drawn like opaque geometry (depth test and
// write, no sorting) into a multisampled target; the fragment's alpha picks
// how many of the pixel's samples it covers (the pass's `alpha_to_coverage`)
// and the resolve averages them (Halén & Wester 2007 §3.1.2, §5.6). Not
// premultiplied: the coverage does the weighting.
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

@fragment
fn fs_main(in: HairVaryings) -> @location(0) vec4<f32> {
    let f = shade_hair(in);
    return vec4<f32>(f.rgb, f.alpha);
}
