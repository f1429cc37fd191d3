enable wgpu_ray_query;
// transparency = ray_traced, ray_trace: one primary ray per pixel, through
// its centre from the eye, collects the nearest `layers` strand hits in
// front of the opaque depth in order (an insertion sort into the pixel's
// slots of ray_hits), then blends them front to back,
//   C += (1 − A) · α · rgb,  A += (1 − A) · α,
// into the premultiplied `hair` image compose_hair_over puts over the scene.
//
// Coverage, as plait's rasterized hair covers a pixel (docs/formats.md,
// "Strand coverage"): the ray stands for its pixel, a box one pixel wide
// across the strand. Its candidates come from the structure of the widened
// vertices (widen.wgsl); a candidate segment is a hit where the ray passes
// its axis within half the strand's true width + half a pixel, and the hit
// covers the part of the pixel's box the strand's true width overlaps —
// plait::strand_coverage::quad_coverage, the quad draw's coverage: a strand
// narrower than a pixel covers width ÷ pixel near its axis (as its
// rasterized line does) and less at its edges, its sum across the strand
// its width in pixels; a wider one covers its band. (With strand coverage
// off every strand is the rasterizer's one-pixel line of coverage 1.) The
// hit's α is the fragment alpha every hair draw uses — the strand's alpha ×
// that coverage × its tip fading, widened by the level of detail, × the
// material alpha — and its colour the strand-space shading buffer's, or
// plait::hair_radiance at the axis point (the chosen shading, self-shadow,
// lighting, occlusion and multiple scattering), as compute_raster's
// tile_blend shades a fragment.
//
// Order: by the ray distance of the ray's closest approach to each axis —
// along one ray, the order of the rasterized fragments' depths.
// Hits past `layers` are not blended: counted in ray_counter[0] (the
// technique's overflow: while ray_layers is its default the session raises
// it until every hit is held; a value the user sets is a cap, reported).
#import plait::frame::frame
#import plait::hair_radiance::hair_radiance
#import plait::ambient_occlusion::occlusion_at
#import plait::shading_space::strand_space_radiance
#import plait::strand_coverage::{strand_width_pixels, strand_tip_scale, quad_coverage}
#import plait::strand_lod::{strand_lod_weight, strand_lod_alpha}
#import plait::hair_point::HairPoint
#import plait::strand_curve::strand_curve_tangent
#import plait::strand_capsule::strand_approach
#import plait::strand_dots::dots_crossing
#import plait::loop_budget::loop_budget_spent

struct Params {
    layers: u32,
}

@group(1) @binding(0) var shadow_map: texture_depth_2d;
@group(1) @binding(60) var<uniform> params: Params;
@group(1) @binding(61) var<storage, read> hair_vertices: array<HairPoint>;
// The structure of the widened vertices (widen.wgsl): a binding of its own,
// not plait::strand_rays' vis_strands, which self_shadow = ray_traced binds
// to the structure of the true widths in the same shader.
@group(1) @binding(62) var primary_strands: acceleration_structure;
// Per pixel `layers` slots of (ray distance bits, segment), nearest first.
@group(1) @binding(63) var<storage, read_write> ray_hits: array<u32>;
// [0] hits past `layers` (not blended), [1] the slots that would hold every
// pixel's hits (its most hits × pixels), [2] invocations lavapipe's loop
// budget cut short (the frame fails).
@group(1) @binding(64) var<storage, read_write> ray_counter: array<atomic<u32>>;
@group(1) @binding(65) var opaque_depth: texture_depth_2d;
@group(1) @binding(66) var hair: texture_storage_2d<rgba16float, write>;
// The widened vertices primary_strands was built from (widen.wgsl): with
// `ray_strand_primitive = "dots"` a segment is four triangles, and which of
// its reported triangles counts it is decided on the quads as built.
@group(1) @binding(67) var<storage, read> primary_vertices: array<HairPoint>;

// A candidate segment where the ray meets it: its place along the segment
// and its fragment alpha there (0: no hit), at ray distance t (−1: none).
struct Hit {
    t: f32,
    along: f32,
    alpha: f32,
}

const MISS: Hit = Hit(-1.0, 0.0, 0.0);

