//! Fuzz target: Pipeline TOML.

use super::*;

/// Pipelines: the top file mutated (its `extends` resolve on disk beside
/// it), `--set` flags drawn from real keys and odd values, then compiled
/// against the real pass library.
#[test]
fn fuzz_pipeline_loader() {
    let files = pipeline_files();
    let seeds: Vec<Vec<u8>> = files.iter().map(|p| read(p)).collect();
    let keys = [
        "params.light_size",
        "params.slices",
        "resources.final.size",
        "resources.final.format",
        "resources.light_bits.size",
        "passes.hair.type",
        "passes.hair.reads.shadow",
        "passes.compose.enabled",
        "passes.hair.params.visibility",
        "pipeline.outputs",
        "pipeline.extends",
        "techniques.x",
        "passes.new.type",
        "passes.hair.writes",
    ];
    let values = [
        "0",
        "-5",
        "1e308",
        "\"1/0\"",
        "\"(((\"",
        "[]",
        "[1, [2]]",
        "{ a = 1 }",
        "\"${light_size}\"",
        "\"screen/0\"",
        "buffer",
        "nope",
        "true",
        "\"fullscreen\"",
        "\"occupancy.toml\"",
        "99999999999999999999",
        "\"\"",
        "\"screen_width * 99999999\"",
    ];
    let sets = vec((0..keys.len(), 0..values.len()), 0..3).prop_map(move |picks| {
        picks
            .into_iter()
            .map(|(k, v)| format!("{}={}", keys[k], values[v]))
            .collect::<Vec<String>>()
    });
    // The sets ride in the input after a NUL so the watchdog can print them.
    let strategy = (mutated(&seeds, TOML_TOKENS), sets).prop_map(|(mut text, sets)| {
        for s in sets {
            text.push(0);
            text.extend_from_slice(s.as_bytes());
        }
        text
    });
    let library = plait_passes::read_library(&[]);
    let registry = library.registry();
    let top = repo_root().join("pipelines/fuzz.toml");
    let opts = plait_graph::CompileOptions {
        screen: (64, 48),
        ..plait_graph::CompileOptions::default()
    };
    let mut checked = 0u32;
    // Measured at the default seed (`cargo test -p plait-tests --test fuzz --
    // --nocapture`): 173 of 4,769 mutated inputs accepted (3.63%); 231 of 231
    // unmutated seeds. The floor is half the mutated fraction.
    fuzz("pipeline", 5_000, 0.018, &seeds, strategy, |input| {
        let mut parts = input.split(|&b| b == 0);
        let Ok(text) = std::str::from_utf8(parts.next().unwrap_or_default()) else {
            return Ok(false);
        };
        let sets: Vec<String> = parts
            .map(|s| String::from_utf8_lossy(s).into_owned())
            .collect();
        let Ok(pipeline) = plait_graph::load_str(&top, text, &sets) else {
            return Ok(false);
        };
        let Ok(schedule) = plait_graph::compile(&pipeline, &registry, &opts) else {
            return Ok(false);
        };
        let _ = plait_graph::schedule_text(&schedule);
        let _ = plait_graph::to_dot(&schedule);
        // Checking the shaders of a pipeline costs ~0.1 s; one in 20 does.
        checked += 1;
        if checked % 20 == 1 {
            let _ = plait_passes::compile_in(&library, &pipeline, &opts);
        }
        Ok(true)
    });
}
