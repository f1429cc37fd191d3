//! Helpers shared by plait's cross-crate tests (`tests/*.rs`).

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, OnceLock};

pub mod bands;
pub mod golden_images;
pub mod strand_trace;
pub mod vertex_ao;

static GPU_LOCK: Mutex<()> = Mutex::new(());

/// Open the GPU or fail with the device crate's message, which says how to
/// install lavapipe (`apt-get install -y mesa-vulkan-drivers`) — never a skip.
/// The lock keeps a test binary's GPU tests one at a time: lavapipe already
/// uses every core for one device, and each test opens its own device so
/// uncaptured GPU errors cannot be blamed on another test.
pub fn open_gpu() -> (MutexGuard<'static, ()>, plait_gpu::Gpu) {
    let guard = GPU_LOCK
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    match plait_gpu::Gpu::new() {
        Ok(gpu) => {
            let _ = DRIVER.set(describe_driver(&gpu));
            (guard, gpu)
        }
        Err(e) => panic!("GPU tests need an adapter and none could be opened: {e}"),
    }
}

static DRIVER: OnceLock<String> = OnceLock::new();

/// The driver and its version, as a golden records the one it was made on
/// (`llvmpipe, Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)`): two Mesa releases
/// rasterize the same lines a little differently, so a golden failing on
/// another driver than its own must say so.
pub fn describe_driver(gpu: &plait_gpu::Gpu) -> String {
    format!("{}, {}", gpu.info.driver, gpu.info.driver_info)
}

/// The driver this test binary renders with: the one [`open_gpu`] opened, or,
/// for a binary that opens its GPU another way, the adapter [`plait_gpu::Gpu::new`] picks.
pub fn driver() -> &'static str {
    DRIVER.get_or_init(|| match plait_gpu::Gpu::new() {
        Ok(gpu) => describe_driver(&gpu),
        Err(e) => format!("no adapter ({e})"),
    })
}

/// The rgba32float textures `targets` of the fixture pipeline
/// `tests/fixtures/FIXTURE` after one frame at `size` on the small scene,
/// texel by texel: the GPU side of the closed-form tests (a technique's value
/// at one direction pair per texel).
pub fn fixture_texels(fixture: &str, size: (u32, u32), targets: &[&str]) -> Vec<Vec<[f32; 4]>> {
    let (_lock, gpu) = open_gpu();
    let scene =
        plait::session::SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
            .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures").join(fixture);
    let prepared = plait::session::prepare(&gpu, &pipeline, &[], &scene, size)
        .unwrap_or_else(|e| panic!("{fixture} prepares: {e}"));
    prepared.render().expect("renders");
    targets
        .iter()
        .map(|name| {
            let read = prepared.read_resource(name).expect(name);
            read.bytes
                .chunks_exact(16)
                .map(|t| {
                    std::array::from_fn(|c| {
                        f32::from_le_bytes(t[4 * c..4 * c + 4].try_into().expect("4 bytes"))
                    })
                })
                .collect()
        })
        .collect()
}

/// The checkout root (the parent of `tests/`).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ has a parent")
        .to_path_buf()
}

/// `examples/scenes/small.toml` with its `[head]` table replaced by `head`
/// (TOML text, e.g. a `[[meshes]]` head read from `head.glb`).
pub fn small_scene_with_head(head: &str) -> plait_hair::Scene {
    let path = repo_root().join("examples/scenes/small.toml");
    let text = std::fs::read_to_string(&path).expect("small.toml");
    let start = text.find("[head]").expect("small.toml has a [head]");
    let end = start
        + text[start..]
            .find("\n\n")
            .expect("a blank line after [head]");
    let text = format!("{}{head}{}", &text[..start], &text[end..]);
    plait_hair::Scene::from_toml_str(&text, &path).expect("the scene parses")
}

/// A coarse wave of 9 points, mostly in the plane z = 0 facing a camera
/// at (0, 0, 6) (it sees about 4.3 × 3.2 of that plane): each segment turns
/// by tens of degrees, through inflections. Out of the plane by up to 0.3,
/// so that no chord has a zero component: in the plane, a mutant testing
/// `all(chord != 0)` where the shader tests `all(chord == 0)`
/// (strand_curve.wgsl 27:15 and 42:15) never took the other branch.
pub fn coarse_wave() -> Vec<glam::Vec3> {
    (0..9)
        .map(|i| {
            let x = i as f32;
            glam::Vec3::new(-1.6 + x * 0.4, (x * 1.1).sin() * 0.4, 0.3 * (x * 0.9).cos())
        })
        .collect()
}

/// A test scene written inline: `text` parsed as if it were the file
/// `tests/<name>` (its errors name that place), its procedural hair replaced
/// by one strand through `points`, of `thickness` (world units), alpha 1 and
/// one `colour`.
pub fn one_strand_scene(
    name: &str,
    text: &str,
    points: &[glam::Vec3],
    thickness: f32,
    colour: f32,
) -> plait::session::SceneData {
    strands_scene(name, text, &[points.to_vec()], thickness, colour)
}

/// [`one_strand_scene`] with its hair replaced by every polyline of
/// `strands`, each of `thickness`, alpha 1 and one `colour`.
pub fn strands_scene(
    name: &str,
    text: &str,
    strands: &[Vec<glam::Vec3>],
    thickness: f32,
    colour: f32,
) -> plait::session::SceneData {
    let path = repo_root().join("tests").join(name);
    let scene = plait_hair::Scene::from_toml_str(text, &path).expect("the scene parses");
    let mut data = plait::session::SceneData::new(scene).expect("the scene loads");
    data.strands = plait_hair::Strands::new();
    for points in strands {
        data.strands
            .push_strand(points, |_| thickness, |_| 1.0, glam::Vec3::splat(colour));
    }
    data
}

