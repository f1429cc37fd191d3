// plait::self_shadow::tressfx — the "depth approximation" self-shadow of AMD
// TressFX 4.1 (GPUOpen-Effects/TressFX, src/Shaders/TressFXLighting.hlsl:
// `ComputeLightShadow` and `ComputeShadowAttenuation`). One depth map of the
// nearest hair from the light; a point Δz behind the nearest hair of a texel
// has (1 - α)^(Δz / s) of the light, s the fiber spacing — and at least one
// fiber's worth once it is behind any hair; the 5×5 texels around the point
// are averaged (percentage-closer filtering).
//
// Written against plait's contract, not copied: (1 - α)^n = exp(-w · n) with
// w = -ln(1 - α) — the `shadow_weight` every provider and the exact reference
// use (opacity of a strand covering the whole ray) — and n = Δz / s the
// fibers a light ray crosses, s = 1 / (ρ · width) the spacing between them
// along the light: ρ = `density` fibers per world unit of depth per world
// unit of width across the light, each of the groom's mean width
// (plait::light_share; no light texel in it, issue 47). The one-fiber floor
// is the fiber the depth map saw, blocking its share of the texel (its width
// over the texel, at most 1). With strand coverage off (whole texels) s =
// 1 / (ρ · texel) and the floor a whole fiber. So TressFX is the modified
// shadow map (Halén & Wester 2007 §3.3.2) with 5×5 PCF and the one-fiber
// floor. TressFX samples its depth atlas with a linear sampler at
// 25 offsets; plait reads the 25 texels themselves. "In front of" is the one
// convention (docs/design.md): `light_lookup`'s depth `in_front_below` = d - ε.
#define_import_path plait::self_shadow::tressfx

#import plait::frame::{frame, light_lookup, light_depth_to_linear, nearest_sampler}
#import plait::light_share::{mean_strand_share, strands_per_depth}

// Nearest hair depth from the light (a `shadow_map` pass drawing hair).
@group(1) @binding(8) var vis_depth: texture_depth_2d;

struct VisibilityParams {
    // w = -ln(1 - α): a fiber covering a whole texel lets exp(-w) = 1 - α
    // of the light through.
    shadow_weight: f32,
    // ρ: fibers crossed per world unit of depth per world unit of width
    // across the light (1 / s = ρ · width).
    density: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

// TressFX's kernelLevel 2: a (2·2+1)² = 25-texel box.
const KERNEL_LEVEL: i32 = 2;

fn hair_visibility(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_depth);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 1.0;
    }
    let w = visibility_params.shadow_weight;
    let density = visibility_params.density;
    let to_world = frame.near_far.w - frame.near_far.z;
    var lit = 0.0;
    for (var j = -KERNEL_LEVEL; j <= KERNEL_LEVEL; j++) {
        for (var i = -KERNEL_LEVEL; i <= KERNEL_LEVEL; i++) {
            // Sampled at texel centres, not loaded: GL cannot textureLoad depth textures.
            let uv = lookup.uv + vec2<f32>(f32(i), f32(j)) / vec2<f32>(size);
            let stored = textureSampleLevel(vis_depth, nearest_sampler, uv, 0);
            let behind = (lookup.in_front_below - light_depth_to_linear(stored)) * to_world;
            if (behind <= 0.0) {
                lit += 1.0;
            } else {
                // Δz / s fibers, at least the one the map saw (its share).
                let fibers = behind * strands_per_depth(uv, stored, size, density);
                lit += exp(-w * max(fibers, mean_strand_share(uv, stored, size)));
            }
        }
    }
    let taps = f32((2 * KERNEL_LEVEL + 1) * (2 * KERNEL_LEVEL + 1));
    return lit / taps;
}
