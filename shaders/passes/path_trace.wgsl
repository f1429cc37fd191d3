enable wgpu_ray_query;
// plait's own path tracer (issue 48; pipelines/physical/path_traced.toml): one path
// per pixel per dispatch (the `path_trace` pass type dispatches this `spp`
// times a frame), added to `pt_sum`.
//
// The scene as Mitsuba 3 renders it from `plait export mitsuba` (issue 42),
// so the two are held to each other (tests/path_traced_gpu.rs):
// - camera rays through the pixel's square, uniformly (Mitsuba's box filter),
//   from the near plane of the scene's projection;
// - a strand is an opaque fibre, its segment a tapered swept sphere
//   (plait::strand_capsule) scattering by Chiang, Bitterli, Tappan & Burley
//   2016's BSDF (shaders/lib/chiang.wgsl, §3–4) about the segment's tangent
//   at the hit's own azimuthal offset h (the ray's signed distance from the
//   axis over the radius: Mitsuba's sin γ from the curve's true normal), the
//   absorption from the strand's colour (§4.2); a strand of alpha < 1 is
//   Mitsuba's `mask` of the export: scattered with probability alpha, else
//   passed straight through (a path vertex, as Mitsuba counts it);
// - a mesh (head, ground, [[meshes]]) is Lambertian with its albedo, about
//   its interpolated normal (black from behind, as Mitsuba's one-sided
//   `diffuse`);
// - next-event estimation toward the key light at every scattering vertex,
//   its shadow ray stopped by any strand or mesh (Mitsuba's fibres are
//   opaque surfaces; their transmission is the BSDF's TT);
// - a ray that escapes returns the ambient radiance (a constant
//   environment), a camera ray the background (Mitsuba's hidden emitters and
//   render.py's background behind alpha);
// - max_depth as Mitsuba's: a path has at most max_depth vertices after the
//   camera, the last the light or the environment (2: single scattering);
//   no Russian roulette (the depth bounds the loop).
// The fibre is importance-sampled as Chiang et al. 2016 §4.3 describe
// (sample_fibre); a mesh by cosine.
#import plait::frame::{frame, background_at}
#import plait::strand_rays::{vis_hair, nearest_hit, ray_blocked, NearestHit}
#import plait::chiang::{Fibre, fibre, longitudinal_lobes, offset_term, fresnel_dielectric, trimmed_logistic}
#import plait::loop_budget::loop_budget_spent

struct PathParams {
    // Dispatches this frame (the pass type's; the shader counts its own).
    spp: u32,
    max_depth: u32,
    seed: u32,
    chiang_beta_m: f32,
    chiang_beta_n: f32,
    chiang_tilt: f32,
    chiang_eta: f32,
}

@group(1) @binding(0) var<uniform> path_params: PathParams;
// Per pixel two vec4: (radiance sum, camera rays that met something), then
// (samples so far, camera rays whose first hit is a strand, 0, 0): the
// hair's coverage, which tests/path_traced_gpu.rs reads back to find the
// hair's pixels. Cleared once a frame, before the first sample.
@group(1) @binding(1) var<storage, read_write> pt_sum: array<vec4<f32>>;
// [0]: invocations lavapipe's loop budget cut short (`incomplete`).
@group(1) @binding(2) var<storage, read_write> pt_status: array<atomic<u32>>;
// The meshes' vertices (10 f32: position, normal, albedo, head), their
// indices, and per mesh (first index, index count, head, 0).
@group(1) @binding(3) var<storage, read> opaque_vertices: array<f32>;
@group(1) @binding(4) var<storage, read> opaque_indices: array<u32>;
@group(1) @binding(5) var<storage, read> opaque_meshes: array<vec4<u32>>;

const PI: f32 = 3.14159265358979;
const NONE: u32 = 0xffffffffu;
// How far a ray leaving a mesh starts off its surface (world units; the
// scenes are a few units across).
const MESH_OFFSET: f32 = 1e-4;

var<private> rng: u32;

// PCG's output permutation (O'Neill 2014) as a hash.
fn pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A uniform number in [0, 1).
fn random() -> f32 {
    rng = pcg(rng);
    return f32(rng >> 8u) * (1.0 / 16777216.0);
}

