//! One device, the built-in library and the built-in small scene; a gallery
//! pipeline compiled for the device's limits, checked against its adapter
//! (the same check and message as `plait check --adapter`), built, rendered
//! offscreen and read back. The last build is kept, so turning the camera
//! renders again without compiling.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use plait::session::{Prepared, SceneData};
use plait::source::PipelineSource;
use plait_gpu::{FrameReport, Gpu, PassLibrary};

/// The scene the page renders: the tests' small scene, built in.
pub const SCENE: &str = "examples/scenes/small.toml";

/// The adapter's name in messages when the browser gives none.
pub const UNNAMED_ADAPTER: &str = "this browser's WebGPU adapter (unnamed)";

/// What the page asks for.
#[derive(Clone, Debug, PartialEq, serde::Deserialize)]
pub struct Request {
    /// A gallery pipeline's file name (`occupancy.toml`).
    pub pipeline: String,
    pub width: u32,
    pub height: u32,
    /// `--set` flags: `techniques.shading=kajiya_kay`, `params.slabs=8`.
    #[serde(default)]
    pub sets: Vec<String>,
    /// The camera turned about its target, radians ([`crate::orbit`]).
    #[serde(default)]
    pub yaw: f32,
    #[serde(default)]
    pub pitch: f32,
    /// A resource of the schedule to read back instead of its output (a
    /// shadow map, say): how a test compares what the page's passes wrote.
    #[serde(default)]
    pub read: Option<String>,
}

/// A frame read back.
pub struct Frame {
    pub width: u32,
    pub height: u32,
    /// 8-bit sRGB RGBA rows, top first (what `plait render` writes as PNG).
    pub rgba: Vec<u8>,
    pub report: FrameReport,
    /// What compile changed to fit the adapter, one sentence each.
    pub notes: Vec<String>,
    /// The built pipeline's choice points and params, for the page's controls.
    pub controls: Controls,
    /// The GPU-time table as `plait render` prints it.
    pub timings: crate::timings::Timings,
    /// The compiled schedule drawn as `plait graph --format svg` draws it.
    pub graph: String,
}

/// A choice point of the built pipeline and what can fill it.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Choice {
    pub point: String,
    pub chosen: String,
    pub choices: Vec<String>,
}

/// The page's controls: a drop-down per choice point, a field per param
/// (as `plait view` has them).
#[derive(Clone, Debug, serde::Serialize)]
pub struct Controls {
    pub techniques: Vec<Choice>,
    pub params: Vec<(String, String)>,
}

impl Controls {
    fn of(schedule: &plait_graph::Schedule, pipeline: &Path) -> Controls {
        let roots = plait_graph::techniques::TechniqueRoots::for_pipeline(pipeline);
        Controls {
            techniques: schedule
                .techniques
                .iter()
                .map(|t| Choice {
                    point: t.point.clone(),
                    chosen: t.name.clone(),
                    choices: roots.choices(&t.point),
                })
                .collect(),
            params: schedule
                .params
                .iter()
                .map(|(k, v)| (k.clone(), v.to_string()))
                .collect(),
        }
    }
}

/// The build a frame was rendered with, kept for the next frame.
struct Built {
    key: (String, u32, u32, Vec<String>),
    prepared: Prepared<'static>,
}

pub struct Engine {
    gpu: &'static Gpu,
    library: Arc<PassLibrary>,
    scene: SceneData,
    built: Option<Built>,
}

/// The built-in path of a gallery pipeline.
pub fn pipeline_path(name: &str) -> PathBuf {
    Path::new(plait_assets::BUILTIN_ROOT)
        .join("pipelines")
        .join(name)
}

/// The gallery: every built-in `pipelines/*.toml`, sorted.
pub fn gallery() -> Vec<String> {
    let mut names: Vec<String> = plait_assets::builtin_files()
        .iter()
        .filter_map(|(rel, _)| rel.strip_prefix("pipelines/"))
        .filter(|n| n.ends_with(".toml") && !n.contains('/'))
        .map(str::to_owned)
        .collect();
    names.sort();
    names
}

