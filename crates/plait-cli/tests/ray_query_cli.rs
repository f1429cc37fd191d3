//! On the real adapter, with its ray queries hidden
//! (`PLAIT_DISABLE_FEATURES=EXPERIMENTAL_RAY_QUERY`, as a driver without
//! them would be), a technique that traces rays is refused by `plait check
//! --adapter` and `plait render` before any GPU work: exit 2, the adapter,
//! the missing feature and the fix named.

mod common;
use common::{assert_ok, assert_refused, root, text, write};

use std::process::{Command, Output};

fn plait_env(args: &[&str], hide_ray_query: bool) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_plait"));
    cmd.current_dir(root()).args(args);
    if hide_ray_query {
        cmd.env("PLAIT_DISABLE_FEATURES", "EXPERIMENTAL_RAY_QUERY");
    }
    cmd.output().expect("run plait")
}

#[test]
fn a_ray_traced_technique_is_refused_on_an_adapter_without_ray_queries() {
    let dir = tempfile::tempdir().expect("tempdir");
    write(
        dir.path(),
        "techniques/self_shadow/needs_rays/technique.toml",
        "[technique]\npoint = \"self_shadow\"\ndescription = \"asks for ray queries\"\n\
         source = \"-\"\nmemory = \"0\"\nadapter = [\"ray_query\"]\n\n\
         [technique.exports]\nparams = { self_shadow = \"none\" }\n",
    );
    write(
        dir.path(),
        "mine.toml",
        "[pipeline]\nname = \"mine\"\nextends = \"occupancy.toml\"\n\n\
         [techniques]\nself_shadow = \"needs_rays\"\n",
    );
    let pipeline = dir.path().join("mine.toml");
    let pipeline = pipeline.to_str().expect("utf-8");
    let wanted = [
        "cannot run pipeline `mine`",
        "adapter `",
        "needs_rays/technique.toml:6:12: technique self_shadow/needs_rays traces rays",
        "the adapter lacks ray queries (wgpu's EXPERIMENTAL_RAY_QUERY, Vulkan's VK_KHR_ray_query)",
        "`bash scripts/ensure-vulkan.sh`",
    ];
    let check = ["check", "--adapter", pipeline];
    assert_refused("check --adapter", &plait_env(&check, true), &wanted);
    let out = dir.path().join("x.png");
    let render = [
        "render",
        pipeline,
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "32x24",
        "--out",
        out.to_str().expect("utf-8"),
    ];
    assert_refused("render", &plait_env(&render, true), &wanted);
    assert!(!out.exists(), "nothing rendered");
    // The adapter as it is (lavapipe of Mesa ≥ 25) has them.
    let o = plait_env(&check, false);
    assert_ok("check --adapter with ray queries", &o);
    assert!(
        text(&o.stdout).contains("runs on adapter"),
        "{}",
        text(&o.stdout)
    );
}

/// A self-shadow provider binding an acceleration structure that its
/// technique does not export: `plait check` names the binding before any GPU
/// work. (Before acceleration structures were a resource kind the binding
/// was left out of the plan silently and the render failed at pipeline
/// creation with wgpu's "binding is missing from the pipeline layout".)
#[test]
fn a_provider_binding_an_acceleration_structure_is_refused_by_check() {
    let dir = tempfile::tempdir().expect("tempdir");
    write(
        dir.path(),
        "techniques/self_shadow/rt_probe/technique.toml",
        "[technique]\npoint = \"self_shadow\"\ndescription = \"a ray query\"\n\
         source = \"-\"\nmemory = \"0\"\nadapter = [\"ray_query\"]\n\n\
         [technique.exports]\nparams = { self_shadow = \"rt_probe\" }\n",
    );
    write(
        dir.path(),
        "techniques/self_shadow/rt_probe/self_shadow.wgsl",
        "enable wgpu_ray_query;\n#define_import_path plait::self_shadow::rt_probe\n\n\
         @group(1) @binding(8) var vis_strands: acceleration_structure;\n\n\
         fn hair_visibility(world: vec3<f32>) -> f32 {\n    var rq: ray_query;\n    \
         rayQueryInitialize(&rq, vis_strands, RayDesc(0u, 0xFFu, 0.01, 1e30, world, vec3<f32>(0.0, 1.0, 0.0)));\n    \
         var n = 0.0;\n    while (rayQueryProceed(&rq)) {\n        n += 1.0;\n    }\n    return exp(-n);\n}\n",
    );
    write(
        dir.path(),
        "mine.toml",
        "[pipeline]\nname = \"mine\"\nextends = \"occupancy.toml\"\n\n\
         [techniques]\nself_shadow = \"rt_probe\"\n",
    );
    let pipeline = dir.path().join("mine.toml");
    let o = plait_env(&["check", pipeline.to_str().expect("utf-8")], false);
    assert_refused(
        "check",
        &o,
        &[
            "pass `hair`: shader binding `vis_strands` (group 1, binding 8) is not provided by the pipeline file",
        ],
    );
}

