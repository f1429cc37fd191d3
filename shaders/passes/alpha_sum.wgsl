// alpha_sum: per pixel, the sum of the hair fragments' alphas (red) and their
// number (green), added by blending. The alpha is hair_shade's exactly: the
// vertex alpha weighed by strand coverage and the tip fading, interpolated, times the material
// alpha, clamped — so Σα / n is the mean alpha of the fragments occupancy-order
// blending weighs (Sintorn & Assarsson 2009 §3.4).
#import plait::frame::{frame, view_proj}
#import plait::strand_coverage::{strand_coverage, strand_tip_scale, is_quad_vertex, quad_corner, segment_is_wide, quad_place, quad_coverage, QuadPlace}
#import plait::strand_lod::{strand_lod_place, strand_lod_clip, strand_lod_alpha, strand_lod_wisps, strand_lod_texel, strand_lod_fraction}

struct SumVertex {
    @location(0) position: vec3<f32>,
    @location(1) thickness: f32,
    @location(2) tangent: vec3<f32>,
    @location(3) alpha: f32,
    @location(4) color: vec3<f32>,
    @location(5) strand_id: u32,
    // The next hair vertex, for the quad draw of strands wider than a pixel
    // (plait::strand_coverage), as plait::hair_fragment's HairVertex.
    @location(6) next_position: vec3<f32>,
    @location(7) next_thickness: f32,
    @location(8) next_tangent: vec3<f32>,
    @location(9) next_alpha: f32,
    @location(10) next_color: vec3<f32>,
    @location(11) next_strand_id: u32,
    @builtin(vertex_index) index: u32,
    @builtin(instance_index) instance: u32,
}

struct SumFragment {
    @builtin(position) clip: vec4<f32>,
    @location(0) alpha: f32,
    // A wisp's strand-texture coordinates (plait::strand_lod).
    @location(1) wisp: vec3<f32>,
    // 0: a line; 1: the line of a wide segment (discarded); 2: its quad,
    // with (distance from the centre line, half width) in pixels.
    @location(2) @interpolate(flat) mode: u32,
    @location(3) @interpolate(linear) across: vec2<f32>,
}

@vertex
fn vs_main(v: SumVertex) -> SumFragment {
    let wide = !strand_lod_wisps() && segment_is_wide(v.position, v.tangent, v.thickness, v.strand_id, v.next_position, v.next_tangent, v.next_thickness, v.next_strand_id);
    if (!is_quad_vertex(v.index)) {
        var out = sum_vertex(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.index, true);
        out.mode = select(0u, 1u, wide);
        return out;
    }
    // A quad corner, as plait::hair_fragment's quad_vertex.
    let corner = quad_corner(v.index);
    var out: SumFragment;
    var q: QuadPlace;
    let segment = v.next_position - v.position;
    if (corner.end) {
        out = sum_vertex(v.next_position, v.next_thickness, v.next_tangent, v.next_alpha, v.next_color, v.next_strand_id, v.instance + 1u, false);
        q = quad_place(v.next_position, v.next_tangent, v.next_thickness, segment, corner.side);
    } else {
        out = sum_vertex(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.instance, false);
        q = quad_place(v.position, v.tangent, v.thickness, segment, corner.side);
    }
    let p = strand_lod_place(v.position, v.thickness, v.tangent, v.alpha, v.color, v.strand_id, v.instance);
    out.clip = select(vec4<f32>(2.0, 2.0, 2.0, 1.0), strand_lod_clip(q.clip, p.weight), wide);
    out.across = q.across;
    out.mode = 2u;
    return out;
}

// Hair vertex `index` placed; `line`: its alpha weighed by the line's
// coverage (a quad's is per pixel).
fn sum_vertex(position: vec3<f32>, thickness: f32, tangent: vec3<f32>, alpha: f32, color: vec3<f32>, strand_id: u32, index: u32, line: bool) -> SumFragment {
    var out: SumFragment;
    // The strands and weights of the hair pass (plait::hair_fragment).
    let p = strand_lod_place(position, thickness, tangent, alpha, color, strand_id, index);
    out.clip = strand_lod_clip(view_proj() * vec4<f32>(p.world, 1.0), p.weight);
    let coverage = select(strand_coverage(position, tangent, thickness), 1.0, strand_lod_wisps() || !line);
    let tip = strand_tip_scale(p.strand, p.segment, strand_lod_fraction(p.segment, p.along));
    out.alpha = strand_lod_alpha(p.alpha * coverage * tip, p.weight);
    out.wisp = p.texture;
    out.mode = 0u;
    out.across = vec2<f32>(0.0, 1.0);
    return out;
}

@fragment
fn fs_main(in: SumFragment) -> @location(0) vec4<f32> {
    if (in.mode == 1u) {
        discard;
    }
    let quad = select(1.0, quad_coverage(in.across), in.mode == 2u);
    return vec4<f32>(clamp(in.alpha * quad * strand_lod_texel(in.wisp).a * frame.hair_color.a, 0.0, 1.0), 1.0, 0.0, 0.0);
}
