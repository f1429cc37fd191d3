// plait::self_shadow::modified_shadow_map — one depth map of the nearest hair from
// the light; transmittance exp(-k Δz) with Δz the distance behind that hair.
// Halén & Wester 2007 §3.3.2 ("modified shadow map").
// Cheap (one depth texture), but it cannot tell sparse hair from dense hair.
#define_import_path plait::self_shadow::modified_shadow_map

#import plait::frame::{frame, light_lookup, light_depth_to_linear, nearest_sampler}

// Nearest hair depth from the light (a `shadow_map` pass drawing hair).
@group(1) @binding(8) var vis_depth: texture_depth_2d;

struct VisibilityParams {
    // Extinction per world unit of hair volume behind the first strand.
    density: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

fn hair_visibility(world: vec3<f32>) -> f32 {
    let lookup = light_lookup(world, textureDimensions(vis_depth));
    if (!lookup.inside) {
        return 1.0;
    }
    // Sampled at the texel's centre, not loaded: GL cannot textureLoad depth textures.
    let first = light_depth_to_linear(textureSampleLevel(vis_depth, nearest_sampler, lookup.uv, 0));
    // Linear light depth: the difference scales to world units.
    let behind = max(0.0, lookup.in_front_below - first) * (frame.near_far.w - frame.near_far.z);
    return exp(-visibility_params.density * behind);
}
