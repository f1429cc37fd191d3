//! GPU tier: the papers' claims, and every technique's measured quality, as
//! tests that fail when they stop holding.
//!
//! Thresholds come from measurement on lavapipe (Mesa 22.3.6, llvmpipe LLVM
//! 15, 256-bit); the measured value is next to each. Ratio floors are the
//! measured ratio / 1.25. Every band table is exclusive (`plait_tests::bands`):
//! no band admits another technique's value, measured or in this run, so a
//! technique that degrades, or turns into another, fails. Where two
//! techniques measure close, the bands are narrower than another driver's
//! rounding would need: lavapipe is deterministic (the same image bit for
//! bit, `tests/determinism.rs`), and `scripts/test.sh` runs the GPU tests on
//! lavapipe unless asked otherwise. Each band reaches from the measured
//! value at most a third of the way to its nearest neighbour's, and at most
//! 25% of the value; the bands of the exact methods (occupancy's visibility
//! on `small`, the fragment lists) start at 0.
//!
//! One convention for images, as `plait ab` measures them: RMSE on the
//! linear radiance (the float `radiance` target, `Prepared::radiance`,
//! `plait_compare::rmse_linear`: light as rendered, before exposure and tone
//! mapping, never clipped), SSIM on the displayed 8-bit images (after the
//! tone mapping, default `agx`). Values recorded before issue 47 were RMSE
//! of the 8-bit images and are quoted as such.
//!
//! Like with like (docs/design.md, "In front of"): every provider and the
//! reference are probed at the same points with the same light-map lookup
//! (no Fig. 9 jitter), and hair "in front of" a point is hair nearer the light
//! by more than the self-shadow bias, for all of them.

use std::path::PathBuf;

use plait::probe::{ProbeGrid, probe_visibility, visibility_error};
use plait::session::{SceneData, prepare};
use plait::source::PipelineSource;
use plait_gpu::Gpu;
use plait_tests::bands::{Row, band_failures};
use plait_tests::{open_gpu, repo_root};

fn pipeline(name: &str) -> PathBuf {
    repo_root().join("pipelines").join(format!("{name}.toml"))
}

