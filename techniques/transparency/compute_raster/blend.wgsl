// compute_raster, tile_blend: one workgroup per screen tile, one thread per
// pixel (tile_size² threads).
//
// 1. The tile's segments (strand_bin) are partitioned into `depth_bins`
//    bins of the camera depth of their midpoints, uniform between the
//    tile's nearest and farthest segment (a counting sort in workgroup
//    memory), and each bin is then sorted by that depth (each segment's
//    rank in its bin, ties by the segment's first vertex, i.e. segment
//    order, so the image is the same every run): the tile's segments front
//    to back, by segment.
// 2. Down the tile's sorted list, 64 segments at a time, each segment's
//    thread projects it into workgroup memory and marks the pixels it may
//    cover (cover_pixels); each pixel blends its marked segments front to
//    back,
//    C += (1 - A) · α · rgb, A += (1 - A) · α, with α the segment's
//    fragment alpha (strand alpha × plait::strand_coverage × its tip
//    fading, plait::strand_coverage::strand_tip_scale, × material
//    alpha, widened by plait::strand_lod, interpolated between its two
//    vertices as the rasterizer interpolates it) times the pixel's
//    analytic coverage of the one-pixel-wide line: 1 − |distance across
//    the line| (a tent: over each column the line crosses it sums to the
//    band's area there, as a rasterized one-pixel-wide line covers it). A
//    segment wider than a pixel is the quad the hair draws' quad draw draws
//    for it instead (plait::compute_raster::strand_quad: its two triangles,
//    the box-filtered coverage of plait::strand_coverage::quad_coverage,
//    the fragment alpha without the line's width factor), so it covers its
//    width. Only where the segment's depth is in front of the opaque depth
//    ("less", as every hair draw tests it).
// 3. A pixel whose A reaches `opacity_threshold` stops; when every pixel of
//    the tile has, the tile stops (the early out of Unity HDRP's High
//    Quality Lines and Frostbite).
//
// Wisps (`geometry = wisps`): a segment is a quad of a wisp's strip
// (plait::compute_raster::wisp_quad); its coverage at a pixel centre is
// its two triangles' (inside one of them) × the strand texture's alpha at
// the perspective-correct (u, v, mip level) there, its depth the
// triangle's there, its colour the texel's rgb × the hair's colour as
// plait::hair_fragment shades a wisp fragment (cover_quad, shade_wisp).
//
// Colour: where the fragment stage gets it (plait::shading_space) —
// strand space interpolates the strand_shading pass's radiance; with
// fragment shading the pixel is shaded here through plait::hair_radiance
// at the interpolated point, as the hair fragment stage shades it.
#import plait::frame::frame
#import plait::hair_radiance::hair_radiance
#import plait::ambient_occlusion::occlusion_at
#import plait::shading_space::strand_space_radiance
#import plait::strand_coverage::{strand_coverage, strand_tip_scale}
#import plait::strand_lod::{strand_lod_weight, strand_lod_alpha}
#import plait::hair_point::{HairPoint, camera_segment}
#import plait::strand_curve::strand_curve_tangent
#import plait::loop_budget::loop_budget_spent
#import plait::compute_raster::triangles::quad_depth
#ifdef GEOMETRY_WISPS
#import plait::compute_raster::wisp_quad::{wisp_quad, wisp_quad_hit, wisp_vertex, wisp_hair_vertex}
#import plait::geometry::wisps::wisp_texel
#else
#import plait::compute_raster::strand_quad::{strand_quad, strand_quad_hit, strand_segment_is_wide}
#endif

struct Params {
    tile_size: u32,
    depth_bins: u32,
    binned_segments: u32,
    opacity_threshold: f32,
}

@group(1) @binding(0) var shadow_map: texture_depth_2d;
@group(1) @binding(60) var<uniform> params: Params;
#ifndef GEOMETRY_WISPS
@group(1) @binding(61) var<storage, read> hair_vertices: array<HairPoint>;
#endif
// [0] dropped and [1] needed (tile_scan's), [2] this pass's invocations
// that did not finish.
@group(1) @binding(63) var<storage, read_write> raster_counter: array<atomic<u32>>;
// The pool, `binned_segments` slots: words [0, P) a slot's segment (strand_bin's,
// then the tile's sorted order, written here); words [P, 3P) per slot the
// segment and its depth key's bits, placed in its depth bin (pair_at).
@group(1) @binding(64) var<storage, read_write> tile_segments: array<u32>;
// Per tile: [2 tile] its count, [2 tile + 1] its first slot.
@group(1) @binding(65) var<storage, read> tile_ranges: array<u32>;
@group(1) @binding(66) var opaque_depth: texture_depth_2d;
// Premultiplied hair, blended front to back (for compose_hair_over).
@group(1) @binding(67) var hair: texture_storage_2d<rgba16float, write>;

