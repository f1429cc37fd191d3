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
#import plait::geometry::wisps::{wisp_corner, wisp_u, wisp_level, wisp_texel}
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
// wisps' triangles, whose vertices carry a guide point each; the functions
// below turn one into its strip's corner and read the strand texture. For
// strands they leave everything as it was.

// Where hair vertex `index` at `position` is drawn: itself, or, for a wisp
// vertex, its strip's corner facing the view.
fn strand_lod_position(position: vec3<f32>, tangent: vec3<f32>, index: u32) -> vec3<f32> {
#ifdef GEOMETRY_WISPS
    return wisp_corner(position, tangent, index);
#else
    return position;
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

// Whether hair draws draw wisps (shaded per fragment whatever the
// shading space: the strand-space pass shades the strands, not the wisps).
fn strand_lod_wisps() -> bool {
#ifdef GEOMETRY_WISPS
    return true;
#else
    return false;
#endif
}

// A wisp vertex's strand-texture coordinates: u across (0, 1 at its sides),
// v along (its `thickness`: 0 root, 1 tip), the mip level; 0 for strands.
fn strand_lod_texture_coordinates(position: vec3<f32>, tangent: vec3<f32>, thickness: f32, index: u32) -> vec3<f32> {
#ifdef GEOMETRY_WISPS
    return vec3<f32>(wisp_u(index), thickness, wisp_level(position, tangent));
#else
    return vec3<f32>(0.0);
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
