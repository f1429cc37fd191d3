//! One fibre's shading (docs/formats.md, "Light and units"): the fibre
//! furnace — a white fibre's reflected energy over the sphere of outgoing
//! directions, ρ(θi) = (1/cos θi) ∫ S(ωi, ωo)·cos θi·cos θo dωo — for each
//! model, and its radiance at chosen directions against the model's closed
//! form on the CPU. The models are the WGSL ones, evaluated on the GPU by
//! `tests/fixtures/fibre_cases.wgsl` (layout there).

use std::f64::consts::PI;

use plait_tests::{fixture_texels, repo_root};

#[path = "fibre/lobes.rs"]
mod lobes;

const AZIMUTHS: usize = 256;
const ANGLES: usize = 128;
const LIGHT_DEGREES: [f64; 4] = [0.0, 30.0, 60.0, 80.0];

/// The fixture's image: `[left, middle, right third]` per pixel, 4 channels each.
struct Sphere {
    texels: Vec<[f32; 4]>,
}

/// The `fibre` target (rgba32float) of the fixture pipeline `fixture` at
/// `size`, one frame on the small scene: each texel a shading technique's
/// value at one (light, outgoing direction) pair.
fn render_fibre(fixture: &str, size: (u32, u32)) -> Vec<[f32; 4]> {
    fixture_texels(fixture, size, &["fibre"]).remove(0)
}

impl Sphere {
    fn render() -> Sphere {
        let size = ((3 * AZIMUTHS) as u32, (4 * ANGLES) as u32);
        Sphere {
            texels: render_fibre("fibre.toml", size),
        }
    }

    /// Third `half` (0 left, 1 middle, 2 right), light `k`, outgoing (θo row
    /// j, φo column i).
    fn at(&self, half: usize, k: usize, j: usize, i: usize) -> [f32; 4] {
        let (x, y) = (half * AZIMUTHS + i, k * ANGLES + j);
        self.texels[y * 3 * AZIMUTHS + x]
    }

    /// ρ(θi) of every channel of a half under light k: the midpoint rule over
    /// θo and φo, dωo = cos θo dθo dφo.
    fn albedo(&self, half: usize, k: usize) -> [f64; 4] {
        let cos_i = LIGHT_DEGREES[k].to_radians().cos();
        let (d_theta, d_phi) = (PI / ANGLES as f64, 2.0 * PI / AZIMUTHS as f64);
        let mut sum = [0.0; 4];
        for j in 0..ANGLES {
            let cos_o = theta_o(j).cos();
            for i in 0..AZIMUTHS {
                let v = self.at(half, k, j, i);
                (0..4).for_each(|c| sum[c] += v[c] as f64 * cos_o * cos_o * d_theta * d_phi);
            }
        }
        sum.map(|s| s / cos_i)
    }
}

/// The failure line of a value outside its band at light angle `degrees`.
fn outside(degrees: f64, name: &str, value: f64, low: f64, high: f64) -> Option<String> {
    (!(low..=high).contains(&value))
        .then(|| format!("θi {degrees}°: {name} {value:.4} outside [{low}, {high}]"))
}

fn theta_o(j: usize) -> f64 {
    -0.5 * PI + (j as f64 + 0.5) * PI / ANGLES as f64
}

fn phi_o(i: usize) -> f64 {
    (i as f64 + 0.5) * 2.0 * PI / AZIMUTHS as f64
}

/// A direction of longitudinal angle θ and azimuth φ about the fibre (+x).
fn direction(theta: f64, phi: f64) -> [f64; 3] {
    [
        theta.sin(),
        theta.cos() * phi.cos(),
        theta.cos() * phi.sin(),
    ]
}

