// sim_verlet.wgsl — guide strands as chains of nodes (Halén & Wester 2007 §4,
// §4.4, §5.9), one thread per guide strand, `substeps` fixed steps a frame:
//
// 1. Verlet integration (4.1): P' = P + k·(P − P_prev) + Δt²·F, unit mass.
//    F = gravity + wind + the §4.4 spring towards the node's reference
//    position: its rest position moved with the head, displaced upward by
//    g / k_L so that gravity and spring cancel at rest. k_L falls off along
//    the strand, k_L = k / (1 + c·L)² (§5.9's quadratic reduction, written
//    with 1 + c·L so the root is finite), and is reduced as the head tilts
//    (§4.4: k_m = ((z·z_h + 1) / 2)(k − α) + α, α = spring_min · k_L).
// 2. `iterations` sweeps of the length constraints (4.2), root to tip: a
//    segment whose parent is the pinned root moves only its child, any other
//    moves both ends by half — each sweep followed by collisions with the
//    head's ellipsoids (a node inside is moved out along the ellipsoid's
//    radius) and with the head mesh's signed distance field (a node where
//    the trilinear distance d < 0 is moved by −d along the field's
//    gradient, onto the surface). Roots are pinned to the head.
// 3. Faults, once per frame: a non-finite node or a strand longer than
//    `max_stretch` × its rest length sets a flag and the strand's index in
//    `status` (read back by the pass after the frame).
#import plait::frame::frame
#import plait::loop_budget::loop_budget_spent

struct SimParams {
    time_step: f32,
    damping: f32,
    gravity: f32,
    spring: f32,
    spring_min: f32,
    spring_falloff: f32,
    wind: vec3<f32>,
    turbulence: f32,
    max_stretch: f32,
    substeps: u32,
    iterations: u32,
}

struct Collider {
    center: vec4<f32>,
    radii: vec4<f32>,
}

@group(1) @binding(0) var<uniform> sim_params: SimParams;
@group(1) @binding(1) var<storage, read> guide_rest: array<vec4<f32>>;
@group(1) @binding(2) var<storage, read> guide_strands: array<vec2<u32>>;
@group(1) @binding(3) var<storage, read> head_colliders: array<Collider>;
@group(1) @binding(4) var<storage, read_write> guide_positions: array<vec4<f32>>;
@group(1) @binding(5) var<storage, read_write> guide_previous: array<vec4<f32>>;
// [0]: fault flags (1 non-finite, 2 stretched, 4 cut short: lavapipe's loop
// budget, 65,535 iterations per group of 8 invocations for all their loops,
// ran out — substeps × iterations × points is past it); [1]: 0xffffffff − the first
// faulty strand (atomicMax of a zeroed buffer finds the smallest index);
// [2]: the stretch of that kind in thousandths.
@group(1) @binding(6) var<storage, read_write> status: array<atomic<u32>>;
// The head mesh's distance field at rest (plait_hair::sdf's layout):
// [0..3] origin, [3] cell, [4..7] dims as u32 bits, [7] 1 if present,
// then the distances, x fastest.
@group(1) @binding(7) var<storage, read> head_sdf: array<f32>;

const UP: vec3<f32> = vec3<f32>(0.0, 1.0, 0.0);

// The head's pose at fraction `t` of this frame, between last frame's and
// this frame's `head_model` (the scene's [animation]): the columns are
// interpolated and re-orthonormalised, so it stays rigid.
fn head_model(t: f32) -> mat4x4<f32> {
    let a = frame.head_model_previous;
    let b = frame.head_model;
    let x = normalize(mix(a[0].xyz, b[0].xyz, t));
    let y0 = mix(a[1].xyz, b[1].xyz, t);
    let y = normalize(y0 - dot(y0, x) * x);
    let z = cross(x, y);
    return mat4x4<f32>(
        vec4<f32>(x, 0.0),
        vec4<f32>(y, 0.0),
        vec4<f32>(z, 0.0),
        vec4<f32>(mix(a[3].xyz, b[3].xyz, t), 1.0),
    );
}

fn finite(v: vec3<f32>) -> bool {
    // By bits: a NaN test by comparison may be optimised away.
    let e = bitcast<vec3<u32>>(v) & vec3<u32>(0x7f800000u);
    return all(e != vec3<u32>(0x7f800000u));
}

