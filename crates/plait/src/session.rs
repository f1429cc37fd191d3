//! Load → check → build → render, the path every program takes.

use std::path::{Path, PathBuf};

use plait_gpu::frame::FrameUniforms;
use plait_gpu::geometry::SceneGeometry;
use plait_gpu::{Gpu, GpuError, PassLibrary, Renderer};
use plait_graph::{CompileOptions, Errors, Schedule};
use plait_hair::scene::{Background, Scene, SceneError};

/// The pipeline `plait render` uses when none is given.
pub const DEFAULT_PIPELINE: &str = "pipelines/occupancy.toml";

/// Anything that can stop a render, each naming its file, pass or flag.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// Pipeline file or shader problems, all of them, with file:line:column.
    #[error("{0}")]
    Pipeline(#[from] Errors),
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error("the pipeline declares no output")]
    NoOutput,
    /// `--size` is what keeps the pipeline from fitting the adapter's
    /// limits: the flag, the largest size of its shape that fits, and what
    /// overflows ([`crate::size_limit`]).
    #[error("{0}")]
    Size(String),
    /// A param the scene cannot satisfy (more shading points than a strand
    /// has points), naming the param and the `--set` flag that gave it.
    #[error("{0}")]
    SceneFit(String),
    /// More strand segments than one acceleration structure of the adapter
    /// holds, with the numbers and the fix ([`crate::structure_limit`]).
    #[error("{0}")]
    StructureLimit(String),
    /// A bounded buffer the session sizes dropped data it cannot hold
    /// ([`crate::overflow`]); each counter says what `--set` would hold it.
    #[error("{}; {message}", crate::overflow::list(.overflow))]
    Dropped {
        message: String,
        overflow: Vec<plait_gpu::Overflow>,
    },
}

/// The checkout plait was built from (benchmarks and tests that need its
/// `examples/`); programs find library files through [`plait_assets`].
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A pipeline named on the command line, or the default one. A path that
/// exists (or is absolute) is taken as is; a plain relative name that does
/// not exist is looked up on the library search path, as given and under
/// `pipelines/` (`plait render forward.toml` from any directory), with the
/// built-in copies last.
pub fn resolve_pipeline(given: Option<&Path>) -> PathBuf {
    let candidate = given
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from(DEFAULT_PIPELINE));
    if candidate.exists() || candidate.is_absolute() || plait_assets::is_builtin(&candidate) {
        return candidate;
    }
    let plain = candidate
        .components()
        .all(|c| matches!(c, std::path::Component::Normal(_)));
    let found = candidate.to_str().filter(|_| plain).and_then(|name| {
        plait_assets::find(name).or_else(|| plait_assets::find(&format!("pipelines/{name}")))
    });
    found.unwrap_or(candidate)
}

/// A scene named on the command line, found like a pipeline: a path that
/// exists (or is absolute, or built in) is taken as is; a plain relative
/// name that does not exist is looked up on the library search path, as
/// given and under `examples/scenes/` (`--scene small.toml` from any
/// directory), with the built-in copies last. A built-in scene carries its
/// text only; `Scene::load` refuses one that names a file.
pub fn resolve_scene(given: &Path) -> PathBuf {
    if given.exists() || given.is_absolute() || plait_assets::is_builtin(given) {
        return given.to_path_buf();
    }
    let plain = given
        .components()
        .all(|c| matches!(c, std::path::Component::Normal(_)));
    let found = given.to_str().filter(|_| plain).and_then(|name| {
        plait_assets::find(name).or_else(|| plait_assets::find(&format!("examples/scenes/{name}")))
    });
    found.unwrap_or_else(|| given.to_path_buf())
}

