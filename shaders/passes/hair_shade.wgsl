// hair_shade: shading of hair fragments, one provider per choice point —
// the key light's reflection (`shading`: Kajiya-Kay by default, Halén &
// Wester 2007 §3.2.1), shadowed by opaque objects (Sintorn & Assarsson 2009
// §3.5) and by the hair itself (`visibility`); the rest of the environment's
// light (`lighting`), darkened by per-vertex occlusion (`occlusion`) — then
// blended into the colour target by the `blend` param.
#import plait::frame::{frame, view_proj, to_light}
#import plait::hair_direct::shade_direct
#import plait::hair_environment::shade_environment
#import plait::hair_occlusion::occlusion_at
#import plait::shadow::opaque_shadow
#import plait::self_shadow::self_shadow
#import plait::transparency::coverage::strand_coverage
#ifdef BLEND_OCCUPANCY_ORDER
#import plait::frame::camera_linear_depth
#import plait::occupancy::{MAX_WORDS, relative_depth_in, slab_position, word_bits, order_in_slab}
#endif
// Transparency modes of their own pass types (depth_peeling.rs, linked_list.rs,
// weighted_average.rs, alpha_to_coverage.rs, opaque_hair.rs): each module hands
// back the fragment's outputs from its shaded colour and alpha.
#ifdef TRANSPARENCY_DEPTH_PEEL
#import plait::transparency::depth_peel::{FragmentOut, hair_fragment}
#else ifdef TRANSPARENCY_FRAGMENT_LIST
#import plait::transparency::fragment_list::{FragmentOut, hair_fragment}
#else ifdef TRANSPARENCY_WEIGHTED_AVERAGE
#import plait::transparency::weighted_average::{FragmentOut, hair_fragment}
#else ifdef TRANSPARENCY_COVERAGE
#import plait::transparency::coverage::{FragmentOut, hair_fragment}
#endif

@group(1) @binding(0) var shadow_map: texture_depth_2d;

#ifdef BLEND_OCCUPANCY_ORDER
// Camera-view depth-range, occupancy and slab maps: the depth order of each
// hair fragment among the pixel's fragments (Sintorn & Assarsson 2009 §3.2, §3.4).
@group(1) @binding(16) var order_range: texture_2d<f32>;
@group(1) @binding(17) var<storage, read> order_bits: array<u32>;
@group(1) @binding(18) var<storage, read> order_slabs: array<u32>;
// Σα (red) and n (green) of the pixel's visible hair fragments (alpha_sum).
@group(1) @binding(19) var order_alpha: texture_2d<f32>;

// ᾱ, the alpha the fragments in front of this one count with (§3.4 assumes
// one alpha for all): the pixel's mean Σα / n — with strand coverage the
// alphas differ from strand to strand and pixel to pixel — or the frame's
// CPU constant (mean_alpha = "frame").
fn order_mean_alpha(pixel: vec2<u32>) -> f32 {
#ifdef MEAN_ALPHA_PIXEL
    let size = textureDimensions(order_alpha);
    let sums = textureLoad(order_alpha, vec2<i32>(min(pixel, size - 1u)), 0);
    return clamp(sums.x / max(sums.y, 1.0), 0.0, 0.999);
#else
    return clamp(frame.hair_stats.x, 0.0, 0.999);
#endif
}

