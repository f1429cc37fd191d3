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
    prepared.render().expect("renders");
    let read = |name: &str| {
        let data = prepared.read_resource(name).expect(name);
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
    let eta = 1.55f64;

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

    // N at θd = 0 (the last row, η' = η'' = η): N_TT, N_TRT with no
    // absorption and their path lengths per unit σa (N_R is evaluated by the
    // lookup, not tabulated).
    let last = n.size - 1;
    // TT at φ = π (cos φ = −1): h = 0, (1 − F(0))² / |2(2/η − 2)|, its path
    // two radii (2 cos γt / cos θt at h = 0, θd = 0).
    let f0 = fresnel_normal(eta);
    let want_tt = (1.0 - f0).powi(2) / (4.0 * (1.0 - 1.0 / eta));
    let tt = n.at(0, last)[0];
    assert!(close(tt, want_tt, 2e-3), "N_TT(π) = {tt}, want {want_tt}");
    let length_tt = n.at(0, last)[2];
    assert!(
        close(length_tt, 2.0, 2e-3),
        "TT's path length at φ = π: {length_tt}"
    );
    // TRT's length is the mean of its roots' 4 cos γt: in (0, 4] wherever
    // it leaves.
    for x in 0..n.size {
        let [_, trt, _, length] = n.at(x, last);
        assert!(
            trt == 0.0 || (length > 0.0 && length <= 4.0 + 4e-3),
            "TRT's path length {length} at cos φ {:.3}",
            n.value(x, -1.0, 1.0)
        );
    }
    // TT leaves only at φ ≥ 2·asin(1/η') (|φ − π| ≤ π − 2c): nothing behind that.
    let c = (1.0 / eta).asin();
    for x in 0..n.size {
        let phi = n.value(x, -1.0, 1.0).acos();
        let tt = n.at(x, last)[0];
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
        let trt = n.at(x, last)[1];
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

/// The final image of `pipelines/marschner.toml` on the small scene with `sets`.
fn render(gpu: &Gpu, sets: &[String]) -> image::RgbaImage {
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    render_scene(gpu, &scene, sets)
}

/// The final image of `pipelines/marschner.toml` on `scene` with `sets`.
fn render_scene(gpu: &Gpu, scene: &SceneData, sets: &[String]) -> image::RgbaImage {
    let pipeline = repo_root().join("pipelines/marschner.toml");
    let prepared = prepare(gpu, &pipeline, sets, scene, (192, 144))
        .unwrap_or_else(|e| panic!("marschner.toml {sets:?}: {e}"));
    prepared.render().expect("renders");
    prepared.image().expect("reads back")
}

/// RMSE over the image and the largest channel difference, both in 1/255.
fn error_255(a: &image::RgbaImage, b: &image::RgbaImage) -> (f64, u8) {
    let rmse = plait_compare::rmse(a, b).expect("same size") * 255.0;
    let max = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..3).map(move |c| p.0[c].abs_diff(q.0[c])))
        .max()
        .unwrap_or(0);
    (rmse, max)
}

// Measured on lavapipe (Mesa 25.0.7, llvmpipe LLVM 15), 192×144, against
// marschner_reference: RMSE 0.335 / 0.233 / 0.140 (1/255) at 16² / 64² /
// 256², max 12 / 13 / 8 (norm47: Marschner et al. 2003's form, σa from the
// colour, no added diffuse — a darker image, so smaller errors in 1/255;
// before it 0.50 / 0.38 / 0.21, max 32 / 37 / 26; the bounds are kept). The bounds leave room for another rasterizer's line ends
// (about 1.5×). The max does not fall: N_TRT jumps at the caustic azimuth
// (the thesis's clamp, §5.8), and interpolation smears a jump over a texel
// at any size; without the caustics the tables are exact to 1/255 (below).
const RMSE_BOUND: [(u32, f64); 3] = [(16, 0.75), (64, 0.57), (256, 0.35)];
const MAX_BOUND: u8 = 60;

#[test]
fn table_image_is_within_a_measured_bound_of_the_reference_and_tightens_as_the_table_grows() {
    let (_lock, gpu) = open_gpu();
    let reference = render(&gpu, &["techniques.shading=marschner_reference".into()]);
    let mut previous = f64::INFINITY;
    let mut finest = 0.0;
    for (size, bound) in RMSE_BOUND {
        let table = render(&gpu, &[format!("params.marschner_table_size={size}")]);
        let (rmse, max) = error_255(&table, &reference);
        eprintln!("table {size}²: RMSE {rmse:.3}/255, max {max}/255 against the reference");
        assert!(
            rmse <= bound && max <= MAX_BOUND,
            "table {size}²: RMSE {rmse:.3}/255 (bound {bound}), max {max}/255 (bound {MAX_BOUND})"
        );
        assert!(
            rmse < previous * 0.85,
            "table {size}²: RMSE {rmse:.3}/255 is not clearly below the smaller table's {previous:.3}"
        );
        previous = rmse;
        finest = rmse;
    }
    // With TRT clamped to almost nothing there is no jump, and the 64²
    // tables match the reference to rounding (measured RMSE 0.06, max 1/255).
    let no_caustic = "params.marschner_caustic_limit=0.001".to_string();
    let smooth_reference = render(
        &gpu,
        &[
            "techniques.shading=marschner_reference".into(),
            no_caustic.clone(),
        ],
    );
    let smooth = render(&gpu, &["params.marschner_table_size=64".into(), no_caustic]);
    let (rmse, max) = error_255(&smooth, &smooth_reference);
    eprintln!("64² without caustics: RMSE {rmse:.3}/255, max {max}/255");
    assert!(
        max <= 2 && rmse <= 0.2,
        "64² tables without caustics: RMSE {rmse:.3}/255, max {max}/255 (bound 0.2, 2)"
    );
    // The comparison can tell models apart: Kajiya-Kay is far from the
    // reference where the tables are close.
    let kajiya_kay = render(&gpu, &["techniques.shading=kajiya_kay".into()]);
    let (kk, _) = error_255(&kajiya_kay, &reference);
    assert!(
        kk > 10.0 * finest,
        "Kajiya-Kay is {kk:.3}/255 from the Marschner reference, the 256² tables {finest:.3}/255"
    );
}

