//! A pipeline the adapter cannot run is refused before any GPU work (issue
//! 20 item 4). The no-Vulkan path is forced by pointing the Vulkan loader at
//! no driver (`VK_ICD_FILENAMES=/nonexistent.json`): wgpu then falls back to
//! Mesa's llvmpipe OpenGL, where `rg32float` is not renderable and depth
//! textures cannot be read as values.

mod common;
use common::{plait, root, text};

use std::process::{Command, Output};

/// `plait ARGS...` with Vulkan hidden, so the adapter is GL's.
fn plait_without_vulkan(args: &[&str]) -> Output {
    let o = Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .args(args)
        .env("VK_ICD_FILENAMES", "/nonexistent.json")
        .env_remove("VK_DRIVER_FILES")
        .env_remove("WGPU_BACKEND")
        .output()
        .expect("run plait");
    let err = text(&o.stderr);
    assert!(
        !err.contains("no GPU adapter found"),
        "no GL adapter either: wgpu's GL backend needs Mesa's EGL and its software driver \
         (apt-get install -y libegl1 libegl-mesa0 libgl1-mesa-dri; scripts/ensure-vulkan.sh \
         installs them). stderr: {err}"
    );
    o
}

/// `text` holds `file:LINE:COLUMN:` right after `file`.
fn has_location(text: &str, file: &str) -> bool {
    text.match_indices(file).any(|(i, _)| {
        let rest = &text[i + file.len()..];
        let mut parts = rest.splitn(3, ':');
        let (_, line, column) = (parts.next(), parts.next(), parts.next());
        let digits = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_digit());
        line.is_some_and(digits)
            && column.is_some_and(|c| digits(c.split(':').next().unwrap_or("")))
    })
}

/// What every refusal of the default pipeline on GL says.
fn assert_occupancy_refusal(err: &str) {
    let expected = [
        "cannot run pipeline `occupancy`",
        "(gl backend",
        "pass `light_range` (technique self_shadow/occupancy) renders into `light_range` (rg32float",
        "Texture usages TextureUsages(RENDER_ATTACHMENT) are not allowed on a texture of type Rg32Float",
        "pass `camera_range` (technique transparency/occupancy_order) renders into `camera_range`",
        "reads depth texture `opaque_shadow` as values",
        "help: install Mesa's Vulkan driver, which plait opens before gl: `apt-get install -y mesa-vulkan-drivers`",
        "VK_ICD_FILENAMES=/nonexistent.json is set",
        // Tried on this adapter before it is suggested (see the test below).
        "--set techniques.self_shadow=density_volume --set techniques.transparency=opaque",
    ];
    for e in expected {
        assert!(err.contains(e), "missing {e:?} in:\n{err}");
    }
    assert!(
        err.starts_with("error: ") && err.contains("adapter `"),
        "the adapter is named: {err}"
    );
    assert!(
        has_location(err, "techniques/self_shadow/light_range.toml"),
        "the slot's line:column: {err}"
    );
    // Found before wgpu saw a call: none of its raw messages.
    assert!(!err.contains("Validation Error"), "{err}");
    assert!(!err.contains("memory plan"), "{err}");
}

