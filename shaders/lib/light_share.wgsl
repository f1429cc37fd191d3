// plait::light_share — the part of a light texel one strand of the groom's
// mean width blocks, for the self-shadow maps that keep no strand: the
// depth-only maps (modified shadow map, TressFX) hold the nearest hair's
// depth, not who drew it, so they take every strand crossed to be of the
// groom's mean width (frame.hair_width.x). A light texel is blocked by a
// strand's share of it (issue 47), as the counting maps weigh each fragment
// (plait::hair_map::map_texel): its width over the texel, at most 1; 1 with
// strand coverage off (frame.conventions.z = 0, whole texels).
#define_import_path plait::light_share

#import plait::frame::frame

// The world point of the light map at texture coordinate `uv` (0..1, y
// down) and stored depth `stored` (what a light-view depth target holds).
fn light_unproject(uv: vec2<f32>, stored: f32) -> vec3<f32> {
    let ndc = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, stored, 1.0);
    let h = frame.light_inv_view_proj * ndc;
    return h.xyz / h.w;
}

// The share of the texel at `uv` of a `size`-texel light map that a strand of
// the mean width blocks where the map stored depth `stored` — there, for a
// spot light's texels grow with distance. The texel is measured in world
// units along both map axes (the fitted light frustum need not be square):
// a strand's width spans the texel's height where it runs along the map's x
// and its width where it runs along y; the share is the mean of the two.
fn mean_strand_share(uv: vec2<f32>, stored: f32, size: vec2<u32>) -> f32 {
    if (frame.conventions.z < 0.5) {
        return 1.0;
    }
    let step = 1.0 / vec2<f32>(size);
    let p = light_unproject(uv, stored);
    let across_x = length(light_unproject(uv + vec2<f32>(step.x, 0.0), stored) - p);
    let across_y = length(light_unproject(uv + vec2<f32>(0.0, step.y), stored) - p);
    let w = frame.hair_width.x;
    return 0.5 * (min(w / max(across_x, 1e-12), 1.0) + min(w / max(across_y, 1e-12), 1.0));
}
