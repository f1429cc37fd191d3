//! The render thread: builds the pipeline through `plait::session`, renders
//! it continuously on its own device, reloads it when a file it reads is
//! saved or a param is edited, and publishes each frame for the window.
//!
//! It runs apart from the window on purpose: a frame on a software
//! rasterizer takes a second or more, and the window must stay responsive
//! meanwhile (its own device paints the UI; frames cross as CPU images).
//! A failed reload keeps the last good pipeline and frame.

use std::path::PathBuf;
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use glam::Vec3;
use plait::session::{self, Prepared, SceneData};
use plait_gpu::Gpu;
use plait_hair::scene::{Background, Camera, HairSource, LightKind};

use crate::inspect::{self, Display};
use crate::published::{Shared, describe_schedule};
use crate::screenshot::write_png;
use crate::timings::Timings;
use crate::watch::FileWatcher;

/// At most ~30 frames a second: a fast pipeline need not keep every core busy.
const MIN_FRAME_INTERVAL: Duration = Duration::from_millis(33);

/// What the viewer was asked to show.
#[derive(Clone, Debug)]
pub struct EngineOptions {
    pub pipeline: PathBuf,
    pub scene: Option<PathBuf>,
    pub size: (u32, u32),
    /// `--set` flags from the command line, applied before the params edited live.
    pub sets: Vec<String>,
    /// The resource the inspector starts with.
    pub inspect: Option<String>,
    pub screenshot: Option<Screenshot>,
}

/// Write the pipeline's output to `path` once `after_reloads` reloads have
/// succeeded and then `after_frames` frames were rendered, and quit.
#[derive(Clone, Debug)]
pub struct Screenshot {
    pub path: PathBuf,
    pub after_frames: u32,
    pub after_reloads: u32,
}

/// Requests from the window.
#[derive(Clone, Debug)]
pub enum Command {
    /// Switch to another pipeline file (live param edits are dropped).
    OpenPipeline(PathBuf),
    /// Set a `[params]` value (`name`, value as TOML text); recompiles.
    SetParam(String, String),
    /// Choose the technique of a choice point (`point`, technique name);
    /// recompiles. Param edits are dropped: the new technique may not have them.
    SetTechnique(String, String),
    /// Drop every live edit (params and techniques).
    ResetParams,
    /// Look from here (`None`: the scene's own camera).
    Camera(Option<Camera>),
    /// The direction the light travels (`None`: the scene's own).
    Light(Option<Vec3>),
    /// Show this resource (`None`: the output) this way (`None`: its default).
    Inspect(Option<String>, Option<Display>),
    Pause(bool),
    Quit,
}

/// A pipeline built and ready.
struct Live<'g> {
    prepared: Prepared<'g>,
    /// Set when a frame failed; cleared by the next rebuild.
    failed: bool,
}

/// A frame rendered and checked by the session, not yet published.
struct Frame {
    checked: plait::frames::Frame,
    output: plait_gpu::readback::TexelData,
}

struct Engine<'g> {
    opts: EngineOptions,
    gpu: &'g Gpu,
    shared: Arc<Mutex<Shared>>,
    wake: Box<dyn Fn() + Send>,
    watcher: FileWatcher,
    scene: Option<SceneData>,
    /// The scene as its file says, before the controls moved camera and light.
    base: Option<plait_hair::scene::Scene>,
    /// The scene file and the files it names, absolute (as the watcher reports them).
    scene_files: Vec<PathBuf>,
    pipeline: PathBuf,
    /// Live edits as (`--set` key, TOML value): `params.slices`, `techniques.self_shadow`.
    edits: Vec<(String, String)>,
    camera: Option<Camera>,
    light: Option<Vec3>,
    inspect: (Option<String>, Option<Display>),
    paused: bool,
    live: Option<Live<'g>>,
    /// The scene's animation plays in real time from here, looping.
    clock: Instant,
    timings: Timings,
    frames_since_build: u64,
    builds: u32,
    /// The drop lines last logged, so a frame loop logs a change, not
    /// every frame.
    dropped_logged: Vec<String>,
}

/// An error as printed: every line starting `error:`.
pub(crate) fn error_text(e: &dyn std::fmt::Display) -> String {
    let text = e.to_string();
    if text.starts_with("error:") {
        text
    } else {
        format!("error: {text}")
    }
}

impl<'g> Engine<'g> {
    fn update(&self, f: impl FnOnce(&mut Shared)) {
        if let Ok(mut s) = self.shared.lock() {
            f(&mut s);
            s.version += 1;
        }
        (self.wake)();
    }