// A smooth pseudo-random field in [-1, 1]³ that drifts with time: gusts.
fn gust(p: vec3<f32>, time: f32) -> vec3<f32> {
    return vec3<f32>(
        sin(dot(p, vec3<f32>(1.7, 2.3, 1.1)) + time * 2.1),
        sin(dot(p, vec3<f32>(2.9, 0.7, 1.9)) + time * 1.3),
        sin(dot(p, vec3<f32>(1.3, 1.9, 2.7)) + time * 1.7),
    );
}

// Moves `p` out of every collider (posed by `model`): the ellipsoids along
// their radius, then the head mesh's distance field.
fn collide(p: vec3<f32>, model: mat4x4<f32>) -> vec3<f32> {
    let rotation = mat3x3<f32>(model[0].xyz, model[1].xyz, model[2].xyz);
    let translation = model[3].xyz;
    var q = transpose(rotation) * (p - translation);
    for (var c = 0u; c < arrayLength(&head_colliders); c++) {
        let shape = head_colliders[c];
        if (any(shape.radii.xyz <= vec3<f32>(0.0))) {
            continue;
        }
        let e = (q - shape.center.xyz) / shape.radii.xyz;
        let d = length(e);
        if (d < 1.0 && d > 1e-6) {
            q = shape.center.xyz + e / d * shape.radii.xyz;
        }
    }
    q = collide_sdf(q);
    return rotation * q + translation;
}

fn sdf_dims() -> vec3<u32> {
    return vec3<u32>(bitcast<u32>(head_sdf[4]), bitcast<u32>(head_sdf[5]), bitcast<u32>(head_sdf[6]));
}

fn sdf_at(i: vec3<u32>, dims: vec3<u32>) -> f32 {
    return head_sdf[8u + i.x + dims.x * (i.y + dims.y * i.z)];
}