fn cosine_about(n: vec3<f32>) -> vec3<f32> {
    let r = sqrt(random());
    let a = 2.0 * PI * random();
    let up = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(n.x) > 0.5);
    let u = normalize(cross(up, n));
    let v = cross(n, u);
    return normalize(r * cos(a) * u + r * sin(a) * v + sqrt(max(0.0, 1.0 - r * r)) * n);
}

// Direction towards the key light from `p` and its irradiance there (on a
// surface facing it), w = the distance the shadow ray may go.
struct LightSample {
    dir: vec3<f32>,
    irradiance: vec3<f32>,
    far: f32,
}

fn key_light(p: vec3<f32>) -> LightSample {
    if (frame.light_direction.w > 0.5) {
        // A spot light: the export's point emitter of radiant intensity
        // light_color (docs/formats.md, "Light and units").
        let d = frame.light_position.xyz - p;
        let dist = length(d);
        return LightSample(d / dist, frame.light_color.rgb / (dist * dist), dist);
    }
    return LightSample(normalize(frame.light_direction.xyz), frame.light_color.rgb, 1e30);
}

// The fibre's Σ_p M_p A_p N_p for the eye (the path's previous vertex) along
// `wo` and the light along `wi`, at offset h about unit `tangent`: radiance
// towards wo per unit irradiance from wi (chiang.wgsl's offset_term, one h).
fn fibre_term(f: Fibre, tangent: vec3<f32>, h: f32, wo: vec3<f32>, wi: vec3<f32>) -> vec3<f32> {
    let sin_o = clamp(dot(wo, tangent), -1.0, 1.0);
    let sin_i = clamp(dot(wi, tangent), -1.0, 1.0);
    let o_perp = wo - sin_o * tangent;
    let i_perp = wi - sin_i * tangent;
    // φ = φi − φo about the tangent, signed as h is (h > 0 on the side
    // cross(o_perp, tangent) points to; R then peaks at φ = −2γo).
    let phi = atan2(dot(i_perp, cross(tangent, o_perp)), dot(i_perp, o_perp));
    let m = longitudinal_lobes(f, sin_i, sin_o);
    return offset_term(f, m, vec4<f32>(1.0), sin_o, phi, asin(clamp(h, -1.0, 1.0)));
}

// The fibre's importance sampling, after Chiang et al. 2016 §4.3 (as
// pbrt-v3's HairBSDF::Sample_f samples it): a lobe p by its attenuation
// A_p(h) (the channels' mean), θi from d'Eon et al. 2011's M_p about θo
// rotated by the lobe's tilt (exactly: M_p is a von Mises–Fisher lobe seen
// along θ), φ from the trimmed logistic N_p about Φ(p, h); p ≥ 3 uniform in
// φ. Angles about the tangent in the frame (e1 = wo across the fibre, e2 =
// tangent × e1), where φ is fibre_term's φi − φo.
struct FibreFrame {
    tangent: vec3<f32>,
    e1: vec3<f32>,
    e2: vec3<f32>,
}

fn fibre_frame(tangent: vec3<f32>, wo: vec3<f32>) -> FibreFrame {
    var e1 = wo - dot(wo, tangent) * tangent;
    if (dot(e1, e1) < 1e-12) {
        let up = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(tangent.x) > 0.5);
        e1 = cross(up, tangent);
    }
    e1 = normalize(e1);
    return FibreFrame(tangent, e1, cross(tangent, e1));
}

// A_0 … A_3 at h for the eye at sin θo: each channel's mean, and the
// azimuthal centres Φ(p, h) of N_0 … N_2 (w unused).
struct Lobes {
    weights: vec4<f32>,
    centres: vec4<f32>,
}

