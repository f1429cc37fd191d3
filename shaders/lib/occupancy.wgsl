// plait::occupancy — reading the occupancy, slab and depth-range maps of
// Sintorn & Assarsson (2009 §3.1–3.2).
//
// Per texel the maps hold: a depth range [near, far] (rg32float, linear depth
// of the view), WORDS 32-bit words of occupancy bits (one bit per slice; slice
// k covers relative depth [k, k+1) / (32 WORDS)), and WORDS fragment counts,
// one per slab of 32 slices. WORDS = 4 gives the paper's 128 slices and 4 slabs.
//
// The order estimate is mirrored on the CPU by `plait_passes::occupancy::
// order_estimate`; a GPU test runs this function and checks the two agree.
#define_import_path plait::occupancy

// Up to 1024 slices (8 × 128) and 1024 slabs per texel.
const MAX_WORDS: u32 = 32u;

struct TexelMaps {
    // 32-bit words of occupancy bits: 32 · words slices.
    words: u32,
    // Fragment counters; each covers 32 · words / slabs consecutive slices.
    slabs: u32,
    near: f32,
    far: f32,
    bits: array<u32, 32>,
    counts: array<u32, 32>,
}

// Relative depth of `depth` within the texel's range; < 0 in front of all
// hair, > 1 behind it. Texels without hair have far < near.
fn relative_depth(maps: ptr<function, TexelMaps>, depth: f32) -> f32 {
    return relative_depth_in(vec2<f32>((*maps).near, (*maps).far), depth);
}

// `relative_depth` for a texel's range (near, far) as the range map holds it.
fn relative_depth_in(range: vec2<f32>, depth: f32) -> f32 {
    let extent = range.y - range.x;
    if (extent <= 0.0) {
        return select(-1.0, 2.0, depth > range.y);
    }
    return (depth - range.x) / extent;
}

// Total fragments recorded in the texel: the sum of its slabs.
fn total_fragments(maps: ptr<function, TexelMaps>) -> f32 {
    var total = 0u;
    for (var i = 0u; i < (*maps).slabs; i++) {
        total += (*maps).counts[i];
    }
    return f32(total);
}

// Set bits among slices [first, last).
fn count_bits(maps: ptr<function, TexelMaps>, first: u32, last: u32) -> u32 {
    var n = 0u;
    for (var w = first / 32u; w * 32u < last; w++) {
        let lo = max(first, w * 32u) - w * 32u;
        let hi = min(last, w * 32u + 32u) - w * 32u;
        // Bits lo..hi of the word (hi may be 32).
        var mask = 0xFFFFFFFFu;
        if (hi < 32u) {
            mask = (1u << hi) - 1u;
        }
        mask = mask & ~((1u << lo) - 1u);
        n += countOneBits((*maps).bits[w] & mask);
    }
    return n;
}

// Estimated number of fragments in front of relative depth `rel` (§3.2):
// the slabs before the fragment's slab count exactly; within its slab each
// set bit stands for F_i / B_total fragments; inside its slice the estimate
// is interpolated linearly between the slice's start and end. Exact at slab
// boundaries; inside a slab off by at most that slab's count F_i.
fn order_estimate(maps: ptr<function, TexelMaps>, rel: f32) -> f32 {
    return order_estimate_excluding(maps, rel, 0.0);
}

// The order of a fragment that is itself recorded in the maps (the camera
// order of §3.4): the fragments strictly in front of it, its own count left
// out — docs/design.md, "In front of". Its slice holds it, so the slice's
// share interpolated across the slice is per_bit - 1 other fragments.
fn fragment_order(maps: ptr<function, TexelMaps>, rel: f32) -> f32 {
    return order_estimate_excluding(maps, rel, 1.0);
}