/// The scene of the self-shadow count tests (`tests/strand_count.rs`,
/// `tests/mutants/ray_traced.rs`), named `tests/<name>`: no ambient, a ground
/// 0.5 below the origin, a camera at (0, 2, 2) looking at the origin, a
/// directional light travelling along `light`, and as its hair `strands`,
/// each a polyline of width `width`, alpha 1 and grey 0.5.
pub fn strands_under_light(
    name: &str,
    strands: &[Vec<glam::Vec3>],
    width: f32,
    light: glam::Vec3,
) -> plait::session::SceneData {
    let text = format!(
        r#"
ambient = 0.0
[hair.procedural]
strands = 1
segments = 1
[ground]
height = -0.5
half_size = 3.0
[camera]
eye = [0.0, 2.0, 2.0]
target = [0.0, 0.0, 0.0]
fov_y_degrees = 35.0
[light]
type = "directional"
direction = [{}, {}, {}]
intensity = 1.0
"#,
        light.x, light.y, light.z
    );
    strands_scene(name, &text, strands, width, 0.5)
}

/// The `plait ab` plan of `options` (one repeat) with its path-traced
/// reference's Mitsuba images rendered or taken from the build folder's
/// cache (`plait::ab::default_cache`, as `plait ab` caches them):
/// `plan.path_traced_images` holds one per scene.
pub fn path_traced_plan(mut options: plait::ab::AbOptions) -> plait::ab::Plan {
    options.repeats = 1;
    let mut plan = plait::ab::Plan::new(options).unwrap_or_else(|e| panic!("the plan: {e}"));
    plait::ab::render_references(&mut plan, &plait::ab::default_cache(), &mut |line| {
        eprintln!("{line}");
        Ok(())
    })
    .unwrap_or_else(|e| panic!("the path-traced references: {e}"));
    plan
}

/// `PLAIT_BLESS=1` (re)writes snapshots and golden images instead of comparing.
pub fn bless() -> bool {
    std::env::var("PLAIT_BLESS").is_ok_and(|v| !v.is_empty() && v != "0")
}

/// Files under `dir` (recursively) whose name ends with `.{ext}`, sorted.
pub fn files_with_ext(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let entries =
            std::fs::read_dir(&d).unwrap_or_else(|e| panic!("cannot list {}: {e}", d.display()));
        for entry in entries {
            let path = entry.expect("directory entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|x| x == ext) {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// Every `pipelines/*.toml` (not recursive); panics when there are none.
pub fn pipeline_files() -> Vec<PathBuf> {
    let dir = repo_root().join("pipelines");
    let files: Vec<PathBuf> = files_with_ext(&dir, "toml")
        .into_iter()
        .filter(|p| p.parent() == Some(dir.as_path()))
        .collect();
    assert!(
        !files.is_empty(),
        "found no pipeline files in {}: the snapshot and golden tests would test nothing",
        dir.display()
    );
    files
}

/// `path` relative to the checkout root, with `/` separators, for messages and snapshots.
pub fn rel(path: &Path) -> String {
    let root = repo_root();
    let root = root.canonicalize().unwrap_or(root);
    let path = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
    path.strip_prefix(&root)
        .unwrap_or(&path)
        .to_string_lossy()
        .replace('\\', "/")
}

/// A minimal line diff: the first differing lines with a little context.
pub fn line_diff(expected: &str, actual: &str) -> String {
    let e: Vec<&str> = expected.lines().collect();
    let a: Vec<&str> = actual.lines().collect();
    let mut out = String::new();
    let first = (0..e.len().max(a.len())).find(|&i| e.get(i) != a.get(i));
    let Some(first) = first else {
        return "(texts differ only in trailing newlines)".into();
    };
    let start = first.saturating_sub(3);
    for l in &e[start..first] {
        out += &format!("   {l}\n");
    }
    // Show up to 20 lines of each side from the first difference.
    for l in e.iter().skip(first).take(20) {
        out += &format!(" - {l}\n");
    }
    for l in a.iter().skip(first).take(20) {
        out += &format!(" + {l}\n");
    }
    format!(
        "first difference at line {} (- committed, + actual):\n{out}",
        first + 1
    )
}

/// The strands of `all` that `keep` accepts (by index), each with its first
/// point's thickness, alpha and colour: a smaller groom of the same scene.
pub fn strands_subset(
    all: &plait_hair::Strands,
    keep: impl Fn(usize) -> bool,
) -> plait_hair::Strands {
    let mut out = plait_hair::Strands::new();
    for s in (0..all.strand_count()).filter(|&s| keep(s)) {
        let r = all.offsets[s] as usize..all.offsets[s + 1] as usize;
        let (t, a) = (all.thickness[r.start], all.alpha[r.start]);
        out.push_strand(&all.points[r.clone()], |_| t, |_| a, all.color[r.start]);
    }
    out
}

/// `all`'s hair taken away but for its bounds: two zero-length, transparent
/// strands at the corners of its bounding box. The light's frustum is fitted
/// to the hair's bounds, so the opaque scene is shadowed and framed as it is
/// with the hair; taking every strand away would leave nothing to fit it to.
/// What a golden's hair pixels are measured against (`golden_images`).
pub fn hair_taken_away(all: &plait_hair::Strands) -> plait_hair::Strands {
    let b = all.bounds();
    let mut out = plait_hair::Strands::new();
    for corner in [b.min, b.max] {
        out.push_strand(&[corner, corner], |_| 0.0, |_| 0.0, glam::Vec3::ZERO);
    }
    out
}
