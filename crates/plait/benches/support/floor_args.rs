//! The floor benchmark's command line, checked before any GPU work: an
//! unknown flag, a flag without its value or a value that is not one is an
//! error naming the flag (the benchmark prints it and exits 2), never a
//! silent default. `--set KEY=VALUE` texts are not parsed here: they go to
//! the pipeline loader exactly as `plait render --set` does
//! ([`check_sets`] loads each pipeline with them, no GPU needed), so both
//! accept and reject the same flags with the same messages.
//! `crates/plait/tests/floor_bench_args.rs` tests this file.

use std::path::{Path, PathBuf};

pub const USAGE: &str = "\
cargo bench -p plait --bench floor [-- OPTIONS]

Each gallery pipeline against its raster floor (the same passes, targets,
clears and draws with trivial shaders), in interleaved repeats.

  --size WxH        frame size (default 160x120; the book's table uses 320x240)
  --repeats N       interleaved repeats after one warm-up (default 3)
  --scene FILE      a scene file instead of the built-in scene
  --only a,b        only these pipelines (file stems of pipelines/*.toml)
  --set KEY=VALUE   repeatable, as `plait render --set`: every pipeline
                    chosen is also rendered with the sets, in a row of its
                    own beside the pipeline as it is, against the floor of
                    its own schedule
  --sets-only       only the --set rows, not the pipelines as they are (to
                    profile a --set row alone with --side)
  --save DIR        write each row's image to DIR
  --one-draw        add the default pipeline with its maps built in one draw
  --side plait|floor  render one side only (to profile it with perf)
  --help            this text";

/// The flags that take a value, and those that do not (`--bench` is
/// cargo's own, passed to every benchmark).
const WITH_VALUE: &[&str] = &[
    "--size",
    "--repeats",
    "--scene",
    "--only",
    "--set",
    "--save",
    "--side",
];
const WITHOUT_VALUE: &[&str] = &["--one-draw", "--sets-only", "--bench", "--help"];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    Both,
    Plait,
    Floor,
}

#[derive(Debug, PartialEq)]
pub struct FloorArgs {
    pub size: (u32, u32),
    pub repeats: usize,
    pub scene: Option<PathBuf>,
    pub only: Option<Vec<String>>,
    /// `--set` texts in the order given, not yet checked against a pipeline.
    pub sets: Vec<String>,
    /// Leave out the rows without the sets.
    pub sets_only: bool,
    pub save: Option<PathBuf>,
    pub one_draw: bool,
    pub side: Side,
    pub help: bool,
}

/// Parse the benchmark's arguments (without the program name).
pub fn parse(args: &[String]) -> Result<FloorArgs, String> {
    let mut out = FloorArgs {
        size: (160, 120),
        repeats: 3,
        scene: None,
        only: None,
        sets: Vec::new(),
        sets_only: false,
        save: None,
        one_draw: false,
        side: Side::Both,
        help: false,
    };
    let mut i = 0;
    while i < args.len() {
        let word = args[i].as_str();
        i += 1;
        // `--flag=value` as well as `--flag value`, as clap takes them.
        let (flag, inline) = match word.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f, Some(v.to_owned())),
            _ => (word, None),
        };
        if flag == "-h" || WITHOUT_VALUE.contains(&flag) {
            if inline.is_some() {
                return Err(format!("{flag} takes no value"));
            }
            match flag {
                "--one-draw" => out.one_draw = true,
                "--sets-only" => out.sets_only = true,
                "-h" | "--help" => out.help = true,
                _ => {}
            }
            continue;
        }
        if !WITH_VALUE.contains(&flag) {
            let known = WITH_VALUE.iter().chain(WITHOUT_VALUE).copied();
            let hint = plait::graph::suggest::nearest(flag, known)
                .map(|n| format!("; did you mean {n}?"))
                .unwrap_or_default();
            return Err(format!(
                "unknown argument `{word}`{hint} (--help lists the flags)"
            ));
        }
        let value = match inline {
            Some(v) => v,
            None => match args.get(i) {
                Some(v) if !v.starts_with("--") => {
                    i += 1;
                    v.clone()
                }
                _ => return Err(format!("{flag} needs a value: {}", example(flag))),
            },
        };
        match flag {
            "--size" => out.size = parse_size(&value)?,
            "--repeats" => {
                out.repeats = value
                    .trim()
                    .parse()
                    .ok()
                    .filter(|&n: &usize| n >= 1)
                    .ok_or_else(|| format!("--repeats {value}: expected a count of 1 or more"))?
            }
            "--scene" => out.scene = Some(PathBuf::from(value)),
            "--only" => out.only = Some(value.split(',').map(|n| n.trim().to_owned()).collect()),
            "--set" => out.sets.push(value),
            "--save" => out.save = Some(PathBuf::from(value)),
            "--side" => {
                out.side = match value.as_str() {
                    "plait" => Side::Plait,
                    "floor" => Side::Floor,
                    other => {
                        return Err(format!("--side {other}: expected `plait` or `floor`"));
                    }
                }
            }
            _ => unreachable!("every flag of WITH_VALUE is matched"),
        }
    }
    if out.sets_only && out.sets.is_empty() {
        return Err("--sets-only needs at least one --set KEY=VALUE".into());
    }
    Ok(out)
}

fn example(flag: &str) -> &'static str {
    match flag {
        "--set" => "--set KEY=VALUE, e.g. --set techniques.shading_space=strand",
        "--size" => "--size WxH, e.g. --size 320x240",
        "--only" => "--only a,b, e.g. --only occupancy,forward",
        "--side" => "--side plait or --side floor",
        "--repeats" => "--repeats N, e.g. --repeats 5",
        _ => "a file or folder",
    }
}

/// `WxH` (either x), as `plait render --size`.
fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("--size {text}: expected WIDTHxHEIGHT (e.g. 320x240)");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(format!("--size {text}: width and height must be 1..=16384"));
    }
    Ok((w, h))
}

/// The row label of `name` rendered with `sets`: `name --set a --set b`.
pub fn label(name: &str, sets: &[String]) -> String {
    let mut label = name.to_owned();
    for s in sets {
        label.push_str(" --set ");
        label.push_str(s);
    }
    label
}

/// A file name for a row's image: its label with everything but letters,
/// digits, `_` and `-` made `_`.
pub fn file_stem(label: &str) -> String {
    label
        .trim()
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Load `pipeline` with `sets` as `plait render --set` does (the same
/// loader: the same key checks, suggestions and messages), without a GPU.
pub fn check_sets(pipeline: &Path, sets: &[String]) -> Result<(), String> {
    plait::source::PipelineSource::new(pipeline, sets)
        .load(&[])
        .map(|_| ())
        .map_err(|e| e.to_string())
}
