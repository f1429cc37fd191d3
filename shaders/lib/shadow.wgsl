// plait::shadow — opaque objects' shadow map lookups (Sintorn & Assarsson 2009 §3.5).
#define_import_path plait::shadow

#import plait::frame::{light_uv_depth, shadow_sampler}

// Fraction of light reaching `world` past opaque geometry: 3×3 PCF with the
// hardware comparison sampler; outside the map counts as lit.
fn opaque_shadow(shadow_map: texture_depth_2d, world: vec3<f32>, bias: f32) -> f32 {
    let p = light_uv_depth(world);
    if (any(p.xy < vec2<f32>(0.0)) || any(p.xy > vec2<f32>(1.0)) || p.z > 1.0) {
        return 1.0;
    }
    let texel = 1.0 / vec2<f32>(textureDimensions(shadow_map));
    var lit = 0.0;
    for (var y = -1; y <= 1; y++) {
        for (var x = -1; x <= 1; x++) {
            lit += textureSampleCompareLevel(shadow_map, shadow_sampler, p.xy + vec2<f32>(f32(x), f32(y)) * texel, p.z - bias);
        }
    }
    return lit / 9.0;
}
