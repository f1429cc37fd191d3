// alpha_to_coverage: the strands drawn like opaque geometry (depth test and
// write, no sorting) into a multisampled target; the fragment's alpha picks
// how many of the pixel's samples it covers and the resolve averages them
// (Halén & Wester 2007 §3.1.2, §5.6). Not premultiplied: the coverage does
// the weighting.
//
// The sample mask is computed here, not by the hardware's alpha to coverage:
// that mapping is the implementation's, and lavapipe's gives one sample of
// four to any alpha above 0 — a 0.05-pixel strand covered as much as a
// 0.2-pixel one, 5× its width (tests/coverage_analytic.rs). Here α × the c
// samples the line covers in the pixel is dithered to whole samples
// (floor(α·c + ξ), ξ a low-discrepancy threshold offset per strand), so the
// expected coverage is α × the line's, and which of the c is rotated by a
// hash of the pixel and the strand, so strands in one pixel do not all pick
// the same ones.
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}

struct HairSamples {
    @location(0) color: vec4<f32>,
    @builtin(sample_mask) mask: u32,
}

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

// PCG (O'Neill 2014) hash: well-mixed bits from a small integer.
fn pcg(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

@fragment
fn fs_main(in: HairVaryings, @builtin(sample_mask) covered: u32) -> HairSamples {
    let f = shade_hair(in);
    let pixel = vec2<u32>(in.clip.xy);
    // A low-discrepancy threshold (Roberts' R2 sequence over the pixel grid),
    // offset per strand: along a strand, at any angle, neighbouring pixels'
    // roundings cancel — a random threshold per pixel left the sum as noisy
    // as a coin per pixel, a 4×4 Bayer matrix as coarse as 4 levels on a row.
    let r2 = vec2<f32>(0.7548776662, 0.5698402910);
    let xi = fract(dot(vec2<f32>(pixel), r2) + f32(pcg(in.strand) >> 8u) / 16777216.0);
    // Of the samples the line covers here, α of them (dithered): the
    // expected coverage is α × the line's, whatever part of the pixel it
    // crosses.
    // A wide strand's quad is the strand's band exactly here, without the
    // apron and the box-filtered edge (QUAD_EDGES_BAND,
    // plait::strand_coverage): the samples it covers are its coverage, as
    // a line's are — a pixel the quad's diagonal crosses has a fragment of
    // each triangle, each with its own samples.
    let c = countOneBits(covered);
    let k = min(u32(floor(f.alpha * f32(c) + xi)), c);
    let r = pcg(pcg(pixel.x + pcg(pixel.y)) ^ pcg(in.strand)) % max(c, 1u);
    var mask = 0u;
    var rank = 0u;
    for (var bit = 0u; bit < 32u; bit += 1u) {
        if ((covered & (1u << bit)) != 0u) {
            if ((rank + c - r) % c < k) {
                mask |= 1u << bit;
            }
            rank += 1u;
        }
    }
    return HairSamples(vec4<f32>(f.rgb, 1.0), mask);
}
