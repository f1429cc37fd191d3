// plait::hair_map — the vertex stage shared by every pass that draws hair into
// a per-texel map (depth range, occupancy, slabs, deep opacity, opacity shadow
// maps, density clusters, depth lists): only the position matters, and the
// fragment gets its linear depth in the pass's view. That depth is an affine
// function of the world position, so interpolating it is exact; it costs one
// interpolant instead of the position's three and no matrix per fragment
// (on a software rasterizer both are per-fragment work).
#define_import_path plait::hair_map

#import plait::frame::{view_proj, view_linear_depth}
#import plait::strand_lod::{strand_lod_place, strand_lod_clip}

struct MapVertex {
    @location(0) position: vec3<f32>,
    // A wisp vertex's slots all place it (plait::strand_lod_place).
    @location(1) thickness: f32,
    @location(2) tangent: vec3<f32>,
    @location(3) alpha: f32,
    @location(4) color: vec3<f32>,
    // The `geometry` point drops the strands the shaded draws drop.
    @location(5) strand_id: u32,
    @builtin(vertex_index) index: u32,
}

struct MapFragment {
    @builtin(position) clip: vec4<f32>,
    // Linear depth in the pass's view (`view_linear_depth`).
    @location(0) depth: f32,
}

fn map_vertex(v: MapVertex) -> MapFragment {
    var out: MapFragment;
    let p = strand_lod_place(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.index);
    out.clip = strand_lod_clip(view_proj() * vec4<f32>(p.world, 1.0), p.weight);
    out.depth = view_linear_depth(p.world);
    return out;
}

// Where a map fragment lands: its texel of a per-texel map as big as the
// texel's hair depth-range texture `range` (near in red, far in green), its
// index in per-texel buffers, and its depth in the pass's view relative to
// that texel's hair — 0 at the nearest, 1 at the farthest.
struct MapTexel {
    size: vec2<u32>,
    texel: vec2<u32>,
    // texel.y * size.x + texel.x
    index: u32,
    near: f32,
    far: f32,
    // linear depth in the pass's view (`view_linear_depth`)
    depth: f32,
    rel: f32,
}

fn map_texel(in: MapFragment, range: texture_2d<f32>) -> MapTexel {
    var m: MapTexel;
    m.size = textureDimensions(range);
    m.texel = min(vec2<u32>(in.clip.xy), m.size - 1u);
    m.index = m.texel.y * m.size.x + m.texel.x;
    let r = textureLoad(range, vec2<i32>(m.texel), 0);
    m.near = r.x;
    m.far = r.y;
    m.depth = in.depth;
    m.rel = (m.depth - r.x) / max(r.y - r.x, 1e-9);
    return m;
}

// u32 words per texel of a per-texel buffer of `words_total` words.
fn words_per_texel(words_total: u32, m: MapTexel) -> u32 {
    return words_total / (m.size.x * m.size.y);
}
