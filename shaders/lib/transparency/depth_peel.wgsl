// plait::transparency::depth_peel — one layer of depth peeling
// (Sintorn & Assarsson 2009 §2.2, Fig. 2 "ground truth"): keep only fragments
// strictly behind the previous layer's depth and in front of the opaque depth;
// the pass's depth test (Less) then leaves the nearest of them — the layer.
#define_import_path plait::transparency::depth_peel

@group(1) @binding(24) var opaque_depth: texture_depth_2d;
@group(1) @binding(25) var peel_prev: texture_depth_2d;

struct FragmentOut {
    @location(0) color: vec4<f32>,
}

fn hair_fragment(clip: vec4<f32>, rgb: vec3<f32>, alpha: f32) -> FragmentOut {
    let p = vec2<i32>(clip.xy);
    if (clip.z >= textureLoad(opaque_depth, p, 0) || clip.z <= textureLoad(peel_prev, p, 0)) {
        discard;
    }
    return FragmentOut(vec4<f32>(rgb * alpha, alpha));
}