/// ∫_{-π/2}^{π/2} cos^p x dx by Simpson's rule (20000 steps), independent of
/// the shader's Γ series.
fn cos_power_integral(p: f64) -> f64 {
    let n = 20000;
    let h = PI / n as f64;
    let f = |k: usize| (-0.5 * PI + k as f64 * h).cos().max(0.0).powf(p);
    let inner: f64 = (1..n)
        .map(|k| if k % 2 == 1 { 4.0 } else { 2.0 } * f(k))
        .sum();
    (f(0) + inner + f(n)) * h / 3.0
}

/// The normalized Kajiya-Kay radiance per unit irradiance, S·cos θi
/// (docs/formats.md): cos θi · (kd/π² + ks·cos^p(cone)/(2π ∫cos^p)), the
/// cone Halén & Wester's, its angle to the tangent shifted by `shift`.
fn kajiya_kay(l: [f64; 3], e: [f64; 3], kd: f64, ks: f64, p: f64, shift: f64) -> f64 {
    let cos_tl = l[0];
    let sin_tl = (1.0 - cos_tl * cos_tl).max(0.0).sqrt();
    let angle_te = e[0].clamp(-1.0, 1.0).acos() + shift;
    let cone = (cos_tl * angle_te.cos() + sin_tl * angle_te.sin()).max(0.0);
    sin_tl * (kd / (PI * PI) + ks * cone.powf(p) / (2.0 * PI * cos_power_integral(p)))
}

/// Unpolarised Fresnel reflectance into the effective indices (η', η'').
fn fresnel(eta_perp: f64, eta_par: f64, cos_i: f64) -> f64 {
    let sin2 = 1.0 - cos_i * cos_i;
    let (s_perp, s_par) = (sin2 / (eta_perp * eta_perp), sin2 / (eta_par * eta_par));
    if s_perp >= 1.0 || s_par >= 1.0 {
        return 1.0;
    }
    let (c_perp, c_par) = ((1.0 - s_perp).sqrt(), (1.0 - s_par).sqrt());
    let r_perp = (cos_i - eta_perp * c_perp) / (cos_i + eta_perp * c_perp);
    let r_par = (eta_par * cos_i - c_par) / (eta_par * cos_i + c_par);
    0.5 * (r_perp * r_perp + r_par * r_par)
}

/// Marschner et al. 2003 at the fixture's defaults (η 1.55, σa 0.1): the
/// effective indices of the slice at θd, and cos θt.
struct Slice {
    eta_perp: f64,
    eta_par: f64,
    cos_t: f64,
}

const IOR: f64 = 1.55;

fn slice(theta_d: f64) -> Slice {
    let (c, s2) = (theta_d.cos(), theta_d.sin().powi(2));
    let root = (IOR * IOR - s2).sqrt();
    Slice {
        eta_perp: root / c,
        eta_par: IOR * IOR * c / root,
        cos_t: (1.0 - s2 / (IOR * IOR)).sqrt(),
    }
}

/// M_p over θr: g(β, θh − α) / 2, angles in degrees.
fn longitudinal(theta_h: f64, shift: f64, width: f64) -> f64 {
    let (a, b) = (shift.to_radians(), width.to_radians());
    let d = theta_h - a;
    0.5 * (-d * d / (2.0 * b * b)).exp() / (b * (2.0 * PI).sqrt())
}

/// The R lobe's S_R·cos θi in closed form: the single root h = −sin(φ/2),
/// |2 dφ/dh|⁻¹ = cos(φ/2)/4 (Marschner et al. 2003 §4.2).
fn marschner_r(theta_i: f64, theta_o: f64, phi: f64) -> f64 {
    let (theta_h, theta_d) = (0.5 * (theta_i + theta_o), 0.5 * (theta_o - theta_i));
    let s = slice(theta_d);
    let n = fresnel(s.eta_perp, s.eta_par, (0.5 * phi).cos()) * (0.5 * phi).cos() / 4.0;
    theta_i.cos() * longitudinal(theta_h, -7.5, 7.5) * n / theta_d.cos().powi(2)
}