const TILE: u32 = #{TILE_SIZE}u;
const THREADS: u32 = TILE * TILE;
// tile_size ≤ 16 and depth_bins ≤ 64 are checked at load (compute_raster.rs).
const MAX_BINS: u32 = 64u;

var<workgroup> bin_count: array<atomic<u32>, MAX_BINS>;
var<workgroup> bin_start: array<u32, 65>;
var<workgroup> key_range: array<atomic<u32>, 2>;
var<workgroup> finished: atomic<u32>;
var<workgroup> all_finished: u32;
// One chunk of a bin's segments (at most 64, so a pixel's set of them is two
// words), projected: screen xy (pixels), NDC z, clip w.
const CHUNK: u32 = min(THREADS, 64u);
const WORDS: u32 = (CHUNK + 31u) / 32u;
var<workgroup> chunk_a: array<vec4<f32>, CHUNK>;
var<workgroup> chunk_b: array<vec4<f32>, CHUNK>;
var<workgroup> chunk_segment: array<u32, CHUNK>;
var<workgroup> chunk_strand: array<u32, CHUNK>;
// The fragment alpha at the segment's first and second vertex (vertex_alpha).
var<workgroup> chunk_alpha: array<vec2<f32>, CHUNK>;
// The part of the segment drawn: its parameters at the near-plane clip (0, 1
// when it is not clipped).
var<workgroup> chunk_range: array<vec2<f32>, CHUNK>;
// A quad's (a wisp's, plait::compute_raster::wisp_quad; a wide strand
// segment's, plait::compute_raster::strand_quad) other two corners (a, b in
// chunk_a, chunk_b) and its corners' places along its segment (between its
// spine points).
var<workgroup> chunk_c: array<vec4<f32>, CHUNK>;
var<workgroup> chunk_d: array<vec4<f32>, CHUNK>;
var<workgroup> chunk_along: array<vec4<f32>, CHUNK>;
#ifndef GEOMETRY_WISPS
// A strand segment drawn as a quad (1; 0: a line), and its corners' signed
// distances from the centre line and half widths (StrandQuad's across, half).
var<workgroup> chunk_wide: array<u32, CHUNK>;
var<workgroup> chunk_across: array<vec4<f32>, CHUNK>;
var<workgroup> chunk_half: array<vec4<f32>, CHUNK>;
#endif
#ifdef GEOMETRY_WISPS
// Per spine point of a wisp quad the strand texture's v and mip level (x, y:
// v; z, w: level); chunk_alpha holds the spine points' hair alpha × tip
// fading.
var<workgroup> chunk_texture: array<vec4<f32>, CHUNK>;
// Where the quad lies along the strand its wisp follows, for strand-space
// shading: that strand's first hair vertex, and its spine points' indices
// along it — the loader's, so a strand-space pixel places no wisp vertex.
var<workgroup> chunk_first: array<u32, CHUNK>;
var<workgroup> chunk_point: array<vec2<f32>, CHUNK>;
#endif
// Per pixel of the tile, the chunk's segments that may cover it (bit k:
// segment k of the chunk), set by each segment's thread for the few pixels
// it reaches (cover_pixels). A pixel then visits only those, in chunk order
// (front to back). Testing every segment of the tile at every pixel was 95 %
// of tile_blend on a CPU rasterizer, where a lane that skips a segment still
// waits for the lanes beside it: the loop's trip count is what costs.
var<workgroup> pixel_segments: array<atomic<u32>, THREADS * WORDS>;

