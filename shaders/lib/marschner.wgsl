// plait::marschner — the Marschner hair scattering model (R, TT, TRT), written
// once for the lookup-table kernel (shaders/passes/marschner_tables.wgsl) and
// the per-fragment reference (techniques/shading/marschner_reference/shading.wgsl),
// so the tables' error is the tables' alone: same constants, same angles.
//
// Halén & Wester 2007 §3.2.2, §3.2.2.1 (Marschner et al. 2003 as they present
// it): S = M(θh) · N(θd, φ) / cos²θd per lobe p ∈ {R, TT, TRT}.
// - M_p: a normalised Gaussian of the half angle θh = (θi + θr) / 2, shifted
//   by the cuticle tilt α_p, width β_p.
// - N_p: the sum over the entry heights h whose path leaves at the relative
//   azimuth φ, φ(p, h) = 2p·γt − 2γi + pπ (sin γi = h, η'·sin γt = h), of
//   A(p, h) · |2 dφ/dh|⁻¹, with A the Fresnel factors and the absorption of
//   the internal path, in the slice's effective index η'(θd).
// Two forms (`marschner_form`, `combine`):
// - 0, Marschner et al. 2003 (the default, the one held to Chiang et al. 2016
//   and Mitsuba): σa per channel from the hair colour by Chiang et al. 2016
//   §4.2 (the chiang technique's mapping, so both models describe one
//   fibre), R + TT + TRT and nothing else;
// - 1, Halén & Wester 2007 §5.8: one absorption for all colours, the hair
//   colour multiplying TT and TRT (R stays white), and Kajiya-Kay's diffuse
//   term added. That diffuse is an isotropic fibre of albedo kd·base on top
//   of lobes that already carry the model's energy: on blond it is 3/4 of the
//   light towards a front-lit eye (scripts/mitsuba/marschner_energy.py).
// Both clamp the caustics to a limit rather than Marschner's Gaussian
// smoothing (§5.8). No eccentricity (a circular cross-section).
//
// Angles, as §5.8 computes them from vectors (no trigonometry in the lookup):
// sin θi = L·T, sin θr = E·T, cos φ = L⊥·E⊥ / (|L⊥| |E⊥|), with L⊥, E⊥ the
// light and eye directions projected on the plane normal to the tangent T.
// cos φ = 1: eye on the light's side (backscatter, R and TRT);
// cos φ = −1: eye opposite the light (forward scattering, TT).
#define_import_path plait::marschner

const PI: f32 = 3.14159265358979;
// 1/π²: the normalization of an isotropic fibre's scattering (plait::kajiya_kay).
const INV_PI2: f32 = 0.10132118364;
const DEGREES: f32 = 0.0174532925199433;
// Bisection steps per monotonic interval of φ(p, h): 2⁻²⁴ of the interval,
// f32's precision.
const ROOT_STEPS: i32 = 24;

// The model's constants, in radians (see `model`).
struct Model {
    // α_R, α_TT, α_TRT: longitudinal shift of each lobe.
    shift: vec3<f32>,
    // β_R, β_TT, β_TRT: longitudinal width (standard deviation) of each lobe.
    width: vec3<f32>,
    // η, the hair's index of refraction (> 1).
    ior: f32,
    // σa, absorption per fibre radius, the same for all colours (§5.8;
    // the Halén & Wester form only: Marschner et al. 2003's comes from the
    // hair colour, `absorption_of`).
    absorption: f32,
    // N_TRT is clamped here (the thesis's treatment of caustics, §5.8).
    caustic_limit: f32,
}

// The forms of `marschner_form`.
const FORM_MARSCHNER: i32 = 0;
const FORM_HALEN_WESTER: i32 = 1;

// The model from user-facing params: angles in degrees.
fn model(shift_degrees: vec3<f32>, width_degrees: vec3<f32>, ior: f32, absorption: f32, caustic_limit: f32) -> Model {
    return Model(shift_degrees * DEGREES, width_degrees * DEGREES, ior, absorption, caustic_limit);
}

// The angles the model is a function of, from unit vectors: x = sin θi,
// y = sin θr, z = cos φ (§5.8's formulas).
fn hair_angles(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>) -> vec3<f32> {
    let sin_i = clamp(dot(to_light, tangent), -1.0, 1.0);
    let sin_r = clamp(dot(to_eye, tangent), -1.0, 1.0);
    let light_perp = to_light - sin_i * tangent;
    let eye_perp = to_eye - sin_r * tangent;
    let norms = dot(light_perp, light_perp) * dot(eye_perp, eye_perp);
    // Light or eye along the strand: the azimuth is undefined; every φ is
    // as good, take the backscatter one.
    var cos_phi = 1.0;
    if (norms > 1e-12) {
        cos_phi = clamp(dot(light_perp, eye_perp) * inverseSqrt(norms), -1.0, 1.0);
    }
    return vec3<f32>(sin_i, sin_r, cos_phi);
}

