// alpha_sum: per pixel, the sum of the hair fragments' alphas (red) and their
// number (green), added by blending. The alpha is hair_shade's exactly: the
// vertex alpha weighed by strand coverage, interpolated, times the material
// alpha, clamped — so Σα / n is the mean alpha of the fragments occupancy-order
// blending weighs (Sintorn & Assarsson 2009 §3.4).
#import plait::frame::{frame, view_proj}
#import plait::strand_coverage::strand_coverage
#import plait::strand_lod::{strand_lod_weight, strand_lod_clip, strand_lod_alpha}

struct SumVertex {
    @location(0) position: vec3<f32>,
    @location(1) thickness: f32,
    @location(2) tangent: vec3<f32>,
    @location(3) alpha: f32,
    @location(5) strand_id: u32,
}

struct SumFragment {
    @builtin(position) clip: vec4<f32>,
    @location(0) alpha: f32,
}

@vertex
fn vs_main(v: SumVertex) -> SumFragment {
    var out: SumFragment;
    // The strands and weights of the hair pass (plait::hair_fragment).
    let lod = strand_lod_weight(v.strand_id);
    out.clip = strand_lod_clip(view_proj() * vec4<f32>(v.position, 1.0), lod);
    out.alpha = strand_lod_alpha(v.alpha * strand_coverage(v.position, v.tangent, v.thickness), lod);
    return out;
}

@fragment
fn fs_main(in: SumFragment) -> @location(0) vec4<f32> {
    return vec4<f32>(clamp(in.alpha * frame.hair_color.a, 0.0, 1.0), 1.0, 0.0, 0.0);
}