/// The files on disk a render of `source` reads, for watching them: the
/// pipeline and every file it extends, the technique files, the shaders of
/// its passes (files it names and the pass types' own), the shader library,
/// the scene and the files the scene names. Best effort: a pipeline that does not load still
/// yields itself and the files its errors point at. Built-in copies are left
/// out (they cannot change). The pass types and the shader library are those
/// of `source`'s library, the value the render just used (the viewer and
/// `render --watch` read a new one on every change): no second library is
/// read to list them.
pub fn watched_files(source: &crate::source::PipelineSource, scene: Option<&Path>) -> Vec<PathBuf> {
    let pipeline = source.path.as_path();
    let library = &source.library;
    let mut files = vec![pipeline.to_path_buf()];
    match plait_graph::load(pipeline, &source.sets) {
        Ok(loaded) => {
            files.extend(loaded.files.iter().cloned());
            for pass in loaded.passes.values() {
                if let Some(shader) = &pass.shader {
                    files.push(shader.value.clone());
                }
                let own = library.get(&pass.type_name.value).and_then(|t| t.shader());
                if let Some(path) = own.and_then(plait_assets::find_on_disk) {
                    files.push(path);
                }
            }
        }
        Err(errors) => files.extend(errors.0.iter().filter_map(|e| match &e.location {
            plait_graph::Location::File { path, .. } => Some(path.clone()),
            _ => None,
        })),
    }
    // Technique files and the fragments they include: the whole folder.
    let roots = plait_graph::techniques::TechniqueRoots::for_pipeline(pipeline);
    for root in roots.layers().filter(|r| !plait_assets::is_builtin(r)) {
        let mut folders = vec![root.clone()];
        while let Some(folder) = folders.pop() {
            for entry in std::fs::read_dir(&folder).into_iter().flatten().flatten() {
                let path = entry.path();
                if path.is_dir() {
                    folders.push(path);
                } else if path.extension().is_some_and(|e| e == "toml") {
                    files.push(path);
                }
            }
        }
    }
    // The shader library as found now: its modules and point files.
    let own_roots = library
        .shaders
        .library()
        .map(|l| l.own_roots.clone())
        .unwrap_or_default();
    files.extend(
        plait_gpu::library::library_files(&own_roots)
            .into_iter()
            .map(|(_, path)| path),
    );
    if let Some(scene_path) = scene {
        files.push(scene_path.to_path_buf());
        if let Ok(loaded) = Scene::load(scene_path) {
            if let plait_hair::scene::HairSource::File(hair) = &loaded.hair.source {
                files.push(hair.clone());
            }
            if let Background::Image(image) = &loaded.background {
                files.push(image.clone());
            }
            files.extend(loaded.environment.files());
        }
    }
    files.retain(|f| !plait_assets::is_builtin(f));
    files.sort();
    files.dedup();
    files
}

/// Load, compile and check a pipeline against a library read for it now,
/// shaders included (naga), without a GPU (see [`compile_checked_in`]).
pub fn compile_checked(
    path: &Path,
    sets: &[String],
    opts: &CompileOptions,
) -> Result<Schedule, Errors> {
    compile_checked_in(&plait_passes::library_for(&[path]), path, sets, opts)
}

/// Load, compile and check a pipeline against `library`, shaders included
/// (naga), without a GPU. A bounded buffer still at its technique's default
/// is lowered to fit `opts`' binding limit, as a render does
/// ([`crate::overflow::compile_fitting`]), so `plait check` and `plait ab`'s
/// checks before any GPU work accept what the render would.
pub fn compile_checked_in(
    library: &PassLibrary,
    path: &Path,
    sets: &[String],
    opts: &CompileOptions,
) -> Result<Schedule, Errors> {
    let loaded = plait_graph::load(path, sets)?;
    let compile = |extra: &[String], opts: &CompileOptions| {
        if extra.is_empty() {
            check_pipeline(library, &loaded, opts)
        } else {
            let again = plait_graph::load(path, &[sets, extra].concat())?;
            check_pipeline(library, &again, opts)
        }
    };
    crate::overflow::compile_fitting(&compile, &[], opts)
}

/// Compile and check a loaded pipeline with `library` (see
/// [`compile_checked_in`]).
pub fn check_pipeline(
    library: &PassLibrary,
    pipeline: &plait_graph::Pipeline,
    opts: &CompileOptions,
) -> Result<Schedule, Errors> {
    plait_passes::compile_in(library, pipeline, opts)
}

/// A scene's geometry on the CPU, built once and shared by every pipeline rendering it.
/// (Clone: `plait ab --camera-distance` copies it per distance rather than
/// reading and baking its files again.)
#[derive(Clone)]
pub struct SceneData {
    pub scene: Scene,
    pub strands: plait_hair::Strands,
    pub meshes: Vec<plait_hair::mesh::Mesh>,
    /// The background image, when the scene names one.
    pub background: Option<image::RgbaImage>,
    /// The scene's environment (the procedural sky unless it names an
    /// image), read once: the `environment_source` of every pass.
    pub environment: plait_hair::EnvironmentImage,
    /// The guide strands simulation moves (every strand its own guide when
    /// the groom has none) and the head's colliders.
    pub guides: plait_hair::guides::Guides,
    pub colliders: Vec<plait_gpu::geometry::Collider>,
    /// The head mesh's signed distance field (a `[[meshes]]` entry with
    /// `role = "head"`), baked once here: the simulation's mesh collider.
    pub head_sdf: Option<plait_hair::sdf::SignedDistanceField>,
}

