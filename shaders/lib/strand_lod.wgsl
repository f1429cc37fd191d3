// plait::strand_lod — what every hair draw does with the `geometry` point's
// answer (techniques/geometry/point.toml): a strand standing for w strands
// is not drawn when w = 0, and weighs its alpha for w strands otherwise.
// plait::hair_fragment, plait::hair_map and alpha_sum all go through here,
// so the shaded image, the per-texel maps and the mean alpha drop the same
// strands and widen the same ones.
#define_import_path plait::strand_lod

#import plait::frame::frame
#import plait::geometry::geometry_strand_weight
#ifdef GEOMETRY_WISPS
#import plait::geometry::wisps::{wisp_point, wisp_texel}
#endif

// How many of the groom's strands this one stands for (0: not drawn).
fn strand_lod_weight(strand_id: u32) -> f32 {
    return geometry_strand_weight(strand_id);
}

// The clip position of a vertex of a strand of weight `weight`: a strand not
// drawn puts every vertex beyond the clip volume's corner (x, y, z > w), so
// each of its segments is clipped whole, before any fragment.
fn strand_lod_clip(clip: vec4<f32>, weight: f32) -> vec4<f32> {
    return select(clip, vec4<f32>(2.0, 2.0, 2.0, 1.0), weight <= 0.0);
}

// The vertex alpha (strand alpha × pixel coverage, before the material's
// alpha, as the hair varyings carry it) of a strand drawn for `weight`
// strands: its fragment alpha a becomes 1 − (1 − a)^weight, what `weight`
// independent strands of alpha a hide together (≈ weight × a, the coverage
// of a strand `weight` times wider, while that is small). Weight 1 leaves
// it exactly as it was.
fn strand_lod_alpha(alpha: f32, weight: f32) -> f32 {
    let material = frame.hair_color.a;
    if (weight == 1.0 || material <= 0.0) {
        return alpha;
    }
    let a = clamp(alpha * material, 0.0, 1.0);
    if (a >= 1.0) {
        return alpha;
    }
    return (1.0 - pow(1.0 - a, weight)) / material;
}

// `geometry = "wisps"` (techniques/geometry/wisps): every hair draw draws the
// wisps' triangles, whose vertices each follow a hair vertex; the functions
// below place them and read the strand texture. For strands they leave
// everything as it was.

// A hair draw's vertex as the geometry places it this frame.
struct LodVertex {
    // Where it is drawn: a strand's point, or a wisp's strip corner.
    world: vec3<f32>,
    tangent: vec3<f32>,
    alpha: f32,
    color: vec3<f32>,
    // How many strands it stands for (strand_lod_weight; 0 = not drawn).
    weight: f32,
    // A wisp's strand-texture coordinates (u across, v along, mip level);
    // 0 for strands.
    texture: vec3<f32>,
    // Where it lies along its strand, for strand-space shading
    // (plait::hair_fragment): the strand, a hair vertex of it (`segment`)
    // and `along`, interpolated, from which the fragment's place is
    // segment + fraction (strand_lod_fraction).
    strand: u32,
    segment: u32,
    along: f32,
}

// Hair vertex buffer entry `index` (the vertex stage's inputs) placed.
fn strand_lod_place(position: vec3<f32>, thickness: f32, tangent: vec3<f32>, alpha: f32, color: vec3<f32>, strand_id: u32, index: u32) -> LodVertex {
    var out: LodVertex;
#ifdef GEOMETRY_WISPS
    // A plait_hair::wisps::WispVertex in the hair vertex's slots.
    let w = wisp_point(position, thickness, tangent, alpha, color, strand_id, index);
    out.world = w.corner;
    out.tangent = w.tangent;
    out.alpha = w.alpha;
    out.color = w.color;
    out.weight = w.weight;
    out.texture = w.texture;
    // The strand's first vertex (flat, the same on the whole wisp) and the
    // point's index along the strand, interpolated across the strip.
    out.strand = w.strand;
    out.segment = w.first;
    out.along = w.point;
#else
    out.world = position;
    out.tangent = tangent;
    out.alpha = alpha;
    out.color = color;
    out.weight = strand_lod_weight(strand_id);
    out.texture = vec3<f32>(0.0);
    // A line's provoking vertex is its first, vertex i of the segment i,
    // i + 1: the parity of the index, interpolated, runs 0 → 1 from an even
    // first vertex and 1 → 0 from an odd one.
    out.strand = strand_id;
    out.segment = index;
    out.along = f32(index & 1u);
#endif
    return out;
}

// How far past hair vertex `segment` a fragment lies along its strand, in
// hair vertices, from its interpolated `along` (strand_lod_place).
fn strand_lod_fraction(segment: u32, along: f32) -> f32 {
#ifdef GEOMETRY_WISPS
    return along;
#else
    return select(along, 1.0 - along, (segment & 1u) == 1u);
#endif
}

// The hair vertex whose per-vertex results (ambient occlusion) this vertex
// reads: itself, or the one a wisp vertex stands for (its `strand_id`).
fn strand_lod_vertex(index: u32, strand_id: u32) -> u32 {
#ifdef GEOMETRY_WISPS
    return strand_id;
#else
    return index;
#endif
}

// Whether hair draws draw wisps (their coverage is their strand texture's
// alpha, not a line's pixel coverage).
fn strand_lod_wisps() -> bool {
#ifdef GEOMETRY_WISPS
    return true;
#else
    return false;
#endif
}

// What the strand texture makes of a fragment at `coordinates`: rgb
// multiplies its colour, alpha its alpha (the wisp's coverage there); 1 for
// strands.
fn strand_lod_texel(coordinates: vec3<f32>) -> vec4<f32> {
#ifdef GEOMETRY_WISPS
    return wisp_texel(coordinates.x, coordinates.y, coordinates.z);
#else
    return vec4<f32>(1.0);
#endif
}
