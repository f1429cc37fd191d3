//! The viewer's render thread without a window (lavapipe): a param edited
//! live recompiles the graph, a bad value keeps the last good frame and
//! shows the error, the inspector lays buffers out as the schedule's texels,
//! and moving the camera changes the picture.

use std::path::PathBuf;
use std::sync::mpsc::{Sender, channel};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use plait_graph::Value;
use plait_view::engine::{self, Command, EngineOptions};
use plait_view::inspect::Display;
use plait_view::orbit::Orbit;
use plait_view::published::Shared;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

struct Running {
    tx: Sender<Command>,
    shared: Arc<Mutex<Shared>>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.tx.send(Command::Quit);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Running {
    /// Wait (up to a minute) until `done` holds for the published state.
    fn until(&self, what: &str, done: impl Fn(&Shared) -> bool) {
        let deadline = Instant::now() + Duration::from_secs(60);
        loop {
            {
                let s = self.shared.lock().expect("shared state");
                assert!(s.fatal.is_none(), "engine stopped: {:?}", s.fatal);
                if done(&s) {
                    return;
                }
                assert!(
                    Instant::now() < deadline,
                    "timed out waiting for {what}; error: {:?}, status: {}",
                    s.error,
                    s.status
                );
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    fn send(&self, c: Command) {
        self.tx.send(c).expect("engine running");
    }
}

fn start(inspect: Option<&str>) -> Running {
    start_with(
        "pipelines/occupancy.toml",
        &["params.light_size=128"],
        inspect,
    )
}

fn start_with(pipeline: &str, sets: &[&str], inspect: Option<&str>) -> Running {
    let (tx, rx) = channel();
    let shared = Arc::new(Mutex::new(Shared::default()));
    let opts = EngineOptions {
        pipeline: root().join(pipeline),
        scene: Some(root().join("examples/scenes/small.toml")),
        size: (64, 48),
        sets: sets.iter().map(|s| (*s).to_owned()).collect(),
        inspect: inspect.map(str::to_owned),
        screenshot: None,
    };
    let published = shared.clone();
    let thread = std::thread::spawn(move || engine::run(opts, rx, published, Box::new(|| {})));
    Running {
        tx,
        shared,
        thread: Some(thread),
    }
}

fn param(s: &Shared, name: &str) -> Option<Value> {
    s.params
        .iter()
        .find(|(k, _)| k == name)
        .map(|(_, v)| v.clone())
}

#[test]
fn params_recompile_live_errors_keep_the_last_frame_and_buffers_are_inspected() {
    let e = start(Some("light_bits"));
    e.until("the first frame", |s| s.frames >= 1);
    {
        let s = e.shared.lock().expect("state");
        assert_eq!(param(&s, "slices"), Some(Value::Int(128)));
        let bits = s.inspected.as_ref().expect("light_bits inspected");
        // 128 slices = 4 words per texel of the 128² light map.
        assert!(
            bits.legend.contains("128×128 texels of 4 u32 words"),
            "{}",
            bits.legend
        );
        assert!(s.passes.iter().any(|p| p.name == "light_occupancy"));
        assert!(s.passes.iter().all(|p| p.writes_bytes > 0));
    }

    // A param edited live: the graph recompiles, the buffer shrinks.
    e.send(Command::SetParam("slices".into(), "64".into()));
    e.send(Command::Inspect(
        Some("light_bits".into()),
        Some(Display::BitCount),
    ));
    e.until("the reload", |s| s.reloads == 1 && s.frames >= 1);
    {
        let s = e.shared.lock().expect("state");
        assert_eq!(param(&s, "slices"), Some(Value::Int(64)));
        assert_eq!(s.edits, vec!["params.slices=64".to_owned()]);
        let bits = s.inspected.as_ref().expect("light_bits inspected");
        assert!(
            bits.legend.contains("of 2 u32 words: set bits"),
            "{}",
            bits.legend
        );
        assert!(s.error.is_none(), "{:?}", s.error);
    }

    // A bad value: the error is published, the last good frame stays.
    let before = e
        .shared
        .lock()
        .expect("state")
        .output
        .clone()
        .expect("a frame");
    e.send(Command::SetParam("light_size".into(), "\"big\"".into()));
    e.until("the error", |s| s.error.is_some());
    {
        let s = e.shared.lock().expect("state");
        let error = s.error.as_deref().unwrap_or_default();
        assert!(error.starts_with("error:"), "{error}");
        assert_eq!(s.reloads, 1, "a failed reload is not counted");
        let shown = s.output.as_ref().expect("the last good frame");
        assert_eq!(shown.image.dimensions(), before.image.dimensions());
    }

    // Fixed by resetting the edits: it recovers.
    e.send(Command::ResetParams);
    e.until("the recovery", |s| {
        s.reloads == 2 && s.error.is_none() && s.frames >= 1
    });
    assert_eq!(
        param(&e.shared.lock().expect("state"), "slices"),
        Some(Value::Int(128))
    );

    // A technique chosen from its drop-down: the graph is rebuilt with it.
    {
        let s = e.shared.lock().expect("state");
        let point = s
            .techniques
            .iter()
            .find(|t| t.point == "self_shadow")
            .expect("the self_shadow choice point");
        assert_eq!(point.chosen, "occupancy");
        assert!(
            point.choices.iter().any(|c| c == "deep_opacity"),
            "{:?}",
            point.choices
        );
    }
    e.send(Command::SetTechnique(
        "self_shadow".into(),
        "deep_opacity".into(),
    ));
    e.until("the technique swap", |s| s.reloads == 3 && s.frames >= 1);
    let s = e.shared.lock().expect("state");
    let point = s
        .techniques
        .iter()
        .find(|t| t.point == "self_shadow")
        .expect("the self_shadow choice point");
    assert_eq!(point.chosen, "deep_opacity");
    assert_eq!(
        s.edits,
        vec!["techniques.self_shadow=\"deep_opacity\"".to_owned()]
    );
    assert!(s.error.is_none(), "{:?}", s.error);
}

#[test]
fn orbiting_the_camera_changes_the_picture() {
    let e = start(None);
    e.until("the first frame", |s| s.frames >= 1);
    let (first, camera) = {
        let s = e.shared.lock().expect("state");
        (
            s.output.clone().expect("a frame"),
            s.scene_camera.clone().expect("the scene's camera"),
        )
    };
    let mut orbit = Orbit::from_camera(&camera);
    orbit.rotate(150.0, 0.0);
    e.send(Command::Camera(Some(orbit.camera(&camera))));
    e.until("a frame from the new camera", |s| {
        s.output
            .as_ref()
            .is_some_and(|o| o.image.as_raw() != first.image.as_raw())
    });
}

/// The geometry point's state as the drop-down shows it.
fn geometry_point(s: &Shared) -> (String, Vec<String>) {
    let point = s
        .techniques
        .iter()
        .find(|t| t.point == "geometry")
        .expect("the geometry choice point");
    (point.chosen.clone(), point.choices.clone())
}

/// After the first frame: `name` is offered by the geometry drop-down, is
/// chosen live, and the engine rebuilds without an error.
fn choose_geometry_live(e: &Running, name: &str) {
    let (_, choices) = geometry_point(&e.shared.lock().expect("state"));
    assert!(choices.iter().any(|c| c == name), "{choices:?}");
    e.send(Command::SetTechnique("geometry".into(), name.into()));
    e.until("the technique swap", |s| {
        s.error.is_some() || (s.reloads == 1 && s.frames >= 1)
    });
    let s = e.shared.lock().expect("state");
    assert!(s.error.is_none(), "{:?}", s.error);
    assert_eq!(geometry_point(&s).0, name);
}

/// The geometry point, which occupancy.toml's [techniques] leaves to its
/// default, is a drop-down of the viewer too: `lod` is chosen live.
#[test]
fn the_geometry_point_is_a_live_choice_though_the_pipeline_does_not_list_it() {
    let e = start(None);
    e.until("the first frame", |s| s.frames >= 1);
    assert_eq!(
        geometry_point(&e.shared.lock().expect("state")).0,
        "strands"
    );
    choose_geometry_live(&e, "lod");
}

/// `wisps` is found by the drop-down like any technique folder, and chosen
/// live: the engine rebuilds with the wisps' strips and their note.
#[test]
fn wisps_are_a_live_choice_of_the_geometry_point() {
    let e = start(None);
    e.until("the first frame", |s| s.frames >= 1);
    choose_geometry_live(&e, "wisps");
}

/// A fragment pool the user capped below what the frame needs (linked_list
/// with one node per pixel): the viewer's frames drop fragments, and the
/// engine publishes it (the UI shows it, the log says it) through the same
/// after-frame check as `plait render`, instead of dropping silently.
#[test]
fn a_capped_pool_that_overflows_is_reported_by_the_viewer() {
    let e = start_with(
        "pipelines/linked_list.toml",
        &["params.nodes_per_pixel=1"],
        None,
    );
    e.until("a frame that reports its drops", |s| {
        s.frames >= 1 && !s.dropped.is_empty()
    });
    let s = e.shared.lock().expect("state");
    let line = &s.dropped[0];
    assert!(line.starts_with("dropped: "), "{line}");
    assert!(line.contains("list_nodes"), "{line}");
    assert!(line.contains("--set params.nodes_per_pixel="), "{line}");
    assert!(
        s.error.is_none(),
        "a user's cap reports, not fails: {:?}",
        s.error
    );
}
