// plait::transparency::coverage — strands written like opaque geometry, with
// depth test and write. With `alpha_to_coverage` the fragment's alpha picks how
// many of the pixel's MSAA samples it covers (Halén & Wester 2007 §3.1.2,
// §5.6) and the resolve averages them; without it (OPAQUE_HAIR) alpha is 1:
// no transparency at all (Sintorn & Assarsson 2009 Fig. 2, right).
#define_import_path plait::transparency::coverage

struct FragmentOut {
    @location(0) color: vec4<f32>,
}

fn hair_fragment(clip: vec4<f32>, rgb: vec3<f32>, alpha: f32) -> FragmentOut {
#ifdef OPAQUE_HAIR
    return FragmentOut(vec4<f32>(rgb, 1.0));
#else
    // Not premultiplied: coverage does the weighting, the resolve averages.
    return FragmentOut(vec4<f32>(rgb, alpha));
#endif
}