// The sort key: camera depth (clip w) of the segment's midpoint — of the
// part in front of the near plane when the segment is clipped there; of a
// wisp's quad (s: its first vertex), the mean of its corners'.
fn segment_key(s: u32) -> f32 {
#ifdef GEOMETRY_WISPS
    let q = wisp_quad(s);
    return max(0.25 * (q.corner[0].w + q.corner[1].w + q.corner[2].w + q.corner[3].w), 0.0);
#else
    let p0 = hair_vertices[s].position;
    let p1 = hair_vertices[s + 1u].position;
    let seg = camera_segment(p0, p1);
    if (seg.t_start > 0.0 || seg.t_stop < 1.0) {
        return 0.5 * (seg.a.w + seg.b.w);
    }
    return max((frame.camera_view_proj * vec4<f32>(0.5 * (p0 + p1), 1.0)).w, 0.0);
#endif
}

// The word of slot `slot`'s (segment, key bits) pair in tile_segments.
fn pair_at(slot: u32) -> u32 {
    return params.binned_segments + 2u * slot;
}

// 1 if slot `slot`'s segment sorts before segment `s` of key bits `k`.
fn before(slot: u32, s: u32, k: u32) -> u32 {
    let other = tile_segments[pair_at(slot) + 1u];
    return select(0u, 1u, other < k || (other == k && tile_segments[pair_at(slot)] < s));
}

fn bin_of(key: f32, lo: f32, hi: f32, bins: u32) -> u32 {
    let f = (key - lo) / max(hi - lo, 1e-20);
    return min(u32(max(f, 0.0) * f32(bins)), bins - 1u);
}

// Where pixel centre `p` meets the line from a to b: x = the part of the
// pixel the one-pixel-wide line covers — a tent of the pixel centre's
// distance across the line, which sums to 1 / cos θ over the pixels of a
// column (θ: the line's angle to its major axis), the area of a
// one-pixel-wide band there, as a rasterized line of width 1 covers it —;
// y = t, the screen-space fraction along the line's major axis (half-open
// [0, 1), so the segments of a strand meet without counting a pixel twice).
fn line_coverage(p: vec2<f32>, a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    let d = b - a;
    var t: f32;
    var off: f32;
    if (abs(d.x) >= abs(d.y)) {
        if (abs(d.x) < 1e-6) {
            return vec2<f32>(0.0);
        }
        t = (p.x - a.x) / d.x;
        off = a.y + t * d.y - p.y;
    } else {
        t = (p.y - a.y) / d.y;
        off = a.x + t * d.x - p.x;
    }
    if (t < 0.0 || t >= 1.0) {
        return vec2<f32>(0.0);
    }
    // The distance across the line: the minor-axis offset × cos θ.
    let across = abs(off) * max(abs(d.x), abs(d.y)) / length(d);
    return vec2<f32>(max(1.0 - across, 0.0), t);
}

// Marks chunk segment `k` (the line from a to b) at every pixel of the tile
// at `origin` whose centre line_coverage may cover: per column (row) of the
// major axis inside the line's span, the rows (columns) whose centre lies
// within 1 / cos θ of the line, beyond which line_coverage's tent is zero —
// with a margin of 1/64 pixel, so rounding never loses a pixel the exact test
// would keep (the mark is a superset; line_coverage decides).
fn cover_pixels(k: u32, a: vec2<f32>, b: vec2<f32>, origin: vec2<f32>) {
    let d = b - a;
    let x_major = abs(d.x) >= abs(d.y);
    if (max(abs(d.x), abs(d.y)) < 1e-6) {
        return;
    }
    // (major, minor) coordinates relative to the tile's origin.
    let a_m = select(a.y - origin.y, a.x - origin.x, x_major);
    let a_n = select(a.x - origin.x, a.y - origin.y, x_major);
    let d_m = select(d.y, d.x, x_major);
    let d_n = select(d.x, d.y, x_major);
    let margin = 1.0 / 64.0;
    let reach = length(d) / abs(d_m) + margin;
    let lo = max(ceil(min(a_m, a_m + d_m) - 0.5 - margin), 0.0);
    let hi = min(floor(max(a_m, a_m + d_m) - 0.5 + margin), f32(TILE) - 1.0);
    let word = k / 32u;
    let bit = 1u << (k % 32u);
    for (var m = lo; m <= hi; m += 1.0) {
        let n = a_n + (m + 0.5 - a_m) / d_m * d_n;
        let n_lo = max(ceil(n - reach - 0.5), 0.0);
        let n_hi = min(floor(n + reach - 0.5), f32(TILE) - 1.0);
        for (var r = n_lo; r <= n_hi; r += 1.0) {
            let pixel = select(u32(m) * TILE + u32(r), u32(r) * TILE + u32(m), x_major);
            atomicOr(&pixel_segments[pixel * WORDS + word], bit);
        }
    }
}