// `own` fragments at `rel` (0 or 1) are not counted in front of it.
fn order_estimate_excluding(maps: ptr<function, TexelMaps>, rel: f32, own: f32) -> f32 {
    let words = (*maps).words;
    let slabs = (*maps).slabs;
    if (words == 0u || slabs == 0u || rel <= 0.0) {
        return 0.0;
    }
    if (rel >= 1.0) {
        return max(total_fragments(maps) - own, 0.0);
    }
    let slices = words * 32u;
    let per_slab = max(slices / slabs, 1u);
    let s = rel * f32(slices);
    let slice = min(u32(floor(s)), slices - 1u);
    let frac = clamp(s - f32(slice), 0.0, 1.0);
    let slab = min(slice / per_slab, slabs - 1u);
    var before = 0.0;
    for (var i = 0u; i < slab; i++) {
        before += f32((*maps).counts[i]);
    }
    let first = slab * per_slab;
    let set_in_slab = count_bits(maps, first, first + per_slab);
    var per_bit = 0.0;
    if (set_in_slab > 0u) {
        per_bit = f32((*maps).counts[slab]) / f32(set_in_slab);
    }
    let bits_before = count_bits(maps, first, slice);
    let bits_through = count_bits(maps, first, slice + 1u);
    let at_start = before + per_bit * f32(bits_before);
    let at_end = before + per_bit * f32(bits_through);
    return at_start + max(at_end - at_start - own, 0.0) * frac;
}

// ---------------------------------------------------------------------------
// The same estimate for readers that fetch only the words it needs from their
// own storage buffers (the visibility provider, hair_shade's camera order),
// instead of copying the texel into a `TexelMaps`. WGSL cannot pass a storage
// buffer to a function, so the reader loops over the words and these functions
// do the arithmetic: `slab_position` says which words to read, `word_bits`
// counts a word's set bits in a range of slices, `order_in_slab` combines them
// exactly as `order_estimate_excluding` does (bit-identical results). On a
// software rasterizer this avoids a 264-byte private array, zeroed and copied
// per fragment and per lookup.

// Where relative depth `rel` (0 < rel < 1) falls: its slab, the slab's first
// slice and one past its last, the slice holding rel and how far into it.
struct SlabPosition {
    slab: u32,
    first: u32,
    end: u32,
    slice: u32,
    frac: f32,
}

fn slab_position(rel: f32, words: u32, slabs: u32) -> SlabPosition {
    let slices = words * 32u;
    let per_slab = max(slices / slabs, 1u);
    let s = rel * f32(slices);
    var p: SlabPosition;
    p.slice = min(u32(floor(s)), slices - 1u);
    p.frac = clamp(s - f32(p.slice), 0.0, 1.0);
    p.slab = min(p.slice / per_slab, slabs - 1u);
    p.first = p.slab * per_slab;
    p.end = p.first + per_slab;
    return p;
}

// Set bits of occupancy word `w` (slices 32w … 32w + 31) among slices [first, last).
fn word_bits(word: u32, w: u32, first: u32, last: u32) -> u32 {
    let base = w * 32u;
    let lo = max(first, base);
    let hi = min(last, base + 32u);
    if (hi <= lo) {
        return 0u;
    }
    var mask = 0xFFFFFFFFu;
    if (hi - base < 32u) {
        mask = (1u << (hi - base)) - 1u;
    }
    mask = mask & ~((1u << (lo - base)) - 1u);
    return countOneBits(word & mask);
}

// The order at `p` from the counts before its slab (`before`, summed in
// slab order as f32), its slab's count, and its slab's set bits: all of
// them, those before its slice and those through its slice; `own` as in
// `order_estimate_excluding`.
fn order_in_slab(p: SlabPosition, before: f32, slab_count: u32, set_in_slab: u32, bits_before: u32, bits_through: u32, own: f32) -> f32 {
    var per_bit = 0.0;
    if (set_in_slab > 0u) {
        per_bit = f32(slab_count) / f32(set_in_slab);
    }
    let at_start = before + per_bit * f32(bits_before);
    let at_end = before + per_bit * f32(bits_through);
    return at_start + max(at_end - at_start - own, 0.0) * p.frac;
}
