// plait::strand_lod — what every hair draw does with the `geometry` point's
// answer (techniques/geometry/point.toml): a strand standing for w strands
// is not drawn when w = 0, and weighs its alpha for w strands otherwise.
// plait::hair_fragment, plait::hair_map and alpha_sum all go through here,
// so the shaded image, the per-texel maps and the mean alpha drop the same
// strands and widen the same ones.
#define_import_path plait::strand_lod

#import plait::frame::frame
#import plait::geometry::geometry_strand_weight

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