fn fibre_lobes(f: Fibre, sin_o: f32, h: f32) -> Lobes {
    let cos_o = sqrt(max(0.0, 1.0 - sin_o * sin_o));
    let sin_t = sin_o / f.eta;
    let cos_t = sqrt(max(0.0, 1.0 - sin_t * sin_t));
    let eta_p = sqrt(f.eta * f.eta - sin_o * sin_o) / max(cos_o, 1e-6);
    let gamma_o = asin(clamp(h, -1.0, 1.0));
    let sin_gt = clamp(h / eta_p, -1.0, 1.0);
    let gamma_t = asin(sin_gt);
    let t = exp(-f.sigma_a * (2.0 * cos(gamma_t) / max(cos_t, 1e-6)));
    let fr = fresnel_dielectric(cos_o * cos(gamma_o), f.eta);
    let a1 = (1.0 - fr) * (1.0 - fr) * t;
    let a2 = a1 * fr * t;
    let a3 = a2 * fr * t / (vec3<f32>(1.0) - t * fr);
    let mean = vec4<f32>(fr, dot(a1, vec3<f32>(1.0 / 3.0)), dot(a2, vec3<f32>(1.0 / 3.0)), dot(a3, vec3<f32>(1.0 / 3.0)));
    let centres = vec4<f32>(-2.0 * gamma_o, 2.0 * gamma_t - 2.0 * gamma_o + PI, 4.0 * gamma_t - 2.0 * gamma_o + 2.0 * PI, 0.0);
    return Lobes(mean / max(mean.x + mean.y + mean.z + mean.w, 1e-12), centres);
}

// The density of sample_fibre's direction wi (per solid angle).
fn fibre_pdf(f: Fibre, frame_: FibreFrame, lobes: Lobes, sin_o: f32, wi: vec3<f32>) -> f32 {
    let sin_i = clamp(dot(wi, frame_.tangent), -1.0, 1.0);
    let phi = atan2(dot(wi, frame_.e2), dot(wi, frame_.e1));
    let m = longitudinal_lobes(f, sin_i, sin_o);
    var pdf = m.w * lobes.weights.w / (2.0 * PI);
    pdf += m.x * lobes.weights.x * trimmed_logistic(f, phi - lobes.centres.x);
    pdf += m.y * lobes.weights.y * trimmed_logistic(f, phi - lobes.centres.y);
    pdf += m.z * lobes.weights.z * trimmed_logistic(f, phi - lobes.centres.z);
    return pdf;
}

fn sample_fibre(f: Fibre, frame_: FibreFrame, lobes: Lobes, sin_o: f32) -> vec3<f32> {
    let cos_o = sqrt(max(0.0, 1.0 - sin_o * sin_o));
    let u = random();
    var p = 3u;
    var tilt = 0.0;
    var variance = 4.0 * f.v;
    var centre = 0.0;
    if (u < lobes.weights.x) {
        p = 0u;
        tilt = 2.0 * f.alpha;
        variance = f.v;
        centre = lobes.centres.x;
    } else if (u < lobes.weights.x + lobes.weights.y) {
        p = 1u;
        tilt = -f.alpha;
        variance = 0.25 * f.v;
        centre = lobes.centres.y;
    } else if (u < lobes.weights.x + lobes.weights.y + lobes.weights.z) {
        p = 2u;
        tilt = -4.0 * f.alpha;
        centre = lobes.centres.z;
    }
    // θo as the lobe sees it (chiang.wgsl's longitudinal_lobes' rotation).
    let sin_op = sin_o * cos(tilt) + cos_o * sin(tilt);
    let cos_op = abs(cos_o * cos(tilt) - sin_o * sin(tilt));
    // d'Eon's lobe about −θo': its angle from the centre, and its azimuth.
    let u1 = max(random(), 1e-7);
    let cos_lobe = 1.0 + variance * log(u1 + (1.0 - u1) * exp(-2.0 / variance));
    let sin_lobe = sqrt(max(0.0, 1.0 - cos_lobe * cos_lobe));
    let around = cos(2.0 * PI * random());
    let sin_i = clamp(-cos_lobe * sin_op + sin_lobe * around * cos_op, -1.0, 1.0);
    let cos_i = sqrt(max(0.0, 1.0 - sin_i * sin_i));
    var phi = 2.0 * PI * random();
    if (p < 3u) {
        // The logistic of scale s trimmed to [−π, π], by its inverse CDF.
        let lo = 1.0 / (1.0 + exp(PI / f.s));
        let hi = 1.0 / (1.0 + exp(-PI / f.s));
        let c = clamp(lo + random() * (hi - lo), 1e-7, 1.0 - 1e-7);
        phi = centre - f.s * log(1.0 / c - 1.0);
    }
    return normalize(sin_i * frame_.tangent + cos_i * (cos(phi) * frame_.e1 + sin(phi) * frame_.e2));
}