#[test]
fn render_without_vulkan_is_refused_naming_pass_resource_capability_and_fix() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("hair.png");
    let o = plait_without_vulkan(&[
        "render",
        "--size",
        "64x48",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert_occupancy_refusal(&err);
    assert!(!out.exists(), "nothing is written");
}

#[test]
fn check_adapter_refuses_what_plain_check_accepts() {
    let plain = plait(&["check", "pipelines/occupancy.toml"]);
    assert!(plain.status.success(), "{}", text(&plain.stderr));
    let o = plait_without_vulkan(&["check", "--adapter", "pipelines/occupancy.toml"]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert_occupancy_refusal(&err);

    // A pass of the pipeline's own: no technique choice fixes it, so none is offered.
    let o = plait_without_vulkan(&["check", "--adapter", "pipelines/forward.toml"]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(
        err.contains("pass `opaque` reads depth texture `hair_depth` as values"),
        "{err}"
    );
    assert!(has_location(&err, "pipelines/forward.toml"), "{err}");
    assert!(!err.contains("--set techniques."), "{err}");
}

#[test]
fn the_suggested_techniques_pass_the_check_and_render_on_gl() {
    let sets = [
        "--set",
        "techniques.self_shadow=density_volume",
        "--set",
        "techniques.transparency=opaque",
    ];
    let mut args = vec!["check", "--adapter", "pipelines/occupancy.toml"];
    args.extend(sets);
    let o = plait_without_vulkan(&args);
    assert!(o.status.success(), "stderr: {}", text(&o.stderr));
    let out = text(&o.stdout);
    assert!(
        out.contains("runs on adapter `") && out.contains("(gl backend"),
        "{out}"
    );

    // Accepted means it renders: an image with the hair in it, not a blank one.
    let tmp = tempfile::tempdir().expect("tempdir");
    let png = tmp.path().join("gl.png");
    let mut args = vec![
        "render",
        "--size",
        "96x72",
        "--out",
        png.to_str().expect("utf-8"),
    ];
    args.extend(sets);
    let o = plait_without_vulkan(&args);
    assert!(o.status.success(), "stderr: {}", text(&o.stderr));
    let image = image::open(&png).expect("the render wrote a PNG").to_rgb8();
    let first = image.get_pixel(0, 0);
    let differing = image.pixels().filter(|p| *p != first).count();
    assert!(
        differing > image.pixels().len() / 10,
        "only {differing} pixels differ from the background"
    );
}

#[test]
fn a_shader_sample_mask_is_refused_on_gl_before_any_gpu_work() {
    // alpha_to_coverage picks its samples in the shader (`@builtin(sample_mask)`),
    // which naga's GLSL output cannot express (gl_SampleMask is an int array
    // in GLSL): refused by the check, not by a failed shader compile.
    let o = plait_without_vulkan(&[
        "check",
        "--adapter",
        "pipelines/occupancy.toml",
        "--set",
        "techniques.self_shadow=none",
        "--set",
        "techniques.transparency=alpha_to_coverage",
    ]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(
        err.contains("pass `hair_coverage` (technique transparency/alpha_to_coverage) uses `@builtin(sample_mask)`"),
        "{err}"
    );
    assert!(err.contains("gl_SampleMask"), "{err}");
    assert!(
        has_location(
            &err,
            "techniques/transparency/alpha_to_coverage/technique.toml"
        ),
        "{err}"
    );
    assert!(
        err.contains("--set techniques.transparency=opaque"),
        "{err}"
    );
    assert!(!err.contains("GPU validation error"), "{err}");
}

/// Hair drawn into multisampled targets renders on GL: alpha_to_coverage's
/// passes with the hardware's alpha to coverage and a shader without
/// `@builtin(sample_mask)`, as a pipeline of a temporary folder.
#[test]
fn multisampled_hair_renders_on_gl() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let technique = tmp.path().join("techniques/transparency/msaa_hw");
    std::fs::create_dir_all(&technique).expect("mkdir");
    let toml = std::fs::read_to_string(
        root().join("techniques/transparency/alpha_to_coverage/technique.toml"),
    )
    .expect("read the technique");
    let depth = "depth = { compare = \"less\", write = true }";
    assert!(toml.contains(depth), "the hair pass's depth line moved");
    let toml = toml.replacen(depth, &format!("{depth}\nalpha_to_coverage = true"), 1);
    let shader = "#import plait::hair_fragment::{HairVertex, HairVaryings, hair_vertex, shade_hair}
@vertex fn vs_main(v: HairVertex) -> HairVaryings { return hair_vertex(v); }
@fragment fn fs_main(in: HairVaryings) -> @location(0) vec4<f32> {
    let f = shade_hair(in);
    return vec4<f32>(f.rgb, f.alpha);
}";
    let pipeline = "[pipeline]\nextends = \"occupancy.toml\"\nname = \"msaa_hw\"\n\
        [techniques]\nself_shadow = \"none\"\ntransparency = \"msaa_hw\"\n";
    let write = |path: std::path::PathBuf, text: &str| std::fs::write(path, text).expect("write");
    write(technique.join("technique.toml"), &toml);
    write(technique.join("hair.wgsl"), shader);
    write(tmp.path().join("msaa.toml"), pipeline);
    let png = tmp.path().join("gl.png");
    let o = plait_without_vulkan(&[
        "render",
        tmp.path().join("msaa.toml").to_str().expect("utf-8"),
        "--size",
        "96x72",
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "stderr: {}", text(&o.stderr));
    // Not blank: llvmpipe's GL drew nothing into multisample textures while
    // the pool made every multisampled target sampleable.
    let image = image::open(&png).expect("the render wrote a PNG").to_rgb8();
    let first = image.get_pixel(0, 0);
    let differing = image.pixels().filter(|p| *p != first).count();
    assert!(
        differing > image.pixels().len() / 10,
        "only {differing} pixels differ from the background"
    );
}

#[test]
fn check_adapter_accepts_the_default_pipeline_on_vulkan() {
    // As the test environment gives it (scripts/test.sh: lavapipe).
    let o = plait(&[
        "check",
        "--adapter",
        "pipelines/occupancy.toml",
        "pipelines/forward.toml",
    ]);
    assert!(o.status.success(), "stderr: {}", text(&o.stderr));
    let out = text(&o.stdout);
    assert_eq!(out.matches("runs on adapter `").count(), 2, "{out}");
    assert!(out.contains("(vulkan backend"), "{out}");
}

#[test]
fn ab_without_vulkan_is_refused_before_any_variant_is_built() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("report");
    let o = plait_without_vulkan(&[
        "ab",
        "pipelines/occupancy.toml",
        "--reference",
        "pipelines/forward.toml",
        "--size",
        "64x48",
        "--repeats",
        "1",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(
        err.contains("pipeline occupancy"),
        "names the variant: {err}"
    );
    assert_occupancy_refusal(&err);
    // No progress line: nothing was built, let alone rendered.
    assert!(!text(&o.stdout).contains("built"), "{}", text(&o.stdout));
    assert!(!out.exists(), "no report directory");
}
