// alpha_sum: per pixel, the sum of the hair fragments' alphas (red) and their
// number (green), added by blending. The alpha is hair_shade's exactly: the
// vertex alpha weighed by strand coverage and the tip fading, interpolated, times the material
// alpha, clamped — so Σα / n is the mean alpha of the fragments occupancy-order
// blending weighs (Sintorn & Assarsson 2009 §3.4).
#import plait::frame::{frame, view_proj}
#import plait::strand_coverage::{strand_coverage, strand_tip_scale}
#import plait::strand_lod::{strand_lod_place, strand_lod_clip, strand_lod_alpha, strand_lod_wisps, strand_lod_texel, strand_lod_fraction}

struct SumVertex {
    @location(0) position: vec3<f32>,
    @location(1) thickness: f32,
    @location(2) tangent: vec3<f32>,
    @location(3) alpha: f32,
    @location(4) color: vec3<f32>,
    @location(5) strand_id: u32,
    @builtin(vertex_index) index: u32,
}

struct SumFragment {
    @builtin(position) clip: vec4<f32>,
    @location(0) alpha: f32,
    // A wisp's strand-texture coordinates (plait::strand_lod).
    @location(1) wisp: vec3<f32>,
}

@vertex
fn vs_main(v: SumVertex) -> SumFragment {
    var out: SumFragment;
    // The strands and weights of the hair pass (plait::hair_fragment).
    let p = strand_lod_place(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.index);
    out.clip = strand_lod_clip(view_proj() * vec4<f32>(p.world, 1.0), p.weight);
    let coverage = select(strand_coverage(v.position, v.tangent, v.thickness), 1.0, strand_lod_wisps());
    let tip = strand_tip_scale(p.strand, p.segment, strand_lod_fraction(p.segment, p.along));
    out.alpha = strand_lod_alpha(p.alpha * coverage * tip, p.weight);
    out.wisp = p.texture;
    return out;
}

@fragment
fn fs_main(in: SumFragment) -> @location(0) vec4<f32> {
    return vec4<f32>(clamp(in.alpha * strand_lod_texel(in.wisp).a * frame.hair_color.a, 0.0, 1.0), 1.0, 0.0, 0.0);
}
