// plait::self_shadow::modified_shadow_map — one depth map of the nearest hair from
// the light; transmittance exp(-k Δz) with Δz the distance behind that hair.
// Halén & Wester 2007 §3.3.2 ("modified shadow map").
// Cheap (one depth texture), but it cannot tell sparse hair from dense hair.
//
// k is not a tuned constant: k = w · ρ · share, the same exp(-w · n) as the
// maps that count (n the shares of the strands in front): ρ strands crossed
// per world unit along the light in one texel (`density`), each blocking its
// share of the texel (issue 47) — the groom's mean width over the texel's
// size where the hair is (plait::light_share), the frustum being fitted per
// frame — and w the opacity of a strand covering a whole texel
// (`shadow_weight`). Thinner strands or a coarser map let proportionally more
// light through.
#define_import_path plait::self_shadow::modified_shadow_map

#import plait::frame::{frame, light_lookup, light_depth_to_linear, nearest_sampler}
#import plait::light_share::mean_strand_share

// Nearest hair depth from the light (a `shadow_map` pass drawing hair).
@group(1) @binding(8) var vis_depth: texture_depth_2d;

struct VisibilityParams {
    // w: -ln of what one strand covering a whole texel lets through.
    shadow_weight: f32,
    // ρ: strands crossed per world unit along the light, behind the first.
    density: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

fn hair_visibility(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_depth);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 1.0;
    }
    // Sampled at the texel's centre, not loaded: GL cannot textureLoad depth textures.
    let stored = textureSampleLevel(vis_depth, nearest_sampler, lookup.uv, 0);
    let first = light_depth_to_linear(stored);
    // Linear light depth: the difference scales to world units.
    let behind = max(0.0, lookup.in_front_below - first) * (frame.near_far.w - frame.near_far.z);
    if (behind <= 0.0) {
        return 1.0;
    }
    let share = mean_strand_share(lookup.uv, stored, size);
    let k = visibility_params.shadow_weight * visibility_params.density * share;
    return exp(-k * behind);
}