// Trilinear distance at grid coordinates `g` (clamped into the grid).
fn sdf_sample(g: vec3<f32>, dims: vec3<u32>) -> f32 {
    let top = vec3<f32>(dims) - vec3<f32>(1.0);
    let c = clamp(g, vec3<f32>(0.0), top);
    let base = min(floor(c), max(top - vec3<f32>(1.0), vec3<f32>(0.0)));
    let f = c - base;
    let b = vec3<u32>(base);
    let x00 = mix(sdf_at(b, dims), sdf_at(b + vec3<u32>(1u, 0u, 0u), dims), f.x);
    let x10 = mix(sdf_at(b + vec3<u32>(0u, 1u, 0u), dims), sdf_at(b + vec3<u32>(1u, 1u, 0u), dims), f.x);
    let x01 = mix(sdf_at(b + vec3<u32>(0u, 0u, 1u), dims), sdf_at(b + vec3<u32>(1u, 0u, 1u), dims), f.x);
    let x11 = mix(sdf_at(b + vec3<u32>(0u, 1u, 1u), dims), sdf_at(b + vec3<u32>(1u, 1u, 1u), dims), f.x);
    return mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

// Moves `q` (head rest space) out of the head mesh: by −d along the
// gradient (central differences over half a cell) where the distance d < 0.
// Outside the grid nothing is inside (the grid reaches past the mesh).
fn collide_sdf(q: vec3<f32>) -> vec3<f32> {
    if (arrayLength(&head_sdf) < 8u || head_sdf[7] != 1.0) {
        return q;
    }
    let dims = sdf_dims();
    let origin = vec3<f32>(head_sdf[0], head_sdf[1], head_sdf[2]);
    let cell = head_sdf[3];
    let g = (q - origin) / cell;
    if (any(g < vec3<f32>(0.0)) || any(g > vec3<f32>(dims) - vec3<f32>(1.0))) {
        return q;
    }
    let d = sdf_sample(g, dims);
    if (d >= 0.0) {
        return q;
    }
    let h = 0.5;
    let grad = vec3<f32>(
        sdf_sample(g + vec3<f32>(h, 0.0, 0.0), dims) - sdf_sample(g - vec3<f32>(h, 0.0, 0.0), dims),
        sdf_sample(g + vec3<f32>(0.0, h, 0.0), dims) - sdf_sample(g - vec3<f32>(0.0, h, 0.0), dims),
        sdf_sample(g + vec3<f32>(0.0, 0.0, h), dims) - sdf_sample(g - vec3<f32>(0.0, 0.0, h), dims),
    );
    let len = length(grad);
    if (len <= 1e-12) {
        return q;
    }
    return q - d * grad / len;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = id.x;
    if (s >= arrayLength(&guide_strands)) {
        return;
    }
    let first = guide_strands[s].x;
    let count = guide_strands[s].y;
    let p = sim_params;
    let dt = p.time_step;
    for (var step = 0u; step < p.substeps; step++) {
        let model = head_model(f32(step + 1u) / f32(p.substeps));
        let head_up = normalize((model * vec4<f32>(UP, 0.0)).xyz);
        let tilt = (dot(UP, head_up) + 1.0) * 0.5;
        let time = frame.jitter.z + f32(step) * dt;
        // 1. Verlet
        var arc = 0.0;
        for (var k = 0u; k < count; k++) {
            let i = first + k;
            let rest = guide_rest[i];
            arc += rest.w;
            let anchor = (model * vec4<f32>(rest.xyz, 1.0)).xyz;
            if (k == 0u) {
                guide_positions[i] = vec4<f32>(anchor, 0.0);
                guide_previous[i] = vec4<f32>(anchor, 0.0);
                continue;
            }
            let now = guide_positions[i].xyz;
            let before = guide_previous[i].xyz;
            var force = vec3<f32>(0.0, -p.gravity, 0.0);
            force += p.wind * (vec3<f32>(1.0) + p.turbulence * gust(now, time));
            let k_l = p.spring / ((1.0 + p.spring_falloff * arc) * (1.0 + p.spring_falloff * arc));
            if (k_l > 0.0) {
                let k_m = tilt * (k_l - p.spring_min * k_l) + p.spring_min * k_l;
                let reference = anchor + UP * (p.gravity / k_l);
                force += k_m * (reference - now);
            }
            let next = now + p.damping * (now - before) + dt * dt * force;
            guide_previous[i] = vec4<f32>(now, 0.0);
            guide_positions[i] = vec4<f32>(next, 0.0);
        }
        // 2. Length constraints and collisions
        for (var it = 0u; it < p.iterations; it++) {
            for (var k = 1u; k < count; k++) {
                let i = first + k;
                let a = guide_positions[i - 1u].xyz;
                let b = guide_positions[i].xyz;
                let d = b - a;
                let len = length(d);
                if (len <= 0.0) {
                    continue;
                }
                let fix = (1.0 - guide_rest[i].w / len) * d;
                if (k == 1u) {
                    guide_positions[i] = vec4<f32>(b - fix, 0.0);
                } else {
                    guide_positions[i - 1u] = vec4<f32>(a + 0.5 * fix, 0.0);
                    guide_positions[i] = vec4<f32>(b - 0.5 * fix, 0.0);
                }
            }
            for (var k = 1u; k < count; k++) {
                let i = first + k;
                guide_positions[i] = vec4<f32>(collide(guide_positions[i].xyz, model), 0.0);
            }
        }
        if (p.iterations == 0u) {
            for (var k = 1u; k < count; k++) {
                let i = first + k;
                guide_positions[i] = vec4<f32>(collide(guide_positions[i].xyz, model), 0.0);
            }
        }
    }
    // 3. Faults
    var length_now = 0.0;
    var length_rest = 0.0;
    var flags = 0u;
    for (var k = 0u; k < count; k++) {
        let i = first + k;
        let x = guide_positions[i].xyz;
        if (!finite(x)) {
            flags |= 1u;
        }
        if (k > 0u) {
            length_now += length(x - guide_positions[i - 1u].xyz);
            length_rest += guide_rest[i].w;
        }
    }
    if (flags == 0u && length_now > p.max_stretch * length_rest) {
        flags |= 2u;
    }
    // Last: did every loop above run to its end? (`substeps` ≥ 1 is a
    // uniform, so the canary loop cannot be unrolled away.)
    if (loop_budget_spent(p.substeps + 1u)) {
        flags |= 4u;
    }
    if (flags != 0u) {
        atomicOr(&status[0], flags);
        atomicMax(&status[1], 0xffffffffu - s);
        if ((flags & 3u) == 2u) {
            atomicMax(&status[2], u32(min(length_now / max(length_rest, 1e-20), 4e6) * 1000.0));
        }
    }
}
