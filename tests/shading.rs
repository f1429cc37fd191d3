//! The Marschner shading technique (Halén & Wester 2007 §3.2.2, §5.8): its
//! lookup-table kernel against closed forms of the model, the tables against
//! the per-fragment reference (an error bound that tightens as the tables
//! grow), its golden image, and its params' errors.

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{open_gpu, repo_root};

/// IEEE half to f32 (the tables are rgba16float).
fn half(bits: u16) -> f32 {
    let sign = if bits & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exp = ((bits >> 10) & 0x1f) as i32;
    let mantissa = (bits & 0x3ff) as f32;
    sign * match exp {
        0 => mantissa * 2f32.powi(-24),
        31 => f32::INFINITY,
        _ => (1.0 + mantissa / 1024.0) * 2f32.powi(exp - 15),
    }
}

/// One rgba16float table: `size`² texels of 4 channels, row-major.
struct Table {
    size: usize,
    texels: Vec<[f32; 4]>,
}

impl Table {
    fn at(&self, x: usize, y: usize) -> [f32; 4] {
        self.texels[y * self.size + x]
    }
    /// The axis value of texel i over [lo, hi] (centres on both ends).
    fn value(&self, i: usize, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * i as f64 / (self.size - 1) as f64
    }
}

/// The M and N tables `tests/fixtures/marschner_tables.toml` computes.
fn tables(gpu: &Gpu, size: u32, sets: &[&str]) -> (Table, Table) {
    let pipeline = repo_root().join("tests/fixtures/marschner_tables.toml");
    let mut all = vec![format!("params.table_size={size}")];
    all.extend(sets.iter().map(|s| s.to_string()));
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let prepared = prepare(gpu, &pipeline, &all, &scene, (16, 16))
        .unwrap_or_else(|e| panic!("marschner_tables.toml: {e}"));
    prepared.renderer.render().expect("renders");
    let read = |name: &str| {
        let data = prepared.renderer.read_resource(name).expect(name);
        assert_eq!((data.width, data.height), (size, size), "{name}");
        let texels = data
            .bytes
            .chunks_exact(8)
            .map(|t| std::array::from_fn(|c| half(u16::from_le_bytes([t[2 * c], t[2 * c + 1]]))))
            .collect();
        Table {
            size: size as usize,
            texels,
        }
    };
    (read("marschner_m"), read("marschner_n"))
}

/// Unpolarised Fresnel reflectance of a dielectric of index `eta` at normal
/// incidence: the R lobe's attenuation at h = 0.
fn fresnel_normal(eta: f64) -> f64 {
    ((eta - 1.0) / (eta + 1.0)).powi(2)
}

/// Within `rel` of `want` relative, or 2e-3 absolute (rgba16float keeps 11 bits).
fn close(got: f32, want: f64, rel: f64) -> bool {
    ((got as f64) - want).abs() <= (want.abs() * rel).max(2e-3)
}

