// plait::transparency::coverage — strands written like opaque geometry, with
// depth test and write. With `alpha_to_coverage` the fragment's alpha picks how
// many of the pixel's MSAA samples it covers (Halén & Wester 2007 §3.1.2,
// §5.6) and the resolve averages them; without it (OPAQUE_HAIR) alpha is 1:
// no transparency at all (Sintorn & Assarsson 2009 Fig. 2, right).
//
// `strand_coverage` is the other coverage: the fraction of a pixel a strand
// thinner than a pixel covers, used by every blending technique (hair_shade's
// vertex stage folds it into the strand's alpha, so alpha to coverage turns it
// into the sample mask too).
#define_import_path plait::transparency::coverage

#import plait::frame::frame

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

// The fraction of a pixel's width a strand of `thickness` (world units, its
// diameter) at `world` along `tangent` covers: its width across the view,
// projected to pixels, at most 1 — lines are drawn one pixel wide, so a thin
// strand must weigh by its true width (as AMD TressFX and vkhr do for their
// lines and strips). frame.conventions.z = 0 turns it off (coverage 1).
fn strand_coverage(world: vec3<f32>, tangent: vec3<f32>, thickness: f32) -> f32 {
    if (frame.conventions.z < 0.5) {
        return 1.0;
    }
    let to_eye = normalize(frame.camera_position.xyz - world);
    // Across the strand and the view ray: the direction its width is seen in.
    var side = cross(tangent, to_eye);
    if (dot(side, side) < 1e-12) {
        side = cross(select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), abs(to_eye.y) > 0.9), to_eye);
    }
    side = normalize(side);
    let a = frame.camera_view_proj * vec4<f32>(world, 1.0);
    let b = frame.camera_view_proj * vec4<f32>(world + side * thickness, 1.0);
    if (a.w <= 0.0 || b.w <= 0.0) {
        return 1.0;
    }
    let pixels = (b.xy / b.w - a.xy / a.w) * 0.5 * frame.screen_size.xy;
    return min(length(pixels), 1.0);
}
