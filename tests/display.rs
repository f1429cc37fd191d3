//! The display transform (issue 47 items 2–3): every tone-mapping operator
//! (`techniques/tone_mapping/*/tone_map.wgsl`) against its published formula
//! evaluated here on the CPU, on known radiance from 0.001 to 1000, at three
//! exposures; exposure +1 doubling the radiance before the operator; the
//! OpenEXR of the radiance holding the float target bit for bit; and the
//! measurement behind the default operator (hair pixels at the display's
//! maximum, per operator, on two scenes).

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

type Rgb = [f64; 3];

/// Each operator's formula, from its source (the citations are in each
/// technique.toml); `c` is the exposed radiance.
fn operator(name: &str, c: Rgb) -> Rgb {
    match name {
        "clip" => c.map(|x| x.clamp(0.0, 1.0)),
        "reinhard" => reinhard(c),
        "aces_fitted" => aces_fitted(c),
        "agx" => agx(c),
        "pbr_neutral" => pbr_neutral(c),
        other => panic!("no CPU formula for operator `{other}`: add one"),
    }
}

/// Reinhard et al. 2002 eq. 3, L_d = L / (1 + L), on Rec. 709 luminance.
fn reinhard(c: Rgb) -> Rgb {
    let l = 0.2126 * c[0].max(0.0) + 0.7152 * c[1].max(0.0) + 0.0722 * c[2].max(0.0);
    if l <= 0.0 {
        return [0.0; 3];
    }
    c.map(|x| (x / (1.0 + l)).clamp(0.0, 1.0))
}

fn rows(m: [Rgb; 3], v: Rgb) -> Rgb {
    m.map(|r| r[0] * v[0] + r[1] * v[1] + r[2] * v[2])
}

/// Columns, as GLSL's mat3(c0, c1, c2) * v.
fn cols(m: [Rgb; 3], v: Rgb) -> Rgb {
    [0, 1, 2].map(|i| m[0][i] * v[0] + m[1][i] * v[1] + m[2][i] * v[2])
}

/// Stephen Hill's ACES fit (BakingLab ACES.hlsl).
fn aces_fitted(c: Rgb) -> Rgb {
    let input = [
        [0.59719, 0.35458, 0.04823],
        [0.07600, 0.90834, 0.01566],
        [0.02840, 0.13383, 0.83777],
    ];
    let output = [
        [1.60475, -0.53108, -0.07367],
        [-0.10208, 1.10813, -0.00605],
        [-0.00327, -0.07276, 1.07602],
    ];
    let fit = rows(input, c)
        .map(|v| (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081));
    rows(output, fit).map(|x| x.clamp(0.0, 1.0))
}

/// AgX as three.js r160's AgXToneMapping (from Filament, from Blender 4).
fn agx(c: Rgb) -> Rgb {
    let to_2020 = [
        [0.6274, 0.0691, 0.0164],
        [0.3293, 0.9195, 0.0880],
        [0.0433, 0.0113, 0.8956],
    ];
    let from_2020 = [
        [1.6605, -0.1246, -0.0182],
        [-0.5876, 1.1329, -0.1006],
        [-0.0728, -0.0083, 1.1187],
    ];
    let inset = [
        [0.856627153315983, 0.137318972929847, 0.11189821299995],
        [0.0951212405381588, 0.761241990602591, 0.0767994186031903],
        [0.0482516061458583, 0.101439036467562, 0.811302368396859],
    ];
    let outset = [
        [
            1.1271005818144368,
            -0.1413297634984383,
            -0.14132976349843826,
        ],
        [
            -0.11060664309660323,
            1.157823702216272,
            -0.11060664309660294,
        ],
        [
            -0.016493938717834573,
            -0.016493938717834257,
            1.2519364065950405,
        ],
    ];
    let (min_ev, max_ev) = (-12.47393, 4.026069);
    let v = cols(inset, cols(to_2020, c)).map(|x| {
        let e = (x.max(1e-10).log2() - min_ev) / (max_ev - min_ev);
        let x = e.clamp(0.0, 1.0);
        let (x2, x4) = (x * x, x * x * x * x);
        15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x
            - 0.00232
    });
    let v = cols(outset, v).map(|x| x.max(0.0).powf(2.2));
    cols(from_2020, v).map(|x| x.clamp(0.0, 1.0))
}

