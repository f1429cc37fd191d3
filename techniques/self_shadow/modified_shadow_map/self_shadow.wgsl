// plait::self_shadow::modified_shadow_map — one depth map of the nearest hair from
// the light; transmittance exp(-k Δz) with Δz the distance behind that hair.
// Halén & Wester 2007 §3.3.2 ("modified shadow map").
// Cheap (one depth texture), but it cannot tell sparse hair from dense hair.
//
// k is not a tuned constant: k = w · ρ · width, the same exp(-w · n) as the
// maps that count (n the shares of the strands in front): ρ strands crossed
// per world unit of depth per world unit of width across the light
// (`density`), each of the groom's mean width, so a light ray crosses
// ρ · width of them per world unit of depth (plait::light_share), and w the
// opacity of a strand covering the whole ray (`shadow_weight`). No light
// texel in it: a finer or coarser map shadows alike (issue 47); thinner
// strands let proportionally more light through. With strand coverage off
// (whole texels) k = w · ρ · texel: each strand crossing the texel's column
// counts whole.
#define_import_path plait::self_shadow::modified_shadow_map

#import plait::frame::{frame, light_lookup, light_depth_to_linear, nearest_sampler}
#import plait::light_share::strands_per_depth

// Nearest hair depth from the light (a `shadow_map` pass drawing hair).
@group(1) @binding(8) var vis_depth: texture_depth_2d;

struct VisibilityParams {
    // w: -ln of what one strand covering a whole texel lets through.
    shadow_weight: f32,
    // ρ: strands crossed per world unit of depth per world unit of width
    // across the light, behind the first.
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
    let crossed = strands_per_depth(lookup.uv, stored, size, visibility_params.density);
    let k = visibility_params.shadow_weight * crossed;
    return exp(-k * behind);
}
