// plait::multiple_scattering::karis — Karis 2016's approximation of
// multiple scattering (techniques/multiple_scattering/karis/technique.toml):
// a wrap-lit diffuse term added to the fibre model's lobes, shadowed like
// the direct light (Unreal multiplies the whole hair BSDF by the
// transmission shadow; its `Shadow` input tints the term).
#define_import_path plait::multiple_scattering::karis

struct MultipleScatteringParams {
    karis_scatter: f32,
}
@group(1) @binding(70) var<uniform> multiple_scattering_params: MultipleScatteringParams;

const PI: f32 = 3.14159265358979;

// The term per unit irradiance, unshadowed but tinted by `shadow`.
fn karis_term(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>, shadow: f32, scatter: f32) -> vec3<f32> {
    let kajiya_diffuse = 1.0 - abs(dot(tangent, to_light));
    // The fake normal: the eye direction projected normal to the strand.
    let fake_normal = normalize(to_eye - tangent * dot(to_eye, tangent));
    // Wrap lighting, wrap 1: (N'·L + 1) / (1 + 1)², saturated.
    let wrap = clamp((dot(fake_normal, to_light) + 1.0) / 4.0, 0.0, 1.0);
    let diffuse_scatter = (1.0 / PI) * mix(wrap, kajiya_diffuse, 0.33) * scatter;
    // A channel of 0 has √base = 0, so the term is 0 whatever the tint; the
    // floors only keep WGSL's pow (exp2(y·log2 x)) off 0⁰ = NaN and 0/0. At
    // 1e-30 they bind only for a black base: a floor of 1e-6 on the luma
    // replaced the formula's tint for any base darker than that (0.26× for
    // the blond colour × 1e-7, tests/karis.rs).
    let luma = max(dot(base, vec3<f32>(0.3, 0.59, 0.11)), 1e-30);
    let tint = pow(max(base / luma, vec3<f32>(1e-30)), vec3<f32>(1.0 - shadow));
    return sqrt(base) * diffuse_scatter * tint;
}

fn hair_multiple_scattering(world: vec3<f32>, tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>, hair_visibility: f32) -> vec3<f32> {
    let s = multiple_scattering_params.karis_scatter;
    return hair_visibility * karis_term(tangent, to_light, to_eye, base, hair_visibility, s);
}