impl SceneData {
    pub fn new(mut scene: Scene) -> Result<Self, SceneError> {
        // Loads the hair and fits a camera or light given as "fit" to it.
        let strands = scene.load_hair()?;
        let meshes = scene.opaque_meshes();
        let background = match &scene.background {
            Background::Image(path) => Some(
                image::open(path)
                    .map_err(|e| SceneError::Invalid {
                        path: path.clone(),
                        message: format!("cannot read the background image: {e}"),
                    })?
                    .to_rgba8(),
            ),
            Background::Color(_) => None,
        };
        let environment = scene.environment.load()?;
        let guides = plait_hair::guides::scene_guides(&scene, &strands)?;
        let colliders = scene
            .head
            .iter()
            .map(|h| plait_gpu::geometry::Collider {
                center: h.center.into(),
                radii: h.radii.into(),
            })
            .collect();
        let head_sdf = scene.head_sdf();
        Ok(SceneData {
            head_sdf,
            scene,
            strands,
            meshes,
            background,
            environment,
            guides,
            colliders,
        })
    }

    /// The scene file, or the built-in default scene.
    pub fn load(path: Option<&Path>) -> Result<Self, SceneError> {
        match path {
            Some(p) => Self::new(Scene::load(p)?),
            None => Self::new(Scene::builtin_default()),
        }
    }

    /// Standard inputs for a frame of this scene at `size`, the scene as it
    /// is at time 0 (its first pose, when it is animated: what a single
    /// `plait render` shows, frame 0 of a sequence).
    pub fn frame(&self, size: (u32, u32), frame_index: u32) -> FrameUniforms {
        let head = self.scene.head_model(0.0);
        let pose = crate::frames::FramePose {
            index: frame_index,
            time: 0.0,
            head,
            head_previous: head,
            camera_distance: self.scene.camera_distance(0.0),
        };
        self.frame_posed(size, &pose, self.hair_posed(head).as_ref())
    }
}

/// A pipeline built on a device for one scene, ready to render frames.
///
/// Front ends render through [`Prepared::render`] and
/// [`Prepared::render_frame`] ([`crate::frames`]), which run the checks
/// every frame owes (a bounded buffer that drops, invocations cut short) and
/// return the frame's notes with its report, so none can forget them. The
/// renderer is private: resources are read back with
/// [`Prepared::read_resource`] and [`Prepared::read_buffer`], the encode
/// bench times [`Prepared::encode_only`], and a test that asserts on the
/// counters of a frame dropping data on purpose names
/// [`Prepared::render_unchecked`]. Outside this crate the frame step cannot
/// be bypassed:
///
/// ```compile_fail
/// fn bypass(prepared: &plait::session::Prepared<'_>) {
///     let _ = prepared.renderer.render();
/// }
/// ```
///
/// while the checked path compiles:
///
/// ```no_run
/// fn checked(prepared: &plait::session::Prepared<'_>) {
///     let _ = prepared.render();
/// }
/// ```
pub struct Prepared<'g> {
    /// Private so that a front end renders only through the frame step
    /// ([`Prepared::render`]), which checks every frame for dropped data and
    /// cut-short loops; reading resources back goes through the read-only
    /// accessors below.
    pub(crate) renderer: Renderer<'g>,
    /// Name of the resource images are read from (the first output).
    pub output: String,
    /// The head pose the uploaded hair follows ([`Prepared::render_frame`]).
    pub(crate) hair_pose: glam::Mat4,
    /// Whether the frame loop moves the hair with the head (rigidly, on the
    /// CPU). A pipeline whose simulation writes the hair on the GPU turns it
    /// off; the light is still fitted to where rigid hair would be.
    pub hair_follows_head: bool,
    /// `geometry = "wisps"`: how many wisps were built (their level of
    /// detail draws a prefix of them, [`crate::wisps::kept_wisps`]).
    pub wisp_count: Option<usize>,
    /// Their `wisp_lod_screen_fraction` ([`crate::wisps::lod_fraction`]).
    pub(crate) wisp_lod_fraction: f32,
    /// The frame inputs set last ([`Prepared::set_frame`]): a frame's
    /// level-of-detail notes are about the camera it was rendered from.
    pub(crate) uniforms: FrameUniforms,
}