    fn sets(&self) -> Vec<String> {
        let mut sets = self.opts.sets.clone();
        sets.extend(self.edits.iter().map(|(k, v)| format!("{k}={v}")));
        sets
    }

    /// Load (or reload) the scene; on failure the last good one stays and the
    /// error is published.
    fn load_scene(&mut self) -> bool {
        match SceneData::load(self.opts.scene.as_deref()) {
            Ok(data) => {
                self.base = Some(data.scene.clone());
                self.scene_files = self.opts.scene.iter().cloned().collect();
                if let HairSource::File(hair) = &data.scene.hair.source {
                    self.scene_files.push(hair.clone());
                }
                if let Background::Image(image) = &data.scene.background {
                    self.scene_files.push(image.clone());
                }
                self.scene_files = self
                    .scene_files
                    .iter()
                    .map(|f| crate::watch::absolute(f))
                    .collect();
                let light = data.scene.light.direction();
                let camera = data.scene.camera.clone();
                self.scene = Some(data);
                self.apply_view();
                self.update(|s| {
                    s.scene_camera = Some(camera);
                    s.scene_light = Some(light);
                    s.scene_version += 1;
                });
                true
            }
            Err(e) => {
                let text = error_text(&e);
                eprintln!("{text}");
                self.update(|s| s.error = Some(text));
                false
            }
        }
    }

    /// Put the controls' camera and light into the scene the frames are made from.
    fn apply_view(&mut self) {
        let (Some(scene), Some(base)) = (&mut self.scene, &self.base) else {
            return;
        };
        scene.scene.camera = self.camera.clone().unwrap_or_else(|| base.camera.clone());
        scene.scene.light = base.light.clone();
        if let Some(dir) = self.light {
            let center = scene.strands.bounds().center();
            match &mut scene.scene.light.kind {
                LightKind::Directional { direction } => *direction = dir.into(),
                // A spot light keeps its distance to the hair and aims at it.
                LightKind::Spot {
                    position,
                    direction,
                    ..
                } => {
                    let distance = (Vec3::from(*position) - center).length();
                    *position = (center - dir.normalize_or(Vec3::NEG_Y) * distance).into();
                    *direction = dir.into();
                }
            }
        }
        if let Some(live) = &mut self.live {
            let frame = session::frame_uniforms(live.prepared.schedule(), scene, self.opts.size, 0);
            live.prepared.set_frame(&frame);
        }
    }

    /// Watch what a build of `source` reads, listed from its library value.
    fn watch(&mut self, source: &plait::source::PipelineSource) {
        let files = session::watched_files(source, self.opts.scene.as_deref());
        if let Err(e) = self.watcher.set_files(&files) {
            eprintln!("{}", error_text(&e));
        }
    }

    fn rebuild(&mut self) {
        let started = Instant::now();
        let sets = self.sets();
        // A new library value per change: the files as they are now, read
        // once for the build and for the list of files to watch.
        let source = plait::source::PipelineSource::new(&self.pipeline, &sets);
        self.watch(&source);
        let Some(scene) = &self.scene else {
            return;
        };
        // One load and one compile per change, with the adapter's capabilities.
        let result = source
            .load(&[])
            .map_err(session::SessionError::from)
            .and_then(|loaded| {
                plait::adapter::compile_on(self.gpu, &loaded, &source, self.opts.size)
            })
            .and_then(|schedule| {
                let shown = schedule.clone();
                // Bounded buffers the user did not size hold every fragment.
                session::prepare_compiled(self.gpu, schedule, &source, scene, self.opts.size)
                    .map(|p| (p, shown))
            });
        match result {
            Ok((prepared, schedule)) => {
                let first = self.builds == 0;
                self.builds += 1;
                let ms = started.elapsed().as_secs_f64() * 1e3;
                let what = if first { "built" } else { "reloaded" };
                eprintln!(
                    "plait view: {what} {} in {ms:.0} ms",
                    self.pipeline.display()
                );
                let notes = prepared.notes().to_vec();
                let output_name = prepared.output.clone();
                self.live = Some(Live {
                    prepared,
                    failed: false,
                });
                self.timings = Timings::default();
                self.frames_since_build = 0;
                self.apply_view();
                let edits = sets[self.opts.sets.len()..].to_vec();
                let pipeline = self.pipeline.clone();
                self.update(|s| {
                    describe_schedule(s, &schedule);
                    s.pipeline = pipeline;
                    s.edits = edits;
                    s.output_name = output_name;
                    s.notes = notes;
                    s.error = None;
                    s.frames = 0;
                    if !first {
                        s.reloads += 1;
                    }
                    s.status = format!("{what} in {ms:.0} ms");
                });
            }
            Err(e) => {
                let text = error_text(&e);
                eprintln!("{text}");
                self.update(|s| {
                    s.error = Some(text);
                    s.status = "the last good frame stays until the error is fixed".into();
                });
            }
        }
    }

