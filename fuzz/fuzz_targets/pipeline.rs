//! Pipelines: the top file (its `extends` resolve in `pipelines/`), then
//! `--set` flags taken from the input's lines after a NUL, then compiled
//! against the real pass library (shaders are fuzzed by `tests/fuzz.rs`).
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::OnceLock;

fuzz_target!(|bytes: &[u8]| {
    static LIBRARY: OnceLock<plait_graph::Registry> = OnceLock::new();
    let registry = LIBRARY.get_or_init(|| plait_passes::library().registry());
    let mut parts = bytes.split(|&b| b == 0);
    let Ok(text) = std::str::from_utf8(parts.next().unwrap_or_default()) else {
        return;
    };
    let sets: Vec<String> = parts
        .take(4)
        .map(|s| String::from_utf8_lossy(s).into_owned())
        .collect();
    let top = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../pipelines/fuzz.toml"
    ));
    let Ok(pipeline) = plait_graph::load_str(&top, text, &sets) else {
        return;
    };
    let opts = plait_graph::CompileOptions {
        screen: (64, 48),
        ..plait_graph::CompileOptions::default()
    };
    if let Ok(schedule) = plait_graph::compile(&pipeline, registry, &opts) {
        let _ = plait_graph::schedule_text(&schedule);
        let _ = plait_graph::to_dot(&schedule);
    }
});