/// Khronos PBR Neutral (2024).
fn pbr_neutral(c: Rgb) -> Rgb {
    let start = 0.8 - 0.04;
    let x = c[0].min(c[1]).min(c[2]);
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let c = c.map(|v| v - offset);
    let peak = c[0].max(c[1]).max(c[2]);
    if peak < start {
        return c;
    }
    let d = 1.0 - start;
    let new_peak = 1.0 - d * d / (peak + d - start);
    let g = 1.0 - 1.0 / (0.15 * (peak - new_peak) + 1.0);
    c.map(|v| v * new_peak / peak * (1.0 - g) + new_peak * g)
}

const OPERATORS: [&str; 5] = ["clip", "reinhard", "aces_fitted", "agx", "pbr_neutral"];

/// (radiance, final) of tests/fixtures/tone_cases.toml with `sets`, as f32 RGBA.
fn tone_cases(gpu: &plait_gpu::Gpu, sets: &[String]) -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/tone_cases.toml");
    let prepared = prepare(gpu, &pipeline, sets, &scene, (80, 4)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let read = |name: &str| {
        let t = prepared.read_resource(name).expect("reads back");
        (0..(t.width * t.height) as usize)
            .map(|i| t.texel(i))
            .collect::<Vec<_>>()
    };
    (read("radiance"), read("final"))
}

