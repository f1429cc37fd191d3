// plait::lighting::irradiance_maps — environment light from Kajiya-Kay
// irradiance maps (Xing et al. 2012 §3). The maps come from
// `techniques/lighting/irradiance_maps/technique.toml` (summed directly) or
// `sh_irradiance_maps.toml` (rebuilt from SH, §5): one atlas, diffuse map
// then M + 1 specular maps, M read from its height.
//
// With `shading = "kajiya_kay"` (or no shading named: the point's default)
// the paper's lookup: the diffuse map and the two specular maps around θ′
// (the angle between the tangent and the eye, shifted by the scene's
// specular shift as the key light's highlight is) looked up by the tangent
// and interpolated linearly, in the units of the key light's normalized
// Kajiya-Kay (docs/formats.md, "Light and units").
//
// With any other fibre (chiang, marschner, marschner_reference) the maps
// hold Kajiya-Kay's responses, not the fibre's, so they are not used as
// such. A stated approximation instead: the fibre's own response to a
// uniform environment (the shading point's `shade_uniform`, exact under
// one) times the environment's effective radiance where that fibre's light
// comes from. Marschner's and Chiang's lobes M_p all lie along the specular
// cone θi ≈ −θo (shifted by the cuticle tilt), so that radiance is the
// specular maps' (the cone's light, weighted by cos^p) over their value
// under a uniform environment of radiance 1. What it misses is the
// azimuth (TT forward, R back: the maps are uniform around the cone) and
// the lobes' widths (the maps' p is the scene's Kajiya-Kay exponent); its
// error against environment_reference with the same fibre is measured in
// tests/lighting_fibres.rs (technique.toml states it). The diffuse map
// alone (the sin θ-weighted whole sphere) was measured too, and is
// further off for chiang.
// Every shading provider but kajiya_kay must be named below (checked by
// tests/lighting_fibres.rs), so a new fibre cannot get Kajiya-Kay's maps.
#define_import_path plait::lighting::irradiance_maps

#import plait::frame::frame
#import plait::cube::{cube_atlas_sample, PI}
#import plait::kajiya_kay::kk_environment_specular_units
#import plait::shading::shade_uniform

@group(1) @binding(31) var light_maps: texture_2d<f32>;

// Xing et al.'s lookup: Kajiya-Kay's diffuse and specular environment light,
// on the key light's cone. The maps hold the paper's mirror cone,
// cos^p(π − θ − θ′) (eq. 6); plait::kajiya_kay (the shading provider) has
// Halén & Wester 2007's printed (t·l)(t·e′) + sin sin = cos^p(θ − θ′), the
// cone through the light (docs/design.md, "Which Kajiya-Kay cone"). Map
// π − θ′ holds cos^p(θ − θ′), so reading the maps there lights the fibre
// with the response the key light has, and environment_reference (which
// sums that response) is the maps' ground truth.
fn kajiya_kay_maps(t: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let dims = textureDimensions(light_maps);
    let intervals = dims.y / (dims.x / 6u) - 2u;
    let theta_eye = clamp(acos(clamp(dot(t, to_eye), -1.0, 1.0)) + frame.hair_shading.w, 0.0, PI);
    let f = (PI - theta_eye) / PI * f32(intervals);
    let m0 = min(u32(floor(f)), intervals);
    let m1 = min(m0 + 1u, intervals);
    let a = f - f32(m0);
    let diffuse = cube_atlas_sample(light_maps, 0u, t).rgb;
    let specular = mix(cube_atlas_sample(light_maps, 1u + m0, t).rgb, cube_atlas_sample(light_maps, 1u + m1, t).rgb, a);
    return base * frame.hair_shading.x * diffuse + frame.hair_shading.y * specular * kk_environment_specular_units(frame.hair_shading.z, theta_eye);
}

// What specular map m holds under a uniform environment of radiance 1:
// 1/π² ∫ cos^p(π − θ − θ′) sin θ dω = (2/π) ∫₀^π cos^p(π − θ − θ′) sin θ dθ
// at θ′ = θ_eye, by the midpoint rule over u = θ + θ′ − π within ±6/√p of
// the cone (and within θ ∈ [0, π]).
fn cone_uniform(theta_eye: f32, exponent: f32) -> f32 {
    let w = min(0.5 * PI, 6.0 * inverseSqrt(max(exponent, 1.0)));
    let lo = max(-w, theta_eye - PI);
    let hi = min(w, theta_eye);
    let step = (hi - lo) / 64.0;
    var sum = 0.0;
    for (var k = 0; k < 64; k++) {
        let u = lo + (f32(k) + 0.5) * step;
        sum += pow(max(0.0, cos(u)), exponent) * max(0.0, sin(theta_eye - u));
    }
    return 2.0 / PI * sum * step;
}

// Any other fibre: its uniform response times the environment's effective
// radiance on the fibre's specular cone, the specular maps around θ′ each
// divided by its value under a uniform environment of radiance 1 (so a
// uniform environment gives the fibre's `shade_uniform` exactly, up to the
// maps' 16-bit storage), interpolated as the paper's lookup does.
fn fibre_on_cone(t: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let dims = textureDimensions(light_maps);
    let intervals = dims.y / (dims.x / 6u) - 2u;
    let theta_eye = clamp(acos(clamp(dot(t, to_eye), -1.0, 1.0)) + frame.hair_shading.w, 0.0, PI);
    let f = theta_eye / PI * f32(intervals);
    let m0 = min(u32(floor(f)), intervals);
    let m1 = min(m0 + 1u, intervals);
    let a = f - f32(m0);
    let p = frame.hair_shading.z;
    let c0 = cube_atlas_sample(light_maps, 1u + m0, t).rgb / cone_uniform(f32(m0) * PI / f32(intervals), p);
    let c1 = cube_atlas_sample(light_maps, 1u + m1, t).rgb / cone_uniform(f32(m1) * PI / f32(intervals), p);
    return shade_uniform(t, to_eye, base) * mix(c0, c1, a);
}

fn hair_environment(world: vec3<f32>, tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let t = normalize(tangent);
#ifdef SHADING_KAJIYA_KAY
    return kajiya_kay_maps(t, to_eye, base);
#else ifdef SHADING_CHIANG
    return fibre_on_cone(t, to_eye, base);
#else ifdef SHADING_MARSCHNER
    return fibre_on_cone(t, to_eye, base);
#else ifdef SHADING_MARSCHNER_REFERENCE
    return fibre_on_cone(t, to_eye, base);
#else
    return kajiya_kay_maps(t, to_eye, base);
#endif
}
