//! `plait_gpu::support::check_schedule` against capability sets made by
//! hand, without a GPU: a complete adapter accepts every gallery pipeline;
//! taking one capability away refuses exactly the passes that need it, at
//! their lines in the files.

use plait::session::{compile_checked, repo_root};
use plait_gpu::Capabilities;
use plait_gpu::support::{AdapterSupport, Problem, Unsupported, check_schedule};
use plait_graph::{CompileOptions, Format, Location, Schedule};
use wgpu::{DownlevelFlags as D, TextureFormatFeatureFlags as F, TextureUsages as U};

/// An adapter that can do everything plait asks of one.
fn complete() -> AdapterSupport {
    AdapterSupport {
        adapter: "test adapter".into(),
        backend: wgpu::Backend::Vulkan,
        driver: String::new(),
        formats: Format::ALL
            .iter()
            .map(|&f| {
                (
                    f,
                    wgpu::TextureFormatFeatures {
                        allowed_usages: U::all(),
                        flags: F::all(),
                    },
                )
            })
            .collect(),
        downlevel: D::all(),
        limits: wgpu::Limits::default(),
        depth_values_readable: true,
        sample_mask: true,
    }
}

fn caps() -> Capabilities {
    Capabilities {
        timestamps: false,
        float32_blendable: true,
        early_depth_test: true,
        max_texture_dimension: 8192,
        max_storage_buffer_binding_size: 1 << 30,
        ray_query: true,
        max_blas_primitives: (1 << 24) - 1,
        max_tlas_instances: (1 << 24) - 1,
    }
}

fn schedule(pipeline: &str, sets: &[&str]) -> Schedule {
    schedule_for(pipeline, sets, &caps())
}

/// The schedule compiled for an adapter with `caps`: compile fits it.
fn schedule_for(pipeline: &str, sets: &[&str], caps: &Capabilities) -> Schedule {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let opts = CompileOptions {
        screen: (320, 240),
        capabilities: caps.compile_capabilities(),
        ..CompileOptions::default()
    };
    compile_checked(&repo_root().join(pipeline), &sets, &opts).expect("the pipeline checks")
}

fn problems(s: &Schedule, support: &AdapterSupport, caps: &Capabilities) -> Vec<Problem> {
    let library = plait_passes::read_library(&[]);
    match check_schedule(s, &library, support, caps) {
        Ok(()) => Vec::new(),
        Err(u) => u.problems,
    }
}

fn file_of(p: &Problem) -> String {
    match &p.location {
        Location::File { path, .. } => path.display().to_string(),
        other => panic!("{p}: not at a line of a file but {other:?}"),
    }
}

fn without(support: &mut AdapterSupport, format: Format, usage: U) {
    for (f, features) in &mut support.formats {
        if *f == format {
            features.allowed_usages.remove(usage);
        }
    }
}