// The fragment alpha at hair vertex `index` (before the material alpha), as
// plait::hair_fragment's vertex stage computes it: a line's weighed by the
// strand's width when it is thinner than a pixel (strand_coverage), a
// quad's not (its coverage is per pixel, quad_coverage).
fn vertex_alpha(v: HairPoint, index: u32, line: bool) -> f32 {
    let tip = strand_tip_scale(v.strand, index, 0.0);
    let coverage = select(1.0, strand_coverage(v.position, v.tangent, v.thickness), line);
    return strand_lod_alpha(v.alpha * coverage * tip, strand_lod_weight(v.strand));
}

// Marks chunk quad `k` (its corners in chunk_a … chunk_d) at every pixel of
// the tile at `origin` whose centre it covers (quad_depth, the inside test
// the pixel repeats): the pixels of its corners' box within the tile.
fn cover_quad(k: u32, origin: vec2<f32>) {
    let corners = array<vec4<f32>, 4>(chunk_a[k], chunk_b[k], chunk_c[k], chunk_d[k]);
    let a = corners[0];
    let b = corners[1];
    let c = corners[2];
    let d = corners[3];
    let box_lo = min(min(a.xy, b.xy), min(c.xy, d.xy)) - origin;
    let box_hi = max(max(a.xy, b.xy), max(c.xy, d.xy)) - origin;
    // Pixel centres x + 0.5 within the box, clamped to the tile before the
    // conversion (a corner can project far off the screen).
    let lo = max(ceil(box_lo - 0.5), vec2<f32>(0.0));
    let hi = min(floor(box_hi - 0.5), vec2<f32>(f32(TILE) - 1.0));
    let word = k / 32u;
    let bit = 1u << (k % 32u);
    for (var y = lo.y; y <= hi.y; y += 1.0) {
        for (var x = lo.x; x <= hi.x; x += 1.0) {
            if (quad_depth(origin + vec2<f32>(x, y) + 0.5, corners).x > 0.0) {
                let pixel = u32(y) * TILE + u32(x);
                atomicOr(&pixel_segments[pixel * WORDS + word], bit);
            }
        }
    }
}

#ifdef GEOMETRY_WISPS
// Straight colour and alpha of chunk quad k at (u across, `along` between
// its spine points), as plait::hair_fragment shades a wisp fragment there:
// the strand texture's texel at (u, v, level) gives the alpha (× the hair
// alpha and the material's) and multiplies the colour — the strand-space
// radiance at the fragment's place along the strand the wisp follows, or
// plait::hair_radiance of the hair's colour at the interpolated point.
fn shade_wisp(k: u32, u: f32, along: f32) -> vec4<f32> {
    let tex = chunk_texture[k];
    let texel = wisp_texel(u, mix(tex.x, tex.y, along), mix(tex.z, tex.w, along));
    let ends = chunk_alpha[k];
    let alpha = clamp(mix(ends.x, ends.y, along) * texel.a * frame.hair_color.a, 0.0, 1.0);
    if (alpha <= 0.0) {
        return vec4<f32>(0.0);
    }
    let points = chunk_point[k];
    // w ≥ 0: shaded in strand space (its tip fading is in chunk_alpha); a
    // constant of the provider, so the other path is compiled out.
    let shaded = strand_space_radiance(chunk_strand[k], chunk_first[k], mix(points.x, points.y, along));
    if (shaded.w >= 0.0) {
        return vec4<f32>(shaded.rgb * texel.rgb, alpha);
    }
    let first = chunk_segment[k];
    let a = wisp_vertex(first);
    let b = wisp_vertex(first + 1u);
    let c = wisp_vertex(first + 2u);
    let d = wisp_vertex(first + 3u);
    // The strip's point there (the quad is a flat parallelogram but for the
    // spine's turn: bilinear across its two triangles).
    let world = mix(mix(a.corner, b.corner, u), mix(c.corner, d.corner, u), along);
    let tangent = mix(a.tangent, c.tangent, along);
    let color = mix(a.color, c.color, along) * texel.rgb;
    let occlusion = mix(occlusion_at(wisp_hair_vertex(first)), occlusion_at(wisp_hair_vertex(first + 2u)), along);
    return vec4<f32>(hair_radiance(shadow_map, world, tangent, color, occlusion), alpha);
}
#else
// Straight colour and alpha of chunk line k at screen fraction t, weighed by
// `weight`.
fn shade_segment(k: u32, t: f32, a: vec4<f32>, b: vec4<f32>, weight: f32) -> vec4<f32> {
    // Perspective-correct fraction along the drawn (clipped) part (1/w is
    // linear on screen), then along the whole segment.
    let clipped = chunk_range[k];
    return shade_along(k, mix(clipped.x, clipped.y, (t / b.w) / ((1.0 - t) / a.w + t / b.w)), weight);
}

