//! Issue 43's multiple-scattering claim against the path-traced reference
//! (Mitsuba 3, Chiang et al. 2016's fibre, 16 scattering events): on blond
//! hair Zinke et al. 2008's dual scattering is closer to the path tracer
//! than single scattering (`none`), and the gap shrinks from blond to dark
//! brown to black (multiple scattering matters less in dark hair). Karis
//! 2016's wrap term is measured beside them.
//!
//! The measure is `scripts/mitsuba/hair_luminance.py`'s: the mean Rec. 709
//! luminance of the linear radiance over the hair pixels (where `karis` or
//! `dual_scattering` changes the `none` image), as a ratio to the path
//! tracer's over the same pixels. Scenes: tests/scenes/ms_*.toml (one groom,
//! three colours), 160×120, `pipelines/occupancy.toml` with
//! `techniques.shading=chiang`; the reference `tests/fixtures/
//! ms_path_traced.toml` (2 × 64 spp), cached by content key in the build
//! folder (`plait::ab::default_cache`) as `plait ab` caches it — the first
//! run renders it (Mitsuba installed by `scripts/ensure-mitsuba.sh`, which
//! `scripts/test.sh` runs), later runs read it.
//!
//! The same three scenes with the head and the ground black
//! (`dual_scattering_with_dark_surroundings`) isolate the hair's own
//! multiple scattering (issue 43): there Zinke's A_b as published, which
//! assumes hair without end behind every point, was 1.4× too bright on
//! blond (1.6× once blond's clear fibre was read at its own σ_a, ds43); the provider counts the strands behind instead (techniques/
//! multiple_scattering/dual_scattering/technique.toml), and every test
//! here measures the published form beside it, in a band of its own.
//!
//! The reference's own noise: `plait ab`'s estimate (half the two seeds'
//! RMSE difference, linear radiance) is asserted under the file's bound,
//! and the standard error it implies on a mean over the hair pixels is
//! printed beside the bands it must stay under.

use plait::ab::AbOptions;
use plait::session::prepare;
use plait_tests::bands::{Row, band_failures};
use plait_tests::{open_gpu, path_traced_plan, repo_root};

const SIZE: (u32, u32) = (160, 120);
const COLOURS: [&str; 3] = ["blond", "dark_brown", "black"];
/// Each variant: its name and its `--set`s beside `shading=chiang`. The
/// last is Zinke et al. 2008's A_b as published — unbounded hair behind
/// every point — which plait's dual scattering replaced by the strands
/// behind it (issue 43; techniques/multiple_scattering/dual_scattering/
/// technique.toml): measured beside it, its band must exclude it.
const METHODS: [(&str, &[&str]); 4] = [
    ("none", &["techniques.multiple_scattering=none"]),
    ("karis", &["techniques.multiple_scattering=karis"]),
    (
        "dual_scattering",
        &["techniques.multiple_scattering=dual_scattering"],
    ),
    (
        "dual_scattering_unbounded",
        &[
            "techniques.multiple_scattering=dual_scattering",
            "params.dual_scattering_count_behind=0",
        ],
    ),
];

/// Rec. 709 luminance of every pixel.
fn luminance(image: &image::Rgba32FImage) -> Vec<f64> {
    image
        .pixels()
        .map(|p| 0.2126 * p.0[0] as f64 + 0.7152 * p.0[1] as f64 + 0.0722 * p.0[2] as f64)
        .collect()
}

/// Per colour: the path tracer's noise RMSE, its mean hair luminance, the
/// hair pixel count, and each method's mean hair luminance over it.
struct Measured {
    noise_rmse: f64,
    reference: f64,
    pixels: usize,
    ratios: [f64; 4],
}

