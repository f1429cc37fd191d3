//! The rest of what a new user met on a fresh clone (issue 20), each item as
//! the binary shows it: messages that name the flag or file the user gave,
//! tables whose columns hold their content, outputs that are ordinary files.

mod common;
use common::{plait, root, text};

use std::path::Path;
use std::process::{Command, Output};

fn fails_with(o: &Output, parts: &[&str]) -> String {
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    for p in parts {
        assert!(stderr.contains(p), "stderr lacks `{p}`:\n{stderr}");
    }
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

fn utf8(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// `--out /proc/x.png` said "No such file or directory" and named the
/// temporary file (`/proc/.plait-dHqF6u`) the user never gave.
#[test]
fn an_unwritable_out_names_the_path_given() {
    let o = plait(&["render", "--out", "/proc/x.png"]);
    let stderr = fails_with(
        &o,
        &[
            "--out /proc/x.png: cannot write the file: the folder /proc exists but takes no new files",
        ],
    );
    assert!(!stderr.contains(".plait-"), "the temporary name: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let o = plait(&["render", "--out", "/nonexistent-folder/x.png"]);
    fails_with(
        &o,
        &["--out /nonexistent-folder/x.png: no folder /nonexistent-folder"],
    );
}

/// `plait graph X --out g.svg` without `--format` wrote DOT into `g.svg`:
/// the extension now picks the format, an extension naming none is an
/// error at the flag, and a `--format` the extension contradicts too.
#[test]
fn graph_takes_its_format_from_out() {
    let dir = tempfile::tempdir().expect("tempdir");
    let svg = dir.path().join("g.svg");
    let o = plait(&["graph", "pipelines/forward.toml", "--out", utf8(&svg)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&svg).expect("g.svg");
    assert!(text.starts_with("<svg"), "{}", &text[..text.len().min(80)]);
    let dot = dir.path().join("g.gv");
    let o = plait(&["graph", "pipelines/forward.toml", "--out", utf8(&dot)]);
    assert!(o.status.success());
    assert!(
        std::fs::read_to_string(&dot)
            .expect("g.gv")
            .starts_with("digraph")
    );
    let png = dir.path().join("g.png");
    let o = plait(&["graph", "pipelines/forward.toml", "--out", utf8(&png)]);
    fails_with(
        &o,
        &["`.png` names no graph format", "--format dot|svg|text"],
    );
    let o = plait(&[
        "graph",
        "pipelines/forward.toml",
        "--format",
        "dot",
        "--out",
        utf8(&svg),
    ]);
    fails_with(&o, &["--format dot but --out", "names an SVG file"]);
    assert!(!png.exists(), "no file is written on an error");
}

/// One form for every input file that cannot be read: `PATH: cannot read file: …`.
#[test]
fn every_missing_input_file_says_cannot_read_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let missing = |name: &str| dir.path().join(name);
    let png = missing("x.png");
    let scene = missing("nope-scene.toml");
    let hair = missing("nope.hair");
    let extends = dir.path().join("child.toml");
    std::fs::write(&extends, "[pipeline]\nextends = \"nope-base.toml\"\n").expect("write");
    let hair_scene = dir.path().join("scene.toml");
    std::fs::write(
        &hair_scene,
        "camera = \"fit\"\nhair = { file = \"nope.hair\" }\n[light]\ntype = \"directional\"\ndirection = [0.0, -1.0, 0.0]\n",
    )
    .expect("write");
    let runs: Vec<(Vec<&str>, String)> = vec![
        (
            vec!["check", "pipelines/nope.toml"],
            "pipelines/nope.toml: cannot read file: ".into(),
        ),
        (
            vec!["render", "--scene", utf8(&scene), "--out", utf8(&png)],
            format!("{}: cannot read file: ", scene.display()),
        ),
        (
            vec!["render", "--scene", utf8(&hair_scene), "--out", utf8(&png)],
            format!("{}: cannot read file: ", hair.display()),
        ),
        (
            vec!["hair", "info", utf8(&hair)],
            format!("{}: cannot read file: ", hair.display()),
        ),
        (
            vec!["check", utf8(&extends)],
            format!(
                "{}: cannot read file: ",
                missing("nope-base.toml").display()
            ),
        ),
        (
            vec![
                "check",
                "pipelines/forward.toml",
                "--set",
                "passes.compose.shader=nope.wgsl",
            ],
            "nope.wgsl: cannot read file: ".into(),
        ),
    ];
    for (args, want) in runs {
        let o = plait(&args);
        fails_with(&o, &[&want]);
    }
    assert!(!png.exists());
}

/// A `--size` the adapter cannot hold named a technique file's buffer, not
/// the flag the user changed.
#[test]
fn a_size_too_large_for_the_adapter_names_the_flag_and_the_largest_size() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let o = plait(&["render", "--size", "8192x8192", "--out", utf8(&png)]);
    let stderr = fails_with(
        &o,
        &[
            "error: --size 8192x8192 is too large for pipelines/occupancy.toml",
            "the largest size of this shape it fits is ",
            "camera_bits",
        ],
    );
    // `plait ab` names the flag the same way, before it renders anything.
    let out = dir.path().join("ab");
    let ab = plait(&[
        "ab",
        "pipelines/occupancy.toml",
        "--reference",
        "pipelines/forward.toml",
        "--size",
        "8192x8192",
        "--out",
        utf8(&out),
    ]);
    fails_with(
        &ab,
        &["error: --size 8192x8192 is too large for pipelines/occupancy.toml"],
    );
    assert!(!out.join("report.html").exists());
    // The size it names fits: rendering at it is not refused for its size.
    let largest = stderr
        .split("it fits is ")
        .nth(1)
        .and_then(|rest| rest.split(';').next())
        .expect("a size");
    let (w, h) = largest.split_once('x').expect("WxH");
    let (w, h): (u32, u32) = (w.parse().expect("w"), h.parse().expect("h"));
    assert_eq!(w, h, "the shape of 8192x8192");
    assert!((1024..8192).contains(&w), "{largest}");
    // Where the adapter's limit is WebGPU's default (lavapipe's is), `plait
    // graph` compiles under the same limit: the size named fits, one more
    // texel each way does not.
    if stderr.contains("at most 128.0 MiB (134217728 bytes)") {
        let graph = |w: u32, h: u32| {
            plait(&[
                "graph",
                "pipelines/occupancy.toml",
                "--size",
                &format!("{w}x{h}"),
            ])
            .status
            .success()
        };
        assert!(graph(w, h), "{w}x{h} does not fit");
        assert!(!graph(w + 1, h + 1), "{}x{} fits too", w + 1, h + 1);
    }
    assert!(!png.exists());
}

/// Without a GPU, `plait graph --size` checks against WebGPU's default
/// limits, and names the flag the same way.
#[test]
fn graph_names_the_size_flag_too() {
    let o = plait(&["graph", "pipelines/occupancy.toml", "--size", "4000x3000"]);
    fails_with(
        &o,
        &[
            "error: --size 4000x3000 is too large for pipelines/occupancy.toml within WebGPU's default limits",
            "the largest size of this shape it fits is 3344x2508",
        ],
    );
}

/// The table: columns as wide as their content, the techniques in effect
/// after a swap, and no "(29.41 MiB without sharing)" beside the same 29.41 MiB.
#[test]
fn the_render_table_holds_its_content_and_names_the_techniques() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let o = plait(&[
        "render",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "32x24",
        "--set",
        "params.light_size=64",
        "--set",
        "techniques.transparency=weighted_average",
        "--out",
        utf8(&png),
    ]);
    let stdout = text(&o.stdout);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(
        stdout.contains("techniques: self_shadow/occupancy, transparency/weighted_average"),
        "{stdout}"
    );
    // The table says which scene file it rendered (issue 41: it never did).
    assert!(
        stdout
            .lines()
            .any(|l| l.starts_with("scene: ") && l.ends_with("examples/scenes/small.toml")),
        "{stdout}"
    );
    let lines: Vec<&str> = stdout.lines().collect();
    let header = lines
        .iter()
        .position(|l| l.starts_with("pass "))
        .expect("a header line");
    let frame = lines
        .iter()
        .position(|l| l.starts_with("frame "))
        .expect("a frame line");
    // Every row ends its GPU ms in the header's column, whatever the names.
    let right = lines[header].chars().count();
    let type_at = lines[header].find("type").expect("type column");
    for row in lines[header + 1..=frame]
        .iter()
        .filter(|r| !r.contains(" culled "))
    {
        assert_eq!(row.chars().count(), right, "misaligned:\n{stdout}");
        assert_eq!(
            row.chars().nth(type_at - 1),
            Some(' '),
            "a pass name runs into its type:\n{stdout}"
        );
    }
    assert!(
        lines[header + 1..frame]
            .iter()
            .any(|r| r.contains("weighted_average_resolve")),
        "{stdout}"
    );
    let memory = lines
        .iter()
        .find(|l| l.starts_with("memory: "))
        .expect("memory");
    assert!(!memory.contains("without sharing"), "{memory}");
    let numbers: Vec<&str> = memory.matches(" MiB").collect();
    assert!(!numbers.is_empty(), "{memory}");
}

#[test]
fn graph_out_says_what_it_wrote() {
    let dir = tempfile::tempdir().expect("tempdir");
    let svg = dir.path().join("g.svg");
    let o = plait(&[
        "graph",
        "pipelines/occupancy.toml",
        "--format",
        "svg",
        "--out",
        utf8(&svg),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert_eq!(text(&o.stdout), format!("wrote {}\n", svg.display()));
    assert!(std::fs::read_to_string(&svg).expect("svg").contains("<svg"));
}

/// Every description starts in one column, past the longest name
/// (`deep_opacity_directions` ran into its description), and a technique
/// lists only params it uses (`occupancy_no_slab` has no slab count).
#[test]
fn techniques_lists_names_in_a_column_and_only_the_params_used() {
    let o = plait(&["techniques"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    let line = |name: &str| {
        out.lines()
            .find(|l| l.trim_start().starts_with(&format!("{name} ")))
            .unwrap_or_else(|| panic!("no line for {name}:\n{out}"))
            .to_owned()
    };
    let start = |l: &str| {
        l.find("Deep opacity")
            .or_else(|| l.find("None"))
            .expect("text")
    };
    let long = line("deep_opacity_directions");
    let short = line("none");
    assert_eq!(start(&long), start(&short), "\n{long}\n{short}");
    let params_of = |name: &str| -> String {
        let mut lines = out
            .lines()
            .skip_while(|l| !l.trim_start().starts_with(&format!("{name} ")));
        lines.next();
        lines
            .take_while(|l| l.starts_with("   "))
            .find(|l| l.contains("params: "))
            .unwrap_or_default()
            .to_owned()
    };
    let no_slab = params_of("occupancy_no_slab");
    assert!(no_slab.contains("slices = 128"), "{no_slab}");
    assert!(!no_slab.contains("slabs"), "{no_slab}");
    assert!(params_of("occupancy").contains("slabs = 4"), "{out}");
}

/// `hair convert` to a 17-vertex `.tfx` warns as `hair info` does.
#[test]
fn hair_convert_warns_about_a_count_tressfx_does_not_load() {
    let dir = tempfile::tempdir().expect("tempdir");
    let hair = dir.path().join("g.hair");
    let tfx = dir.path().join("g.tfx");
    let o = plait(&[
        "hair",
        "generate",
        "--strands",
        "5",
        "--segments",
        "16",
        "--out",
        utf8(&hair),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let o = plait(&["hair", "convert", utf8(&hair), utf8(&tfx)]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let convert = text(&o.stderr);
    let info = text(&plait(&["hair", "info", utf8(&tfx)]).stderr);
    let warning =
        "17 vertices per strand: plait reads it, TressFX itself loads only 4, 8, 16, 32 or 64";
    assert!(info.contains(warning), "{info}");
    assert!(convert.contains(warning), "convert said: {convert}");
    // A count TressFX loads: no warning.
    let o = plait(&[
        "hair",
        "convert",
        utf8(&hair),
        utf8(&tfx),
        "--vertices-per-strand",
        "16",
    ]);
    assert!(!text(&o.stderr).contains("warning"), "{}", text(&o.stderr));
}

/// Outputs are ordinary files: 0666 less the umask, 0644 under umask 022
/// (temporary files are created 0600, which the viewer's screenshot kept).
#[test]
fn outputs_get_an_ordinary_files_permissions() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let hair = dir.path().join("x.hair");
    let svg = dir.path().join("x.svg");
    let script = format!(
        "umask 022 && '{exe}' render pipelines/forward.toml --scene examples/scenes/small.toml --size 16x12 --out '{png}' >/dev/null \
         && '{exe}' hair generate --strands 2 --segments 2 --out '{hair}' >/dev/null \
         && '{exe}' graph pipelines/forward.toml --format svg --out '{svg}' >/dev/null",
        exe = env!("CARGO_BIN_EXE_plait"),
        png = png.display(),
        hair = hair.display(),
        svg = svg.display()
    );
    let o = Command::new("sh")
        .args(["-c", &script])
        .current_dir(root())
        .output()
        .expect("sh");
    assert!(o.status.success(), "{}", text(&o.stderr));
    #[cfg(unix)]
    for file in [&png, &hair, &svg] {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(file)
            .expect("written")
            .permissions()
            .mode()
            & 0o777;
        assert_eq!(mode, 0o644, "{} is {mode:o}", file.display());
    }
}

/// "did you mean `light_range`?; its textures" — what follows a suggestion
/// is a parenthesis, in every message that lists the valid names.
#[test]
fn a_suggestion_is_not_followed_by_stray_punctuation() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let runs: Vec<Vec<&str>> = vec![
        vec!["render", "--show", "light_rnage", "--out", utf8(&png)],
        vec![
            "check",
            "pipelines/occupancy.toml",
            "--set",
            "passes.hair.view=\"lihgt\"",
        ],
        vec![
            "check",
            "pipelines/occupancy.toml",
            "--set",
            "resources.final.kind=\"textre\"",
        ],
    ];
    for args in runs {
        let o = plait(&args);
        let stderr = fails_with(&o, &["did you mean `"]);
        for stray in ["?;", "?,", "?."] {
            assert!(!stderr.contains(stray), "`{stray}` in:\n{stderr}");
        }
        assert!(stderr.contains("? ("), "{stderr}");
    }
}

/// Choice lists come in the same order on every run: two runs of each
/// error print the same bytes.
#[test]
fn choice_lists_are_the_same_on_every_run() {
    let runs: Vec<Vec<&str>> = vec![
        vec![
            "render",
            "--show",
            "nothing_like_it",
            "--out",
            "/tmp/never.png",
        ],
        vec![
            "check",
            "pipelines/occupancy.toml",
            "--set",
            "techniques.self_shadow=nope",
        ],
        vec!["check", "pipelines/occupancy.toml", "--set", "params.zzz=1"],
        vec![
            "check",
            "pipelines/occupancy.toml",
            "--set",
            "passes.hair.params.zzz=1",
        ],
        vec![
            "check",
            "pipelines/occupancy.toml",
            "--set",
            "passes.hair.type=\"zzz\"",
        ],
        vec![
            "check",
            "pipelines/occupancy.toml",
            "--set",
            "passes.hair.params.self_shadow=\"zzz\"",
        ],
    ];
    for args in runs {
        let first = plait(&args);
        let second = plait(&args);
        fails_with(&first, &["error:"]);
        assert_eq!(
            text(&first.stderr),
            text(&second.stderr),
            "plait {args:?} differs between runs"
        );
    }
}

/// `--set`'s help says how techniques are swapped now (`techniques.POINT=NAME`),
/// not the files in `pipelines/` they used to be.
#[test]
fn set_help_describes_technique_swaps() {
    for command in ["render", "check", "graph", "view", "ab"] {
        let help = text(&plait(&[command, "--help"]).stdout);
        assert!(help.contains("techniques.POINT=NAME"), "{command}: {help}");
        assert!(
            !help.contains("pipelines/deep_opacity.toml"),
            "{command}: {help}"
        );
    }
}

/// A broken expression in a pipeline's TOML is reported as an expression,
/// with its file:line:col, not as "string values must be quoted".
#[test]
fn a_broken_unquoted_expression_is_named_as_one() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pipeline = dir.path().join("p.toml");
    let base = root().join("pipelines/occupancy.toml");
    std::fs::write(
        &pipeline,
        format!(
            "[pipeline]\nextends = \"{}\"\n\n[params]\nlight_size = 1024 +\n",
            base.display()
        ),
    )
    .expect("write");
    let o = plait(&["check", utf8(&pipeline)]);
    let stderr = fails_with(
        &o,
        &[
            &format!("{}:5:14: ", pipeline.display()),
            "`1024 +` is not a complete expression (expression ends too early)",
        ],
    );
    assert!(!stderr.contains("must be quoted"), "{stderr}");
}