fn scene(name: &str) -> SceneData {
    let path = repo_root().join(format!("examples/scenes/{name}.toml"));
    SceneData::load(Some(&path)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Mean |ΔV| of `variant`'s provider against `exact_shadow.toml` over the
/// probe rays through the hair (as `plait ab` measures it: 16×16 rays, 48 depths).
fn visibility_errors(gpu: &Gpu, scene: &SceneData, variants: &[&str]) -> Vec<f64> {
    let grid = ProbeGrid::through_hair(scene, (16, 16), 48);
    let probe = |name: &str| {
        let source = PipelineSource::new(&pipeline(name), &[]);
        probe_visibility(gpu, &source, scene, (64, 48), &grid)
            .unwrap_or_else(|e| panic!("probing {name}: {e}"))
            .unwrap_or_else(|| panic!("{name} has no visibility provider"))
    };
    let reference = probe("exact_shadow");
    variants
        .iter()
        .map(|v| visibility_error(&grid, &reference, &probe(v)).mean_abs_error)
        .collect()
}

/// Sintorn & Assarsson 2009 Fig. 4–5: occupancy + slab maps follow the
/// visibility function better than deep opacity maps with 3 layers, and the
/// slab map helps (occupancy bits alone are worse) — on every scene, by at
/// least the factors of [`VISIBILITY_RATIO_FLOORS`] (the book's claims
/// table states them).
#[test]
fn occupancy_follows_visibility_better_than_deep_opacity_maps() {
    let (_lock, gpu) = open_gpu();
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for (name, dom_floor, slab_floor) in VISIBILITY_RATIO_FLOORS {
        let errors = visibility_errors(
            &gpu,
            &scene(name),
            &["occupancy", "occupancy_no_slab", "deep_opacity"],
        );
        let (occupancy, bits_alone, dom) = (errors[0], errors[1], errors[2]);
        let (dom_ratio, slab_ratio) = (dom / occupancy, bits_alone / occupancy);
        let line = format!(
            "{name}: mean |ΔV| occupancy {occupancy:.6}, occupancy_no_slab {bits_alone:.6}, \
             deep_opacity {dom:.6}: DOM-3 {dom_ratio:.1}× occupancy's (asserted ≥ {dom_floor}), \
             without slabs {slab_ratio:.2}× (asserted ≥ {slab_floor})"
        );
        if !(dom_ratio >= dom_floor && slab_ratio >= slab_floor) {
            failures.push(line.clone());
        }
        report.push(line);
    }
    println!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// (scene, DOM-3's mean |ΔV| over occupancy's, occupancy bits alone over
/// occupancy's): the asserted floors, each the ratio measured on lavapipe
/// divided by 1.25 and rounded down. Measured since the light maps weigh a
/// strand by its share of a texel (issue 47; mean |ΔV| occupancy / no slab /
/// DOM-3): small 0.000127 / 0.001038 / 0.003699 (29.2×, 8.19×); stray
/// 0.000321 / 0.002033 / 0.004994 (15.5×, 6.33×); default 0.000925 /
/// 0.003172 / 0.007980 (8.6×, 3.43×). Before, occupancy counted whole
/// fragments and was within 0.000001 of exact on small (floors 1000× and
/// 100×; stray 30× / 4×, default 9× / 1.8×): its bits only place a slab's
/// count, so with shares each set bit stands for the slab's mean share while
/// the exact lists count each fragment's own.
const VISIBILITY_RATIO_FLOORS: [(&str, f64, f64); 3] = [
    ("small", 23.0, 6.5),
    ("stray", 12.0, 5.0),
    ("default", 6.8, 2.7),
];

/// Every self-shadowing technique's mean |ΔV| on `small` stays in a band
/// around its measured value, and no band admits another technique's value
/// (`plait_tests::bands`): a change that degrades one, or turns it into
/// another, fails here.
#[test]
fn every_self_shadowing_technique_keeps_its_measured_error() {
    let (_lock, gpu) = open_gpu();
    // (pipeline, measured mean |ΔV| on small, allowed band)
    let expected: [Row; 9] = [
        ("occupancy", MEASURED_OCCUPANCY, (0.0, 0.00016)),
        ("occupancy_no_slab", MEASURED_NO_SLAB, (0.0009, 0.0013)),
        ("deep_opacity", MEASURED_DOM, (0.0030, 0.0046)),
        ("opacity_shadow_maps", MEASURED_OSM, (0.00030, 0.00048)),
        ("density_clustering", MEASURED_DC, (0.00020, 0.00028)),
        ("modified_shadow_map", MEASURED_MSM, (0.124, 0.169)),
        ("tressfx_shadow", MEASURED_TRESSFX, (0.0651, 0.078)),
        ("density_volume", MEASURED_DENSITY_VOLUME, (0.052, 0.0625)),
        ("no_self_shadow", MEASURED_NONE, (0.088, 0.12)),
    ];
    let names: Vec<&str> = expected.iter().map(|e| e.0).collect();
    let errors = visibility_errors(&gpu, &scene("small"), &names);
    let failures = band_failures("self-shadowing, mean |ΔV| on small", &expected, &errors);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

// Mean |ΔV| against exact_shadow.toml on examples/scenes/small.toml, measured
// on lavapipe with the probe of `plait ab` (16×16 rays × 48 depths), since
// every light map weighs a strand by its share of a texel (issue 47). Before
// (whole texels): occupancy 0.000001148, no slab 0.0005612, DOM-3 0.004802,
// OSM 0.0003157, DC 0.0002214, MSM 0.1709, TressFX 0.08474, none 0.1269 —
// the exact reference shadows less now (a thin strand blocks its share), so
// no self-shadowing is nearer it. The depth-only maps carried no share then
// (MSM 0.1885, TressFX 0.09283, their density a constant k = 0.4); since
// each strand crossed blocks its share of a light ray (k = w · ρ · width, ρ
// strands per unit depth and width, the groom's mean width,
// shaders/lib/light_share.wgsl; the default ρ = 264.2 gives small at
// light_size 512 the k of 2.67 strands per texel's column, each blocking its
// share of the texel, tests/shadow_coverage.rs) they measure 0.1357 and
// 0.06757 (re-measured after ρ lost the texel: the same values) (the density volume's upper bound tightened from 0.063 to 0.0625,
// a third of the way to TressFX's new value). The modified shadow map is
// still further from exact than no self-shadowing: one ρ for every texel
// cannot tell where the groom is thin.
//
// Since strands wider than a light texel are drawn at their width in the
// light maps (issue 47 item 4: quads, on small at 512 the strands' roots,
// 0.01 over a texel of 0.009 × 0.0115), exact's Σ (1 − V) over the probe's
// samples is the same (127.8 against 128.7 with one-texel lines) but spread
// over two more of the 256 rays (29 pass through hair, 27 before), each
// with a strand's edge in its texel: no self-shadowing's mean over those
// rays falls 0.09925 → 0.09181 (its band's floor 0.097 → 0.088, still above
// TressFX's band). Opacity shadow maps 0.0003443 → 0.0004078 (band's top
// 0.00040 → 0.00048, below occupancy_no_slab's floor): more texels hold a
// strand's share, each a place where its slices' interpolation misplaces it
// (not isolated further). The others stay in their bands; every value
// below is that run's (before: occupancy 0.0001267, no slab 0.001038, DOM
// 0.003699, DC 0.0002525, MSM 0.1357, TressFX 0.06757, density volume
// 0.06008).
const MEASURED_OCCUPANCY: f64 = 0.000_142_6;
const MEASURED_NO_SLAB: f64 = 0.000_976_7;
const MEASURED_DOM: f64 = 0.003_369;
const MEASURED_OSM: f64 = 0.000_407_8;
const MEASURED_DC: f64 = 0.000_260_0;
const MEASURED_MSM: f64 = 0.1276;
const MEASURED_TRESSFX: f64 = 0.06867;
const MEASURED_NONE: f64 = 0.09181;
// The density volume at its default 32³ (issue 43): a voxel spreads a
// strand's shadow over its cross-section, so a point right behind a strand
// reads less than the texel's exact list gives and a point beside it more;
// along the probe's rays its optical depth is 0.475× exact's on small's 400
// strands, 0.85× on the default groom, while the total over the light's
// plane is conserved (tests/shadow_coverage.rs). 0.0570 at 64³ (plait ab on
// small, 480×360, pipelines extending density_volume.toml with each R).
const MEASURED_DENSITY_VOLUME: f64 = 0.05831;

/// The band check fails for a band that admits another technique: the
/// self-shadowing bands as they were (the modified shadow map's [0.10, 0.25]
/// held no self-shadowing's 0.127), and passes once they are exclusive.
/// CPU only.
#[test]
fn a_band_that_admits_another_technique_fails() {
    let loose: [Row; 2] = [
        ("modified_shadow_map", 0.1709, (0.10, 0.25)),
        ("no_self_shadow", 0.1269, (0.08, 0.18)),
    ];
    let got = [0.1709, 0.1269];
    let failures = band_failures("loose", &loose, &got);
    assert!(
        failures
            .iter()
            .any(|f| f.contains("admits no_self_shadow (measured"))
            && failures
                .iter()
                .any(|f| f.contains("admits no_self_shadow (this run"))
            && failures.iter().any(|f| f.contains("overlaps")),
        "{failures:?}"
    );
    let tight: [Row; 2] = [
        ("modified_shadow_map", 0.1709, (0.157, 0.21)),
        ("no_self_shadow", 0.1269, (0.113, 0.141)),
    ];
    assert_eq!(band_failures("tight", &tight, &got), Vec::<String>::new());
    // One technique rendered as the other: its value leaves its band and
    // enters the other's.
    let swapped = band_failures("tight", &tight, &[0.1269, 0.1269]);
    assert!(
        swapped
            .iter()
            .any(|f| f.contains("modified_shadow_map 0.1269 outside")),
        "{swapped:?}"
    );
}

struct ImageError {
    rmse: f64,
    ssim: f64,
}

/// The papers' strands: lines of one alpha each (the groom varies it by ±0.1
/// between strands), no strand coverage (which weighs
/// a thin strand's alpha by the part of the pixel it covers, so alphas differ
/// along and between strands). Occupancy-order blending measures ᾱ per pixel
/// (Σα / n of its visible fragments), which is the paper's constant where all
/// alphas are equal; the claims hold with coverage (the default) and without.
const PAPER_STRANDS: &str = "params.strand_coverage=false";

/// A rendered frame as `plait ab` compares it: the linear radiance (for
/// RMSE) and the displayed 8-bit image (for SSIM).
struct Frame {
    shown: image::RgbaImage,
    radiance: image::Rgba32FImage,
}

impl Frame {
    /// RMSE against `other` in linear radiance, as `plait ab` measures it.
    fn rmse(&self, other: &Frame) -> f64 {
        plait_compare::rmse_linear(&self.radiance, &other.radiance).expect("same size")
    }
}

fn render(gpu: &Gpu, name: &str, scene: &SceneData, size: (u32, u32), sets: &[String]) -> Frame {
    let prepared = prepare(gpu, &pipeline(name), sets, scene, size)
        .unwrap_or_else(|e| panic!("preparing {name}: {e}"));
    let report = prepared
        .render_unchecked()
        .unwrap_or_else(|e| panic!("rendering {name}: {e}"));
    // A reference (the fragment lists on stray) that lost fragments would
    // make every comparison against it wrong.
    let dropped: Vec<String> = report.dropped().map(|o| o.to_string()).collect();
    assert!(dropped.is_empty(), "{name} dropped data: {dropped:?}");
    Frame {
        shown: prepared
            .image()
            .unwrap_or_else(|e| panic!("reading {name}: {e}")),
        radiance: prepared
            .radiance()
            .unwrap_or_else(|e| panic!("reading {name}'s radiance: {e}")),
    }
}

fn image_errors(
    gpu: &Gpu,
    scene: &SceneData,
    size: (u32, u32),
    reference: &str,
    variants: &[&str],
    sets: &[String],
) -> Vec<ImageError> {
    let truth = render(gpu, reference, scene, size, sets);
    variants
        .iter()
        .map(|v| {
            let img = render(gpu, v, scene, size, sets);
            ImageError {
                rmse: truth.rmse(&img),
                ssim: plait_compare::ssim(&truth.shown, &img.shown).expect("same size"),
            }
        })
        .collect()
}

/// Sintorn & Assarsson 2009 §3.4, Fig. 2: occupancy-order blending is closer
/// to the exactly sorted image than weighted-average blending and than opaque
/// strands, in RMSE and in SSIM, by at least the factors of
/// [`BLENDING_CASES`] (measured ratio / [`MARGIN`]; the book's claims table
/// states them). `small`
/// against depth peeling (the paper's ground truth); `stray` against the
/// per-pixel fragment lists sorted exactly (`linked_list.toml`), which equal
/// depth peeling (tested below on `small`) and cost far less on that scene
/// (`cargo bench -p plait --bench claims`). With strand coverage (the
/// defaults) and with the papers' strands of one alpha. Each variant's RMSE
/// also stays in its band, and no band admits another variant's RMSE
/// (`plait_tests::bands`).
#[test]
fn occupancy_order_blending_is_closest_to_sorted_blending() {
    let (_lock, gpu) = open_gpu();
    let mut failures = Vec::new();
    for case in BLENDING_CASES {
        let sets: Vec<String> = case
            .paper_strands
            .then(|| PAPER_STRANDS.to_owned())
            .into_iter()
            .collect();
        let strands = if case.paper_strands {
            "paper strands"
        } else {
            "coverage"
        };
        let e = image_errors(
            &gpu,
            &scene(case.scene),
            case.size,
            case.reference,
            &["occupancy", "weighted_average", "opaque"],
            &sets,
        );
        let (occ, wa, opaque) = (&e[0], &e[1], &e[2]);
        // Dissimilarity: how far SSIM is from 1.
        let dis = |x: &ImageError| (1.0 - x.ssim).max(1e-9);
        let ratios = [
            wa.rmse / occ.rmse,
            opaque.rmse / occ.rmse,
            dis(wa) / dis(occ),
            dis(opaque) / dis(occ),
        ];
        let what = [
            "RMSE weighted_average / occupancy",
            "RMSE opaque / occupancy",
            "1 - SSIM weighted_average / occupancy",
            "1 - SSIM opaque / occupancy",
        ];
        println!(
            "{} ({strands}) vs {}: RMSE occupancy {:.6}, weighted_average {:.6}, opaque {:.6}; \
             1 - SSIM occupancy {:.6}, weighted_average {:.6}, opaque {:.6}",
            case.scene,
            case.reference,
            occ.rmse,
            wa.rmse,
            opaque.rmse,
            dis(occ),
            dis(wa),
            dis(opaque)
        );
        for ((what, got), measured) in what.iter().zip(ratios).zip(case.ratios) {
            let floor = measured / MARGIN;
            let line = format!(
                "{} ({strands}): {what} {got:.2}× (measured {measured}×, asserted ≥ {floor:.2}×)",
                case.scene
            );
            println!("{line}");
            if got < floor {
                failures.push(format!("margin: {line}"));
            }
        }
        let rmse = [occ.rmse, wa.rmse, opaque.rmse];
        let table = format!("{} ({strands}) vs {}, RMSE", case.scene, case.reference);
        failures.extend(band_failures(&table, &case.rmse, &rmse));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// How much of its measured lead over another technique a technique may
/// lose before a ratio test fails: a fifth (the ratio falls below measured /
/// 1.25).
const MARGIN: f64 = 1.25;

struct BlendingCase {
    scene: &'static str,
    reference: &'static str,
    size: (u32, u32),
    paper_strands: bool,
    /// RMSE against the reference of occupancy, weighted average and
    /// opaque: measured, and the band each is held to.
    rmse: [Row; 3],
    /// Weighted average's and opaque's RMSE over occupancy's, then their
    /// 1 - SSIM over occupancy's, as measured on lavapipe (the test prints
    /// them). The asserted floor of each is the measured ratio / [`MARGIN`].
    ratios: [f64; 4],
}

const BLENDING_CASES: [BlendingCase; 4] = [
    BlendingCase {
        scene: "small",
        reference: "depth_peeling",
        size: (160, 120),
        paper_strands: false,
        rmse: [
            ("occupancy", 0.000_371_8, (0.000359, 0.000464)),
            ("weighted_average", 0.001282, (0.000979, 0.0016)),
            ("opaque", 0.09208, (0.0704, 0.115)),
        ],
        ratios: [3.45, 247.66, 13.70, 6192.14],
    },
    BlendingCase {
        scene: "stray",
        reference: "linked_list",
        size: (128, 96),
        paper_strands: false,
        rmse: [
            ("occupancy", 0.000_332_5, (0.00025, 0.000415)),
            ("weighted_average", 0.004214, (0.00317, 0.00526)),
            ("opaque", 0.07909, (0.0594, 0.0988)),
        ],
        ratios: [12.67, 237.86, 37.89, 3876.45],
    },
    BlendingCase {
        scene: "small",
        reference: "depth_peeling",
        size: (160, 120),
        paper_strands: true,
        rmse: [
            ("occupancy", 0.000_560_6, (0.000421, 0.0007)),
            ("weighted_average", 0.008186, (0.00776, 0.0102)),
            ("opaque", 0.01915, (0.0155, 0.0239)),
        ],
        ratios: [14.60, 34.16, 101.05, 176.78],
    },
    BlendingCase {
        scene: "stray",
        reference: "linked_list",
        size: (128, 96),
        paper_strands: true,
        // Weighted average and opaque strands measure within 6% of each
        // other here (their bands stop a third of the way between).
        rmse: [
            ("occupancy", 0.000_610_0, (0.000458, 0.000762)),
            ("weighted_average", 0.01208, (0.00906, 0.0123)),
            ("opaque", 0.01278, (0.0126, 0.0159)),
        ],
        ratios: [19.80, 20.95, 42.46, 42.43],
    },
];

/// Every transparency technique's RMSE against depth peeling on `small`
/// stays in a band around its measured value, and no band admits another
/// technique's; the fragment lists sorted exactly match peeling at the
/// tolerance actually measured.
#[test]
fn every_transparency_technique_keeps_its_measured_error() {
    let (_lock, gpu) = open_gpu();
    // (pipeline, measured RMSE on small at 160×120, allowed band)
    // The fragment lists differ from peeling only in 16-bit list colours and
    // fragments at equal depth: their band starts at 0.
    let expected: [Row; 6] = [
        ("occupancy", 0.000_560_6, (0.000421, 0.0007)),
        ("weighted_average", 0.008186, (0.00776, 0.0102)),
        ("alpha_to_coverage", 0.03734, (0.0313, 0.0466)),
        ("opaque", 0.01915, (0.0155, 0.0239)),
        ("linked_list", 0.000_121_0, (0.0, 0.000151)),
        // The 3 nearest fragments' colour, unordered (see the ShortCut test).
        ("shortcut", 0.006900, (0.00518, 0.00732)),
    ];
    let names: Vec<&str> = expected.iter().map(|e| e.0).collect();
    let errors = image_errors(
        &gpu,
        &scene("small"),
        (160, 120),
        "depth_peeling",
        &names,
        &[PAPER_STRANDS.into()],
    );
    for (name, got) in names.iter().zip(&errors) {
        println!("{name}: RMSE {:.5} SSIM {:.5}", got.rmse, got.ssim);
    }
    let rmse: Vec<f64> = errors.iter().map(|e| e.rmse).collect();
    let failures = band_failures("transparency, RMSE on small", &expected, &rmse);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// With strand coverage (the default), against depth peeling on `small` at
/// 160×120. Coverage makes alphas differ from fragment to fragment (a pixel's
/// mean runs from 0.05 to 0.25 here, tests/coverage.rs), so occupancy-order
/// blending weighs the fragments in front, and corrects the total by
/// Λ = 1 - (1-ᾱ)^n, with the pixel's own mean ᾱ = Σα / n (§3.4's one alpha,
/// measured where it applies). With the frame's one ᾱ instead
/// (`mean_alpha = "frame"`) it was 0.0094, behind weighted average's 0.0034
/// (RMSE of the 8-bit images, before issue 47) — the defect this measurement
/// keeps fixed. Opaque strands ignore coverage, so they are far from the thin
/// strands of the others. Bands as above, exclusive: the fragment lists'
/// 0.000333 and occupancy order's 0.000372 are 11% apart, and both bands
/// stop a third of the way between.
#[test]
fn transparency_with_strand_coverage_keeps_its_measured_error() {
    let (_lock, gpu) = open_gpu();
    let expected: [Row; 6] = [
        ("occupancy", 0.000_371_8, (0.000359, 0.000464)),
        ("weighted_average", 0.001282, (0.000979, 0.0016)),
        // The shader's alpha-to-coverage mask since issue 47 (the hardware's
        // set one sample of four for any alpha above 0).
        ("alpha_to_coverage", 0.02703, (0.0203, 0.0337)),
        ("opaque", 0.09208, (0.0704, 0.115)),
        // 11% below occupancy order. `plait ab`'s diff map shows one pixel
        // (largest |Δ| 0.045 of radiance; that in 3 channels of one pixel
        // alone is RMSE 0.00032 at 160×120); the tone curve shrank it in the
        // 8-bit images (0.00024 there). That pixel, (55, 77) on the ground
        // under a stray strand, is darker with the lists (displayed 169 vs
        // 173): likely a fragment at the same depth as another, which the
        // lists keep and peeling drops (peel.wgsl discards clip.z <= the
        // previous layer's); not yet checked fragment by fragment.
        ("linked_list", 0.000_333_3, (0.0, 0.000346)),
        // Behind weighted average here, yet equal to its own definition at
        // every pixel (tests/shortcut.rs): with alphas ~0.13 the exact
        // blend's shares decay by only (1-α) per layer, so its colour is
        // nearer an average over all n than over the 3 nearest (book:
        // "ShortCut behind weighted average").
        ("shortcut", 0.003269, (0.00261, 0.00408)),
    ];
    let names: Vec<&str> = expected.iter().map(|e| e.0).collect();
    let errors = image_errors(
        &gpu,
        &scene("small"),
        (160, 120),
        "depth_peeling",
        &names,
        &[],
    );
    let rmse: Vec<f64> = errors.iter().map(|e| e.rmse).collect();
    let failures = band_failures(
        "transparency with coverage, RMSE on small",
        &expected,
        &rmse,
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// AMD TressFX 4.1 ShortCut (techniques/transparency/shortcut/technique.toml): the
/// colour of the k nearest fragments, weighted by alpha but not by order, at
/// the coverage of every fragment. Two consequences, held on `small` at
/// 160×120 with the papers' strands of one alpha (0.6):
/// - with k at least every pixel's depth complexity it keeps every fragment,
///   so its colour is weighted average's Σα·rgb / Σα and, with one alpha,
///   its coverage 1 - Π(1-α) is weighted average's 1 - (1-ᾱ)ⁿ: the two
///   images agree to the 16-bit sums (RMSE ≤ 0.001 between them);
/// - as k shrinks towards 1 the colour comes from fewer fragments in front,
///   which the sorted blend weighs most (α, α(1-α), α(1-α)², …): with α = 0.6
///   k = 1 is closer to depth peeling than k = 3, and k = 3 closer than
///   weighted average (each by at least the measured factor / 1.25).
///
/// With strand coverage the alphas are ~0.13 and k = 3 is behind weighted
/// average (`transparency_with_strand_coverage_keeps_its_measured_error`):
/// not a defect — ShortCut renders its definition (tests/shortcut.rs) — but
/// the exact blend's shares α·Π(1-α) then fall slowly with depth, and an
/// even share over all n fragments stays nearer them than one over the
/// nearest 3 (book/src/guide/claims.md, "ShortCut behind weighted average").
#[test]
fn shortcut_is_weighted_average_in_the_limit_and_gains_from_the_nearest() {
    let (_lock, gpu) = open_gpu();
    let small = scene("small");
    let size = (160, 120);
    let sets = |extra: &[&str]| -> Vec<String> {
        std::iter::once(PAPER_STRANDS)
            .chain(extra.iter().copied())
            .map(str::to_owned)
            .collect()
    };
    let all = render(
        &gpu,
        "shortcut",
        &small,
        size,
        &sets(&["params.nearest=256"]),
    );
    let wa = render(&gpu, "weighted_average", &small, size, &sets(&[]));
    let limit = all.rmse(&wa);
    let truth = render(&gpu, "depth_peeling", &small, size, &sets(&[]));
    let error = |img: &Frame| truth.rmse(img);
    let k1 = error(&render(
        &gpu,
        "shortcut",
        &small,
        size,
        &sets(&["params.nearest=1"]),
    ));
    let k3 = error(&render(&gpu, "shortcut", &small, size, &sets(&[])));
    let wa_error = error(&wa);
    println!(
        "shortcut k=256 vs weighted_average: RMSE {limit:.5}; against depth peeling: \
         k=1 {k1:.6}, k=3 {k3:.6}, weighted average {wa_error:.6}"
    );
    // Measured on lavapipe, RMSE of the linear radiance: k=1 0.002918,
    // k=3 0.006900, weighted average 0.008186 (k=256 against weighted
    // average: 0.00014). On the 8-bit images before issue 47: 0.00746,
    // 0.01649, 0.02063, ratios 2.21× and 1.25×.
    const K1_OVER_K3: f64 = 2.36;
    const K3_OVER_WA: f64 = 1.18;
    // The claim is an order: a floor below 1 (1.18 / 1.25) would admit k=3
    // behind weighted average, so the floor is at least 1.
    let k3_floor = (K3_OVER_WA / MARGIN).max(1.0);
    let mut failures = Vec::new();
    if limit > 0.001 {
        failures.push(format!(
            "k=256 differs from weighted average: RMSE {limit:.5} > 0.001"
        ));
    }
    if k3 / k1 < K1_OVER_K3 / MARGIN {
        failures.push(format!(
            "k=1 ({k1:.5}) not {:.2}× closer than k=3 ({k3:.5})",
            K1_OVER_K3 / MARGIN
        ));
    }
    if wa_error / k3 < k3_floor {
        failures.push(format!(
            "k=3 ({k3:.5}) not {k3_floor:.2}× closer than weighted average ({wa_error:.5})"
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Sintorn & Assarsson 2009 §4: at 512² the occupancy method's light maps
/// take 10 MB, against 130 MB for OSM-128 and 18 MB for DOM-16. plait's
/// light maps (every `light_*` resource of the self-shadowing technique, by
/// the memory plan; no GPU), each with the 2 MiB depth range and its 1 MiB
/// scratch: occupancy's bits + slabs 8 MiB (11 in all), OSM-16's slices
/// 16 MiB (19), DOM-3's 3 MiB (6), the exact reference's lists and counts
/// 97 MiB (100).
#[test]
fn light_map_memory_matches_the_papers_sizes() {
    const MIB: u64 = 1 << 20;
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for (name, want_mib) in [
        ("occupancy", 11),
        ("opacity_shadow_maps", 19),
        ("deep_opacity", 6),
        ("exact_shadow", 100),
    ] {
        let options = plait_graph::CompileOptions {
            screen: (320, 240),
            ..Default::default()
        };
        let schedule = plait::session::compile_checked(&pipeline(name), &[], &options)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let maps: Vec<(String, u64)> = schedule
            .resources
            .iter()
            .filter(|r| r.name.starts_with("light_"))
            .map(|r| (r.name.clone(), r.desc.bytes()))
            .collect();
        let total: u64 = maps.iter().map(|(_, b)| b).sum();
        let line = format!("{name}: {:.2} MiB in {maps:?}", total as f64 / MIB as f64);
        if (total + MIB / 2) / MIB != want_mib {
            failures.push(format!("{line}: expected {want_mib} MiB"));
        }
        report.push(line);
    }
    println!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