// The fragment's order among its pixel's fragments, its own count left out
// (`plait::occupancy::fragment_order`), reading only the words it needs.
fn camera_order(pixel: vec2<u32>, depth: f32) -> f32 {
    let size = textureDimensions(order_range);
    let p = min(pixel, size - 1u);
    let texels = size.x * size.y;
    let words = min(arrayLength(&order_bits) / texels, MAX_WORDS);
    let slabs = min(arrayLength(&order_slabs) / texels, MAX_WORDS);
    let rel = relative_depth_in(textureLoad(order_range, vec2<i32>(p), 0).xy, depth);
    // One path for every case, as `light_order` (plait::visibility::occupancy).
    let behind = rel >= 1.0;
    let at = slab_position(select(max(rel, 0.0), 0.99999994, behind), max(words, 1u), max(slabs, 1u));
    let index = p.y * size.x + p.x;
    var before = 0.0;
    for (var i = 0u; i < at.slab; i++) {
        before += f32(order_slabs[index * slabs + i]);
    }
    var set_in_slab = 0u;
    var bits_before = 0u;
    var bits_through = 0u;
    for (var w = at.first / 32u; w * 32u < at.end; w++) {
        let word = order_bits[index * words + w];
        set_in_slab += word_bits(word, w, at.first, at.end);
        bits_before += word_bits(word, w, at.first, at.slice);
        bits_through += word_bits(word, w, at.first, at.slice + 1u);
    }
    let slab_count = order_slabs[index * slabs + at.slab];
    let order = select(order_in_slab(at, before, slab_count, set_in_slab, bits_before, bits_through, 1.0), max(before + f32(slab_count) - 1.0, 0.0), behind);
    return select(order, 0.0, words == 0u || slabs == 0u || rel <= 0.0);
}
#endif

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) thickness: f32,
    @location(2) tangent: vec3<f32>,
    @location(3) alpha: f32,
    @location(4) color: vec3<f32>,
    // The vertex's index in the hair vertex buffer: per-vertex resources
    // (ambient occlusion) are indexed by it.
    @builtin(vertex_index) index: u32,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) tangent: vec3<f32>,
    @location(2) color: vec3<f32>,
    @location(3) alpha: f32,
    // Fraction of the environment's light reaching the strand here.
    @location(4) occlusion: f32,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = view_proj() * vec4<f32>(v.position, 1.0);
    out.world = v.position;
    out.tangent = v.tangent;
    out.color = v.color;
    // A strand thinner than a pixel covers only part of it: its coverage
    // weighs its alpha in every blending technique (and sets the sample mask
    // of alpha to coverage).
    out.alpha = v.alpha * strand_coverage(v.position, v.tangent, v.thickness);
    out.occlusion = occlusion_at(v.index);
    return out;
}

@fragment
#ifdef TRANSPARENCY_MODULE
fn fs_main(in: VertexOut) -> FragmentOut {
#else
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
#endif
    let tangent = normalize(in.tangent);
    let l = to_light(in.world);
    let e = normalize(frame.camera_position.xyz - in.world);
    let visibility = self_shadow(in.world) * opaque_shadow(shadow_map, in.world, 0.002);
    let base = in.color * frame.hair_color.rgb;
    let direct = shade_direct(tangent, l, e, base);
    let environment = shade_environment(in.world, tangent, e, base) * in.occlusion;
    let rgb = frame.light_color.rgb * direct * visibility + environment;
#ifdef TRANSPARENCY_MODULE
    return hair_fragment(in.clip, rgb, clamp(in.alpha * frame.hair_color.a, 0.0, 1.0));
#else ifdef BLEND_OCCUPANCY_ORDER
    // Front-to-back weights from the estimated order o: (1-ᾱ)^o · α, added
    // unsorted into a float target (§3.4). The fragments in front are
    // unknown, so they count with the mean alpha ᾱ — the method's
    // "same alpha for every fragment" — while this fragment keeps its own.
    let alpha = clamp(in.alpha * frame.hair_color.a, 0.0, 1.0);
    let mean_alpha = order_mean_alpha(vec2<u32>(in.clip.xy));
    let order = camera_order(vec2<u32>(in.clip.xy), camera_linear_depth(in.world));
    let weight = pow(1.0 - mean_alpha, order) * alpha;
    return vec4<f32>(rgb * weight, weight);
#else
    let alpha = clamp(in.alpha * frame.hair_color.a, 0.0, 1.0);
    // Premultiplied: the blend state composites "over" what is already there.
    return vec4<f32>(rgb * alpha, alpha);
#endif
}
