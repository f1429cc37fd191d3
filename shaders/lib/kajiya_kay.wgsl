// plait::kajiya_kay — the Kajiya-Kay hair shading model.
//
// Halén & Wester (2007 §3.2.1): diffuse is proportional
// to sin(T, L), specular to (cos(T,L) cos(T,E) + sin(T,L) sin(T,E))^p. The shift
// moves the highlight along the strand as the cuticle tilt does.
#define_import_path plait::kajiya_kay

// Returns (diffuse, specular) factors for unit tangent, light and eye vectors.
fn kajiya_kay(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, kd: f32, ks: f32, exponent: f32, shift: f32) -> vec2<f32> {
    let cos_tl = clamp(dot(tangent, to_light), -1.0, 1.0);
    let sin_tl = sqrt(max(0.0, 1.0 - cos_tl * cos_tl));
    // Shifting the angle between T and E by `shift` radians moves the highlight.
    let cos_te0 = clamp(dot(tangent, to_eye), -1.0, 1.0);
    let angle_te = acos(cos_te0) + shift;
    let cos_te = cos(angle_te);
    let sin_te = sin(angle_te);
    let spec_base = max(0.0, cos_tl * cos_te + sin_tl * sin_te);
    let diffuse = kd * sin_tl;
    let specular = ks * pow(spec_base, exponent);
    return vec2<f32>(diffuse, specular);
}

const KK_PI: f32 = 3.14159265358979;
// 1/π²: the far-field scattering function of a fibre that scatters uniformly
// in every direction (Kajiya & Kay 1989's diffuse term) with albedo 1, since
// ∫ cos θo dωo over the sphere (θ from the fibre's normal plane) is π².
const KK_DIFFUSE_NORMALIZATION: f32 = 0.10132118364;

// ∫_{-π/2}^{π/2} cos^p x dx = √π Γ((p+1)/2) / Γ(p/2 + 1): the longitudinal
// integral of the specular cone cos^p. Γ(x+½)/Γ(x+1) at x = p/2 is raised
// by four steps of Γ(z+1) = zΓ(z), then the asymptotic series in 1/x (better
// than 1e-6 relative for p ≥ 0).
fn cos_power_integral(p: f32) -> f32 {
    var x = 0.5 * max(p, 0.0);
    var scale = 1.0;
    for (var i = 0; i < 4; i++) {
        scale *= (x + 1.0) / (x + 0.5);
        x += 1.0;
    }
    let u = 1.0 / x;
    let series = 1.0 + u * (-1.0 / 8.0 + u * (1.0 / 128.0 + u * (5.0 / 1024.0 - u * 21.0 / 32768.0)));
    return sqrt(KK_PI) * scale * series * inverseSqrt(x);
}

// 1 / (2π ∫cos^p): the specular cone cos^p of a longitudinal angle, uniform
// in azimuth, normalized so a fibre of ks = 1 scatters at most what it
// receives (the cone's ∫ cos^p(θo − θc) cos²θo dθo ≤ ∫ cos^p).
fn kk_specular_normalization(p: f32) -> f32 {
    return 1.0 / (2.0 * KK_PI * cos_power_integral(p));
}

// The radiance a fibre sends towards the eye per unit irradiance from the
// light, S(ωi, ωo)·cos θi (docs/formats.md, "Light and units"), with the
// energy-normalized Kajiya-Kay scattering function
// S = kd·base/π² + ks·cos^p(cone)/(2π∫cos^p): a fibre with kd·base + ks ≤ 1
// reflects no more than it receives. cos θi = sin(T, L), Kajiya & Kay's
// diffuse factor.
fn kajiya_kay_radiance(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>, kd: f32, ks: f32, exponent: f32, shift: f32) -> vec3<f32> {
    let kk = kajiya_kay(tangent, to_light, to_eye, 1.0, 1.0, exponent, shift);
    let diffuse = base * (kd * KK_DIFFUSE_NORMALIZATION);
    let specular = ks * kk.y * kk_specular_normalization(exponent);
    return kk.x * (diffuse + vec3<f32>(specular));
}

// Xing et al. 2012's specular irradiance maps hold
// 1/π² Σ cos^p(π − θ − θ′) L dω (eq. 8); the key light's normalized cone
// above is ks/(2π∫cos^p) · cos^p · cos θi. This factor turns the first into
// the second: π²/(2π∫cos^p), and cos θi taken at the cone, sin θ′ (the
// narrow-cone limit: the maps keep no per-light cos θi).
fn kk_environment_specular_units(exponent: f32, theta_eye: f32) -> f32 {
    return KK_PI * KK_PI * kk_specular_normalization(exponent) * sin(theta_eye);
}

// The radiance the fibre sends towards the eye per unit radiance of a
// uniform environment, ∫ S cos θi dωi (docs/formats.md, "Light and units"):
// the diffuse part kd/π² integrates over the sphere (∫ cos θi dωi = π²) to
// kd · base exactly; the specular cone to ks · ∫cos^p(θi − θc) cos²θi dθi /
// ∫cos^p, taken in the narrow-cone limit ks · cos²θc, where the cone's
// longitudinal angle θc has cos θc = sin θ′ (θ′ the tangent-to-eye angle
// with the shift).
fn kajiya_kay_uniform(tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>, kd: f32, ks: f32, shift: f32) -> vec3<f32> {
    let theta_eye = acos(clamp(dot(normalize(tangent), to_eye), -1.0, 1.0)) + shift;
    let cone = sin(theta_eye);
    return base * kd + vec3<f32>(ks * cone * cone);
}
