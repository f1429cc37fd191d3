// compute_raster, tile_depth: the farthest opaque depth of every screen tile,
// so strand_bin can leave out a segment that lies behind the opaque scene
// over a whole tile (hair behind the head is neither binned nor counted).
// Conservative: a segment is dropped from a tile only if its nearest depth
// is at or behind every opaque texel of the tile (the depth test is "less").

@group(1) @binding(0) var opaque_depth: texture_depth_2d;
// One word per tile (row-major, ceil(width / tile_size) tiles a row): the
// largest opaque depth's f32 bits (depths in [0, 1] order as their bits).
@group(1) @binding(1) var<storage, read_write> tile_far: array<u32>;

struct Params {
    tile_size: u32,
}
@group(1) @binding(2) var<uniform> params: Params;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(opaque_depth);
    let t = params.tile_size;
    let tiles = (size + vec2<u32>(t - 1u)) / t;
    if (id.x >= tiles.x * tiles.y) {
        return;
    }
    let origin = vec2<u32>(id.x % tiles.x, id.x / tiles.x) * t;
    let end = min(origin + vec2<u32>(t), size);
    var far = 0.0;
    for (var y = origin.y; y < end.y; y++) {
        for (var x = origin.x; x < end.x; x++) {
            far = max(far, textureLoad(opaque_depth, vec2<u32>(x, y), 0));
        }
    }
    tile_far[id.x] = bitcast<u32>(far);
}