impl Engine {
    /// Opens the device (in a browser, its WebGPU adapter with WebGPU's
    /// default limits, [`plait_gpu::Gpu::new_async`]) and reads the library
    /// and scene. The device lives as long as the page: it is leaked, so a
    /// build can borrow it.
    pub async fn open() -> Result<Engine, String> {
        let mut gpu = Gpu::new_async(&[]).await.map_err(|e| e.to_string())?;
        // A browser may keep its adapter's name to itself (headless
        // Chromium's SwiftShader gives none): messages still name something.
        if gpu.info.name.is_empty() {
            gpu.info.name = UNNAMED_ADAPTER.into();
            gpu.support.adapter = UNNAMED_ADAPTER.into();
        }
        let gpu: &'static Gpu = Box::leak(Box::new(gpu));
        let library = plait_passes::library_for(&[]);
        let scene_path = Path::new(plait_assets::BUILTIN_ROOT).join(SCENE);
        let scene = plait_hair::Scene::load(&scene_path)
            .and_then(SceneData::new)
            .map_err(|e| e.to_string())?;
        Ok(Engine {
            gpu,
            library,
            scene,
            built: None,
        })
    }

    /// `adapter (backend)`, as `plait render` prints it.
    pub fn adapter(&self) -> String {
        format!("{} ({})", self.gpu.adapter_name(), self.gpu.backend_name())
    }

    /// Whether frames carry per-pass GPU times: in a browser through the
    /// passes' `timestampWrites` ([`plait_gpu::timing`]).
    pub fn timestamps(&self) -> bool {
        self.gpu.timestamp_way().is_some()
    }

    /// Render `req`; an error is the text the CLI gives for the same
    /// pipeline, flags and adapter. A failed request keeps the last build.
    pub async fn render(&mut self, req: &Request) -> Result<Frame, String> {
        let size = (req.width, req.height);
        let key = (
            req.pipeline.clone(),
            req.width,
            req.height,
            req.sets.clone(),
        );
        if self.built.as_ref().is_none_or(|b| b.key != key) {
            let prepared = self.prepare(req).map_err(|e| e.to_string())?;
            self.built = Some(Built { key, prepared });
        }
        let Some(built) = &mut self.built else {
            unreachable!("built above")
        };
        // The frame's inputs from the scene with its camera turned.
        let turned = crate::orbit::orbit(&self.scene.scene.camera, req.yaw, req.pitch);
        let scene_camera = std::mem::replace(&mut self.scene.scene.camera, turned);
        let frame = plait::session::frame_uniforms(built.prepared.schedule(), &self.scene, size, 0);
        self.scene.scene.camera = scene_camera;
        let prepared = &mut built.prepared;
        prepared.set_frame(&frame);
        // The session's frame step, as every front end's: a bounded buffer
        // that dropped data fails the frame (natively the first frame sizes
        // it; see the report's note), and the frame's notes come with it.
        let checked = prepared.render_async().await.map_err(|e| e.to_string())?;
        let read = req.read.as_deref().unwrap_or(&prepared.output);
        let texels = prepared
            .read_resource_async(read)
            .await
            .map_err(|e| e.to_string())?;
        let image = texels.to_image();
        let schedule = prepared.schedule();
        let timed = self.gpu.timestamp_way().is_some();
        Ok(Frame {
            timings: crate::timings::Timings::of(schedule, &checked.report, timed),
            graph: plait_graph::to_svg(schedule),
            width: image.width(),
            height: image.height(),
            rgba: image.into_raw(),
            report: checked.report,
            notes: prepared
                .notes()
                .iter()
                .cloned()
                .chain(checked.notes)
                .chain(checked.dropped)
                .collect(),
            controls: Controls::of(built.prepared.schedule(), &pipeline_path(&req.pipeline)),
        })
    }

    /// Compile for this device (adapter check included), fit params to the
    /// scene, build: `plait::session::prepare` without its sizing frame,
    /// which would have to wait for the GPU.
    fn prepare(&self, req: &Request) -> Result<Prepared<'static>, plait::session::SessionError> {
        let size = (req.width, req.height);
        let path = pipeline_path(&req.pipeline);
        let source = PipelineSource::with_library(&path, &req.sets, self.library.clone());
        let schedule = plait::adapter::compile_on(self.gpu, &source.load(&[])?, &source, size)?;
        let fit = plait::scene_fit::fit_to_scene(&schedule, &source, &self.scene)?;
        let mut schedule = if fit.sets.is_empty() {
            schedule
        } else {
            let opts = plait::session::gpu_options(self.gpu, size);
            source.compile(&fit.sets, &opts)?
        };
        schedule.notes.extend(fit.notes);
        plait::session::build(self.gpu, schedule, &source, &self.scene, size)
    }
}
