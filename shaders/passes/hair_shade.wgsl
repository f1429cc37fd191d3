// hair_shade: hair shaded by the shared hair-fragment stage
// (shaders/lib/hair_fragment.wgsl: one provider per choice point) and
// blended premultiplied "over" the colour target in draw order, not depth
// order — the error every transparency technique removes its own way.
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

@fragment
fn fs_main(in: HairVaryings) -> @location(0) vec4<f32> {
    let f = shade_hair(in);
    // Premultiplied: the blend state composites "over" what is already there.
    return vec4<f32>(f.rgb * f.alpha, f.alpha);
}