impl Prepared<'_> {
    pub fn schedule(&self) -> &Schedule {
        self.renderer.schedule()
    }

    /// What the build adapted or chose for the adapter and scene (format
    /// downgrades, values fitted to the scene, sizes lowered to fit), for
    /// the front end to show once.
    pub fn notes(&self) -> &[String] {
        self.renderer.notes()
    }

    /// Read the output back as an 8-bit sRGB image.
    pub fn image(&self) -> Result<image::RgbaImage, GpuError> {
        Ok(self.renderer.read_resource(&self.output)?.to_image())
    }

    /// Read texture resource `name` back (layer 0).
    pub fn read_resource(&self, name: &str) -> Result<plait_gpu::readback::TexelData, GpuError> {
        self.renderer.read_resource(name)
    }

    /// Read buffer resource `name` back as bytes.
    pub fn read_buffer(&self, name: &str) -> Result<Vec<u8>, GpuError> {
        self.renderer.read_buffer(name)
    }

    /// Render one frame WITHOUT the frame step's checks: for a test that
    /// asserts on the overflow counters of a frame that drops data on
    /// purpose, or that renders a schedule whose checks are what it
    /// measures. Front ends use [`Prepared::render`], which fails a frame
    /// that dropped data nobody chose to drop.
    pub fn render_unchecked(&self) -> Result<plait_gpu::FrameReport, GpuError> {
        self.renderer.render()
    }

    /// Record one frame's commands without submitting them: for measuring
    /// the CPU cost of encoding (`benches/encode.rs`). A frame is rendered
    /// only by [`Prepared::render`]. Native only: a pass may wait for the GPU
    /// while recording (depth peeling), which a browser awaits instead.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn encode_only(&self) -> wgpu::CommandBuffer {
        self.renderer.encode()
    }

    /// Read the linear radiance (before the display transform) back as
    /// 32-bit floats: what a measurement in physical units reads, since the
    /// 8-bit output is tone-mapped ([`crate::linear`]).
    pub fn radiance(&self) -> Result<image::Rgba32FImage, GpuError> {
        let texels = self.renderer.read_resource(crate::linear::RADIANCE)?;
        Ok(crate::linear::to_f32_image(&texels))
    }
}

/// Compile, check (against the adapter too) and build `pipeline` for
/// `scene` at `size` on `gpu`, its bounded buffers sized to hold the first
/// frame unless the user sized them ([`crate::overflow`]).
pub fn prepare<'g>(
    gpu: &'g Gpu,
    pipeline: &Path,
    sets: &[String],
    scene: &SceneData,
    size: (u32, u32),
) -> Result<Prepared<'g>, SessionError> {
    let source = crate::source::PipelineSource::new(pipeline, sets);
    let schedule = crate::adapter::compile_on(gpu, &source.load(&[])?, &source, size)?;
    prepare_compiled(gpu, schedule, &source, scene, size)
}

/// [`prepare`] for a schedule already compiled for `gpu` at `size`
/// ([`crate::adapter::compile_on`]): nothing is compiled again unless a
/// bounded buffer the user did not size must grow to hold the first frame.
pub fn prepare_compiled<'g>(
    gpu: &'g Gpu,
    schedule: Schedule,
    source: &crate::source::PipelineSource,
    scene: &SceneData,
    size: (u32, u32),
) -> Result<Prepared<'g>, SessionError> {
    let fit = crate::scene_fit::fit_to_scene(&schedule, source, scene)?;
    let opts = gpu_options(gpu, size);
    // A grown buffer changes only sizes, which the executor checks again
    // against the adapter before it allocates anything. Every compile keeps
    // the values fitted to the scene and says so.
    let compile = |extra: &[String], opts: &CompileOptions| {
        source.compile(&[fit.sets.as_slice(), extra].concat(), opts)
    };
    let recompile = |extra: &[String]| {
        let mut schedule = crate::overflow::compile_fitting(&compile, extra, &opts)?;
        schedule.notes.extend(fit.notes.iter().cloned());
        Ok(schedule)
    };
    let schedule = if fit.sets.is_empty() {
        schedule
    } else {
        recompile(&[])?
    };
    crate::overflow::prepare_holding(gpu, schedule, &recompile, source, scene, size)
}