// One opaque vertex's float `k` of 10.
fn vertex_float(v: u32, k: u32) -> f32 {
    return opaque_vertices[v * 10u + k];
}

fn vertex_vec3(v: u32, k: u32) -> vec3<f32> {
    return vec3<f32>(vertex_float(v, k), vertex_float(v, k + 1u), vertex_float(v, k + 2u));
}

// A mesh hit's shading normal, face normal (both world, unit) and albedo.
struct MeshPoint {
    normal: vec3<f32>,
    face: vec3<f32>,
    albedo: vec3<f32>,
}

fn mesh_point(hit: NearestHit) -> MeshPoint {
    let mesh = opaque_meshes[hit.instance - 1u];
    let first = mesh.x + 3u * hit.primitive;
    let i0 = opaque_indices[first];
    let i1 = opaque_indices[first + 1u];
    let i2 = opaque_indices[first + 2u];
    let b = vec3<f32>(1.0 - hit.barycentrics.x - hit.barycentrics.y, hit.barycentrics);
    let n = b.x * vertex_vec3(i0, 3u) + b.y * vertex_vec3(i1, 3u) + b.z * vertex_vec3(i2, 3u);
    let p0 = vertex_vec3(i0, 0u);
    let face = cross(vertex_vec3(i1, 0u) - p0, vertex_vec3(i2, 0u) - p0);
    let albedo = b.x * vertex_vec3(i0, 6u) + b.y * vertex_vec3(i1, 6u) + b.z * vertex_vec3(i2, 6u);
    // The head's instance moves it rigidly: its matrix turns normals too.
    let m = hit.object_to_world;
    return MeshPoint(normalize(m * vec4<f32>(n, 0.0)), normalize(m * vec4<f32>(face, 0.0)), albedo);
}

// The camera ray through `pixel` (pixels, y down): from the near plane
// through the far plane of the scene's projection.
struct Ray {
    origin: vec3<f32>,
    dir: vec3<f32>,
}

fn camera_ray(pixel: vec2<f32>) -> Ray {
    let ndc = vec2<f32>(pixel.x * frame.screen_size.z * 2.0 - 1.0, 1.0 - pixel.y * frame.screen_size.w * 2.0);
    let near = frame.camera_inv_view_proj * vec4<f32>(ndc, 0.0, 1.0);
    let far = frame.camera_inv_view_proj * vec4<f32>(ndc, 1.0, 1.0);
    let a = near.xyz / near.w;
    return Ray(a, normalize(far.xyz / far.w - a));
}

