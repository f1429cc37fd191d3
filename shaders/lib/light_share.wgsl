// plait::light_share — how much hair the depth-only self-shadow maps
// (modified shadow map, TressFX) assume behind the nearest hair. They hold
// the nearest hair's depth, not who drew it, so they take the hair behind to
// be a medium: ρ strands crossed per world unit of depth per world unit of
// width across the light (`density`, strand length per unit volume as the
// light sees it), every strand of the groom's mean width (frame.hair_width.x).
// A light ray then crosses ρ · width strands per world unit of depth,
// whatever the light map's texel (issue 47): a finer map does not darken the
// shadow, as the counting maps' shares (plait::hair_map::map_texel) fall
// with the texel. With strand coverage off (frame.conventions.z = 0, whole
// texels) every strand crossing a texel's column counts whole, as the
// counting maps then count it: ρ · texel per world unit of depth.
#define_import_path plait::light_share

#import plait::frame::frame

// The world point of the light map at texture coordinate `uv` (0..1, y
// down) and stored depth `stored` (what a light-view depth target holds).
fn light_unproject(uv: vec2<f32>, stored: f32) -> vec3<f32> {
    let ndc = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, stored, 1.0);
    let h = frame.light_inv_view_proj * ndc;
    return h.xyz / h.w;
}

// The texel at `uv` of a `size`-texel light map where the map stored depth
// `stored` (there: a spot light's texels grow with distance), in world units
// along the map's x and y (the fitted light frustum need not be square).
fn light_texel(uv: vec2<f32>, stored: f32, size: vec2<u32>) -> vec2<f32> {
    let step = 1.0 / vec2<f32>(size);
    let p = light_unproject(uv, stored);
    let across_x = length(light_unproject(uv + vec2<f32>(step.x, 0.0), stored) - p);
    let across_y = length(light_unproject(uv + vec2<f32>(0.0, step.y), stored) - p);
    return max(vec2<f32>(across_x, across_y), vec2<f32>(1e-12));
}

// The share of its texel one strand of the mean width blocks: its width over
// the texel's side, at most 1 — across the texel's height where the strand
// runs along the map's x, across its width where it runs along y; the mean
// of the two. 1 with strand coverage off. TressFX's one-fibre floor: the
// depth map knows that much hair is in the texel.
fn mean_strand_share(uv: vec2<f32>, stored: f32, size: vec2<u32>) -> f32 {
    if (frame.conventions.z < 0.5) {
        return 1.0;
    }
    let t = light_texel(uv, stored, size);
    let w = frame.hair_width.x;
    return 0.5 * (min(w / t.x, 1.0) + min(w / t.y, 1.0));
}

// Strands a light ray crosses per world unit of depth for `density` ρ:
// ρ · the groom's mean width — no texel in it. With strand coverage off,
// ρ · the texel's side (the harmonic mean of the two, so that it is
// ρ · width / mean_strand_share for strands thinner than the texel).
fn strands_per_depth(uv: vec2<f32>, stored: f32, size: vec2<u32>, density: f32) -> f32 {
    if (frame.conventions.z >= 0.5) {
        return density * frame.hair_width.x;
    }
    let t = light_texel(uv, stored, size);
    return density * 2.0 / (1.0 / t.x + 1.0 / t.y);
}
