// plait::map_share — how a light map carries the part of a texel a strand
// covers (its share, at most 1: a line's width across the light in texels,
// a wide strand's quad's coverage of the texel; see
// plait::hair_map::map_texel). A light texel is blocked by the strand's share
// of it (issue 47), so every self-shadow map weighs a fragment by it:
//   counting maps (slabs, deep opacity layers, opacity slices, density
//   clusters) add round(share · MAP_SHARE_SCALE) where they added 1, and
//   their providers divide the count by MAP_SHARE_SCALE;
//   the exact depth lists store the share with each depth (pack_depth_share):
//   the light linear depth with the share in the low 8 bits of the f32's
//   mantissa. Depths in [0, 1] keep 15 mantissa bits (a relative error
//   under 2^-15, far below the self-shadow bias); the share is kept to 1/255.
#define_import_path plait::map_share

// 4096 keeps 2^20 whole-texel fragments per u32 counter.
const MAP_SHARE_SCALE: f32 = 4096.0;

fn pack_depth_share(depth: f32, share: f32) -> u32 {
    let s = u32(round(clamp(share, 0.0, 1.0) * 255.0));
    // At least 1/255: a strand thinner than that still counts a little.
    return (bitcast<u32>(depth) & 0xFFFFFF00u) | max(s, 1u);
}

fn list_depth(entry: u32) -> f32 {
    return bitcast<f32>(entry & 0xFFFFFF00u);
}

fn list_share(entry: u32) -> f32 {
    return f32(entry & 0xFFu) / 255.0;
}