// cos θd, θd = (θr − θi) / 2: the table keeps it beside M (§5.8: "the alpha
// channel of the first lookup table").
fn cos_theta_d(sin_i: f32, sin_r: f32) -> f32 {
    return cos(0.5 * (asin(sin_r) - asin(sin_i)));
}

// M_R, M_TT, M_TRT at (sin θi, sin θr): g(β_p, θh − α_p), in 1 / radian.
fn longitudinal(m: Model, sin_i: f32, sin_r: f32) -> vec3<f32> {
    let theta_h = 0.5 * (asin(sin_i) + asin(sin_r));
    let d = vec3<f32>(theta_h) - m.shift;
    return exp(-d * d / (2.0 * m.width * m.width)) / (m.width * sqrt(2.0 * PI));
}

// Unpolarised Fresnel reflectance at incidence cos_i from outside into a
// medium with the effective indices η' (perpendicular polarisation) and η''
// (parallel) — §3.2.2's F; indices below 1 are the inside looking out.
fn fresnel(eta_perp: f32, eta_par: f32, cos_i: f32) -> f32 {
    let sin2_i = max(0.0, 1.0 - cos_i * cos_i);
    let sin2_perp = sin2_i / (eta_perp * eta_perp);
    let sin2_par = sin2_i / (eta_par * eta_par);
    if (sin2_perp >= 1.0 || sin2_par >= 1.0) {
        return 1.0;
    }
    let cos_perp = sqrt(1.0 - sin2_perp);
    let cos_par = sqrt(1.0 - sin2_par);
    let r_perp = (cos_i - eta_perp * cos_perp) / (cos_i + eta_perp * cos_perp);
    let r_par = (eta_par * cos_i - cos_par) / (eta_par * cos_i + cos_par);
    return 0.5 * (r_perp * r_perp + r_par * r_par);
}

// φ(p, h) = 2p·asin(h / η') − 2·asin(h) + pπ.
fn exit_azimuth(p: f32, h: f32, eta: f32) -> f32 {
    return 2.0 * p * asin(h / eta) - 2.0 * asin(h) + p * PI;
}

// dφ/dh of `exit_azimuth`.
fn exit_azimuth_slope(p: f32, h: f32, eta: f32) -> f32 {
    return 2.0 * p / sqrt(max(eta * eta - h * h, 1e-12)) - 2.0 / sqrt(max(1.0 - h * h, 1e-12));
}

// The fraction of the light entering at height h that leaves by path p with
// no absorption, A(p, h) of §3.2.2 (Marschner et al. 2003) at σa = 0:
// Fresnel at entry, internal reflections and exit.
fn clear_attenuation(p: f32, h: f32, eta_perp: f32, eta_par: f32) -> f32 {
    let cos_gamma_i = sqrt(max(0.0, 1.0 - h * h));
    let f = fresnel(eta_perp, eta_par, cos_gamma_i);
    if (p < 0.5) {
        return f;
    }
    let sin_gamma_t = h / eta_perp;
    let cos_gamma_t = sqrt(max(0.0, 1.0 - sin_gamma_t * sin_gamma_t));
    let f_inside = fresnel(1.0 / eta_perp, 1.0 / eta_par, cos_gamma_t);
    var internal = 1.0;
    if (p > 1.5) {
        internal = f_inside;
    }
    return (1.0 - f) * (1.0 - f_inside) * internal;
}

// Path p's length inside the fibre per unit σa (σa per fibre radius):
// p crossings of 2·cos γt, lengthened by 1 / cos θt for the path's tilt
// along the fibre. A(p, h) = clear_attenuation · exp(−σa · path_length).
fn path_length(p: f32, h: f32, eta_perp: f32, cos_theta_t: f32) -> f32 {
    let sin_gamma_t = h / eta_perp;
    let cos_gamma_t = sqrt(max(0.0, 1.0 - sin_gamma_t * sin_gamma_t));
    return p * 2.0 * cos_gamma_t / cos_theta_t;
}