/// Every operator, at exposures -2, 0 and +1, within 2e-4 of its formula on
/// every case (f32 on the GPU against f64 here). A changed constant or a
/// dropped step in a tone_map.wgsl fails here.
#[test]
fn every_operator_matches_its_formula_at_every_exposure() {
    let (_lock, gpu) = open_gpu();
    let mut failures = Vec::new();
    for op in OPERATORS {
        for exposure in [-2.0f64, 0.0, 1.0] {
            let sets = vec![
                format!("techniques.tone_mapping=\"{op}\""),
                format!("params.exposure={exposure}"),
            ];
            let (radiance, shown) = tone_cases(&gpu, &sets);
            let mut worst = (0.0f64, 0usize);
            for (i, (r, s)) in radiance.iter().zip(&shown).enumerate() {
                let exposed = [0, 1, 2].map(|c| r[c] as f64 * exposure.exp2());
                let want = operator(op, exposed);
                for c in 0..3 {
                    let err = (s[c] as f64 - want[c]).abs();
                    if err > worst.0 {
                        worst = (err, i);
                    }
                }
            }
            println!(
                "{op:12} exposure {exposure:+}: largest |GPU - formula| {:.2e}",
                worst.0
            );
            if worst.0 > 2e-4 {
                let i = worst.1;
                failures.push(format!(
                    "{op} at exposure {exposure}: pixel {i} radiance {:?} shows {:?}, formula {:?}",
                    radiance[i],
                    shown[i],
                    operator(
                        op,
                        radiance[i].map(|v| v as f64 * exposure.exp2())[..3]
                            .try_into()
                            .unwrap()
                    )
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Exposure +1 doubles the radiance before the operator: with `clip`, every
/// case whose doubled radiance is below 1 shows exactly twice its radiance,
/// and the cases at or above 1 show 1.
#[test]
fn exposure_plus_one_doubles_the_radiance() {
    let (_lock, gpu) = open_gpu();
    let sets = vec![
        "techniques.tone_mapping=\"clip\"".to_owned(),
        "params.exposure=1".to_owned(),
    ];
    let (radiance, shown) = tone_cases(&gpu, &sets);
    let mut checked = 0;
    for (r, s) in radiance.iter().zip(&shown) {
        for c in 0..3 {
            let want = (2.0 * r[c]).min(1.0);
            assert!(
                (s[c] - want).abs() <= 1e-6 * want.max(1e-3),
                "radiance {} shows {} at exposure +1, want {want}",
                r[c],
                s[c]
            );
            checked += usize::from(2.0 * r[c] < 1.0 && r[c] > 0.0);
        }
    }
    assert!(checked > 100, "only {checked} unclipped cases");
}

/// `plait render --out x.exr` path: the default pipeline's radiance
/// (rgba16float) read back, widened to f32 and written as OpenEXR reads back
/// bit for bit (f16 → f32 is exact, and the EXR holds 32-bit floats).
#[test]
fn the_exr_holds_the_float_target_bit_for_bit() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(None).expect("the default scene");
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let sets = ["pipeline.outputs=[\"final\", \"radiance\"]".to_owned()];
    let prepared = prepare(&gpu, &pipeline, &sets, &scene, (64, 48)).expect("prepares");
    prepared.render_unchecked().expect("renders");
    let texels = prepared.read_resource("radiance").expect("reads");
    assert_eq!(texels.format, plait_graph::Format::Rgba16Float);
    let exr = plait::linear::encode_exr(&plait::linear::to_f32_image(&texels)).expect("encodes");
    let back = image::load_from_memory_with_format(&exr, image::ImageFormat::OpenExr)
        .expect("decodes")
        .into_rgba32f();
    assert_eq!(back.dimensions(), (64, 48));
    let mut above_one = 0;
    for (i, p) in back.pixels().enumerate() {
        for c in 0..4 {
            let o = i * 8 + c * 2;
            let half = u16::from_le_bytes([texels.bytes[o], texels.bytes[o + 1]]);
            let want = f16_to_f32(half);
            assert_eq!(p.0[c].to_bits(), want.to_bits(), "pixel {i} channel {c}");
            above_one += usize::from(c < 3 && want > 1.0);
        }
    }
    println!("{above_one} channels above 1 kept (they would clip in an 8-bit target)");
}

/// IEEE 754 binary16 to f32, by hand (independent of the readback's own
/// conversion): every f16 is exactly an f32.
fn f16_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exp = ((h >> 10) & 0x1f) as i32;
    let frac = (h & 0x3ff) as f32;
    sign * match exp {
        0 => frac * 2f32.powi(-24),
        31 if frac == 0.0 => f32::INFINITY,
        31 => f32::NAN,
        e => (1.0 + frac / 1024.0) * 2f32.powi(e - 15),
    }
}

/// The evidence behind the default operator: per operator, on the default
/// scene and on the mesh head, at exposure 0 and +2 (radiance 4× brighter,
/// as an image of brighter light), the share of hair pixels (hair coverage
/// over one half) and of all pixels with a channel at the display's maximum
/// (255), and the mean displayed hair value (sRGB, 0…1: dimmed mid-tones
/// show as a low mean). The default pipeline's operator must show at most
/// 2 % of hair pixels at the maximum at either exposure.
#[test]
fn tone_mapping_choice() {
    let worst = choice_table("pipelines/occupancy.toml", &[0.0, 2.0]);
    assert!(
        worst.at_max <= 0.02,
        "the default operator `{}` shows {:.1} % of hair pixels at the display's maximum",
        worst.operator,
        100.0 * worst.at_max
    );
}

/// The same evidence for `pipelines/default.toml` (issue 43: the Chiang
/// fibre with dual scattering, what `scripts/render.sh` renders), written
/// into that file's comment by `bash scripts/tone_mapping_choice.sh
/// default`: at its own exposure and one and two stops above, its operator
/// shows at most 2 % of hair pixels at the display's maximum, and at its own
/// exposure the mean displayed hair is not dimmer than occupancy.toml's
/// (0.387 on the default scene, 0.366 on the mesh head, at 320x240: the
/// table in techniques/tone_mapping/point.toml) by more than 0.02.
#[test]
fn default_pipeline_tone_mapping_choice() {
    let pipeline = repo_root().join("pipelines/default.toml");
    let own = pipeline_exposure(&pipeline);
    let worst = choice_table("pipelines/default.toml", &[own, own + 1.0, own + 2.0]);
    assert!(
        worst.at_max <= 0.02,
        "default.toml's operator `{}` shows {:.1} % of hair pixels at the display's maximum",
        worst.operator,
        100.0 * worst.at_max
    );
    for (scene, floor) in [("default", 0.387 - 0.02), ("mesh_head", 0.366 - 0.02)] {
        let mean = worst.mean_at_own[scene];
        assert!(
            mean >= floor,
            "default.toml's hair on {scene} shows a mean of {mean:.3}, dimmer than {floor:.3}"
        );
    }
}

/// What [`choice_table`] found for the pipeline's own operator: the largest
/// share of hair pixels at the maximum over the exposures, and the mean
/// displayed hair per scene at the first exposure.
struct Worst {
    operator: String,
    at_max: f64,
    mean_at_own: std::collections::HashMap<&'static str, f64>,
}

/// Print the table of every operator at each of `exposures` (stops, as
/// `params.exposure`) on the default scene and the mesh head, rendered by
/// `pipeline` (relative to the repository), marking the pipeline's own.
fn choice_table(pipeline: &str, exposures: &[f64]) -> Worst {
    let (_lock, gpu) = open_gpu();
    let pipeline = repo_root().join(pipeline);
    let scenes = [
        ("default", None),
        (
            "mesh_head",
            Some(repo_root().join("examples/scenes/mesh_head.toml")),
        ),
    ];
    let default_op = default_operator(&pipeline);
    println!("adapter: {}", gpu.adapter_name());
    println!(
        "| scene | exposure | operator | hair px at 255 | all px at 255 | mean shown hair (sRGB) |"
    );
    println!("|---|---|---|---|---|---|");
    let mut worst = Worst {
        operator: default_op.clone(),
        at_max: 0.0,
        mean_at_own: Default::default(),
    };
    for (label, path) in &scenes {
        let scene = SceneData::load(path.as_deref()).expect("scene loads");
        for (i, exposure) in exposures.iter().enumerate() {
            for op in OPERATORS {
                let sets = [
                    format!("techniques.tone_mapping=\"{op}\""),
                    format!("params.exposure={exposure}"),
                    "pipeline.outputs=[\"final\", \"hair\"]".to_owned(),
                ];
                let share = clipped_shares(&gpu, &pipeline, &sets, &scene);
                let marker = if op == default_op { " (default)" } else { "" };
                println!(
                    "| {label} | {exposure:+} | {op}{marker} | {:.1} % of {} | {:.1} % | {:.3} |",
                    100.0 * share.hair,
                    share.hair_pixels,
                    100.0 * share.all,
                    share.hair_mean
                );
                if op == default_op {
                    worst.at_max = worst.at_max.max(share.hair);
                    if i == 0 {
                        worst.mean_at_own.insert(label, share.hair_mean);
                    }
                }
            }
        }
    }
    worst
}

struct Shares {
    hair: f64,
    hair_pixels: usize,
    all: f64,
    hair_mean: f64,
}

/// Render `pipeline` with `sets` at 320x240 and measure [`Shares`].
fn clipped_shares(
    gpu: &plait_gpu::Gpu,
    pipeline: &std::path::Path,
    sets: &[String],
    scene: &SceneData,
) -> Shares {
    let p = prepare(gpu, pipeline, sets, scene, (320, 240)).expect("prepares");
    p.render_unchecked().expect("renders");
    let shown = p.image().expect("final");
    let hair = p.read_resource("hair").expect("hair");
    let (mut n, mut at_max, mut all_max, mut sum) = (0usize, 0usize, 0usize, 0.0f64);
    for (i, px) in shown.pixels().enumerate() {
        let max = px.0[..3].contains(&255);
        all_max += usize::from(max);
        if hair.texel(i)[3] > 0.5 {
            n += 1;
            at_max += usize::from(max);
            sum += px.0[..3].iter().map(|&v| v as f64).sum::<f64>() / 765.0;
        }
    }
    Shares {
        hair: at_max as f64 / n.max(1) as f64,
        hair_pixels: n,
        all: all_max as f64 / (shown.width() * shown.height()) as f64,
        hair_mean: sum / n.max(1) as f64,
    }
}

/// `params.exposure` of `pipeline` as loaded (0 when it sets none).
fn pipeline_exposure(pipeline: &std::path::Path) -> f64 {
    let loaded = plait_graph::load(pipeline, &[]).expect("loads");
    loaded
        .params
        .get("exposure")
        .and_then(|v| v.value.as_f64())
        .unwrap_or(0.0)
}

/// `[techniques] tone_mapping` of `pipeline` as compiled.
fn default_operator(pipeline: &std::path::Path) -> String {
    let loaded = plait_graph::load(pipeline, &[]).expect("loads");
    loaded
        .techniques
        .iter()
        .find(|t| t.point == "tone_mapping")
        .map(|t| t.name.clone())
        .expect("the pipeline chooses a tone_mapping technique")
}
