// occlusion_directions: per-vertex ambient occlusion from deep opacity maps
// rendered from N directions on the sphere (Xing et al. 2012 §4, Fig. 4). The
// paper runs it offline and stores the summed transmittance per vertex; plait
// runs it as a GPU precompute in the graph. Two kernels of one file, picked by
// a define (the pass `occlusion_directions` records them, crates/plait-passes/
// src/occlusion_directions.rs):
//
// - AO_FRAMES: one workgroup finds the hair's bounding sphere and writes, per
//   direction, a copy of the frame whose light is an orthographic view along
//   that direction fitted to the sphere, so the depth-range and deep-opacity
//   kernels of self-shadowing (shaders/passes/depth_range.wgsl,
//   shaders/passes/deep_opacity.wgsl) and the deep-opacity provider run
//   unchanged from it;
// - otherwise (gather): after the maps of one direction, each vertex adds its
//   transmittance from the provider `plait::self_shadow::deep_opacity`
//   (exp(-w · hair in front), "in front of" as in docs/design.md) divided by N.
//   One thread per vertex, dispatches in order: the sum is deterministic.
//
// Directions: the paper samples 100 random points on the sphere; plait takes a
// spherical Fibonacci lattice of N points (deterministic and evenly spread, so
// the error against more directions falls steadily).
#import plait::frame::{Frame, frame}
#ifdef AO_FRAMES
#import plait::hair_bounds::{BOUNDS_GROUP, workgroup_bounds}
#else
#import plait::self_shadow::deep_opacity::hair_visibility
#endif

struct HairVertex {
    position: vec3<f32>,
    thickness: f32,
    tangent: vec3<f32>,
    alpha: f32,
    color: vec3<f32>,
    strand_id: u32,
}

// One direction's frame, padded to 768 bytes so each can be bound as the
// frame uniform at a 256-byte aligned offset (Frame is 752 bytes since it
// holds head_model, head_model_previous, hair_sphere and hair_width).
struct DirectionFrame {
    uniforms: Frame,
    pad: vec4<f32>,
}

struct AoParams {
    directions: u32,
}

@group(1) @binding(0) var<storage, read> hair_vertices: array<HairVertex>;
@group(1) @binding(1) var<storage, read_write> direction_frames: array<DirectionFrame>;
// Ambient visibility per hair vertex: 1 = unoccluded.
@group(1) @binding(2) var<storage, read_write> vertex_ao: array<f32>;
@group(1) @binding(3) var<uniform> ao_params: AoParams;

// Point `i` of the spherical Fibonacci lattice of `n` points, +Y the pole.
fn lattice_direction(i: u32, n: u32) -> vec3<f32> {
    let y = 1.0 - (2.0 * f32(i) + 1.0) / f32(n);
    let ring = sqrt(max(1.0 - y * y, 0.0));
    // The golden angle, 2π(1 - 1/φ).
    let phi = f32(i) * 2.399963229728653;
    return vec3<f32>(ring * cos(phi), y, ring * sin(phi));
}

#ifdef AO_FRAMES

// The frame with its light replaced by an orthographic view towards `b`
// (unit, from the scene towards the light) around the sphere (`center`,
// `radius`); matrices as glam's look_at_rh and orthographic_rh build them.
fn direction_frame(b: vec3<f32>, center: vec3<f32>, radius: f32) -> Frame {
    var f = frame;
    var hint = vec3<f32>(0.0, 1.0, 0.0);
    if (abs(b.y) > 0.99) {
        hint = vec3<f32>(1.0, 0.0, 0.0);
    }
    let s = normalize(cross(hint, b));
    let u = cross(b, s);
    let near = radius;
    let far = 3.0 * radius;
    let eye = center + b * (2.0 * radius);
    let view = mat4x4<f32>(
        vec4<f32>(s.x, u.x, b.x, 0.0),
        vec4<f32>(s.y, u.y, b.y, 0.0),
        vec4<f32>(s.z, u.z, b.z, 0.0),
        vec4<f32>(-dot(s, eye), -dot(u, eye), -dot(b, eye), 1.0),
    );
    let span = far - near;
    let proj = mat4x4<f32>(
        vec4<f32>(1.0 / radius, 0.0, 0.0, 0.0),
        vec4<f32>(0.0, 1.0 / radius, 0.0, 0.0),
        vec4<f32>(0.0, 0.0, -1.0 / span, 0.0),
        vec4<f32>(0.0, 0.0, -near / span, 1.0),
    );
    let inv_view = mat4x4<f32>(vec4<f32>(s, 0.0), vec4<f32>(u, 0.0), vec4<f32>(b, 0.0), vec4<f32>(eye, 1.0));
    let inv_proj = mat4x4<f32>(
        vec4<f32>(radius, 0.0, 0.0, 0.0),
        vec4<f32>(0.0, radius, 0.0, 0.0),
        vec4<f32>(0.0, 0.0, -span, 0.0),
        vec4<f32>(0.0, 0.0, -near, 1.0),
    );
    // The self-shadow bias stays the same in world units (docs/design.md).
    let bias_world = frame.conventions.x * (frame.near_far.w - frame.near_far.z);
    f.light_view = view;
    f.light_view_proj = proj * view;
    f.light_inv_view_proj = inv_view * inv_proj;
    f.light_direction = vec4<f32>(b, 0.0);
    f.light_position = vec4<f32>(eye, 0.0);
    f.near_far = vec4<f32>(frame.near_far.xy, near, far);
    // No lookup jitter: every vertex reads the texel it falls in. Strand
    // coverage as the scene has it (z): a direction's texel is blocked by
    // each strand's share of it (plait::hair_map::map_weight, issue 47), as
    // in the self-shadow maps, so ambient occlusion follows strand width;
    // with coverage off every fragment blocks a whole texel, Xing et al.'s
    // counts.
    f.conventions = vec4<f32>(bias_world / span, 0.0, frame.conventions.z, frame.conventions.w);
    return f;
}

@compute @workgroup_size(256)
fn main(@builtin(local_invocation_index) t: u32) {
    let n = arrayLength(&hair_vertices);
    var a = vec3<f32>(3.0e38);
    var z = vec3<f32>(-3.0e38);
    for (var i = t; i < n; i += BOUNDS_GROUP) {
        let p = hair_vertices[i].position;
        a = min(a, p);
        z = max(z, p);
    }
    let box = workgroup_bounds(t, a, z);
    let center = (box.lo + box.hi) * 0.5;
    // A margin of 1% and a floor keep the outermost hair off the map's edge
    // and a single point from a zero-size view.
    let radius = max(length(box.hi - box.lo) * 0.5 * 1.01, 1e-3);
    let count = min(ao_params.directions, arrayLength(&direction_frames));
    for (var d = t; d < count; d += BOUNDS_GROUP) {
        direction_frames[d].uniforms = direction_frame(lattice_direction(d, ao_params.directions), center, radius);
    }
}
#else
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&hair_vertices) || i >= arrayLength(&vertex_ao)) {
        return;
    }
    let transmittance = hair_visibility(hair_vertices[i].position);
    vertex_ao[i] += transmittance / f32(ao_params.directions);
}
#endif
