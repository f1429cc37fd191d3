//! A technique that traces rays (`[technique] adapter = ["ray_query"]`) is
//! refused on an adapter without ray queries before any GPU work: the check
//! takes the adapter's capabilities as a value, so the refusal is tested
//! here without a second driver, with a capability set lacking them.

use std::path::{Path, PathBuf};

use plait::session::compile_checked;
use plait_gpu::Capabilities;
use plait_gpu::support::{AdapterSupport, Unsupported, check_schedule};
use plait_graph::{CompileOptions, Format, Location, Schedule};
use wgpu::{DownlevelFlags as D, TextureFormatFeatureFlags as F, TextureUsages as U};

/// An adapter with every format usage and downlevel flag.
fn support() -> AdapterSupport {
    let all = wgpu::TextureFormatFeatures {
        allowed_usages: U::all(),
        flags: F::all(),
    };
    AdapterSupport {
        adapter: "old lavapipe".into(),
        backend: wgpu::Backend::Vulkan,
        driver: "Mesa 22.3.6".into(),
        formats: Format::ALL.iter().map(|&f| (f, all)).collect(),
        downlevel: D::all(),
        limits: wgpu::Limits::default(),
        depth_values_readable: true,
        sample_mask: true,
    }
}

fn caps(ray_query: bool) -> Capabilities {
    Capabilities {
        timestamps: false,
        float32_blendable: true,
        early_depth_test: true,
        max_texture_dimension: 8192,
        max_storage_buffer_binding_size: 1 << 30,
        ray_query,
        max_blas_primitives: if ray_query { (1 << 24) - 1 } else { 0 },
        max_tlas_instances: if ray_query { (1 << 24) - 1 } else { 0 },
    }
}

/// A pipeline beside its own technique `self_shadow/needs_rays`, which
/// asks for ray queries and otherwise is `none`.
fn pipeline_needing_rays(dir: &Path) -> PathBuf {
    let folder = dir.join("techniques/self_shadow/needs_rays");
    std::fs::create_dir_all(&folder).expect("mkdir");
    std::fs::write(
        folder.join("technique.toml"),
        "[technique]\npoint = \"self_shadow\"\ndescription = \"asks for ray queries\"\n\
         source = \"-\"\nmemory = \"0\"\nadapter = [\"ray_query\"]\n\n\
         [technique.exports]\nparams = { self_shadow = \"none\" }\n",
    )
    .expect("write the technique");
    let pipeline = dir.join("mine.toml");
    std::fs::write(
        &pipeline,
        "[pipeline]\nname = \"mine\"\nextends = \"occupancy.toml\"\n\n\
         [techniques]\nself_shadow = \"needs_rays\"\n",
    )
    .expect("write the pipeline");
    pipeline
}

fn compiled(pipeline: &Path, caps: &Capabilities) -> Schedule {
    let opts = CompileOptions {
        screen: (64, 48),
        capabilities: caps.compile_capabilities(),
        ..CompileOptions::default()
    };
    compile_checked(pipeline, &[], &opts).expect("the pipeline checks")
}

fn check(s: &Schedule, caps: &Capabilities) -> Result<(), Box<Unsupported>> {
    let library = plait_passes::read_library(&[]);
    check_schedule(s, &library, &support(), caps)
}

#[test]
fn a_technique_needing_ray_queries_is_refused_without_them_at_its_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pipeline = pipeline_needing_rays(dir.path());
    let with = caps(true);
    assert!(check(&compiled(&pipeline, &with), &with).is_ok());

    let without = caps(false);
    let refused = check(&compiled(&pipeline, &without), &without).expect_err("refused");
    assert_eq!(refused.problems.len(), 1, "{refused}");
    let p = &refused.problems[0];
    assert_eq!(p.technique.as_deref(), Some("self_shadow/needs_rays"));
    match &p.location {
        // `adapter = ["ray_query"]` is line 6; the string starts at column 12.
        Location::File { path, line, column } => {
            assert!(path.ends_with("needs_rays/technique.toml"), "{p}");
            assert_eq!((*line, *column), (6, 12), "{p}");
        }
        other => panic!("not at a line of the technique file: {other:?}"),
    }
    let text = refused.to_string();
    for wanted in [
        "adapter `old lavapipe` (vulkan backend, Mesa 22.3.6) cannot run pipeline `mine`",
        "technique self_shadow/needs_rays traces rays (`adapter = [\"ray_query\"]`)",
        "the adapter lacks ray queries (wgpu's EXPERIMENTAL_RAY_QUERY, Vulkan's VK_KHR_ray_query)",
        "`bash scripts/ensure-vulkan.sh` installs Mesa ≥ 25's software Vulkan driver (lavapipe)",
    ] {
        assert!(text.contains(wanted), "no `{wanted}` in\n{text}");
    }
}

/// A pipeline whose own passes trace rays (an acceleration structure it
/// declares itself, outside any technique: plait's path tracer) is refused
/// the same way, at the structure's declaration.
#[test]
fn the_path_tracer_is_refused_without_ray_queries_at_its_structure() {
    let root = plait::session::repo_root();
    let pipeline = root.join("pipelines/physical/path_traced.toml");
    let with = caps(true);
    assert!(check(&compiled(&pipeline, &with), &with).is_ok());

    let without = caps(false);
    let refused = check(&compiled(&pipeline, &without), &without).expect_err("refused");
    assert_eq!(refused.problems.len(), 1, "{refused}");
    let p = &refused.problems[0];
    assert_eq!(p.resource.as_deref(), Some("pt_strands"), "{p}");
    match &p.location {
        Location::File { path, .. } => {
            assert!(path.ends_with("physical/path_traced.toml"), "{p}");
        }
        other => panic!("not at a line of the pipeline file: {other:?}"),
    }
    let text = refused.to_string();
    for wanted in [
        "`pt_strands` is an acceleration structure the pipeline traces rays through",
        "the adapter lacks ray queries",
        "`bash scripts/ensure-vulkan.sh`",
    ] {
        assert!(text.contains(wanted), "no `{wanted}` in\n{text}");
    }
}

#[test]
fn an_unknown_adapter_capability_is_an_error_at_its_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pipeline = pipeline_needing_rays(dir.path());
    let file = dir
        .path()
        .join("techniques/self_shadow/needs_rays/technique.toml");
    let text = std::fs::read_to_string(&file).expect("read");
    std::fs::write(&file, text.replace("\"ray_query\"", "\"ray_querys\"")).expect("write");
    let opts = CompileOptions::default();
    let errors = compile_checked(&pipeline, &[], &opts).expect_err("refused");
    let text = format!("{errors}");
    assert!(
        text.contains("technique.adapter: no adapter capability `ray_querys`; did you mean `ray_query`? (capabilities: ray_query)"),
        "{text}"
    );
    assert!(text.contains("needs_rays/technique.toml:6:12"), "{text}");
}
