// plait::self_shadow::density_volume — self-shadowing from the hair density
// volume (plait::density_volume): the expected number n of strands between
// a point and the key light, n = ∫ λ ds, λ = q / V^(1/3) the strands
// crossed per world unit; visibility = exp(−w · n), w = shadow_weight — the
// convention of exact self-shadowing, whose n is Σ share of the fragments in
// front (one strand across the ray: n = 1).
// n is integrated exactly, voxel by voxel, once a frame from every voxel's
// centre (density_light.wgsl, plait::density_march) into `vis_toward`; a
// point reads it trilinearly where the ray from it (moved the self-shadow
// bias toward the light, "In front of", docs/design.md) meets the volume: at
// the point inside it, at the entry outside it (the head, the ground: the
// volume's outer voxels hold no hair, so n there is the entry's). The point's
// own strand is not excluded beyond the bias: its voxel's density is spread
// over the neighbouring centres' values.
#define_import_path plait::self_shadow::density_volume

#import plait::frame::frame
#import plait::density_volume::{DensityBox, density_box_from, density_cell, density_clip, density_index, density_to_light}

@group(1) @binding(10) var<storage, read> vis_box: array<f32, 8>;
@group(1) @binding(11) var<storage, read> vis_toward: array<f32>;

struct VisibilityParams {
    // Opacity added by one strand in front (w of Sintorn & Assarsson 2009 §3.3).
    shadow_weight: f32,
}
@group(1) @binding(15) var<uniform> visibility_params: VisibilityParams;

fn toward_at(b: DensityBox, v: vec3<i32>) -> f32 {
    let r = i32(b.res) - 1;
    return vis_toward[density_index(b, vec3<u32>(clamp(v, vec3<i32>(0), vec3<i32>(r))))];
}

// n at grid coordinate g (voxel centres at i + 0.5), trilinear; constant
// past the outer centres.
fn toward_trilinear(b: DensityBox, g: vec3<f32>) -> f32 {
    let c = clamp(g - 0.5, vec3<f32>(0.0), vec3<f32>(f32(b.res) - 1.0));
    let i = vec3<i32>(floor(c));
    let f = c - floor(c);
    let x00 = mix(toward_at(b, i), toward_at(b, i + vec3<i32>(1, 0, 0)), f.x);
    let x10 = mix(toward_at(b, i + vec3<i32>(0, 1, 0)), toward_at(b, i + vec3<i32>(1, 1, 0)), f.x);
    let x01 = mix(toward_at(b, i + vec3<i32>(0, 0, 1)), toward_at(b, i + vec3<i32>(1, 0, 1)), f.x);
    let x11 = mix(toward_at(b, i + vec3<i32>(0, 1, 1)), toward_at(b, i + vec3<i32>(1, 1, 1)), f.x);
    return mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

// Expected number of strands between `world` and the key light.
fn strands_toward(world: vec3<f32>) -> f32 {
    let b = density_box_from(vis_box);
    if (b.res == 0u) {
        return 0.0;
    }
    let to_light = density_to_light(world, frame.light_direction, frame.light_position);
    let bias = frame.conventions.x * (frame.near_far.w - frame.near_far.z);
    let cell = density_cell(b);
    let g0 = (world + to_light * bias - b.lo) / cell;
    let d = to_light / cell;
    let span = density_clip(g0, d, f32(b.res));
    let t0 = max(span.x, 0.0);
    if (span.y <= t0) {
        return 0.0;
    }
    return toward_trilinear(b, g0 + d * t0);
}

fn hair_visibility(world: vec3<f32>) -> f32 {
    return exp(-visibility_params.shadow_weight * strands_toward(world));
}

// The strands in front of and behind the point (the self_shadow point's
// optional function): the volume's count at the point, and its count from beyond the hair
// less that from just past the point's own strand (two biases behind it), along the
// light's ray — `plait::frame::light_behind`'s span, as a count toward the
// light from both ends.
fn hair_strands_along_light(world: vec3<f32>) -> vec2<f32> {
    let bias = frame.conventions.x * (frame.near_far.w - frame.near_far.z);
    let away = -density_to_light(world, frame.light_direction, frame.light_position);
    let through = strands_toward(world + away * (2.0 * bias));
    let beyond = strands_toward(world + away * (2.0 * frame.hair_sphere.w + 2.0 * bias));
    return vec2<f32>(strands_toward(world), max(beyond - through, 0.0));
}