/// The TT lobe's S_TT·cos θi at relative azimuth φ: the one root h of
/// φ(1, h) = 2 asin(h/η') − 2 asin(h) + π = φ (falling over [−1, 1]), found
/// by bisection, and its share A(1, h) / |2 dφ/dh| (Marschner et al. 2003
/// §4.2), absorption 0.1 along 2 cos γt / cos θt.
fn marschner_tt(theta_i: f64, theta_o: f64, phi: f64) -> f64 {
    let (theta_h, theta_d) = (0.5 * (theta_i + theta_o), 0.5 * (theta_o - theta_i));
    let s = slice(theta_d);
    let exit = |h: f64| 2.0 * (h / s.eta_perp).asin() - 2.0 * h.asin() + PI;
    let goal = if phi < 0.0 { phi + 2.0 * PI } else { phi };
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if exit(mid) > goal { lo = mid } else { hi = mid }
    }
    let h = 0.5 * (lo + hi);
    let f = fresnel(s.eta_perp, s.eta_par, (1.0 - h * h).sqrt());
    let gt = h / s.eta_perp;
    let cos_gt = (1.0 - gt * gt).sqrt();
    let f_in = fresnel(1.0 / s.eta_perp, 1.0 / s.eta_par, cos_gt);
    let a = (1.0 - f) * (1.0 - f_in) * (-2.0 * 0.1 * cos_gt / s.cos_t).exp();
    let slope = 2.0 / (s.eta_perp * s.eta_perp - h * h).sqrt() - 2.0 / (1.0 - h * h).sqrt();
    theta_i.cos() * longitudinal(theta_h, 3.75, 3.75) * a
        / (2.0 * slope).abs()
        / theta_d.cos().powi(2)
}

/// The mean over entry heights of path p's attenuation at zero absorption,
/// in the slice at θd: what N_p integrates to over φ, the model's own share
/// of the light for path p.
fn mean_attenuation(theta_d: f64, p: u32) -> f64 {
    let s = slice(theta_d);
    let n = 4000;
    (0..n)
        .map(|k| {
            let h = -1.0 + (k as f64 + 0.5) * 2.0 / n as f64;
            let f = fresnel(s.eta_perp, s.eta_par, (1.0 - h * h).sqrt());
            let gt = h / s.eta_perp;
            let f_in = fresnel(1.0 / s.eta_perp, 1.0 / s.eta_par, (1.0 - gt * gt).sqrt());
            match p {
                0 => f,
                1 => (1.0 - f) * (1.0 - f_in),
                _ => (1.0 - f) * (1.0 - f_in) * f_in,
            }
        })
        .sum::<f64>()
        / n as f64
}