// Segment `s` (hair vertices s, s + 1) as the ray from the eye along `dir`
// sees it, with the pixel's `opaque` depth.
fn hit_segment(origin: vec3<f32>, dir: vec3<f32>, s: u32, opaque: f32) -> Hit {
    let v0 = hair_vertices[s];
    let v1 = hair_vertices[s + 1u];
    if (v0.strand != v1.strand) {
        return MISS;
    }
    let weight = strand_lod_weight(v0.strand);
    if (weight <= 0.0) {
        return MISS;
    }
    let approach = strand_approach(origin, dir, v0.position, v1.position);
    if (approach.x <= 0.0) {
        return MISS;
    }
    let along = approach.y;
    let world = mix(v0.position, v1.position, along);
    // The rasterized fragment's depth test ("less" than the opaque depth,
    // in front of the near plane), at the axis point.
    let clip = frame.camera_view_proj * vec4<f32>(world, 1.0);
    if (clip.w <= 0.0 || clip.z < 0.0 || clip.z / clip.w >= opaque) {
        return MISS;
    }
    // Pixels per world unit across the view there (as widen.wgsl).
    let tangent = mix(v0.tangent, v1.tangent, along);
    let probe = 1e-3 * max(distance(frame.camera_position.xyz, world), 1e-6);
    let scale = strand_width_pixels(world, tangent, probe) / probe;
    if (scale <= 0.0) {
        return MISS;
    }
    let across = approach.z * scale;
    var cover: f32;
    if (frame.conventions.z < 0.5) {
        cover = select(0.0, 1.0, across < 0.5);
    } else {
        cover = quad_coverage(vec2<f32>(across, 0.5 * mix(v0.thickness, v1.thickness, along) * scale));
    }
    let tip = strand_tip_scale(v0.strand, s, along);
    let alpha = strand_lod_alpha(mix(v0.alpha, v1.alpha, along) * cover * tip, weight);
    let a = clamp(alpha * frame.hair_color.a, 0.0, 1.0);
    if (a <= 0.0) {
        return MISS;
    }
    return Hit(approach.x, along, a);
}

// Whether the ray crosses the DOTS quads of segment `s` (of the widened
// vertices), which the structure then reports itself.
fn dots_crossed(origin: vec3<f32>, dir: vec3<f32>, s: u32) -> bool {
    let w0 = primary_vertices[s];
    let w1 = primary_vertices[s + 1u];
    return w0.strand == w1.strand
        && dots_crossing(origin, dir, w0.position, 0.5 * w0.thickness, w1.position, 0.5 * w1.thickness).y >= 0.0;
}

// The segment a DOTS crossing of segment `s` is a hit of: `s`, or the
// neighbour of the same strand whose stretch of the axis holds the ray's
// closest approach (hit_segment's owner, plait::strand_capsule) when the
// ray, oblique to the strand near a joint, crosses `s`'s quads but passes
// nearest the neighbour's axis — unless the ray crosses the neighbour's own
// quads, which are reported and counted themselves.
fn dots_owner(origin: vec3<f32>, dir: vec3<f32>, s: u32) -> u32 {
    let a = primary_vertices[s].position;
    let e = primary_vertices[s + 1u].position - a;
    let w = origin - a;
    let de = dot(dir, e);
    let denom = dot(e, e) - de * de;
    if (denom <= 1e-8 * dot(e, e)) {
        return s;
    }
    let along = (dot(e, w) - de * dot(dir, w)) / denom;
    let strand = primary_vertices[s].strand;
    if (along < 0.0 && s > 0u && primary_vertices[s - 1u].strand == strand && !dots_crossed(origin, dir, s - 1u)) {
        return s - 1u;
    }
    let next = s + 2u < arrayLength(&primary_vertices) && primary_vertices[s + 2u].strand == strand;
    if (along >= 1.0 && next && !dots_crossed(origin, dir, s + 1u)) {
        return s + 1u;
    }
    return s;
}

// Hits the ray met (held or not), for the overflow count.
var<private> met: u32;