// Straight colour and alpha of chunk segment k at `along` it (0 at its
// first vertex), weighed by `weight`. The fragment alphas at the segment's
// two vertices (chunk_alpha) are the chunk loader's, once per segment, not
// once per pixel.
fn shade_along(k: u32, along: f32, weight: f32) -> vec4<f32> {
    let i0 = chunk_segment[k];
    let i1 = i0 + 1u;
    let ends = chunk_alpha[k];
    let alpha = clamp(mix(ends.x, ends.y, along) * frame.hair_color.a, 0.0, 1.0) * weight;
    // w ≥ 0: shaded in strand space (its tip fading is in chunk_alpha); a
    // constant of the provider, so the other path is compiled out.
    let shaded = strand_space_radiance(chunk_strand[k], i0, along);
    if (shaded.w >= 0.0) {
        return vec4<f32>(shaded.rgb, alpha);
    }
    let v0 = hair_vertices[i0];
    let v1 = hair_vertices[i1];
    let world = mix(v0.position, v1.position, along);
    // The smooth curve's tangent there, as the raster path shades about.
    let tangent = strand_curve_tangent(v0.position, v1.position, v0.tangent, v1.tangent, along);
    let color = mix(v0.color, v1.color, along);
    let occlusion = mix(occlusion_at(i0), occlusion_at(i1), along);
    return vec4<f32>(hair_radiance(shadow_map, world, tangent, color, occlusion), alpha);
}
#endif

