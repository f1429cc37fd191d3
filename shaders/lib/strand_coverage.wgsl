// plait::strand_coverage — the part of a pixel a strand thinner than a pixel
// covers. Every blending technique weighs the strand's alpha by it (the shared
// hair-fragment stage, plait::hair_fragment, folds it into the fragment's
// alpha, so alpha to coverage turns it into the sample mask too), and so does
// the per-pixel mean alpha of occupancy-order blending (alpha_sum).
#define_import_path plait::strand_coverage

#import plait::frame::frame
// Tip fading is strand space's own (as the wisps' texture is geometry =
// wisps', plait::strand_lod): the shading_space contract answers where the
// colour is shaded with a constant w, so the fading cannot ride on it.
#ifdef SHADING_SPACE_STRAND
#import plait::shading_space::strand::strand_tip
#endif

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

// The strand's tip fading at a place along it (strand `strand`, hair vertex
// `segment`, `along` past it): the scale on its width, hence on its
// coverage — strand space's `tip_scale` there, 1 for every other
// shading_space. Every hair draw scales its vertices' coverage by it — the
// shaded draws, the mean alpha (alpha_sum) and the compute rasterizer — so a
// faded tip hides what it shows.
fn strand_tip_scale(strand: u32, segment: u32, along: f32) -> f32 {
#ifdef SHADING_SPACE_STRAND
    return strand_tip(strand, segment, along);
#else
    return 1.0;
#endif
}