/// The fibre furnace of every model, and Marschner's against its own
/// energy. A white fibre reflects no more than it receives: ρ(θi) ≤ 1 for
/// Kajiya-Kay's diffuse (exactly 1: kd/π² integrates to kd), its specular
/// cone (ks = 1), Halén & Wester's diffuse (1), and Marschner as the
/// technique shades a white fibre at its defaults (form 0: σa of white is 0,
/// a lossless fibre; the scene's default kd 0.8, which form 0 does not add):
/// measured 0.948 / 1.008 / 1.086 / 0.778 at θi 0° / 30° / 60° / 80°, held
/// ≤ 1.10: up to 9 % over 1 where the wide TRT lobe's 1/cos²θd outgrows the
/// outgoing measure (the model's own, below). Halén & Wester's form
/// (plait's before issue 47's norm47) added the diffuse kd·base/π² to the
/// lobes: 1.58–1.89 here, and the test fails (checked by reverting). With no absorption and no
/// caustic clamp, Marschner's R + TT + TRT carries 0.75–1.12 × the model's
/// own energy Σ_p mean A_p (at θd = θi, where the lobes peak): Marschner et
/// al. 2003's form is not exactly energy-conserving — the 1/cos²θd matches
/// the outgoing measure only at a lobe's peak (over 1 for the wide TRT lobe
/// at θi = 60°), and lobes past the pole are cut at θi = 80°. Without the ½
/// of M_p over θr every Marschner figure doubles (0.79 → 1.59 at θi = 0)
/// and the test fails; without the 1/π² of the diffuse terms they read π².
#[test]
fn a_white_fibre_reflects_no_more_than_it_receives() {
    let sphere = Sphere::render();
    let mut failures = Vec::new();
    for (k, degrees) in LIGHT_DEGREES.iter().enumerate() {
        let [kk_d, kk_s, marschner, clear] = sphere.albedo(0, k);
        let [_, _, _, hw_diffuse] = sphere.albedo(1, k);
        let own: f64 = (0..3)
            .map(|p| mean_attenuation(degrees.to_radians(), p))
            .sum();
        println!(
            "θi {degrees:>2}°: Kajiya-Kay diffuse {kk_d:.4}, specular {kk_s:.4}; Marschner as shaded {marschner:.4}, \
             clear {clear:.4} (model's own {own:.4}, ratio {:.3}); H&W diffuse {hw_diffuse:.4}",
            clear / own
        );
        for (name, value, low, high) in [
            ("Kajiya-Kay diffuse", kk_d, 0.995, 1.005),
            ("Kajiya-Kay specular", kk_s, 0.0, 1.0),
            ("Marschner as shaded, white lossless", marschner, 0.0, 1.10),
            ("Halén & Wester diffuse", hw_diffuse, 0.995, 1.005),
            ("clear Marschner / own energy", clear / own, 0.75, 1.12),
        ] {
            failures.extend(outside(*degrees, name, value, low, high));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Marschner's response to a uniform environment (`hair_uniform`,
/// plait::marschner::uniform_response) against the sphere integral it
/// stands for. S is symmetric in its two directions (M_p of θh, N_p of φ
/// and θd, 1/cos²θd), so ∫ S(ωi, ωo) cos θi dωi seen from θo is the
/// furnace albedo ρ(θi = θo) of `a_white_fibre_reflects_no_more_than_it_receives`:
/// the clear fibre (no absorption, no clamp) measured 1.005 / 1.005 /
/// 0.987 / 0.920 at θo 0° / 30° / 60° / 80°, held within 3 % up to 60° and
/// 10 % at 80° (8 nodes per lobe: near grazing the R lobe's 1/cos²θd
/// steepens towards θd = 90° between them); the technique's white fibre
/// (caustic clamp 0.25, which the uniform response does not apply) likewise
/// with 1 % more; form 1's diffuse alone (kd 1, lobes off) within 0.5 % of
/// its closed form kd · base = 1.
#[test]
fn marschner_uniform_response_is_its_sphere_integral() {
    let sphere = Sphere::render();
    let mut failures = Vec::new();
    for (k, degrees) in LIGHT_DEGREES.iter().enumerate() {
        let [_, _, shaded, clear] = sphere.albedo(0, k);
        let [u_clear, u_shaded, u_diffuse, _] = sphere.at(2, k, 0, 0).map(f64::from);
        println!(
            "θo {degrees:>2}°: uniform clear {u_clear:.4} (sphere {clear:.4}, ratio {:.3}); \
             white as shaded {u_shaded:.4} (sphere {shaded:.4}, ratio {:.3}); form 1 diffuse {u_diffuse:.4}",
            u_clear / clear,
            u_shaded / shaded
        );
        let low = if *degrees <= 60.0 { 0.97 } else { 0.90 };
        for (name, value, low, high) in [
            ("uniform / sphere, clear", u_clear / clear, low, 1.03),
            (
                "uniform / sphere, as shaded",
                u_shaded / shaded,
                low - 0.01,
                1.04,
            ),
            ("form 1 diffuse", u_diffuse, 0.995, 1.005),
        ] {
            failures.extend(outside(*degrees, name, value, low, high));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// One fibre's radiance per unit irradiance at chosen directions against the
/// closed forms above: Kajiya-Kay (diffuse, and specular at its peak and
/// off it) and Halén & Wester's diffuse within 0.1 %, Marschner's R lobe at
/// several azimuths and TT within 2 %: Vulkan lets sin and cos err by 2⁻¹¹
/// absolute, and 3σ down the narrow TT lobe's flank (θi 60°, θo −30°) that
/// moves M_TT by 1.1 % on lavapipe.
#[test]
fn one_fibre_reads_its_model_closed_form() {
    let sphere = Sphere::render();
    let mut failures = Vec::new();
    let mut check = |what: String, got: f32, want: f64, rel: f64| {
        if ((got as f64) - want).abs() > rel * want.abs() + 1e-6 {
            failures.push(format!("{what}: {got}, closed form {want:.6}"));
        }
    };
    for (k, degrees) in LIGHT_DEGREES.iter().enumerate() {
        let ti = degrees.to_radians();
        let l = direction(ti, 0.0);
        // Rows: the peak of the shifted cone, a flank, the lobes' region.
        let peak = ((ti + 0.05 + 0.5 * PI) / PI * ANGLES as f64) as usize;
        for j in [
            peak.min(ANGLES - 1),
            ANGLES / 2,
            ANGLES / 3,
            ANGLES / 2 - 2 * k - 3,
        ] {
            for i in [0, AZIMUTHS / 8, AZIMUTHS / 3, AZIMUTHS / 2] {
                let (to, po) = (theta_o(j), phi_o(i));
                let e = direction(to, po);
                let [d, s, _, _] = sphere.at(0, k, j, i);
                let [r, tt, _, hw] = sphere.at(1, k, j, i);
                let at = format!(
                    "θi {degrees}°, θo {:.1}°, φo {:.1}°",
                    to.to_degrees(),
                    po.to_degrees()
                );
                check(
                    format!("{at}: Kajiya-Kay diffuse"),
                    d,
                    kajiya_kay(l, e, 1.0, 0.0, 60.0, -0.05),
                    1e-3,
                );
                check(
                    format!("{at}: Kajiya-Kay specular"),
                    s,
                    kajiya_kay(l, e, 0.0, 1.0, 60.0, -0.05),
                    1e-3,
                );
                check(format!("{at}: H&W diffuse"), hw, ti.cos() / (PI * PI), 1e-3);
                let phi = po.cos().clamp(-1.0, 1.0).acos();
                check(
                    format!("{at}: Marschner R"),
                    r,
                    marschner_r(ti, to, phi),
                    2e-2,
                );
                check(
                    format!("{at}: Marschner TT"),
                    tt,
                    marschner_tt(ti, to, phi),
                    2e-2,
                );
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Chiang et al. 2016's fibre (`tests/fixtures/fibre_chiang_cases.wgsl`):
/// four quarters of the grid above, `[quarter][light][row][column]`.
struct ChiangSphere {
    texels: Vec<[f32; 4]>,
}

impl ChiangSphere {
    fn render() -> ChiangSphere {
        let size = ((4 * AZIMUTHS) as u32, (5 * ANGLES) as u32);
        ChiangSphere {
            texels: render_fibre("fibre_chiang.toml", size),
        }
    }

    fn at(&self, quarter: usize, k: usize, j: usize, i: usize) -> [f32; 4] {
        let (x, y) = (quarter * AZIMUTHS + i, k * ANGLES + j);
        self.texels[y * 4 * AZIMUTHS + x]
    }

    /// Channel `c` of a quarter under light k integrated over outgoing
    /// directions, with cos θo^`cosines` dθo dφo: 1 is ∫ f dωo (pbrt's
    /// furnace, Chiang's normalization), 2 is ∫ f cos θo dωo (plait's ρ·cos θi).
    fn integral(&self, quarter: usize, c: usize, k: usize, cosines: i32) -> f64 {
        let (d_theta, d_phi) = (PI / ANGLES as f64, 2.0 * PI / AZIMUTHS as f64);
        let mut sum = 0.0;
        for j in 0..ANGLES {
            let w = theta_o(j).cos().powi(cosines) * d_theta * d_phi;
            sum += (0..AZIMUTHS)
                .map(|i| self.at(quarter, k, j, i)[c] as f64)
                .sum::<f64>()
                * w;
        }
        sum
    }

    /// The largest relative difference between channels `a` and `b` of
    /// quarter 0 under light k, over the directions where `b` is at least 1 %
    /// of its peak: the 64-point mean over h against 512 points.
    fn quadrature_error(&self, k: usize, a: usize, b: usize) -> f64 {
        let cells = || (0..ANGLES).flat_map(|j| (0..AZIMUTHS).map(move |i| (j, i)));
        let peak = cells()
            .map(|(j, i)| self.at(0, k, j, i)[b])
            .fold(0.0f32, f32::max) as f64;
        cells()
            .map(|(j, i)| self.at(0, k, j, i))
            .filter(|v| v[b] as f64 >= 0.01 * peak)
            .map(|v| ((v[a] - v[b]) / v[b]).abs() as f64)
            .fold(0.0, f64::max)
    }
}

/// Chiang's white furnace (σ_a = 0): ∫ (S·cos θi) dωo. d'Eon's M_p is
/// normalized over cos θo dθo and the A_p sum to 1, so it is 1 but for the
/// tilted lobes cut at the pole: within pbrt-v3's [0.95, 1.05] up to θi 30°,
/// measured 1.013 / 1.044; at θi 60° 1.043 and 80° 0.861, as Mitsuba's own
/// BSDF at the export's scale_tilt −2 (1.045, 0.862: scripts/mitsuba/
/// fibre_table.py's furnace rows, held here within 1 % at every θi; at +2,
/// R's peak on the other side of the mirror direction, they were 0.992,
/// 0.915, 0.733 — which lobes the pole cuts depends on the tilt's sign). plait's ρ(θi) = ∫ (S·cos θi) cos θo dωo / cos θi,
/// the other models' furnace above, is printed beside it: Chiang's fibre is
/// normalized for a path tracer's measure, not for ρ (1.66 at θi 80°). The
/// 64-point mean over h against 512 points, direction by direction where
/// the lobe is above 1 % of its peak: measured 0.8–1.3 % at β_n 0.3 and
/// 2.4–6.4 % at β_n 0.15 (the param's lower bound), held within 2 % and 7 %.
#[test]
fn chiang_white_furnace() {
    let sphere = ChiangSphere::render();
    let table =
        std::fs::read_to_string(repo_root().join("tests/fixtures/chiang_mitsuba.txt")).unwrap();
    let mitsuba: Vec<f64> = table
        .lines()
        .filter_map(|l| l.strip_prefix("furnace "))
        .map(|l| l.split_whitespace().nth(2).unwrap().parse().unwrap())
        .collect();
    assert_eq!(
        mitsuba.len(),
        LIGHT_DEGREES.len(),
        "the fixture's furnace rows"
    );
    let mut failures = Vec::new();
    for (k, degrees) in LIGHT_DEGREES.iter().enumerate() {
        let energy = sphere.integral(0, 0, k, 1);
        let rho = sphere.integral(0, 0, k, 2) / degrees.to_radians().cos();
        let lobes = [1, 2, 3].map(|q| sphere.integral(q, 3, k, 1));
        let (q3, q15) = (
            sphere.quadrature_error(k, 0, 1),
            sphere.quadrature_error(k, 2, 3),
        );
        println!(
            "θi {degrees:>2}°: ∫f dωo {energy:.4} (Mitsuba {:.4}); ρ {rho:.4}; R {:.4} TT {:.4} TRT {:.4}, \
             p ≥ 3 {:.4}; 64 vs 512 points: {:.2} % at β_n 0.3, {:.2} % at β_n 0.15",
            mitsuba[k],
            lobes[0],
            lobes[1],
            lobes[2],
            energy - lobes.iter().sum::<f64>(),
            100.0 * q3,
            100.0 * q15
        );
        let pbrt = if *degrees <= 30.0 {
            (0.95, 1.05)
        } else {
            (0.0, 1.05)
        };
        for (name, value, low, high) in [
            ("∫f dωo", energy, pbrt.0, pbrt.1),
            ("∫f dωo ÷ Mitsuba's", energy / mitsuba[k], 0.99, 1.01),
            ("64 vs 512 points at β_n 0.3", q3, 0.0, 0.02),
            ("64 vs 512 points at β_n 0.15", q15, 0.0, 0.07),
        ] {
            failures.extend(outside(*degrees, name, value, low, high));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// One convention for σ_a: the WGSL's mapping from colour (Chiang 2016
/// §4.2, `plait::chiang::sigma_a_from_color`) and the Mitsuba export's
/// (`plait::mitsuba::sigma_a_from_color`) agree within 10⁻⁵ relative on
/// the fixture's blond, dark brown and black, at the default β_n.
#[test]
fn chiang_sigma_a_is_the_mitsuba_exports() {
    let sphere = ChiangSphere::render();
    let beta_n =
        plait::mitsuba::Fibre::standard(&plait_passes::read_library(&[])).azimuthal_roughness;
    for (q, colour) in [[0.85, 0.65, 0.40], [0.32, 0.20, 0.11], [0.02; 3]]
        .iter()
        .enumerate()
    {
        let want =
            plait::mitsuba::sigma_a_from_color(glam::Vec3::from_array(*colour), beta_n).unwrap();
        let got = sphere.at(q + 1, LIGHT_DEGREES.len(), 0, 0);
        for c in 0..3 {
            let (g, w) = (got[c] as f64, want[c] as f64);
            assert!(
                (g - w).abs() <= 1e-5 * w,
                "{colour:?} channel {c}: WGSL σ_a {g}, Rust {w}"
            );
        }
        println!("{colour:?}: σ_a {:?} (WGSL) {want:?} (Rust)", &got[..3]);
    }
}

/// The `chiang` technique's model against Mitsuba 3's `hair` BSDF at the
/// points of `tests/fixtures/chiang_mitsuba.txt` (scripts/mitsuba/
/// fibre_table.py: the BSDF's eval averaged over h, 400 points), white and
/// three absorbing colours, every channel: within 2 % + 2·10⁻⁴ (the 64-point
/// mean over h and f32; measured below).
#[test]
fn chiang_reads_mitsubas_hair_bsdf() {
    let sphere = ChiangSphere::render();
    let table =
        std::fs::read_to_string(repo_root().join("tests/fixtures/chiang_mitsuba.txt")).unwrap();
    let (mut failures, mut worst, mut count) = (Vec::new(), 0.0f64, 0);
    for line in table
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("furnace"))
    {
        let f: Vec<&str> = line.split_whitespace().collect();
        let [k, j, i] = [1, 2, 3].map(|n| f[n].parse::<usize>().unwrap());
        let want: Vec<f64> = f[7..10].iter().map(|v| v.parse().unwrap()).collect();
        let (to, po) = (theta_o(j).to_degrees(), phi_o(i).to_degrees());
        let stated: [f64; 2] = [f[5].parse().unwrap(), f[6].parse().unwrap()];
        assert!(
            (to - stated[0]).abs() < 1e-3 && (po - stated[1]).abs() < 1e-3,
            "grid: {line}"
        );
        let got = match f[0] {
            "white" => [sphere.at(0, k, j, i)[0]; 3],
            colour => {
                let q = ["blond", "dark_brown", "black"]
                    .iter()
                    .position(|c| *c == colour)
                    .unwrap()
                    + 1;
                let v = sphere.at(q, k, j, i);
                [v[0], v[1], v[2]]
            }
        };
        for c in 0..3 {
            let (g, w) = (got[c] as f64, want[c]);
            worst = worst.max((g - w).abs() / (0.02 * w + 2e-4));
            count += 1;
            if (g - w).abs() > 0.02 * w + 2e-4 {
                failures.push(format!(
                    "{} θi {} θo {to:.1}° φ {po:.1}° channel {c}: plait {g:.6}, Mitsuba {w:.6}",
                    f[0], f[4]
                ));
            }
        }
    }
    println!("{count} values, worst at {worst:.3} of the tolerance");
    assert!(
        failures.is_empty(),
        "{} of {count} values:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// One fibre description: the `chiang` technique's exported params
/// (techniques/shading/chiang/technique.toml), the shading point's defaults
/// (techniques/shading/point.toml, as the typed passes read them) and the
/// Mitsuba export's `Fibre::standard` are the same four numbers.
#[test]
fn chiang_defaults_are_the_mitsuba_exports_fibre() {
    let text =
        std::fs::read_to_string(repo_root().join("techniques/shading/chiang/technique.toml"))
            .unwrap();
    let value = |name: &str| -> f64 {
        let line = text
            .lines()
            .find(|l| l.split('=').next().map(str::trim) == Some(name))
            .unwrap_or_else(|| panic!("technique.toml has no {name}"));
        line.split('=').nth(1).unwrap().trim().parse().unwrap()
    };
    let toml = [
        "chiang_beta_m",
        "chiang_beta_n",
        "chiang_tilt",
        "chiang_eta",
    ]
    .map(value);
    let library = plait_passes::read_library(&[]);
    let f = plait::mitsuba::Fibre::standard(&library);
    let mitsuba = [
        f.longitudinal_roughness,
        f.azimuthal_roughness,
        f.scale_tilt_degrees,
        f.eta,
    ]
    .map(f64::from);
    let typed = [
        "chiang_beta_m",
        "chiang_beta_n",
        "chiang_tilt",
        "chiang_eta",
    ]
    .map(
        |name| match plait::passes::points::default(&library, "shading", name) {
            Some(plait_graph::Value::Float(f)) => f,
            other => panic!("the shading point's {name}: {other:?}"),
        },
    );
    for k in 0..4 {
        assert_eq!(
            toml[k], typed[k],
            "technique.toml vs the shading point's default, field {k}"
        );
        assert!(
            (mitsuba[k] - typed[k]).abs() < 1e-6,
            "Fibre::standard vs the shading point's default, field {k}"
        );
    }
}

/// Out-of-range fibre params are refused at load, naming the param and
/// the `--set` flag (ranges in the chiang technique's `[param_ranges]`).
#[test]
fn chiang_bad_params_are_errors_naming_the_param() {
    let opts = plait_graph::CompileOptions::default();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    for (set, param) in [
        ("params.chiang_beta_m=0", "chiang_beta_m"),
        ("params.chiang_beta_m=1.5", "chiang_beta_m"),
        ("params.chiang_beta_n=0.1", "chiang_beta_n"),
        ("params.chiang_tilt=-12", "chiang_tilt"),
        ("params.chiang_eta=1.0", "chiang_eta"),
        ("params.chiang_eta=nan", "chiang_eta"),
    ] {
        let sets = vec!["techniques.shading=chiang".to_string(), set.to_string()];
        let message = match plait::session::compile_checked(&pipeline, &sets, &opts) {
            Ok(_) => panic!("{set} compiled"),
            Err(e) => e.to_string(),
        };
        assert!(
            message.contains(&format!("param `{param}`"))
                && message.contains(&format!("--set {set}")),
            "{set}: {message}"
        );
    }
}