    fn render(&mut self) {
        let started = Instant::now();
        match self.frame() {
            Ok(Some(frame)) => self.show(frame, started),
            Ok(None) => {}
            Err(text) => {
                // Kept until the next rebuild: the last good frame stays shown.
                if let Some(live) = &mut self.live {
                    live.failed = true;
                }
                eprintln!("{text}");
                self.update(|s| s.error = Some(text));
            }
        }
    }

    /// One frame of the live pipeline: posed at the animation's time,
    /// rendered and checked by the session's frame step, as `plait render`'s
    /// (a bounded buffer that drops while you watch is shown and logged,
    /// never silent), and read back. `None` with nothing built.
    fn frame(&mut self) -> Result<Option<Frame>, String> {
        let Some(live) = &mut self.live else {
            return Ok(None);
        };
        // An animated scene plays in real time at 30 frames a second, looping
        // over its keys (`plait::frames`, as `plait render --frames` does).
        if let Some(scene) = &self.scene
            && let Some(animation) = &scene.scene.animation
        {
            const FPS: f32 = 30.0;
            let frames = (animation.duration() * FPS) as u64 + 1;
            let index = (self.clock.elapsed().as_secs_f32() * FPS) as u64 % frames;
            let frame = live
                .prepared
                .pose_frame(scene, self.opts.size, index as u32, FPS)
                .map_err(|e| error_text(&e))?;
            live.prepared.set_frame(&frame);
        }
        let checked = live.prepared.render().map_err(|e| error_text(&e))?;
        let output = live
            .prepared
            .read_resource(&live.prepared.output)
            .map_err(|e| error_text(&e))?;
        Ok(Some(Frame { checked, output }))
    }

    /// Publishes a rendered frame: the output, the inspected resource, the
    /// pass timings' medians, the drops; and the screenshot when it is due.
    fn show(&mut self, frame: Frame, started: Instant) {
        let Some(live) = &self.live else {
            return;
        };
        let dropped = frame.checked.dropped;
        if dropped != self.dropped_logged {
            for line in &dropped {
                eprintln!("plait view: {line}");
            }
            self.dropped_logged = dropped.clone();
        }
        // The build's notes and this frame's level-of-detail notes.
        let mut notes = live.prepared.notes().to_vec();
        notes.extend(frame.checked.notes);
        let schedule = live.prepared.schedule();
        let output_view = Arc::new(inspect::texture(
            &live.prepared.output,
            &frame.output,
            Display::Color,
        ));
        let inspected = match &self.inspect {
            (None, None) => Ok(None),
            (name, display) => {
                let name = name.clone().unwrap_or_else(|| live.prepared.output.clone());
                inspect::resource(&live.prepared, schedule, &name, *display).map(Some)
            }
        };
        self.timings.record(&frame.checked.report, started);
        let medians = self.timings.pass_medians(schedule);
        let frame_median = self.timings.frame_median();
        self.frames_since_build += 1;
        let frames = self.frames_since_build;
        let screenshot = self.screenshot_due().then(|| output_view.clone());
        self.update(|s| {
            for (row, m) in s.passes.iter_mut().zip(medians) {
                row.median_ms = m;
            }
            s.frame_median_ms = frame_median;
            s.output = Some(output_view);
            match inspected {
                Ok(i) => {
                    s.inspected = i.map(Arc::new);
                    s.inspect_error = None;
                }
                Err(e) => {
                    s.inspected = None;
                    s.inspect_error = Some(e);
                }
            }
            s.frames = frames;
            s.total_frames += 1;
            s.dropped = dropped;
            s.notes = notes;
        });
        if let Some(image) = screenshot {
            self.write_screenshot(&image.image);
        }
    }

    fn screenshot_due(&self) -> bool {
        let Some(shot) = &self.opts.screenshot else {
            return false;
        };
        let reloads = self.builds.saturating_sub(1);
        reloads >= shot.after_reloads && self.frames_since_build >= shot.after_frames.max(1) as u64
    }