/// Per scene `tests/scenes/ms_<name>.toml`, in order.
fn measure(names: &[String]) -> Vec<Measured> {
    let root = repo_root();
    let mut options = AbOptions::new(
        vec![root.join("pipelines/occupancy.toml")],
        root.join("tests/fixtures/ms_path_traced.toml"),
    );
    options.scenes = names
        .iter()
        .map(|c| root.join(format!("tests/scenes/ms_{c}.toml")))
        .collect();
    options.sets = vec!["techniques.shading=chiang".to_owned()];
    options.size = SIZE;
    let plan = path_traced_plan(options);
    let (_lock, gpu) = open_gpu();
    let pipeline = root.join("pipelines/occupancy.toml");
    plan.scenes
        .iter()
        .zip(&plan.path_traced_images)
        .map(|(scene, reference)| {
            let images: Vec<Vec<f64>> = METHODS
                .iter()
                .map(|(m, variant)| {
                    let mut sets = vec!["techniques.shading=chiang".to_owned()];
                    sets.extend(variant.iter().map(|s| s.to_string()));
                    let prepared = prepare(&gpu, &pipeline, &sets, &scene.data, SIZE)
                        .unwrap_or_else(|e| panic!("{m} on {}: {e}", scene.name));
                    prepared.render_unchecked().expect("renders");
                    luminance(&prepared.radiance().expect("reads the radiance"))
                })
                .collect();
            let (none, karis, dual) = (&images[0], &images[1], &images[2]);
            let hair: Vec<usize> = (0..none.len())
                .filter(|&i| (dual[i] - none[i]).abs() > 1e-5 || (karis[i] - none[i]).abs() > 1e-5)
                .collect();
            assert!(
                hair.len() > 1000,
                "{}: {} hair pixels",
                scene.name,
                hair.len()
            );
            let mean = |l: &[f64]| hair.iter().map(|&i| l[i]).sum::<f64>() / hair.len() as f64;
            let reference_mean = mean(&luminance(&reference.linear));
            Measured {
                noise_rmse: reference.noise_rmse,
                reference: reference_mean,
                pixels: hair.len(),
                ratios: std::array::from_fn(|k| mean(&images[k]) / reference_mean),
            }
        })
        .collect()
}