// The ray's nearest `layers` hits into the pixel's slots from `base`, nearest
// first; returns how many it holds. The ray query is declared here, in a
// function and outside any loop (one declared in a loop made naga emit a
// null constant of the ray-query type, which Mesa rejects: wgpu PR 9945).
fn collect(origin: vec3<f32>, dir: vec3<f32>, base: u32, opaque: f32) -> u32 {
    var rq: ray_query;
    // Mask 1: the strands' instances only (STRAND_INSTANCES in
    // plait::strand_rays); the structure also holds the scene's meshes as
    // triangle instances (mask 2), which the opaque depth already stands for.
    rayQueryInitialize(&rq, primary_strands, RayDesc(RAY_FLAG_FORCE_NO_OPAQUE, 1u, 0.0, 1e30, origin, dir));
    let layers = params.layers;
    var held = 0u;
    met = 0u;
    while (rayQueryProceed(&rq)) {
        let c = rayQueryGetCandidateIntersection(&rq);
        // A box is segment i (swept spheres); with DOTS, triangles
        // 4i … 4i + 3 are, and only the first the ray crosses counts it
        // (plait::strand_dots: one hit per segment, as one box gives).
        let dots = c.kind == RAY_QUERY_INTERSECTION_TRIANGLE;
        if (c.kind != RAY_QUERY_INTERSECTION_AABB && !dots) {
            continue;
        }
        var s = select(c.primitive_index, c.primitive_index / 4u, dots);
        if (dots) {
            let w0 = primary_vertices[s];
            let w1 = primary_vertices[s + 1u];
            let first = dots_crossing(origin, dir, w0.position, 0.5 * w0.thickness, w1.position, 0.5 * w1.thickness);
            if (w0.strand != w1.strand || first.y != f32(c.primitive_index % 4u)) {
                continue;
            }
            s = dots_owner(origin, dir, s);
        }
        let h = hit_segment(origin, dir, s, opaque);
        if (h.t <= 0.0) {
            continue;
        }
        met += 1u;
        // Insert by distance: the farthest held hit falls out when all are
        // taken (counted by `met` > held).
        var j = held;
        if (held == layers) {
            if (h.t >= bitcast<f32>(ray_hits[2u * (base + layers - 1u)])) {
                continue;
            }
            j = layers - 1u;
        } else {
            held += 1u;
        }
        loop {
            if (j == 0u) {
                break;
            }
            let before = bitcast<f32>(ray_hits[2u * (base + j - 1u)]);
            // Ties by segment, so the order is the same every run.
            if (before < h.t || (before == h.t && ray_hits[2u * (base + j - 1u) + 1u] < s)) {
                break;
            }
            ray_hits[2u * (base + j)] = ray_hits[2u * (base + j - 1u)];
            ray_hits[2u * (base + j) + 1u] = ray_hits[2u * (base + j - 1u) + 1u];
            j -= 1u;
        }
        ray_hits[2u * (base + j)] = bitcast<u32>(h.t);
        ray_hits[2u * (base + j) + 1u] = s;
    }
    return held;
}

// Straight colour of segment s at `along`, as compute_raster's tile_blend
// shades its fragment there.
fn shade(s: u32, along: f32) -> vec3<f32> {
    let v0 = hair_vertices[s];
    let v1 = hair_vertices[s + 1u];
    // w ≥ 0: shaded in strand space; a constant of the provider.
    let shaded = strand_space_radiance(v0.strand, s, along);
    if (shaded.w >= 0.0) {
        return shaded.rgb;
    }
    let world = mix(v0.position, v1.position, along);
    let tangent = strand_curve_tangent(v0.position, v1.position, v0.tangent, v1.tangent, along);
    let color = mix(v0.color, v1.color, along);
    let occlusion = mix(occlusion_at(s), occlusion_at(s + 1u), along);
    return hair_radiance(shadow_map, world, tangent, color, occlusion);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<u32>(frame.screen_size.xy);
    if (any(id.xy >= size)) {
        return;
    }
    // Counted until the invocation shows, at its end, that its loops ran to
    // completion.
    atomicAdd(&ray_counter[2], 1u);
    let pixel = id.xy;
    let opaque = textureLoad(opaque_depth, pixel, 0);
    // The ray from the eye through the pixel's centre (y down on screen).
    let centre = (vec2<f32>(pixel) + 0.5) * frame.screen_size.zw;
    let ndc = vec4<f32>(2.0 * centre.x - 1.0, 1.0 - 2.0 * centre.y, 0.5, 1.0);
    let far = frame.camera_inv_view_proj * ndc;
    let origin = frame.camera_position.xyz;
    let dir = normalize(far.xyz / far.w - origin);
    let layers = params.layers;
    let base = (pixel.y * size.x + pixel.x) * layers;
    let held = collect(origin, dir, base, opaque);
    if (met > held) {
        atomicAdd(&ray_counter[0], met - held);
        let pixels = size.x * size.y;
        atomicMax(&ray_counter[1], min(met, 0xffffffffu / pixels) * pixels);
    }
    var color = vec3<f32>(0.0);
    var alpha = 0.0;
    for (var j = 0u; j < held; j++) {
        let s = ray_hits[2u * (base + j) + 1u];
        let h = hit_segment(origin, dir, s, opaque);
        let a = (1.0 - alpha) * h.alpha;
        color += a * shade(s, h.along);
        alpha += a;
    }
    textureStore(hair, pixel, vec4<f32>(color, alpha));
    // lavapipe ends an invocation's loops silently once 8 invocations have
    // run 65,535 iterations (plait::loop_budget): only an invocation that
    // gets here with budget left takes itself off the count.
    if (!loop_budget_spent(layers)) {
        atomicSub(&ray_counter[2], 1u);
    }
}
