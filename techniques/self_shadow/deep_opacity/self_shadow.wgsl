// plait::self_shadow::deep_opacity — deep opacity maps (Yuksel & Keyser 2008,
// Yuksel & Keyser 2008 §3, step three). Per light texel: z0 (the near
// depth of the light depth-range map) and K fragment counts, one per layer
// [z0 + d_{k-1}, z0 + d_k), d_k = layer_size · k(k+1)/2 (linearly increasing
// sizes; the last layer also holds everything beyond it). The opacity at a
// layer's end is the prefix sum of the counts (a fragment counts in its
// layer and every layer behind it); between the ends it is interpolated
// linearly. Visibility = exp(-w · count), w = shadow_weight as in occupancy.
#define_import_path plait::self_shadow::deep_opacity

#import plait::frame::{frame, light_behind, light_lookup}
#import plait::map_share::MAP_SHARE_SCALE

@group(1) @binding(9) var vis_range: texture_2d<f32>;
@group(1) @binding(10) var<storage, read> vis_layers: array<u32>;

struct VisibilityParams {
    // Opacity added by one hair fragment in front (w of Sintorn & Assarsson 2009 §3.3).
    shadow_weight: f32,
    // Thickness of the first layer, world units (same value as the deep_opacity pass's).
    layer_size: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

// Fragments in front of linear light depth `depth` at `texel`.
fn deep_opacity_count(texel: vec2<u32>, size: vec2<u32>, depth: f32) -> f32 {
    let range = textureLoad(vis_range, vec2<i32>(texel), 0);
    if (range.y < range.x) {
        return 0.0; // no hair in this texel
    }
    let count = arrayLength(&vis_layers) / (size.x * size.y);
    let base = (texel.y * size.x + texel.x) * count;
    let behind = (depth - range.x) * (frame.near_far.w - frame.near_far.z);
    if (behind <= 0.0) {
        return 0.0;
    }
    var before = 0.0;
    var start = 0.0;
    for (var k = 0u; k < count; k++) {
        let end = visibility_params.layer_size * f32((k + 1u) * (k + 2u)) * 0.5;
        // Layers count strands' shares of the texel (plait::map_share).
        let n = f32(vis_layers[base + k]) / MAP_SHARE_SCALE;
        if (behind < end) {
            return before + n * (behind - start) / (end - start);
        }
        before += n;
        start = end;
    }
    return before;
}

fn hair_visibility(world: vec3<f32>) -> f32 {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return 1.0;
    }
    return exp(-visibility_params.shadow_weight * deep_opacity_count(lookup.texel, size, lookup.in_front_below));
}

// The strands in front of and behind the point (the self_shadow point's
// optional function): the layers' fragment counts in front of the point, and beyond
// the hair less up to just past the point's own strand
// (`plait::frame::light_behind`), in strands, in the point's own texel.
fn hair_strands_along_light(world: vec3<f32>) -> vec2<f32> {
    let size = textureDimensions(vis_range);
    let lookup = light_lookup(world, size);
    if (!lookup.inside) {
        return vec2<f32>(0.0);
    }
    let behind = light_behind(world);
    let n = deep_opacity_count(lookup.texel, size, lookup.in_front_below);
    let through = deep_opacity_count(lookup.texel, size, behind.x);
    let beyond = deep_opacity_count(lookup.texel, size, behind.y);
    return vec2<f32>(n, max(beyond - through, 0.0));
}