/// A groom with more segments than one acceleration structure holds
/// (issue 48, bad input): on the real adapter asked for a device holding
/// 6,798 primitives (`PLAIT_MAX_BLAS_PRIMITIVES`), the small scene's 6,799
/// boxes are refused by `plait check --adapter --scene` and by `plait
/// render` before any GPU work — exit 2, the numbers, the adapter and the
/// fix, no image — and 6,799 holds them.
#[test]
fn a_groom_past_the_blas_limit_is_refused_with_the_numbers() {
    let limited = |args: &[&str], limit: &str| {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_plait"));
        cmd.current_dir(root())
            .args(args)
            .env("PLAIT_MAX_BLAS_PRIMITIVES", limit);
        cmd.output().expect("run plait")
    };
    let set = "techniques.self_shadow=ray_traced";
    let scene = "examples/scenes/small.toml";
    let wanted = [
        "techniques/self_shadow/ray_traced/technique.toml:",
        "pass `strand_structure` (technique self_shadow/ray_traced)",
        "400 strands, 6800 points, 6799 boxes",
        "more than the 6798 primitives one bottom-level structure holds on adapter `",
        "draw fewer strands (at most 399 of this groom's 17.0 points each)",
    ];
    let check = [
        "check",
        "--adapter",
        "pipelines/occupancy.toml",
        "--set",
        set,
        "--scene",
        scene,
    ];
    assert_refused("check --adapter", &limited(&check, "6798"), &wanted);
    assert_ok("check --adapter at the limit", &limited(&check, "6799"));
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("x.png");
    let render = [
        "render",
        "pipelines/occupancy.toml",
        "--set",
        set,
        "--scene",
        scene,
        "--size",
        "32x24",
        "--out",
        out.to_str().expect("utf-8"),
    ];
    assert_refused("render", &limited(&render, "6798"), &wanted);
    assert!(!out.exists(), "nothing rendered");
}

/// `transparency = ray_traced` (issue 48) on the real adapter with its ray
/// queries hidden: refused by `plait check --adapter` at its technique
/// file's `adapter` line, naming the adapter, the feature and the fix; on
/// the adapter as it is, it runs.
#[test]
fn ray_traced_transparency_is_refused_without_ray_queries() {
    let set = "techniques.transparency=ray_traced";
    let check = [
        "check",
        "--adapter",
        "pipelines/reference.toml",
        "--set",
        set,
    ];
    let wanted = [
        "cannot run pipeline `reference`",
        "techniques/transparency/ray_traced/technique.toml:",
        "technique transparency/ray_traced traces rays",
        "the adapter lacks ray queries (wgpu's EXPERIMENTAL_RAY_QUERY, Vulkan's VK_KHR_ray_query)",
        "`bash scripts/ensure-vulkan.sh`",
    ];
    assert_refused("check --adapter", &plait_env(&check, true), &wanted);
    assert_ok(
        "check --adapter with ray queries",
        &plait_env(&check, false),
    );
}