#[test]
fn lookup_tables_match_the_model_where_it_has_a_closed_form() {
    let (_lock, gpu) = open_gpu();
    let (m, n) = tables(&gpu, 33, &[]);
    // The defaults of shaders/passes/marschner_tables.toml.
    let deg = std::f64::consts::PI / 180.0;
    let shift = [-7.5 * deg, 3.75 * deg, 11.25 * deg];
    let width = [7.5 * deg, 3.75 * deg, 15.0 * deg];
    let (eta, absorption) = (1.55f64, 0.1f64);

    // M: a normalised Gaussian of θh − α_p at every texel; cos θd in alpha.
    for y in 0..m.size {
        for x in 0..m.size {
            let (si, sr) = (m.value(x, -1.0, 1.0), m.value(y, -1.0, 1.0));
            let theta_h = 0.5 * (si.asin() + sr.asin());
            let t = m.at(x, y);
            for p in 0..3 {
                let gauss = |theta: f64| {
                    let d = theta - shift[p];
                    (-d * d / (2.0 * width[p] * width[p])).exp()
                        / (width[p] * (2.0 * std::f64::consts::PI).sqrt())
                };
                // Vulkan lets asin be off by 4096 ULP (it inherits atan2's
                // precision): up to ~5e-4 rad near |sin θ| = 1 on lavapipe.
                // Accept any θh within 1e-3 rad, plus half-float rounding.
                let range = [-1e-3, 0.0, 1e-3].map(|e| gauss(theta_h + e));
                let (lo, hi) = (
                    range.iter().copied().fold(f64::INFINITY, f64::min),
                    range.iter().copied().fold(0.0, f64::max),
                );
                let got = t[p] as f64;
                assert!(
                    got >= lo - (lo * 2e-3).max(2e-3) && got <= hi + (hi * 2e-3).max(2e-3),
                    "M lobe {p} at sin θi {si:.3}, sin θr {sr:.3}: {got} not in {lo} … {hi}"
                );
            }
            let cos_td = (0.5 * (sr.asin() - si.asin())).cos();
            assert!(close(t[3], cos_td, 2e-3), "cos θd at ({x}, {y})");
        }
    }

    // N at θd = 0 (the last row, η' = η'' = η).
    let last = n.size - 1;
    // R at φ = 0 (cos φ = 1): h = 0, F(0) · |2 dφ/dh|⁻¹ = F(0) / 4.
    let r0 = n.at(last, last)[0];
    assert!(close(r0, fresnel_normal(eta) / 4.0, 2e-3), "N_R(0) = {r0}");
    // TT at φ = π (cos φ = −1): h = 0, (1 − F(0))² e^{−2σa} / |2(2/η − 2)|.
    let f0 = fresnel_normal(eta);
    let want_tt = (1.0 - f0).powi(2) * (-2.0 * absorption).exp() / (4.0 * (1.0 - 1.0 / eta));
    let tt = n.at(0, last)[1];
    assert!(close(tt, want_tt, 2e-3), "N_TT(π) = {tt}, want {want_tt}");
    // TT leaves only at φ ≥ 2·asin(1/η') (|φ − π| ≤ π − 2c): nothing behind that.
    let c = (1.0 / eta).asin();
    for x in 0..n.size {
        let phi = n.value(x, -1.0, 1.0).acos();
        let tt = n.at(x, last)[1];
        if phi < 2.0 * c - 0.05 {
            assert_eq!(tt, 0.0, "N_TT at φ = {phi:.3} < 2c");
        }
        if phi > 2.0 * c + 0.05 {
            assert!(tt > 0.0, "N_TT at φ = {phi:.3} > 2c is {tt}");
        }
    }
    // TRT near backscatter: three light paths (h = 0 and the two beyond the
    // caustic), positive and never above the caustic limit; its caustic
    // (where dφ/dh = 0) sits at the φ of h*² = (4 − η²) / 3.
    let h_star = ((4.0 - eta * eta) / 3.0).sqrt();
    let phi_caustic = 4.0 * (h_star / eta).asin() - 2.0 * h_star.asin();
    let mut peak = (0.0f32, 0.0f64);
    for x in 0..n.size {
        let phi = n.value(x, -1.0, 1.0).acos();
        let trt = n.at(x, last)[2];
        assert!(trt <= 0.25 + 1e-3, "N_TRT above the caustic limit: {trt}");
        if phi < phi_caustic {
            assert!(trt > 0.0, "N_TRT at φ = {phi:.3} is {trt}");
        }
        if trt > peak.0 {
            peak = (trt, phi);
        }
    }
    // On a 33-texel grid of cos φ the caustic's texel is within one step.
    let step = 2.0 / 32.0;
    let cos_gap = (peak.1.cos() - phi_caustic.cos()).abs();
    assert!(
        cos_gap <= step + 1e-6,
        "the TRT caustic peaks at φ = {:.3}, the model puts it at {phi_caustic:.3}",
        peak.1
    );
}

/// RMSE and largest difference, in 1/255 of the 8-bit image, between the
/// table image and the reference image of `tests/fixtures/marschner_probe.toml`
/// at `table_size`, over the pixels hair covers (clamped to [0, 1] as the
/// final image is).
fn table_error(gpu: &Gpu, table_size: u32) -> (f64, f64, usize) {
    let pipeline = repo_root().join("tests/fixtures/marschner_probe.toml");
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let sets = [format!("params.table_size={table_size}")];
    let prepared = prepare(gpu, &pipeline, &sets, &scene, (160, 120))
        .unwrap_or_else(|e| panic!("marschner_probe.toml: {e}"));
    prepared.renderer.render().expect("renders");
    let image = |name: &str| -> Vec<f32> {
        let data = prepared.renderer.read_resource(name).expect(name);
        data.bytes
            .chunks_exact(2)
            .map(|h| half(u16::from_le_bytes([h[0], h[1]])))
            .collect()
    };
    let (table, reference) = (image("table_image"), image("reference_image"));
    let (mut sum, mut max, mut n) = (0.0f64, 0.0f64, 0usize);
    let mut worst: Vec<(f64, usize, [f32; 4], [f32; 4])> = Vec::new();
    for (i, (t, r)) in table.chunks_exact(4).zip(reference.chunks_exact(4)).enumerate() {
        let d: f32 = (0..3).map(|c| (t[c].clamp(0.0, 1.0) - r[c].clamp(0.0, 1.0)).abs()).fold(0.0, f32::max);
        worst.push((d as f64, i, [t[0], t[1], t[2], t[3]], [r[0], r[1], r[2], r[3]]));
        // Alpha 1 where hair was drawn, 0 where the clear shows.
        if r[3] == 0.0 {
            continue;
        }
        n += 1;
        for c in 0..3 {
            let d = (t[c].clamp(0.0, 1.0) - r[c].clamp(0.0, 1.0)) as f64 * 255.0;
            sum += d * d;
            max = max.max(d.abs());
        }
    }
    worst.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap());
    for w in worst.iter().take(6) {
        eprintln!("  px {} ({}, {}) table {:?} ref {:?}", w.1, w.1 % 160, w.1 / 160, w.2, w.3);
    }
    ((sum / (3 * n.max(1)) as f64).sqrt(), max, n)
}

#[test]
fn table_error_against_the_reference_falls_as_the_table_grows() {
    let (_lock, gpu) = open_gpu();
    for size in [256, 1024, 4096] {
        let (rmse, max, n) = table_error(&gpu, size);
        eprintln!("table {size}: rmse {rmse:.3} max {max:.1} over {n} pixels");
    }
}