@compute @workgroup_size(TILE, TILE)
fn main(
    @builtin(local_invocation_index) lid: u32,
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let bins = clamp(params.depth_bins, 1u, MAX_BINS);
    let tile = group.y * groups.x + group.x;
    // The tile's slots; those past the pool were never written (counted as
    // dropped by tile_scan).
    let base = tile_ranges[2u * tile + 1u];
    let held = params.binned_segments - min(base, params.binned_segments);
    if (lid < MAX_BINS) {
        atomicStore(&bin_count[lid], 0u);
    }
    if (lid == 0u) {
        atomicStore(&key_range[0], 0xffffffffu);
        atomicStore(&key_range[1], 0u);
        atomicStore(&finished, 0u);
    }
    // Counted until the invocation shows, at its end, that its loops ran to
    // completion (see the end of main).
    atomicAdd(&raster_counter[2], 1u);
    workgroupBarrier();
    let n = min(tile_ranges[2u * tile], held);

    // 1. Depth range, bin counts, placement, per-bin sort.
    for (var i = lid; i < n; i += THREADS) {
        let bits = bitcast<u32>(segment_key(tile_segments[base + i]));
        atomicMin(&key_range[0], bits);
        atomicMax(&key_range[1], bits);
    }
    workgroupBarrier();
    let lo = bitcast<f32>(atomicLoad(&key_range[0]));
    let hi = bitcast<f32>(atomicLoad(&key_range[1]));
    for (var i = lid; i < n; i += THREADS) {
        atomicAdd(&bin_count[bin_of(segment_key(tile_segments[base + i]), lo, hi, bins)], 1u);
    }
    workgroupBarrier();
    if (lid == 0u) {
        var sum = 0u;
        for (var b = 0u; b < bins; b++) {
            bin_start[b] = sum;
            sum += atomicLoad(&bin_count[b]);
            atomicStore(&bin_count[b], 0u);
        }
        bin_start[bins] = sum;
    }
    workgroupBarrier();
    for (var i = lid; i < n; i += THREADS) {
        let s = tile_segments[base + i];
        let key = segment_key(s);
        let b = bin_of(key, lo, hi, bins);
        let at = base + bin_start[b] + atomicAdd(&bin_count[b], 1u);
        tile_segments[pair_at(at)] = s;
        tile_segments[pair_at(at) + 1u] = bitcast<u32>(key);
    }
    storageBarrier();
    workgroupBarrier();
    // Each segment's place in its bin is its rank there: the bin's segments
    // before it by (key bits, segment) — a total order, so the sorted list is
    // the same every run whatever order the atomics placed them in. All
    // threads share the work (a thread per bin running an insertion sort,
    // quadratic in the bin, could spend lavapipe's loop budget alone).
    for (var i = lid; i < n; i += THREADS) {
        let s = tile_segments[pair_at(base + i)];
        let k = tile_segments[pair_at(base + i) + 1u];
        let b = bin_of(bitcast<f32>(k), lo, hi, bins);
        let first = bin_start[b];
        // Four of the bin's segments a lap: the same comparisons, a quarter
        // of the laps lavapipe counts against its loop budget.
        let last = bin_start[b + 1u];
        var rank = 0u;
        var j = first;
        for (; j + 4u <= last; j += 4u) {
            rank += before(base + j, s, k) + before(base + j + 1u, s, k)
                + before(base + j + 2u, s, k) + before(base + j + 3u, s, k);
        }
        for (; j < last; j++) {
            rank += before(base + j, s, k);
        }
        tile_segments[base + first + rank] = s;
    }
    storageBarrier();
    workgroupBarrier();

    // 2. Front to back, bin after bin, a chunk of projected segments at a time.
    let pixel = group.xy * TILE + local.xy;
    let size = vec2<u32>(frame.screen_size.xy);
    let inside = all(pixel < size);
    var opaque = 0.0;
    if (inside) {
        opaque = textureLoad(opaque_depth, pixel, 0);
    }
    let centre = vec2<f32>(pixel) + 0.5;
    var color = vec3<f32>(0.0);
    var alpha = 0.0;
    var done = !inside;
    if (done) {
        atomicAdd(&finished, 1u);
    }
    // The bins lie one after another in the sorted list, so the chunks run over
    // the tile's whole sorted list: a chunk per bin left most of each chunk
    // empty (a tile's bins hold a few segments each) and paid its barriers
    // 32 times over.
    let end = workgroupUniformLoad(&bin_start[bins]);
    for (var c = 0u; c < end; c += CHUNK) {
        for (var w = 0u; w < WORDS; w++) {
            atomicStore(&pixel_segments[lid * WORDS + w], 0u);
        }
        workgroupBarrier();
        let j = c + lid;
        if (lid < CHUNK && j < end) {
            let s = tile_segments[base + j];
#ifdef GEOMETRY_WISPS
            let q = wisp_quad(s);
            let a = wisp_vertex(s);
            let c = wisp_vertex(s + 2u);
            chunk_segment[lid] = s;
            chunk_strand[lid] = a.strand;
            // The hair alpha × the tip fading at each spine point, as the
            // hair draws' vertex stage (plait::hair_fragment) weighs it.
            let tips = vec2<f32>(strand_tip_scale(a.strand, a.first, a.point), strand_tip_scale(c.strand, c.first, c.point));
            chunk_alpha[lid] = vec2<f32>(a.alpha, c.alpha) * tips;
            chunk_texture[lid] = vec4<f32>(a.texture.y, c.texture.y, a.texture.z, c.texture.z);
            chunk_first[lid] = a.first;
            chunk_point[lid] = vec2<f32>(a.point, c.point);
            chunk_a[lid] = q.corner[0];
            chunk_b[lid] = q.corner[1];
            chunk_c[lid] = q.corner[2];
            chunk_d[lid] = q.corner[3];
            chunk_along[lid] = q.along;
            // A binned quad is always kept (the same computation binned it).
            if (q.kept) {
                cover_quad(lid, vec2<f32>(group.xy * TILE));
            }
#else
            let v0 = hair_vertices[s];
            let v1 = hair_vertices[s + 1u];
            // Clipped at the near plane as in strand_bin (tiles.wgsl).
            let seg = camera_segment(v0.position, v1.position);
            let a = seg.a;
            let e = seg.b;
            chunk_range[lid] = vec2<f32>(seg.t_start, seg.t_stop);
            chunk_segment[lid] = s;
            chunk_strand[lid] = v0.strand;
            // Wider than a pixel: the quad (the binning's test, so a binned
            // wide segment is a kept quad).
            let wide = strand_segment_is_wide(v0, v1);
            chunk_wide[lid] = select(0u, 1u, wide);
            chunk_alpha[lid] = vec2<f32>(vertex_alpha(v0, s, !wide), vertex_alpha(v1, s + 1u, !wide));
            if (wide) {
                let q = strand_quad(v0, v1);
                chunk_a[lid] = q.corner[0];
                chunk_b[lid] = q.corner[1];
                chunk_c[lid] = q.corner[2];
                chunk_d[lid] = q.corner[3];
                chunk_along[lid] = q.along;
                chunk_across[lid] = q.across;
                chunk_half[lid] = q.half;
                if (q.kept) {
                    cover_quad(lid, vec2<f32>(group.xy * TILE));
                }
            } else {
                chunk_a[lid] = a;
                chunk_b[lid] = e;
                cover_pixels(lid, a.xy, e.xy, vec2<f32>(group.xy * TILE));
            }
#endif
        }
        workgroupBarrier();
        for (var w = 0u; w < WORDS; w++) {
            var bits = atomicLoad(&pixel_segments[lid * WORDS + w]);
            loop {
                if (bits == 0u || done) {
                    break;
                }
                let k = w * 32u + firstTrailingBit(bits);
                bits &= bits - 1u;
#ifdef GEOMETRY_WISPS
                // x: covered, y: NDC z, z: u across, w: along.
                let hit = wisp_quad_hit(centre, chunk_a[k], chunk_b[k], chunk_c[k], chunk_d[k], chunk_along[k]);
                if (hit.x <= 0.0 || hit.y < 0.0 || hit.y >= opaque) {
                    continue;
                }
                let f = shade_wisp(k, hit.z, hit.w);
#else
                var f: vec4<f32>;
                if (chunk_wide[k] != 0u) {
                    // x: coverage, y: NDC z, z: along the segment.
                    let hit = strand_quad_hit(centre, chunk_a[k], chunk_b[k], chunk_c[k], chunk_d[k], chunk_along[k], chunk_across[k], chunk_half[k]);
                    if (hit.x <= 0.0 || hit.y < 0.0 || hit.y >= opaque) {
                        continue;
                    }
                    f = shade_along(k, hit.z, hit.x);
                } else {
                    let a = chunk_a[k];
                    let e = chunk_b[k];
                    let cover = line_coverage(centre, a.xy, e.xy);
                    let z = mix(a.z, e.z, cover.y);
                    if (cover.x <= 0.0 || z < 0.0 || z >= opaque) {
                        continue;
                    }
                    f = shade_segment(k, cover.y, a, e, cover.x);
                }
#endif
                color += (1.0 - alpha) * f.a * f.rgb;
                alpha += (1.0 - alpha) * f.a;
                if (alpha >= params.opacity_threshold) {
                    done = true;
                    atomicAdd(&finished, 1u);
                }
            }
        }
        workgroupBarrier();
        // 3. Every pixel of the tile opaque: the rest of the segments are hidden.
        if (lid == 0u) {
            all_finished = atomicLoad(&finished);
        }
        if (workgroupUniformLoad(&all_finished) >= THREADS) {
            break;
        }
    }
    if (inside) {
        textureStore(hair, pixel, vec4<f32>(color, alpha));
    }
    // lavapipe gives 8 invocations 65,535 loop iterations in all, then ends
    // every loop after its current iteration — silently, and with barriers
    // in the loops the rest of the workgroup may never write. Only an
    // invocation that gets here with budget left (plait::loop_budget, a last
    // loop of tile_size laps) takes itself off the count, so
    // raster_counter[2] counts every invocation that was cut short or never
    // got here, and the engine fails the frame.
    if (!loop_budget_spent(params.tile_size)) {
        atomicSub(&raster_counter[2], 1u);
    }
}