    fn write_screenshot(&mut self, image: &image::RgbaImage) {
        let Some(shot) = &self.opts.screenshot else {
            return;
        };
        let result = write_png(&shot.path, image);
        match &result {
            Ok(()) => eprintln!("plait view: wrote {}", shot.path.display()),
            Err(e) => eprintln!("error: --screenshot {}: {e}", shot.path.display()),
        }
        self.update(|s| {
            s.finished = true;
            if let Err(e) = result {
                s.fatal = Some(format!("--screenshot {}: {e}", shot.path.display()));
            }
        });
    }

    fn handle(&mut self, command: Command) -> bool {
        match command {
            Command::OpenPipeline(path) => {
                self.pipeline = path;
                self.edits.clear();
                self.rebuild();
            }
            Command::SetParam(name, value) => {
                let key = format!("params.{name}");
                self.edits.retain(|(k, _)| *k != key);
                self.edits.push((key, value));
                self.rebuild();
            }
            Command::SetTechnique(point, name) => {
                let key = format!("techniques.{point}");
                self.edits
                    .retain(|(k, _)| k.starts_with("techniques.") && *k != key);
                self.edits.push((key, format!("{name:?}")));
                self.rebuild();
            }
            Command::ResetParams => {
                self.edits.clear();
                self.rebuild();
            }
            Command::Camera(camera) => {
                self.camera = camera;
                self.apply_view();
            }
            Command::Light(light) => {
                self.light = light;
                self.apply_view();
            }
            Command::Inspect(name, display) => self.inspect = (name, display),
            Command::Pause(p) => self.paused = p,
            Command::Quit => return false,
        }
        true
    }

    fn run(&mut self, commands: &Receiver<Command>) {
        self.load_scene();
        self.rebuild();
        let mut last_frame = Instant::now();
        loop {
            let idle = self.paused
                || self.live.as_ref().is_none_or(|l| l.failed)
                || self.shared.lock().map(|s| s.finished).unwrap_or(true);
            // Wait for work when there is no frame to render.
            let wait = if idle {
                Duration::from_millis(50)
            } else {
                MIN_FRAME_INTERVAL.saturating_sub(last_frame.elapsed())
            };
            match commands.recv_timeout(wait) {
                Ok(c) => {
                    if !self.handle(c) {
                        return;
                    }
                    while let Ok(c) = commands.try_recv() {
                        if !self.handle(c) {
                            return;
                        }
                    }
                }
                Err(RecvTimeoutError::Disconnected) => return,
                Err(RecvTimeoutError::Timeout) => {}
            }
            let changed = self.watcher.changes(Duration::ZERO);
            if !changed.is_empty() {
                for f in &changed {
                    eprintln!("plait view: {} changed", f.display());
                }
                let scene_changed = changed.iter().any(|c| self.scene_files.contains(c));
                // A broken scene keeps its error on screen until it is fixed
                // (a rebuild on the old scene would clear it).
                let scene_ok = if scene_changed || self.scene.is_none() {
                    self.load_scene()
                } else {
                    true
                };
                if scene_ok {
                    self.rebuild();
                }
            }
            if !idle && last_frame.elapsed() >= MIN_FRAME_INTERVAL {
                last_frame = Instant::now();
                self.render();
            }
        }
    }
}

/// Run the engine on this thread until `Quit`, the screenshot, or the
/// window going away. `wake` asks the window to repaint.
pub fn run(
    opts: EngineOptions,
    commands: Receiver<Command>,
    shared: Arc<Mutex<Shared>>,
    wake: Box<dyn Fn() + Send>,
) {
    let fail = |message: String| {
        eprintln!("error: {message}");
        if let Ok(mut s) = shared.lock() {
            s.fatal = Some(message);
            s.finished = true;
            s.version += 1;
        }
        wake();
    };
    let gpu = match Gpu::new() {
        Ok(g) => g,
        Err(e) => return fail(e.to_string()),
    };
    let watcher = match FileWatcher::new() {
        Ok(w) => w,
        Err(e) => return fail(e.to_string()),
    };
    if let Ok(mut s) = shared.lock() {
        s.adapter = format!("{} ({})", gpu.adapter_name(), gpu.backend_name());
        s.pipeline = opts.pipeline.clone();
    }
    let inspect = opts.inspect.clone();
    let mut engine = Engine {
        pipeline: opts.pipeline.clone(),
        opts,
        gpu: &gpu,
        shared: shared.clone(),
        wake,
        watcher,
        scene: None,
        base: None,
        scene_files: Vec::new(),
        edits: Vec::new(),
        camera: None,
        light: None,
        inspect: (inspect, None),
        paused: false,
        live: None,
        clock: Instant::now(),
        timings: Timings::default(),
        frames_since_build: 0,
        dropped_logged: Vec::new(),
        builds: 0,
    };
    engine.run(&commands);
}