#[test]
fn a_complete_adapter_runs_every_gallery_pipeline() {
    let mut files: Vec<_> = std::fs::read_dir(repo_root().join("pipelines"))
        .expect("pipelines/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() > 10);
    for path in files {
        let name = format!("pipelines/{}", path.file_name().unwrap().to_string_lossy());
        let found = problems(&schedule(&name, &[]), &complete(), &caps());
        assert!(found.is_empty(), "{name}: {found:#?}");
    }
}

#[test]
fn rg32float_not_renderable_refuses_the_range_passes_at_their_slots() {
    let mut gl = complete();
    without(&mut gl, Format::Rg32Float, U::RENDER_ATTACHMENT);
    let found = problems(&schedule("pipelines/occupancy.toml", &[]), &gl, &caps());
    let passes: Vec<_> = found
        .iter()
        .map(|p| p.pass.as_deref().unwrap_or("-"))
        .collect();
    // The camera's alpha sums are rg32float too (blended: FLOAT32_BLENDABLE
    // is claimed here, so they are not fitted to rg16float).
    assert_eq!(
        passes,
        ["light_range", "camera_range", "camera_alpha"],
        "{found:#?}"
    );
    for (p, (resource, file)) in found.iter().zip([
        ("light_range", "techniques/self_shadow/light_range.toml"),
        (
            "camera_range",
            "techniques/transparency/occupancy_order/technique.toml",
        ),
        (
            "camera_alpha",
            "techniques/transparency/occupancy_order/technique.toml",
        ),
    ]) {
        assert_eq!(p.resource.as_deref(), Some(resource));
        assert!(file_of(p).ends_with(file), "{p}");
        assert_eq!(
            p.missing,
            "Texture usages TextureUsages(RENDER_ATTACHMENT) are not allowed on a texture of type Rg32Float due to downlevel restrictions"
        );
    }
    // Techniques that render no rg32float target run there.
    let fixed = schedule(
        "pipelines/occupancy.toml",
        &[
            "techniques.self_shadow=none",
            "techniques.transparency=opaque",
        ],
    );
    assert_eq!(problems(&fixed, &gl, &caps()), []);
}

#[test]
fn depth_read_as_values_is_refused_where_the_backend_cannot() {
    let mut gl = complete();
    gl.depth_values_readable = false;
    let found = problems(&schedule("pipelines/forward.toml", &[]), &gl, &caps());
    let named: Vec<_> = found
        .iter()
        .map(|p| {
            (
                p.pass.as_deref().unwrap_or("-"),
                p.resource.as_deref().unwrap_or("-"),
            )
        })
        .collect();
    assert_eq!(
        named,
        [("opaque", "hair_depth"), ("hair", "hair_depth")],
        "{found:#?}"
    );
    assert!(
        found
            .iter()
            .all(|p| file_of(p).ends_with("pipelines/forward.toml"))
    );
    // Comparison sampling (`opaque_shadow`, bound to the same passes) is
    // fine: only the modified shadow map's plain reads of `hair_depth` count.
}

#[test]
fn missing_downlevel_flags_name_the_passes_that_need_them() {
    let mut no_compute = complete();
    no_compute.downlevel.remove(D::COMPUTE_SHADERS);
    let s = schedule(
        "pipelines/occupancy.toml",
        &["techniques.simulation=verlet"],
    );
    let found = problems(&s, &no_compute, &caps());
    assert!(!found.is_empty());
    assert!(
        found.iter().all(|p| p.what == "is a compute pass"
            && p.missing == "the adapter lacks DownlevelFlags(COMPUTE_SHADERS)"
            && p.technique.as_deref() == Some("simulation/verlet")),
        "{found:#?}"
    );
    assert_eq!(problems(&s, &complete(), &caps()), []);

    let mut no_fragment_storage = complete();
    no_fragment_storage
        .downlevel
        .remove(D::FRAGMENT_WRITABLE_STORAGE);
    let found = problems(
        &schedule("pipelines/linked_list.toml", &[]),
        &no_fragment_storage,
        &caps(),
    );
    assert!(
        found.iter().any(
            |p| p.technique.as_deref() == Some("transparency/linked_list")
                && p.what.contains("from its fragment shader")
                && p.missing.contains("FRAGMENT_WRITABLE_STORAGE")
        ),
        "{found:#?}"
    );
}

#[test]
fn multisampling_the_format_lacks_is_refused_at_the_resource() {
    let mut no_msaa = complete();
    for (_, f) in &mut no_msaa.formats {
        f.flags.remove(F::MULTISAMPLE_X4);
    }
    let found = problems(
        &schedule("pipelines/alpha_to_coverage.toml", &[]),
        &no_msaa,
        &caps(),
    );
    assert!(!found.is_empty());
    assert!(
        found
            .iter()
            .all(|p| p.pass.is_none() && p.missing.starts_with("Sample count 4 is not supported")),
        "{found:#?}"
    );
}

#[test]
fn float32_targets_without_blending_are_fitted_not_refused() {
    // Without FLOAT32_BLENDABLE compile blends 32-bit float targets in 16
    // bits; the check judges the schedule as compiled for the adapter.
    let mut no_blend = complete();
    for (f, features) in &mut no_blend.formats {
        if matches!(
            f,
            Format::R32Float | Format::Rg32Float | Format::Rgba32Float
        ) {
            features.flags.remove(F::BLENDABLE);
        }
    }
    let fitted = Capabilities {
        float32_blendable: false,
        ..caps()
    };
    let s = schedule_for("pipelines/occupancy.toml", &[], &fitted);
    assert_eq!(problems(&s, &no_blend, &fitted), []);
    // A schedule compiled claiming FLOAT32_BLENDABLE, run where the format
    // is not blendable, is refused.
    let s = schedule("pipelines/occupancy.toml", &[]);
    let found = problems(&s, &no_blend, &caps());
    assert!(
        found
            .iter()
            .any(|p| p.what.starts_with("blends into") && p.missing.contains("is not blendable")),
        "{found:#?}"
    );
}

#[test]
fn the_message_says_what_to_do() {
    let mut gl = complete();
    gl.backend = wgpu::Backend::Gl;
    without(&mut gl, Format::Rg32Float, U::RENDER_ATTACHMENT);
    let library = plait_passes::read_library(&[]);
    let s = schedule("pipelines/occupancy.toml", &[]);
    let mut u: Box<Unsupported> = check_schedule(&s, &library, &gl, &caps()).expect_err("refused");
    let text = u.to_string();
    assert!(
        text.starts_with("adapter `test adapter` (gl backend) cannot run pipeline `occupancy`:"),
        "{text}"
    );
    assert_eq!(
        text.lines().filter(|l| l.starts_with("error: ")).count(),
        3,
        "{text}"
    );
    assert!(
        text.contains("`apt-get install -y mesa-vulkan-drivers`"),
        "{text}"
    );
    assert!(text.contains("`plait techniques` lists them"), "{text}");
    u.suggestion = Some(vec!["techniques.self_shadow=none".into()]);
    assert!(u.to_string().contains(
        "help: or choose techniques that run on this adapter: `--set techniques.self_shadow=none`"
    ));
    // Already on Vulkan: installing it is no advice.
    u.backend = wgpu::Backend::Vulkan;
    assert!(!u.to_string().contains("mesa-vulkan-drivers"));
}

#[test]
fn a_shader_sample_mask_is_refused_where_the_backend_cannot() {
    let mut gl = complete();
    gl.sample_mask = false;
    let a2c = schedule(
        "pipelines/occupancy.toml",
        &[
            "techniques.self_shadow=none",
            "techniques.transparency=alpha_to_coverage",
        ],
    );
    let found = problems(&a2c, &gl, &caps());
    let named: Vec<_> = found
        .iter()
        .map(|p| (p.pass.as_deref().unwrap_or("-"), p.missing.as_str()))
        .collect();
    assert_eq!(named.len(), 1, "{found:#?}");
    assert_eq!(named[0].0, "hair_coverage", "{found:#?}");
    assert!(named[0].1.contains("gl_SampleMask"), "{found:#?}");
    assert!(
        file_of(&found[0]).ends_with("techniques/transparency/alpha_to_coverage/technique.toml"),
        "{found:#?}"
    );
    // Where the builtin compiles, the same schedule has no problem.
    assert_eq!(problems(&a2c, &complete(), &caps()), []);
}