// One root's share A(p, h) · |2 dφ/dh|⁻¹ with no absorption.
fn root_share(p: f32, h: f32, eta_perp: f32, eta_par: f32) -> f32 {
    let slope = abs(2.0 * exit_azimuth_slope(p, h, eta_perp));
    return clear_attenuation(p, h, eta_perp, eta_par) / max(slope, 1e-6);
}

// The root of φ(p, h) = goal in [h0, h1], where φ(p, h) is monotonic, found
// by bisection; −2 when the interval holds none.
fn root_in(p: f32, h0: f32, h1: f32, goal: f32, eta: f32) -> f32 {
    let f0 = exit_azimuth(p, h0, eta) - goal;
    let f1 = exit_azimuth(p, h1, eta) - goal;
    if (f0 * f1 > 0.0 || h1 <= h0) {
        return -2.0;
    }
    var lo = h0;
    var hi = h1;
    let rising = f1 > f0;
    for (var i = 0; i < ROOT_STEPS; i++) {
        let mid = 0.5 * (lo + hi);
        if ((exit_azimuth(p, mid, eta) > goal) == rising) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    return 0.5 * (lo + hi);
}

// TT and TRT at one relative azimuth: the sums over their roots.
struct Transmitted {
    // N_TT, N_TRT with no absorption.
    clear: vec2<f32>,
    // Each lobe's path length per unit σa, the mean over its roots weighted
    // by their clear shares (TT has one root: its length exactly).
    length: vec2<f32>,
    // N_TT, N_TRT at the absorption σa, per channel.
    tt: vec3<f32>,
    trt: vec3<f32>,
}

// N_TT and N_TRT at the relative azimuth phi ∈ [0, π]: the sum over the
// roots h of φ(p, h) = φ (mod 2π). φ(1, h) falls monotonically over
// [−1, 1]; φ(2, h) turns at ±h*, where dφ/dh = 0 (h*² = (4 − η'²) / 3 when
// η' < 2), so [−1, −h*], [−h*, h*], [h*, 1] hold at most one root each.
// One loop over the four pieces keeps a single bisection loop in the
// shader: a software rasterizer's compiler unrolls every copy.
fn transmitted(phi: f32, eta_perp: f32, eta_par: f32, cos_theta_t: f32, sigma_a: vec3<f32>) -> Transmitted {
    let turn2 = (4.0 - eta_perp * eta_perp) / 3.0;
    let turns = turn2 > 0.0 && turn2 < 1.0;
    let turn = sqrt(clamp(turn2, 0.0, 1.0));
    var out = Transmitted(vec2<f32>(0.0), vec2<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    var weighted = vec2<f32>(0.0);
    for (var piece = 0; piece < 4; piece++) {
        var p = 2.0;
        var h0 = -1.0;
        var h1 = 1.0;
        if (piece == 0) {
            p = 1.0;
        } else if (!turns) {
            // TRT without turning points is one piece.
            if (piece > 1) {
                break;
            }
        } else if (piece == 1) {
            h1 = -turn;
        } else if (piece == 2) {
            h0 = -turn;
            h1 = turn;
        } else {
            h0 = turn;
        }
        // The exit azimuth is taken modulo 2π; φ(p, h) stays within pπ ± π.
        let goal = phi + 2.0 * PI * round((p * PI - phi) / (2.0 * PI));
        let h = root_in(p, h0, h1, goal, eta_perp);
        if (h > -1.5) {
            let share = root_share(p, h, eta_perp, eta_par);
            let length = path_length(p, h, eta_perp, cos_theta_t);
            let absorbed = share * exp(-sigma_a * length);
            if (p < 1.5) {
                out.clear.x += share;
                weighted.x += share * length;
                out.tt += absorbed;
            } else {
                out.clear.y += share;
                weighted.y += share * length;
                out.trt += absorbed;
            }
        }
    }
    out.length = weighted / max(out.clear, vec2<f32>(1e-12));
    return out;
}

// The 2D slice normal to the fibre at θd (§3.2.2): the effective indices η'
// (perpendicular polarisation) and η'' (parallel), and cos θt of the path's
// tilt inside the fibre (sin θt = sin θd / η). Square roots only.
struct Slice {
    eta_perp: f32,
    eta_par: f32,
    cos_theta_t: f32,
}

fn slice(ior: f32, cos_td: f32) -> Slice {
    let cos_d = clamp(cos_td, 1e-4, 1.0);
    let sin2_d = 1.0 - cos_d * cos_d;
    let root = sqrt(max(ior * ior - sin2_d, 1e-12));
    let cos_theta_t = sqrt(max(1.0 - sin2_d / (ior * ior), 1e-8));
    return Slice(root / cos_d, ior * ior * cos_d / root, cos_theta_t);
}

// N_R at (cos φ, slice): φ(0, h) = −2 asin(h) has the single root
// h = −sin(φ/2), where cos γi = cos(φ/2), and |2 dφ/dh|⁻¹ = cos(φ/2) / 4.
// Square roots only, so the lookup shader evaluates it exactly (the table
// keeps its channel for TRT's absorption).
fn reflection(cos_phi: f32, s: Slice) -> f32 {
    let cos_half = sqrt(clamp(0.5 * (1.0 + cos_phi), 0.0, 1.0));
    return fresnel(s.eta_perp, s.eta_par, cos_half) * cos_half * 0.25;
}

// The azimuthal terms at (cos φ, cos θd) for the absorption σa per channel.
struct Azimuthal {
    r: f32,
    tt: vec3<f32>,
    trt: vec3<f32>,
    // The table's part: N_TT and N_TRT with no absorption (N_TRT clamped)
    // and their path lengths per unit σa (`Transmitted`).
    clear: vec2<f32>,
    length: vec2<f32>,
}

// N_R, N_TT, N_TRT at (cos φ, cos θd). N_TRT's caustics are clamped on its
// clear value (§5.8's limit, a property of the paths' geometry), the
// absorption then scaling the clamped lobe: the tables' form exactly.
fn azimuthal(m: Model, cos_phi: f32, cos_td: f32, sigma_a: vec3<f32>) -> Azimuthal {
    let s = slice(m.ior, cos_td);
    let phi = acos(clamp(cos_phi, -1.0, 1.0));
    let t = transmitted(phi, s.eta_perp, s.eta_par, s.cos_theta_t, sigma_a);
    // Only TRT has caustics (dφ/dh = 0 at ±h*); R and TT stay finite.
    let clamped = min(t.clear.y, m.caustic_limit);
    let scale = clamped / max(t.clear.y, 1e-12);
    return Azimuthal(reflection(cos_phi, s), t.tt, t.trt * scale, vec2<f32>(t.clear.x, clamped), t.length);
}

// The absorption per fibre radius of each form (see the header): Marschner
// et al. 2003's from the colour (`from_color`, plait::chiang::
// sigma_a_from_color of the hair colour, given by the caller), Halén &
// Wester's one σa.
fn absorption_of(m: Model, form: i32, from_color: vec3<f32>) -> vec3<f32> {
    if (form == FORM_HALEN_WESTER) {
        return vec3<f32>(m.absorption);
    }
    return from_color;
}

// Where a table of `size` texels per side samples the value x of an axis
// that spans [lo, hi] with texel centres on both ends, so the table is exact
// at its texels and covers the whole range.
fn table_coordinate(x: f32, lo: f32, hi: f32, size: f32) -> f32 {
    let t = clamp((x - lo) / (hi - lo), 0.0, 1.0);
    return (t * (size - 1.0) + 0.5) / size;
}

// The axis value of texel i (the inverse of `table_coordinate` at centres).
fn table_value(i: u32, lo: f32, hi: f32, size: u32) -> f32 {
    return lo + (hi - lo) * f32(i) / f32(max(size, 2u) - 1u);
}

// Radiance towards the eye per unit irradiance from the light,
// S(ωi, ωo)·cos θi (docs/formats.md, "Light and units"), from the lobes'
// M_p and absorbed N_p (`azimuthal`), energy-normalized:
// - the lobes: Marschner et al. 2003's S_p = M_p(θh) · N_p / cos²θd with
//   M_p read as a density over θr: M_p is a unit Gaussian in θh = (θi + θr)/2,
//   and dθr = 2 dθh, so over θr it is g(θh − α_p) / 2. With that factor a
//   lobe's reflected energy ∫ S_p cos θi cos θo dωo / cos θi is close to
//   N_p's integral over φ, the mean attenuation of path p (1/cos²θd undoes
//   the cos²θo of the outgoing measure at the lobe's peak θo = −θi); the
//   fibre furnace of tests/fibre.rs measures it. Times the specular gain
//   (1: the model; §5.8's thesis used a free gain, which breaks energy
//   conservation);
// - form 0 (Marschner et al. 2003): nothing else — the colour is in N_p's
//   absorption;
// - form 1 (Halén & Wester 2007 §5.8): R white, TT and TRT times the hair
//   colour, and the Kajiya-Kay diffuse term kd · base normalized as
//   Kajiya-Kay's (plait::kajiya_kay): kd · base / π², an isotropic fibre of
//   albedo kd · base, added to lobes that already carry the model's energy.
// All times cos θi, the light's incidence on the fibre. The caustic clamp of
// N_TRT (`azimuthal`) only removes energy.
fn combine(m: vec3<f32>, n_r: f32, n_tt: vec3<f32>, n_trt: vec3<f32>, cos_td: f32, sin_i: f32, base: vec3<f32>, kd: f32, form: i32, specular_gain: f32) -> vec3<f32> {
    let cos_i = sqrt(max(0.0, 1.0 - sin_i * sin_i));
    let k = 0.5 / max(cos_td * cos_td, 1e-4);
    var transmitted = m.y * n_tt + m.z * n_trt;
    var diffuse = vec3<f32>(0.0);
    if (form == FORM_HALEN_WESTER) {
        transmitted *= base;
        diffuse = kd * INV_PI2 * base;
    }
    let specular = k * (vec3<f32>(m.x * n_r) + transmitted);
    return cos_i * (diffuse + specular_gain * specular);
}

// ½ ∫ A(p, h) dh over the fibre's width in the slice s, per channel: what
// N_p integrates to over φ (`steps` midpoints in γ = asin h, weight cos γ).
// No caustic clamp: the clamp moves a caustic's light, the integral keeps it.
fn mean_attenuation(p: f32, s: Slice, sigma_a: vec3<f32>, steps: i32) -> vec3<f32> {
    let step = PI / f32(steps);
    var sum = vec3<f32>(0.0);
    for (var k = 0; k < steps; k++) {
        let gamma = -0.5 * PI + (f32(k) + 0.5) * step;
        let h = sin(gamma);
        let a = clear_attenuation(p, h, s.eta_perp, s.eta_par);
        sum += cos(gamma) * a * exp(-sigma_a * path_length(p, h, s.eta_perp, s.cos_theta_t));
    }
    return 0.5 * step * sum;
}

// Quadrature of `uniform_response`: nodes over each lobe's θh, and over h
// for Ā_p at each node.
const UNIFORM_NODES: i32 = 8;

// The fibre's response to a uniform environment of unit radiance, seen from
// the eye at sin θo: ∫ S(ωi, ωo) cos θi dωi (the shading point's
// `hair_uniform`). N_p integrates over φ to its mean attenuation Ā_p(θd), so
//   Σ_p ∫ cos²θi · g(θh − α_p) / 2 · Ā_p(θd) / cos²θd dθi,
// θh = (θi + θo)/2, θd = (θo − θi)/2 = θo − θh. With θi = 2θh − θo the
// Gaussian is integrated over θh (8 midpoints over α_p ± 4β_p, light
// directions past the poles dropped), Ā_p at each node by 8 midpoints in γ:
// Ā_p moves with θd across a wide lobe near grazing (taken once at the
// lobe's centre it read 9 % high at θo 60°). Form 1 adds its diffuse
// kd · base (the integral of kd · base / π² · cos θi) and tints TT and TRT.
// tests/fibre.rs holds it to the sphere integral of `combine`.
fn uniform_response(m: Model, sin_o: f32, sigma_a: vec3<f32>, base: vec3<f32>, kd: f32, form: i32, specular_gain: f32) -> vec3<f32> {
    let theta_o = asin(clamp(sin_o, -1.0, 1.0));
    var lobes = array<vec3<f32>, 3>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    for (var p = 0; p < 3; p++) {
        let shift = m.shift[p];
        let width = m.width[p];
        let step = 8.0 * width / f32(UNIFORM_NODES);
        var sum = vec3<f32>(0.0);
        for (var k = 0; k < UNIFORM_NODES; k++) {
            let theta_h = shift - 4.0 * width + (f32(k) + 0.5) * step;
            let theta_i = 2.0 * theta_h - theta_o;
            if (abs(theta_i) < 0.5 * PI) {
                let d = theta_h - shift;
                let g = exp(-d * d / (2.0 * width * width)) / (width * sqrt(2.0 * PI));
                let cos_i = cos(theta_i);
                let cos_d = cos(theta_o - theta_h);
                let a = mean_attenuation(f32(p), slice(m.ior, cos_d), sigma_a, UNIFORM_NODES);
                sum += g * cos_i * cos_i / max(cos_d * cos_d, 1e-4) * step * a;
            }
        }
        lobes[p] = sum;
    }
    var transmitted = lobes[1] + lobes[2];
    var diffuse = vec3<f32>(0.0);
    if (form == FORM_HALEN_WESTER) {
        transmitted *= base;
        diffuse = kd * base;
    }
    return diffuse + specular_gain * (lobes[0] + transmitted);
}
