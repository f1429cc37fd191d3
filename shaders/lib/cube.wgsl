// plait::cube — cube maps and equirectangular images as plait lays them out
// (the CPU twin is plait_hair::environment::{cube, image}; tests compare the
// two). Six faces +x, −x, +y, −y, +z, −z with the Vulkan / Direct3D
// orientation, side by side in one 6n × n atlas texture (face f's texel
// (x, y) at (f·n + x, y)). Equirectangular (u, v): φ = 2π(u − ½), θ = πv,
// d = (sin θ sin φ, cos θ, −sin θ cos φ).
#define_import_path plait::cube

const PI: f32 = 3.14159265358979;

// Direction through face `face` at s, t ∈ [−1, 1] (s right, t down); not normalized.
fn cube_direction(face: u32, s: f32, t: f32) -> vec3<f32> {
    switch face {
        case 0u: { return vec3<f32>(1.0, -t, -s); }
        case 1u: { return vec3<f32>(-1.0, -t, s); }
        case 2u: { return vec3<f32>(s, 1.0, t); }
        case 3u: { return vec3<f32>(s, -1.0, -t); }
        case 4u: { return vec3<f32>(s, -t, 1.0); }
        default: { return vec3<f32>(-s, -t, -1.0); }
    }
}

struct CubeCoord {
    face: u32,
    s: f32,
    t: f32,
}

// The inverse of cube_direction.
fn cube_face_of(d: vec3<f32>) -> CubeCoord {
    let a = abs(d);
    if (a.x >= a.y && a.x >= a.z) {
        if (d.x > 0.0) {
            return CubeCoord(0u, -d.z / a.x, -d.y / a.x);
        }
        return CubeCoord(1u, d.z / a.x, -d.y / a.x);
    }
    if (a.y >= a.z) {
        if (d.y > 0.0) {
            return CubeCoord(2u, d.x / a.y, d.z / a.y);
        }
        return CubeCoord(3u, d.x / a.y, -d.z / a.y);
    }
    if (d.z > 0.0) {
        return CubeCoord(4u, d.x / a.z, -d.y / a.z);
    }
    return CubeCoord(5u, -d.x / a.z, -d.y / a.z);
}

// Unit direction through the centre of atlas texel `texel` of a cube of n × n faces.
fn cube_texel_direction(texel: vec2<u32>, n: u32) -> vec3<f32> {
    let face = texel.x / n;
    let s = 2.0 * (f32(texel.x % n) + 0.5) / f32(n) - 1.0;
    let t = 2.0 * (f32(texel.y) + 0.5) / f32(n) - 1.0;
    return normalize(cube_direction(face, s, t));
}

fn cube_corner_area(s: f32, t: f32) -> f32 {
    return atan2(s * t, sqrt(1.0 + s * s + t * t));
}

// Solid angle of texel (x, y) of an n × n face: the integral of
// (1 + s² + t²)^(−3/2) over it (the six faces sum to 4π).
fn cube_texel_solid_angle(n: u32, x: u32, y: u32) -> f32 {
    let s0 = 2.0 * f32(x) / f32(n) - 1.0;
    let s1 = 2.0 * f32(x + 1u) / f32(n) - 1.0;
    let t0 = 2.0 * f32(y) / f32(n) - 1.0;
    let t1 = 2.0 * f32(y + 1u) / f32(n) - 1.0;
    return cube_corner_area(s1, t1) - cube_corner_area(s0, t1) - cube_corner_area(s1, t0) + cube_corner_area(s0, t0);
}

// Equirectangular (u, v) of a unit direction.
fn equirect_uv(d: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(0.5 + atan2(d.x, -d.z) / (2.0 * PI), acos(clamp(d.y, -1.0, 1.0)) / PI);
}

// Bilinear read of atlas map `map` (rows map·n …) of cube maps at a unit
// direction, clamped at the face's edges.
fn cube_atlas_sample(atlas: texture_2d<f32>, map: u32, d: vec3<f32>) -> vec4<f32> {
    let n = textureDimensions(atlas).x / 6u;
    let c = cube_face_of(d);
    let f = vec2<f32>((c.s + 1.0) * 0.5, (c.t + 1.0) * 0.5) * f32(n) - 0.5;
    let f0 = floor(f);
    let a = f - f0;
    let last = i32(n) - 1;
    let x0 = clamp(i32(f0.x), 0, last);
    let x1 = clamp(i32(f0.x) + 1, 0, last);
    let y0 = clamp(i32(f0.y), 0, last);
    let y1 = clamp(i32(f0.y) + 1, 0, last);
    let ox = i32(c.face * n);
    let oy = i32(map * n);
    let v00 = textureLoad(atlas, vec2<i32>(ox + x0, oy + y0), 0);
    let v10 = textureLoad(atlas, vec2<i32>(ox + x1, oy + y0), 0);
    let v01 = textureLoad(atlas, vec2<i32>(ox + x0, oy + y1), 0);
    let v11 = textureLoad(atlas, vec2<i32>(ox + x1, oy + y1), 0);
    return mix(mix(v00, v10, a.x), mix(v01, v11, a.x), a.y);
}
