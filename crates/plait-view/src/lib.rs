//! `plait view`: a live window onto a pipeline, and the file watching it
//! shares with `plait render --watch`.
//!
//! Two threads, two devices. The engine ([`engine`]) owns plait's device: it
//! builds the pipeline through `plait::session` (the one path from a file to
//! pixels), renders it continuously, reads the output and the inspected
//! resource back, and rebuilds when a file it reads is saved ([`watch`]) or a
//! control changes. The window ([`app`], [`ui`]) owns a second device that
//! only paints egui, so it stays responsive while a frame takes seconds on a
//! software rasterizer. A failed reload is shown in the window and on stderr;
//! the last good frame stays.
//!
//! Its heavy dependencies (winit, egui) live in this crate only.

mod app;
pub mod engine;
pub mod inspect;
pub mod orbit;
pub mod published;
mod screenshot;
mod timings;
mod ui;
pub mod watch;

use std::path::PathBuf;
use std::sync::{Arc, Mutex, mpsc};

pub use engine::Screenshot;

/// What `plait view` shows.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    pub pipeline: PathBuf,
    pub scene: Option<PathBuf>,
    /// Render size: the pipeline renders at this size whatever the window's.
    pub size: (u32, u32),
    pub sets: Vec<String>,
    /// Start with this resource in the inspector (`None`: the output).
    pub inspect: Option<String>,
    pub screenshot: Option<Screenshot>,
}

#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    #[error(
        "cannot open a window: {0}. `plait view` needs an X11 display (DISPLAY); on a machine \
         without one run it under Xvfb (`xvfb-run -a plait view …`), or use \
         `plait render --watch`, which needs no display"
    )]
    NoDisplay(String),
    #[error("{0}")]
    Window(String),
    #[error("{0}")]
    Engine(String),
}

/// winit's message without the source location it starts with
/// (`os error at …/mod.rs:765: neither … is set.`).
fn window_system_reason(text: &str) -> String {
    let reason = match text.split_once(".rs:") {
        Some((_, rest)) => rest.split_once(": ").map_or(rest, |(_, r)| r),
        None => text,
    };
    reason.trim().trim_end_matches('.').to_owned()
}

/// Open the window and run until it is closed (or the screenshot is written).
pub fn run(opts: ViewOptions) -> Result<(), ViewError> {
    let event_loop = winit::event_loop::EventLoop::<app::Wake>::with_user_event()
        .build()
        .map_err(|e| ViewError::NoDisplay(window_system_reason(&e.to_string())))?;
    let (tx, rx) = mpsc::channel();
    let shared = Arc::new(Mutex::new(published::Shared::default()));
    let proxy = event_loop.create_proxy();
    let engine_options = engine::EngineOptions {
        pipeline: opts.pipeline,
        scene: opts.scene,
        size: opts.size,
        sets: opts.sets,
        inspect: opts.inspect.clone(),
        screenshot: opts.screenshot,
    };
    let wake_proxy = proxy;
    let engine_shared = shared.clone();
    let engine_thread = std::thread::Builder::new()
        .name("plait-render".into())
        .spawn(move || {
            let wake = Box::new(move || {
                let _ = wake_proxy.send_event(app::Wake);
            });
            engine::run(engine_options, rx, engine_shared, wake);
        })
        .map_err(|e| ViewError::Engine(format!("cannot start the render thread: {e}")))?;
    let mut app = app::App::new(tx, shared.clone(), opts.inspect);
    let ran = event_loop
        .run_app(&mut app)
        .map_err(|e| ViewError::Window(e.to_string()));
    // The render thread holds its own device: let it finish before the
    // process exits. Exiting while it still ran inside the driver crashed
    // the viewer now and then (SIGSEGV after the screenshot, under load on
    // lavapipe). Dropping the app closes the command channel, which ends
    // the thread if `Quit` did not.
    let failure = app.failure.take();
    drop(app);
    let _ = engine_thread.join();
    ran?;
    if let Some(failure) = failure {
        return Err(ViewError::Window(failure));
    }
    let fatal = shared.lock().ok().and_then(|s| s.fatal.clone());
    match fatal {
        Some(message) => Err(ViewError::Engine(message)),
        None => Ok(()),
    }
}