// The radiance one path brings to `pixel`, and what its camera ray met
// first (w: 0 nothing, 1 a mesh, 2 a strand).
fn trace_path(pixel: vec2<f32>) -> vec4<f32> {
    var ray = camera_ray(pixel);
    var near = 0.0;
    var skip = NONE;
    var throughput = vec3<f32>(1.0);
    var radiance = vec3<f32>(0.0);
    var covered = 0.0;
    let max_depth = path_params.max_depth;
    for (var depth = 1u; depth <= max_depth; depth++) {
        let hit = nearest_hit(ray.origin, ray.dir, near, 1e30, skip);
        if (depth == 1u) {
            covered = select(f32(hit.kind), 3.0 - f32(hit.kind), hit.kind != 0u);
        }
        if (hit.kind == 0u) {
            if (depth == 1u) {
                radiance += background_at(pixel);
            } else {
                radiance += throughput * frame.ambient.rgb;
            }
            break;
        }
        // A vertex at max_depth ends the path: light it reaches would be
        // one vertex more.
        if (depth == max_depth) {
            break;
        }
        let p = ray.origin + hit.t * ray.dir;
        let wo = -ray.dir;
        let light = key_light(p);
        if (hit.kind == 1u) {
            let a = vis_hair[hit.primitive];
            let b = vis_hair[hit.primitive + 1u];
            let axis = b.position - a.position;
            // The strand's own tangent (root to tip, the curve's direction
            // at the points, as plait's shading and the export's B-spline
            // take it), not the chord: the cuticle tilt's side depends on it.
            let s_axis = clamp(dot(ray.origin + hit.t * ray.dir - a.position, axis) / dot(axis, axis), 0.0, 1.0);
            let tangent = normalize(mix(a.tangent, b.tangent, s_axis));
            // Where along the segment the ray passes the axis, and on which
            // side: h = the signed distance over the radius there.
            let s = clamp(dot(p - a.position, axis) / dot(axis, axis), 0.0, 1.0);
            let radius = max(0.5 * mix(a.thickness, b.thickness, s), 1e-12);
            let o_perp = wo - dot(wo, tangent) * tangent;
            let side = normalize(cross(o_perp, tangent));
            let h = dot(p - (a.position + s * axis), side) / radius;
            let alpha = mix(a.alpha, b.alpha, s);
            let f = fibre(path_params.chiang_beta_m, path_params.chiang_beta_n, path_params.chiang_tilt, path_params.chiang_eta, mix(a.color, b.color, s));
            if (!ray_blocked(p, light.dir, 0.0, light.far, hit.primitive)) {
                radiance += throughput * alpha * fibre_term(f, tangent, h, wo, light.dir) * light.irradiance;
            }
            skip = hit.primitive;
            near = 0.0;
            if (random() < alpha) {
                let sin_o = clamp(dot(wo, tangent), -1.0, 1.0);
                let frame_ = fibre_frame(tangent, wo);
                let lobes = fibre_lobes(f, sin_o, h);
                let wi = sample_fibre(f, frame_, lobes, sin_o);
                let pdf = fibre_pdf(f, frame_, lobes, sin_o, wi);
                if (pdf <= 0.0) {
                    break;
                }
                throughput *= fibre_term(f, tangent, h, wo, wi) / pdf;
                ray = Ray(p, wi);
            } else {
                // Mitsuba's mask: straight through, a vertex of the path.
                ray = Ray(p, ray.dir);
            }
        } else {
            let m = mesh_point(hit);
            if (dot(m.normal, wo) <= 0.0) {
                break;
            }
            let face = select(-m.face, m.face, dot(m.face, wo) > 0.0);
            let origin = p + MESH_OFFSET * face;
            let cos_l = dot(m.normal, light.dir);
            if (cos_l > 0.0 && !ray_blocked(origin, light.dir, 0.0, light.far, NONE)) {
                radiance += throughput * m.albedo / PI * cos_l * light.irradiance;
            }
            throughput *= m.albedo;
            ray = Ray(origin, cosine_about(m.normal));
            skip = NONE;
            near = 0.0;
        }
        // Russian roulette from the fifth vertex on, as Mitsuba's path
        // integrator (rr_depth 5): unbiased, and long paths of light hair
        // cost less.
        if (depth >= 5u) {
            let q = min(max(throughput.x, max(throughput.y, throughput.z)), 0.95);
            if (random() >= q) {
                break;
            }
            throughput /= q;
        }
        if (all(throughput <= vec3<f32>(0.0))) {
            break;
        }
    }
    return vec4<f32>(radiance, covered);
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let width = u32(frame.screen_size.x);
    let pixels = width * u32(frame.screen_size.y);
    let i = id.x;
    if (i >= pixels || 2u * i + 1u >= arrayLength(&pt_sum)) {
        return;
    }
    let counts = pt_sum[2u * i + 1u];
    let count = counts.x;
    // A fresh stream per pixel, sample, seed and frame.
    rng = pcg(i ^ pcg(u32(count) ^ pcg(path_params.seed ^ pcg(u32(frame.jitter.w)))));
    let pixel = vec2<f32>(f32(i % width) + random(), f32(i / width) + random());
    let sample = trace_path(pixel);
    pt_sum[2u * i] += vec4<f32>(sample.rgb, min(sample.w, 1.0));
    pt_sum[2u * i + 1u] = vec4<f32>(count + 1.0, counts.y + select(0.0, 1.0, sample.w > 1.5), 0.0, 0.0);
    if (loop_budget_spent(path_params.max_depth + 2u)) {
        atomicAdd(&pt_status[0], 1u);
    }
}
