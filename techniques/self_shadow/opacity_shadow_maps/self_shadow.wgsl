// plait::self_shadow::opacity_shadow_maps — opacity shadow maps (Kim & Neumann
// 2001; Halén & Wester 2007 §3.3.2 formulas 3.1-3.2, §5.7 formula 5.1).
// Per light texel: N fragment counts, one per uniform slice of the texel's
// hair range [near, far] (per-texel range, from the light depth-range map).
// σ(z_i) at slice boundary i is the sum of the slices before it; σ(z) is
// interpolated linearly between the two closest boundaries (formula 5.1);
// transmittance T = exp(-w · σ) (formula 3.1 with k = w = shadow_weight,
// the opacity of one fragment, as in occupancy).
#define_import_path plait::self_shadow::opacity_shadow_maps

#import plait::frame::{light_behind, light_lookup}
#import plait::map_share::MAP_SHARE_SCALE

@group(1) @binding(9) var vis_range: texture_2d<f32>;
@group(1) @binding(10) var<storage, read> vis_slices: array<u32>;

struct VisibilityParams {
    // Opacity added by one hair fragment in front (w of Sintorn & Assarsson 2009 §3.3).
    shadow_weight: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

// σ: fragments in front of linear light depth `depth` at `texel`.
fn opacity_thickness(texel: vec2<u32>, size: vec2<u32>, depth: f32) -> f32 {
    let range = textureLoad(vis_range, vec2<i32>(texel), 0);
    if (range.y < range.x) {
        return 0.0; // no hair in this texel
    }
    let n = arrayLength(&vis_slices) / (size.x * size.y);
    let base = (texel.y * size.x + texel.x) * n;
    let rel = (depth - range.x) / max(range.y - range.x, 1e-9);
    if (rel <= 0.0) {
        return 0.0;
    }
    let s = min(rel, 1.0) * f32(n);
    let slice = min(u32(floor(s)), n - 1u);
    var before = 0.0;
    for (var i = 0u; i < slice; i++) {
        before += f32(vis_slices[base + i]);
    }
    return before + f32(vis_slices[base + slice]) * clamp(s - f32(slice), 0.0, 1.0);
}

fn hair_visibility(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 1.0;
    }
    // Slices count strands' shares of the texel (plait::map_share).
    let sigma = opacity_thickness(lookup.texel, size, lookup.in_front_below) / MAP_SHARE_SCALE;
    return exp(-visibility_params.shadow_weight * sigma);
}

// The strands in front of and behind the point (the self_shadow point's
// optional function): the slices' fragment counts in front of the point, and beyond
// the hair less up to just past the point's own strand
// (`plait::frame::light_behind`), in strands, in the point's own texel.
fn hair_strands_along_light(world: vec3<f32>) -> vec2<f32> {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return vec2<f32>(0.0);
    }
    let behind = light_behind(world);
    let n = opacity_thickness(lookup.texel, size, lookup.in_front_below);
    let through = opacity_thickness(lookup.texel, size, behind.x);
    let beyond = opacity_thickness(lookup.texel, size, behind.y);
    return vec2<f32>(n, max(beyond - through, 0.0)) / MAP_SHARE_SCALE;
}
