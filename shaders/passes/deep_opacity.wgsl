// deep_opacity: the opacity map of deep opacity maps (Yuksel & Keyser 2008
// §3, step two). z0 = the texel's nearest hair (red of the depth_range map,
// step one); layer k spans [z0 + d_{k-1}, z0 + d_k) with linearly increasing
// sizes d_k - d_{k-1} = k · layer_size (world units); fragments beyond the last
// layer go to the last. Each fragment counts itself in its layer (atomicAdd:
// exact counts, the paper's additive blending). K = the `layers` buffer's u32
// words per texel.
#import plait::frame::frame
#import plait::hair_map::{MapVertex, MapFragment, map_vertex, map_texel, map_weight, words_per_texel}

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> layers: array<atomic<u32>>;

struct DomParams {
    // Thickness of the first layer, world units.
    layer_size: f32,
}
@group(1) @binding(2) var<uniform> dom_params: DomParams;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v, textureDimensions(range));
}

@fragment
fn fs_main(in: MapFragment) {
    let m = map_texel(in, range);
    let count = words_per_texel(arrayLength(&layers), m);
    // Distance behind z0 = the texel's nearest hair, in world units (linear
    // depth × the light's depth span).
    let behind = max(m.depth - m.near, 0.0) * (frame.near_far.w - frame.near_far.z);
    // Layer k (0-based) ends at d_{k+1} = layer_size · (k+1)(k+2)/2.
    var k = 0u;
    loop {
        let end = dom_params.layer_size * f32((k + 1u) * (k + 2u)) * 0.5;
        if (behind < end || k + 1u >= count) {
            break;
        }
        k++;
    }
    // Weighted by the strand's share of the texel (plait::hair_map::map_weight).
    atomicAdd(&layers[m.index * count + k], map_weight(m));
}