/// The claim, and every method's ratio in a band per colour that admits no
/// other method's value (`plait_tests::bands`).
#[test]
fn dual_scattering_is_closer_than_single_scattering_on_blond_and_the_gap_shrinks() {
    let start = std::time::Instant::now();
    let measured = measure(&COLOURS.map(String::from));
    let mut report = Vec::new();
    let mut failures = Vec::new();
    let mut gaps = Vec::new();
    for ((colour, m), rows) in COLOURS.iter().zip(&measured).zip(BANDS) {
        // The noise RMSE is over the whole image; all of it in the hair
        // pixels makes their RMSE noise · √(pixels / hair), and the mean of
        // N = hair independent pixels errs by that / √N.
        let all = (SIZE.0 * SIZE.1) as f64;
        let standard_error = m.noise_rmse * all.sqrt() / m.pixels as f64 / m.reference;
        let [none, karis, dual, unbounded] = m.ratios;
        let gap = (none - 1.0).abs() - (dual - 1.0).abs();
        gaps.push(gap);
        report.push(format!(
            "{colour}: {} hair pixels, path tracer mean luminance {:.5} (noise RMSE {:.4}, \
             standard error of the mean ≤ {standard_error:.4} of it); luminance ÷ path tracer: \
             none {none:.3}, karis {karis:.3}, dual_scattering {dual:.3} \
             (unbounded A_b {unbounded:.3}); |none − 1| − |dual − 1| = {gap:.3}",
            m.pixels, m.reference, m.noise_rmse
        ));
        if m.noise_rmse > NOISE_BOUND {
            failures.push(format!(
                "{colour}: noise RMSE {:.4} > {NOISE_BOUND}",
                m.noise_rmse
            ));
        }
        failures.extend(band_failures(colour, &rows, &m.ratios));
    }
    if gaps[0] < BLOND_MARGIN {
        failures.push(format!(
            "blond: dual scattering closer than single scattering by {:.3} of the path tracer's luminance, asserted ≥ {BLOND_MARGIN}",
            gaps[0]
        ));
    }
    if !(gaps[0] > gaps[1] && gaps[1] > gaps[2]) {
        failures.push(format!(
            "the gap does not shrink blond → dark brown → black: {gaps:.3?}"
        ));
    }
    report.push(format!("{:.1} s", start.elapsed().as_secs_f64()));
    println!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The bound on the reference's noise RMSE (linear radiance, `plait ab`'s
/// two-seed estimate): the largest measured, blond's 0.0389 (dark brown
/// 0.0279, black 0.0107), × 1.5 — the file's `max_noise_rmse`, which
/// `plait ab` enforces too. The standard error it bounds on a mean over
/// the 4647 hair pixels (all the noise in them) is ≤ 0.0044 of the path
/// tracer's (blond; dark brown 0.0040, black 0.0028): the bands are ± 0.02,
/// black's none/dual pair ± 0.0063 (2.3 standard errors) — a bound for
/// another Mitsuba build; this one's seeded reference is the same image on
/// every run.
const NOISE_BOUND: f64 = 0.06;

/// The blond gap |none − 1| − |dual − 1| asserted: 0.048 (dark brown
/// 0.046, black 0.012) / 1.25, measured after the cuticle tilt's sign fix
/// (issue 42: R towards the root in `chiang` and in the Mitsuba export);
/// 0.067 / 0.060 / 0.014 before it, 0.069 / 0.060 / 0.013 before shading
/// followed the curve's tangent. It was 0.218 with Zinke's A_b as
/// published (unbounded hair behind every point); most of that was
/// back-scattering by hair the groom does not have (issue 43, the
/// dark-surroundings test below).
const BLOND_MARGIN: f64 = 0.038;

/// Per colour (blond, dark brown, black), each variant's mean hair
/// luminance ÷ the path tracer's, measured on lavapipe with this test
/// (Mitsuba 3 as scripts/ensure-mitsuba.sh pins it, LLVM 19), and its band:
/// ± a third of the way to the nearest other variant's value, at most
/// ± 0.02 (4.5 times the bound on the mean's standard error; lavapipe and
/// the seeded reference are deterministic — black's dual scattering lies
/// 0.0050 from the unbounded A_b's, so its band is ± 0.0017). Re-measured
/// after shading began to follow the curve's tangent (issue 47): every value
/// moved by at most 0.039 (karis on dark brown, dark surroundings); the claim
/// held. Re-measured again after the cuticle tilt's sign fix (issue 42): the
/// published A_b moved most (blond 0.622 → 0.534; 1.375 → 1.130 with dark
/// surroundings), karis with dark surroundings 3.248 → 3.659; the claim
/// holds by less (BLOND_MARGIN). Re-measured after the dual-scattering
/// tables' absorption rows began at the clear fibre (ds43: blond's σ_a, all
/// under the old first row's 0.032, read that row): blond's dual scattering
/// 0.4492 → 0.4619, its published A_b 0.534 → 0.623, dark brown's 0.5267 →
/// 0.5255 (its red σ_a 0.037 is near the old row), black unchanged; the
/// claim's gaps 0.061 / 0.044 / 0.012. Dual scattering undershoots the path
/// tracer on every colour (0.45 on blond), Karis's wrap term lands nearest
/// in mean luminance (1.05) with no error bound; on black even `none` is 0.78: the path tracer's light
/// from the lit ground and head onto the hair, which no real-time method
/// here models (issue 47's residual), not multiple scattering in the hair.
// Black's `none` measured 0.7853, which clippy takes for π/4: a ratio, not π.
#[allow(clippy::approx_constant)]
const BANDS: [[Row; 4]; 3] = [
    [
        ("none", 0.4009, (0.3848, 0.417)),
        ("karis", 1.05, (1.03, 1.07)),
        ("dual_scattering", 0.4619, (0.4419, 0.4819)),
        ("dual_scattering_unbounded", 0.6226, (0.6026, 0.6426)),
    ],
    [
        ("none", 0.4811, (0.4663, 0.4959)),
        ("karis", 0.9395, (0.9195, 0.9595)),
        ("dual_scattering", 0.5255, (0.5107, 0.5403)),
        ("dual_scattering_unbounded", 0.5879, (0.5679, 0.6079)),
    ],
    [
        ("none", 0.7804, (0.7762, 0.7846)),
        ("karis", 1.034, (1.014, 1.054)),
        ("dual_scattering", 0.7929, (0.7912, 0.7946)),
        ("dual_scattering_unbounded", 0.7979, (0.7962, 0.7996)),
    ],
];

/// Issue 43's isolation of the hair's own multiple scattering: the same
/// three scenes with the head and the ground black
/// (tests/scenes/ms_*_dark_surroundings.toml), where no light reaches the
/// hair by them in the path tracer either, so what differs from it is the
/// hair's own scattering. Each variant in a band that admits no other's
/// value — Zinke's A_b as published among them.
#[test]
fn dual_scattering_with_dark_surroundings() {
    let start = std::time::Instant::now();
    let measured = measure(&COLOURS.map(|c| format!("{c}_dark_surroundings")));
    let mut failures = Vec::new();
    for ((colour, m), rows) in COLOURS.iter().zip(&measured).zip(DARK_BANDS) {
        let [none, karis, dual, unbounded] = m.ratios;
        let all = (SIZE.0 * SIZE.1) as f64;
        let standard_error = m.noise_rmse * all.sqrt() / m.pixels as f64 / m.reference;
        println!(
            "{colour}, dark surroundings: {} hair pixels, path tracer mean luminance {:.5} \
             (noise RMSE {:.4}, standard error of the mean ≤ {standard_error:.4} of it); \
             luminance ÷ path tracer: none {none:.3}, karis {karis:.3}, \
             dual_scattering {dual:.3} (unbounded A_b {unbounded:.3})",
            m.pixels, m.reference, m.noise_rmse
        );
        if m.noise_rmse > NOISE_BOUND {
            failures.push(format!(
                "{colour}: noise RMSE {:.4} > {NOISE_BOUND}",
                m.noise_rmse
            ));
        }
        failures.extend(band_failures(colour, &rows, &m.ratios));
    }
    println!("{:.1} s", start.elapsed().as_secs_f64());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The blond dark-surroundings groom at 20000 strands instead of 3000
/// (tests/scenes/ms_blond_dense_dark_surroundings.toml): hair deep behind
/// the visible points, nearer the unbounded hair Zinke's A_b assumes. Not
/// a claim — a measurement for the book (`--ignored`; its reference takes
/// Mitsuba about 20 s more on a cold cache).
#[test]
#[ignore = "a measurement for the book, not a claim, run by hand: cargo test -p plait-tests --test multiple_scattering_claim dense -- --ignored --nocapture"]
fn dense_groom_against_the_path_tracer() {
    for m in measure(&["blond_dense_dark_surroundings".to_owned()]) {
        let [none, karis, dual, unbounded] = m.ratios;
        println!(
            "blond, 20000 strands, dark surroundings: {} hair pixels, path tracer mean \
             luminance {:.5} (noise RMSE {:.4}); luminance ÷ path tracer: none {none:.3}, \
             karis {karis:.3}, dual_scattering {dual:.3} (unbounded A_b {unbounded:.3})",
            m.pixels, m.reference, m.noise_rmse
        );
    }
}

/// As `BANDS`, with the head and the ground black (same command, same
/// rule). With Zinke's A_b as published dual scattering is 1.38 / 1.38 /
/// 1.15 of the path tracer; counting the strands behind each point it is
/// 0.75 / 0.89 / 1.09 — nearer on every colour, and single scattering
/// (0.46 / 0.58 / 0.95) below both. After the tables' rows began at the
/// clear fibre (ds43), blond 0.7135 → 0.7758 (published A_b 1.130 →
/// 1.564), dark brown 0.853 → 0.846, black 1.098 → 1.096 (inside its band).
const DARK_BANDS: [[Row; 4]; 3] = [
    [
        ("none", 0.4766, (0.4566, 0.4966)),
        ("karis", 3.659, (3.639, 3.679)),
        ("dual_scattering", 0.7758, (0.7558, 0.7958)),
        ("dual_scattering_unbounded", 1.564, (1.544, 1.584)),
    ],
    [
        ("none", 0.59, (0.57, 0.61)),
        ("karis", 3.233, (3.213, 3.253)),
        ("dual_scattering", 0.846, (0.826, 0.866)),
        ("dual_scattering_unbounded", 1.206, (1.186, 1.226)),
    ],
    [
        ("none", 0.971, (0.951, 0.991)),
        ("karis", 3.55, (3.53, 3.57)),
        ("dual_scattering", 1.098, (1.081, 1.115)),
        ("dual_scattering_unbounded", 1.149, (1.132, 1.166)),
    ],
];

/// The strands behind a point (the dual_scattering provider's `m`) come from
/// the self-shadow technique's strand count at a point beyond the hair,
/// which every provider must answer as "all the hair on this light ray":
/// on the blond dark-surroundings scene, the whole image's mean luminance
/// with `m` counted ÷ with Zinke's unbounded hair is measured 0.494
/// (exact) to 0.536 (deep_opacity) across the six providers (this test,
/// after the tables' rows began at the clear fibre, ds43: 0.630 to 0.668
/// before it; 0.544 to 0.579 before the cuticle tilt's sign fix, issue 42). With m = 0
/// everywhere (the count beyond the hair read at the point instead) every
/// provider measured 0.390–0.396 before that fix. Held: every provider
/// within 0.05 of exact's ratio and in [0.47, 0.80] — above m = 0's, below
/// the unbounded form's 1 (a provider answering 0 beyond the hair gives
/// m = 0).
#[test]
fn strands_behind_agree_across_strand_count_providers() {
    let root = repo_root();
    let (_lock, gpu) = open_gpu();
    let pipeline = root.join("pipelines/occupancy.toml");
    let path = root.join("tests/scenes/ms_blond_dark_surroundings.toml");
    let text = std::fs::read_to_string(&path).expect("reads the scene");
    let scene = plait_hair::Scene::from_toml_str(&text, &path).expect("parses");
    let data = plait::session::SceneData::new(scene).expect("loads");
    let mean_luminance = |self_shadow: &str, count_behind: &str| {
        let sets = [
            "techniques.shading=chiang".to_owned(),
            "techniques.multiple_scattering=dual_scattering".to_owned(),
            format!("techniques.self_shadow={self_shadow}"),
            format!("params.dual_scattering_count_behind={count_behind}"),
        ];
        let prepared = prepare(&gpu, &pipeline, &sets, &data, SIZE)
            .unwrap_or_else(|e| panic!("{self_shadow}: {e}"));
        prepared.render_unchecked().expect("renders");
        let l = luminance(&prepared.radiance().expect("reads the radiance"));
        l.iter().sum::<f64>() / l.len() as f64
    };
    let providers = [
        "exact",
        "occupancy",
        "occupancy_no_slab",
        "deep_opacity",
        "opacity_shadow_maps",
        "density_volume",
    ];
    let ratios: Vec<f64> = providers
        .iter()
        .map(|p| {
            let ratio = mean_luminance(p, "1") / mean_luminance(p, "0");
            println!("{p}: counted ÷ unbounded {ratio:.3}");
            ratio
        })
        .collect();
    let failures: Vec<String> = providers
        .iter()
        .zip(&ratios)
        .filter(|(_, r)| (**r - ratios[0]).abs() > 0.05 || !(0.47..=0.80).contains(*r))
        .map(|(p, r)| format!("{p}: {r:.3} (exact {:.3})", ratios[0]))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
