// depth_lists: every hair fragment's linear light depth in its texel's list
// (the exact fragment count of Sintorn & Assarsson 2009 §3, Fig. 5). A slot
// comes from atomicAdd on the texel's counter; past the capacity (the `lists`
// buffer's words per texel) the fragment is dropped and counted in `overflow`:
// [0] dropped fragments, [1] overflowing texels, [2] the longest list asked for.
#import plait::hair_map::{MapVertex, MapFragment, map_vertex, map_texel, words_per_texel}
#import plait::map_share::pack_depth_share

@group(1) @binding(0) var range: texture_2d<f32>;
@group(1) @binding(1) var<storage, read_write> lists: array<u32>;
@group(1) @binding(2) var<storage, read_write> counts: array<atomic<u32>>;
@group(1) @binding(3) var<storage, read_write> overflow: array<atomic<u32>>;

@vertex
fn vs_main(v: MapVertex) -> MapFragment {
    return map_vertex(v, textureDimensions(range));
}

@fragment
fn fs_main(in: MapFragment) {
    let m = map_texel(in, range);
    let capacity = words_per_texel(arrayLength(&lists), m);
    let slot = atomicAdd(&counts[m.index], 1u);
    if (slot < capacity) {
        lists[m.index * capacity + slot] = pack_depth_share(m.depth, m.share);
    } else {
        atomicAdd(&overflow[0], 1u);
        if (slot == capacity) {
            atomicAdd(&overflow[1], 1u);
        }
        // The capacity that would have held this texel's list (only written
        // past the capacity, so a list that fits costs no extra atomic).
        atomicMax(&overflow[2], slot + 1u);
    }
}