/// Standard inputs for frame `index` of `scene` at `size` as `schedule`
/// wants them: strand coverage unless its `[params]` say
/// `strand_coverage = false`.
pub fn frame_uniforms(
    schedule: &Schedule,
    scene: &SceneData,
    size: (u32, u32),
    index: u32,
) -> FrameUniforms {
    scene
        .frame(size, index)
        .with_strand_coverage(strand_coverage(schedule))
}

/// The pipeline's `strand_coverage` param (on unless it says otherwise).
pub fn strand_coverage(schedule: &Schedule) -> bool {
    schedule
        .params
        .get("strand_coverage")
        .and_then(|v| match v {
            plait_graph::Value::Bool(b) => Some(*b),
            _ => None,
        })
        .unwrap_or(true)
}

/// Compile options for rendering at `size` on `gpu`.
pub fn gpu_options(gpu: &Gpu, size: (u32, u32)) -> CompileOptions {
    CompileOptions {
        screen: size,
        max_texture_dimension: gpu.capabilities.max_texture_dimension,
        max_buffer_binding_size: gpu.capabilities.max_storage_buffer_binding_size,
        capabilities: gpu.capabilities.compile_capabilities(),
    }
}

/// Build a checked schedule for `scene` at `size` on `gpu` with the library
/// it was compiled with: `source` is where it came from (relative shader
/// paths resolve against its folder).
pub fn build<'g>(
    gpu: &'g Gpu,
    mut schedule: Schedule,
    source: &crate::source::PipelineSource,
    scene: &SceneData,
    size: (u32, u32),
) -> Result<Prepared<'g>, SessionError> {
    let pipeline = source.path.as_path();
    let output = schedule
        .outputs
        .first()
        .map(|&id| schedule.resources[id].name.clone())
        .ok_or(SessionError::NoOutput)?;
    // Before any GPU resource: a structure the adapter cannot hold.
    crate::structure_limit::check(
        &schedule,
        crate::structure_limit::HairSize::of(&scene.strands),
        &crate::structure_limit::mesh_sizes(&scene.meshes),
        &gpu.capabilities,
        &gpu.support.describe(),
    )?;
    let frame = frame_uniforms(&schedule, scene, size, 0);
    // A pass that writes the drawn hair (guide interpolation) moves it itself.
    let hair_written = schedule.passes.iter().any(|p| {
        p.writes.iter().any(|b| {
            b.resolved(&schedule.resources)
                .is_some_and(|r| r.scene && r.name == "hair_vertices")
        })
    });
    // The hair as it is at time 0 (the head's first pose).
    let hair_pose = scene.scene.head_model(0.0);
    let posed = scene.hair_posed(hair_pose);
    let hair = posed.as_ref().unwrap_or(&scene.strands);
    let mut geometry = SceneGeometry::upload_with_guides(
        &gpu.device,
        hair,
        &scene.meshes,
        &scene.guides,
        &scene.colliders,
        scene.head_sdf.as_ref(),
        hair_pose,
    );
    geometry.set_environment(&gpu.device, &gpu.queue, &scene.environment);
    let mut wisp_count = None;
    let mut wisp_lod_fraction = 0.0;
    if let Some((wisps, note)) = crate::wisps::build(&schedule, &source.library, scene) {
        geometry.set_wisps(&gpu.device, &wisps);
        schedule.notes.push(note);
        wisp_count = Some(wisps.wisp_count);
        wisp_lod_fraction = crate::wisps::lod_fraction(&schedule, &source.library);
    }
    let base_dir = pipeline.parent().unwrap_or(Path::new("."));
    let mut renderer = Renderer::new(gpu, schedule, &source.library, geometry, &frame, base_dir)?;
    if let Some(image) = &scene.background {
        renderer.set_background_image(image);
    }
    Ok(Prepared {
        renderer,
        output,
        hair_pose,
        hair_follows_head: !hair_written,
        wisp_count,
        wisp_lod_fraction,
        uniforms: frame,
    })
}
