// environment_cube — the scene's environment image averaged over the texels
// of a small cube (the 16×16×6 of Xing et al. 2012 §5): what the irradiance
// maps, their SH projection and the brute-force reference all sum. One thread
// per atlas texel; `samples` × `samples` bilinear reads of the
// equirectangular `environment_source` per texel, after turning it by
// `rotate` degrees about +y (a shift of u, as plait_hair's
// EnvironmentImage::rotated). Alpha holds the texel's solid angle.
#import plait::cube::{cube_direction, cube_texel_solid_angle, equirect_uv}

@group(1) @binding(0) var environment_source: texture_2d<f32>;
@group(1) @binding(1) var cube: texture_storage_2d<rgba32float, write>;

struct EnvironmentParams {
    rotate: f32,
    samples: u32,
}
@group(1) @binding(2) var<uniform> environment_params: EnvironmentParams;

fn source_texel(x: i32, y: i32, size: vec2<i32>) -> vec3<f32> {
    let wrapped = ((x % size.x) + size.x) % size.x;
    return textureLoad(environment_source, vec2<i32>(wrapped, clamp(y, 0, size.y - 1)), 0).rgb;
}

// Bilinear, wrapping in u, clamped in v (as LinearImage::bilinear).
fn radiance(d: vec3<f32>) -> vec3<f32> {
    let size = vec2<i32>(textureDimensions(environment_source));
    let uv = equirect_uv(d) + vec2<f32>(environment_params.rotate / 360.0, 0.0);
    let f = uv * vec2<f32>(size) - 0.5;
    let f0 = floor(f);
    let a = f - f0;
    let x = i32(f0.x);
    let y = i32(f0.y);
    return mix(
        mix(source_texel(x, y, size), source_texel(x + 1, y, size), a.x),
        mix(source_texel(x, y + 1, size), source_texel(x + 1, y + 1, size), a.x),
        a.y,
    );
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(cube);
    if (id.x >= dims.x || id.y >= dims.y) {
        return;
    }
    let n = dims.y;
    let face = id.x / n;
    let x = id.x % n;
    let k = max(environment_params.samples, 1u);
    var sum = vec3<f32>(0.0);
    for (var j = 0u; j < k; j++) {
        for (var i = 0u; i < k; i++) {
            let s = 2.0 * (f32(x) + (f32(i) + 0.5) / f32(k)) / f32(n) - 1.0;
            let t = 2.0 * (f32(id.y) + (f32(j) + 0.5) / f32(k)) / f32(n) - 1.0;
            sum += radiance(normalize(cube_direction(face, s, t)));
        }
    }
    textureStore(cube, id.xy, vec4<f32>(sum / f32(k * k), cube_texel_solid_angle(n, x, id.y)));
}
