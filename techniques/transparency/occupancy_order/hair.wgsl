// occupancy_order, the hair pass (Sintorn & Assarsson 2009 §3.4): every hair
// fragment, shaded by the shared hair-fragment stage, is weighted
// (1-ᾱ)^o · α with o its depth order among its pixel's fragments, estimated
// from the camera-view occupancy and slab maps (§3.2), and added unsorted
// into a float target (the pass's additive `blend`); the compose pass applies
// the Λ correction. The fragments in front count with the mean alpha ᾱ: per
// pixel (`mean_alpha = "pixel"`, Σα / n from `order_alpha`) or one constant
// for the frame (`"frame"`).
#import plait::frame::{frame, camera_linear_depth}
#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}
#import plait::occupancy::{MAX_WORDS, relative_depth_in, slab_position, word_bits, order_in_slab}

// Camera-view depth-range, occupancy and slab maps: the depth order of each
// hair fragment among the pixel's fragments (Sintorn & Assarsson 2009 §3.2, §3.4).
@group(1) @binding(60) var order_range: texture_2d<f32>;
@group(1) @binding(61) var<storage, read> order_bits: array<u32>;
@group(1) @binding(62) var<storage, read> order_slabs: array<u32>;
// Σα (red) and n (green) of the pixel's visible hair fragments (alpha_sum).
@group(1) @binding(63) var order_alpha: texture_2d<f32>;

// ᾱ, the alpha the fragments in front of this one count with (§3.4 assumes
// one alpha for all): the pixel's mean Σα / n — with strand coverage the
// alphas differ from strand to strand and pixel to pixel — or the frame's
// CPU constant (mean_alpha = "frame").
fn order_mean_alpha(pixel: vec2<u32>) -> f32 {
#ifdef MEAN_ALPHA_PIXEL
    let size = textureDimensions(order_alpha);
    let sums = textureLoad(order_alpha, vec2<i32>(min(pixel, size - 1u)), 0);
    return clamp(sums.x / max(sums.y, 1.0), 0.0, 0.999);
#else ifdef MEAN_ALPHA_FRAME
    return clamp(frame.hair_stats.x, 0.0, 0.999);
#else
    // Neither value: the name below exists nowhere, so composing the shader
    // fails and the message names it.
    return mean_alpha_must_be_pixel_or_frame;
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
    // One path for every case, as `light_order` (plait::self_shadow::occupancy).
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

@vertex
fn vs_main(v: HairVertex) -> HairVaryings {
    return hair_vertex(v);
}

@fragment
fn fs_main(in: HairVaryings) -> @location(0) vec4<f32> {
    let f = shade_hair(in);
    // Front-to-back weights from the estimated order o: (1-ᾱ)^o · α, added
    // unsorted into a float target (§3.4). The fragments in front are
    // unknown, so they count with the mean alpha ᾱ — the method's
    // "same alpha for every fragment" — while this fragment keeps its own.
    let mean_alpha = order_mean_alpha(vec2<u32>(in.clip.xy));
    let order = camera_order(vec2<u32>(in.clip.xy), camera_linear_depth(in.world));
    let weight = pow(1.0 - mean_alpha, order) * f.alpha;
    return vec4<f32>(f.rgb * weight, weight);
}
