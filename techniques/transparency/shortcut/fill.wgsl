// shortcut, the second hair draw (AMD TressFX 4.1 ShortCut): the depth test
// against the k-th nearest depth (kth.wgsl) lets only the k nearest
// fragments reach this shader — they alone are shaded, by the shared
// hair-fragment stage, and summed unsorted: α·rgb and α (the pass's additive
// blend). Fragments at exactly the k-th depth all pass. Those fainter than
// `min_alpha` took no slot in the k-buffer (depths.wgsl), so they add
// nothing here either, wherever they lie.
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}

struct ShortcutParams {
    min_alpha: f32,
}
@group(1) @binding(60) var<uniform> shortcut_params: ShortcutParams;

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

@fragment
fn fs_main(in: HairVaryings) -> @location(0) vec4<f32> {
    let f = shade_hair(in);
    if (f.alpha < shortcut_params.min_alpha) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(f.rgb * f.alpha, f.alpha);
}