/// The tables apply each strand colour's absorption as the reference does
/// (Marschner et al. 2003's form: σa per channel from the colour, outside
/// the tables, exp(−σa · path length)): the small scene with its hair
/// tinted dark (`material.color` 0.1, 0.08, 0.06: σa up to 0.4 per radius,
/// so TT and TRT lose half their light and more), 128² tables against the
/// reference, measured RMSE 0.092/255, max 7/255 on lavapipe, held at 0.3
/// and 12. Applying no absorption to TRT in the lookup reads RMSE
/// 0.75/255, max 25/255 and fails; TT's (forward scattering) does not show
/// on this front-lit scene in 8 bits (unchanged RMSE): tests/fibre.rs and
/// scripts/physical-check.sh's tables row cover it.
#[test]
fn tables_apply_the_hair_colours_absorption_as_the_reference() {
    let (_lock, gpu) = open_gpu();
    let mut scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    scene.scene.material.color = [0.1, 0.08, 0.06];
    let reference = render_scene(
        &gpu,
        &scene,
        &["techniques.shading=marschner_reference".into()],
    );
    let table = render_scene(&gpu, &scene, &[]);
    let (rmse, max) = error_255(&table, &reference);
    eprintln!("dark hair, 128² tables: RMSE {rmse:.3}/255, max {max}/255 against the reference");
    assert!(
        rmse <= 0.3 && max <= 12,
        "dark hair, 128² tables: RMSE {rmse:.3}/255 (bound 0.3), max {max}/255 (bound 12)"
    );
}

/// Each bad value is an error that names the param, and where it was given:
/// the `--set` flag that set it, or the technique file when the flag set a
/// param the file passes on (`${…}` inside a larger value).
#[test]
fn bad_params_are_errors_naming_the_param() {
    let opts = plait_graph::CompileOptions::default();
    let cases: &[(&[&str], &str)] = &[
        (&["params.marschner_table_size=0"], "param `table_size`"),
        (&["params.marschner_table_size=1"], "param `table_size`"),
        (&["params.marschner_ior=1.0"], "param `ior`"),
        (&["params.marschner_absorption=-1"], "param `absorption`"),
        (&["params.marschner_width_tt=0"], "param `width_tt`"),
        (
            &["params.marschner_caustic_limit=0"],
            "param `caustic_limit`",
        ),
        (
            &["params.marschner_specular_gain=-2"],
            "param `marschner_specular_gain`",
        ),
        (
            &[
                "techniques.shading=marschner_reference",
                "params.marschner_ior=0.9",
            ],
            "param `marschner_ior` of pass `hair`",
        ),
    ];
    let pipeline = repo_root().join("pipelines/marschner.toml");
    for (sets, want) in cases {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let message = match plait::session::compile_checked(&pipeline, &sets, &opts) {
            Ok(_) => panic!("{sets:?} compiled"),
            Err(e) => e.to_string(),
        };
        assert!(message.contains(want), "{sets:?}: {message}");
        let flag = sets.iter().any(|s| message.contains(&format!("--set {s}")));
        assert!(
            flag || message.contains("techniques/shading/marschner"),
            "{sets:?} names neither its flag nor the technique file: {message}"
        );
    }
}

/// The tables are drawn on the first frame only (`run = "once"`) and keep
/// their texels on later frames, while the hair pass reads them every frame.
#[test]
fn tables_are_drawn_once_and_kept_across_frames() {
    let (_lock, gpu) = open_gpu();
    let pipeline = repo_root().join("pipelines/marschner.toml");
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let size = (96, 72);
    let mut prepared = prepare(
        &gpu,
        &pipeline,
        &["params.marschner_table_size=32".into()],
        &scene,
        size,
    )
    .unwrap_or_else(|e| panic!("marschner.toml: {e}"));
    let tables = |prepared: &plait::session::Prepared<'_>| {
        ["marschner_m", "marschner_n"].map(|name| {
            prepared
                .read_resource(name)
                .unwrap_or_else(|e| panic!("{name}: {e}"))
                .bytes
        })
    };
    let mut first = None;
    for frame in 0..3u32 {
        prepared.set_frame(&scene.frame(size, frame));
        let report = prepared.render_unchecked().expect("renders");
        let pass = report
            .passes
            .iter()
            .find(|p| p.name == "marschner_tables")
            .expect("the table pass is scheduled");
        assert_eq!(
            pass.cached,
            frame > 0,
            "frame {frame}: the table pass ran again or not at all"
        );
        let now = tables(&prepared);
        assert!(
            now.iter().all(|t| t.iter().any(|&b| b != 0)),
            "frame {frame}: a table is empty"
        );
        match &first {
            None => first = Some(now),
            Some(f) => assert!(*f == now, "frame {frame}: the tables changed after frame 0"),
        }
    }
}
