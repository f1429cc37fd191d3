// plait::sh — real spherical harmonics (Green 2003, with the Condon–Shortley
// phase; index l² + l + m; y is the polar axis) and the Kajiya-Kay responses
// the irradiance maps integrate (Xing et al. 2012 eq. 4 and 6). The CPU twin
// is plait_hair::environment::{sh, irradiance}.
#define_import_path plait::sh

const PI: f32 = 3.14159265358979;

// 1/π² = 1 / ∫ sin θ dω: a uniform environment of radiance 1 gives diffuse 1.
const KK_NORMALIZATION: f32 = 0.10132118364;

// sin θ of cos θ = t · l (eq. 4).
fn kk_diffuse(cos_tl: f32) -> f32 {
    return sqrt(max(0.0, 1.0 - cos_tl * cos_tl));
}

// cos^p(π − θ − θ′), clamped at 0 (eq. 6, θ̄ = π − θ).
fn kk_specular(cos_tl: f32, theta_eye: f32, exponent: f32) -> f32 {
    let theta = acos(clamp(cos_tl, -1.0, 1.0));
    return pow(max(0.0, cos(PI - theta - theta_eye)), exponent);
}

// Associated Legendre polynomial P_l^m(x), m ≥ 0.
fn sh_legendre(l: u32, m: u32, x: f32) -> f32 {
    var pmm = 1.0;
    if (m > 0u) {
        let somx2 = sqrt(max(0.0, (1.0 - x) * (1.0 + x)));
        var fact = 1.0;
        for (var i = 0u; i < m; i++) {
            pmm *= -fact * somx2;
            fact += 2.0;
        }
    }
    if (l == m) {
        return pmm;
    }
    var pmmp1 = x * f32(2u * m + 1u) * pmm;
    if (l == m + 1u) {
        return pmmp1;
    }
    var pll = 0.0;
    for (var ll = m + 2u; ll <= l; ll++) {
        pll = (f32(2u * ll - 1u) * x * pmmp1 - f32(ll + m - 1u) * pmm) / f32(ll - m);
        pmm = pmmp1;
        pmmp1 = pll;
    }
    return pll;
}

fn sh_normalization(l: u32, m: u32) -> f32 {
    var ratio = 1.0;
    for (var k = l - m + 1u; k <= l + m; k++) {
        ratio /= f32(k);
    }
    return sqrt(f32(2u * l + 1u) / (4.0 * PI) * ratio);
}

// Y_lm of a unit direction, coefficient index i = l² + l + m.
fn sh_basis(i: u32, d: vec3<f32>) -> f32 {
    let l = u32(floor(sqrt(f32(i)) + 1e-3));
    let m = i32(i) - i32(l * l + l);
    let am = u32(abs(m));
    let k = sh_normalization(l, am) * sh_legendre(l, am, clamp(d.y, -1.0, 1.0));
    if (m == 0) {
        return k;
    }
    let phi = atan2(d.z, d.x);
    if (m > 0) {
        return 1.41421356 * k * cos(f32(am) * phi);
    }
    return 1.41421356 * k * sin(f32(am) * phi);
}
