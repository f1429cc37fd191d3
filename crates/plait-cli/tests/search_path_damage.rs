//! No data file on the search path can panic plait (issue 41 item 1).
//!
//! The library (`shaders/`, `techniques/`, `pipelines/`, and the small scene
//! a render loads) is copied into a temporary folder that is the whole
//! search path (`PLAIT_PATH`), and the pipelines run are that copy's own, so
//! a pipeline's sibling `techniques/` is the damaged copy too. Then, one file
//! at a time, that file is damaged — cut to half its bytes, emptied, and a
//! few seeded mutations (numbers swapped for edge values, lines deleted or
//! doubled, words swapped, tokens of the file's language inserted, bytes
//! overwritten) — and `plait check` runs on every pipeline that reads it; a
//! seeded sample of the damages also runs a tiny `plait render`.
//!
//! The property: exit code 0 (damage the run does not read, or that leaves
//! the file valid) or 2 with an error at a file:line:col or naming the
//! damaged file — naming it whenever that file no longer reads on its own
//! (not UTF-8, or TOML that does not parse) — never a panic (exit 101,
//! "panicked at"), another code, or a hang. An undamaged run must exit 0 first, so a refusal
//! is the damage's.
//!
//! `PLAIT_DAMAGE_MUTANTS=N` draws N mutants per file (default 2) and
//! `PLAIT_DAMAGE_SEED=S` another stream (default 41), for a longer hunt.

mod common;
use common::root;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What the copy holds: the library folders a run reads.
const LIBRARY: [&str; 3] = ["shaders", "techniques", "pipelines"];
/// The scene the sampled renders draw (a few hundred strands).
const SCENE: &str = "examples/scenes/small.toml";
/// The pipeline a technique's files are checked through, with that
/// technique swapped in (every technique checks on it).
const BASE: &str = "pipelines/occupancy.toml";
/// How many damages also run `plait render` (seeded sample).
const RENDERS: usize = 24;
/// A run taking longer than this is a hang.
const HANG: Duration = Duration::from_secs(120);

/// splitmix64: a tiny seeded generator, so every run damages alike.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Numbers that take parsers and size arithmetic to their edges.
const NUMBERS: [&str; 12] = [
    "0",
    "-1",
    "1e39",
    "-1e39",
    "4294967296",
    "18446744073709551616",
    "2147483647",
    "65536",
    "0.5",
    "-0.0",
    "nan",
    "inf",
];

const TOML_TOKENS: [&str; 12] = [
    "=",
    "[",
    "]",
    "\"",
    "{",
    "}",
    ",",
    "'''",
    ".",
    "\n[x]\n",
    "\n[[y]]\n",
    "\nz = 1\n",
];

const WGSL_TOKENS: [&str; 14] = [
    "}",
    "{",
    ";",
    "(",
    ")",
    "fn",
    "<",
    "@group(0) @binding(99) var<storage, read_write> zz: array<u32>;\n",
    "#import plait::nowhere\n",
    "#define_import_path plait::other\n",
    "#ifdef X\n",
    "array<f32, 0>",
    "@builtin(position)",
    "const Q: u32 = 0u / 0u;\n",
];

/// One way to damage a file.
#[derive(Clone, Copy, Debug)]
enum Damage {
    /// The first half of its bytes (may end inside a UTF-8 character).
    Half,
    /// No bytes at all.
    Empty,
    /// 1–3 seeded edits.
    Mutant(u64),
}

fn damaged(original: &[u8], damage: Damage, wgsl: bool) -> Vec<u8> {
    match damage {
        Damage::Half => original[..original.len() / 2].to_vec(),
        Damage::Empty => Vec::new(),
        Damage::Mutant(seed) => {
            let mut rng = Rng(seed);
            let mut data = original.to_vec();
            for _ in 0..1 + rng.below(3) {
                data = mutate(data, &mut rng, wgsl);
            }
            data
        }
    }
}

/// Byte ranges of numeric literals (`-12`, `0.5`, `1e3`, `4u`).
fn numbers(data: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < data.len() {
        let starts = data[i].is_ascii_digit() && (i == 0 || !data[i - 1].is_ascii_alphanumeric());
        if !starts {
            i += 1;
            continue;
        }
        let start = if i > 0 && data[i - 1] == b'-' {
            i - 1
        } else {
            i
        };
        while i < data.len() && (data[i].is_ascii_alphanumeric() || data[i] == b'.') {
            i += 1;
        }
        out.push((start, i));
    }
    out
}

/// Byte ranges of words (identifiers and keys).
fn words(data: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < data.len() {
        if data[i].is_ascii_alphabetic() || data[i] == b'_' {
            let start = i;
            while i < data.len() && (data[i].is_ascii_alphanumeric() || data[i] == b'_') {
                i += 1;
            }
            out.push((start, i));
        } else {
            i += 1;
        }
    }
    out
}

/// Byte ranges of lines, newline included.
fn lines(data: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, b) in data.iter().enumerate() {
        if *b == b'\n' {
            out.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < data.len() {
        out.push((start, data.len()));
    }
    out
}

fn splice(data: &mut Vec<u8>, (start, end): (usize, usize), with: &[u8]) {
    data.splice(start..end, with.iter().copied());
}

/// One seeded edit.
fn mutate(mut data: Vec<u8>, rng: &mut Rng, wgsl: bool) -> Vec<u8> {
    let pick = |rng: &mut Rng, ranges: Vec<(usize, usize)>| {
        (!ranges.is_empty()).then(|| ranges[rng.below(ranges.len())])
    };
    match rng.below(6) {
        0 => {
            if let Some(r) = pick(rng, numbers(&data)) {
                let n = NUMBERS[rng.below(NUMBERS.len())];
                splice(&mut data, r, n.as_bytes());
            }
        }
        1 => {
            if let Some(r) = pick(rng, lines(&data)) {
                splice(&mut data, r, b"");
            }
        }
        2 => {
            if let Some(r) = pick(rng, lines(&data)) {
                let line = data[r.0..r.1].to_vec();
                splice(&mut data, (r.0, r.0), &line);
            }
        }
        3 => {
            let all = words(&data);
            if let (Some(a), Some(b)) = (pick(rng, all.clone()), pick(rng, all)) {
                let word = data[b.0..b.1].to_vec();
                splice(&mut data, a, &word);
            }
        }
        4 => {
            let tokens: &[&str] = if wgsl { &WGSL_TOKENS } else { &TOML_TOKENS };
            let at = rng.below(data.len() + 1);
            splice(
                &mut data,
                (at, at),
                tokens[rng.below(tokens.len())].as_bytes(),
            );
        }
        _ => {
            if !data.is_empty() {
                let at = rng.below(data.len());
                data[at] = [0x00, 0xff, 0x80, b'"', b'\n'][rng.below(5)];
            }
        }
    }
    data
}

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("mkdir");
    for entry in std::fs::read_dir(from).expect("read_dir") {
        let entry = entry.expect("entry");
        let target = to.join(entry.file_name());
        if entry.file_type().expect("file type").is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).expect("copy");
        }
    }
}

/// A fresh copy of the library in a temporary folder.
fn library_copy() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    for folder in LIBRARY {
        copy_tree(&root().join(folder), &dir.path().join(folder));
    }
    let scene = dir.path().join(SCENE);
    std::fs::create_dir_all(scene.parent().expect("parent")).expect("mkdir");
    std::fs::copy(root().join(SCENE), &scene).expect("copy the scene");
    dir
}

/// Every file of the library, relative (`techniques/shading/point.toml`).
fn library_files() -> Vec<String> {
    let mut files = Vec::new();
    for folder in LIBRARY {
        for ext in ["toml", "wgsl"] {
            for path in plait_files(&root().join(folder), ext) {
                let rel = path.strip_prefix(root()).expect("inside the checkout");
                files.push(rel.to_string_lossy().replace('\\', "/"));
            }
        }
    }
    files.sort();
    files
}

fn plait_files(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).expect("read_dir") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            out.extend(plait_files(&path, ext));
        } else if path.extension().is_some_and(|e| e == ext) {
            out.push(path);
        }
    }
    out
}

/// `techniques.POINT=NAME` when `rel` lies in a technique's folder, and the
/// choices its (undamaged) technique.toml requires beside it.
fn technique_of(rel: &str) -> Option<Vec<String>> {
    let parts: Vec<&str> = rel.split('/').collect();
    (parts.len() >= 4 && parts[0] == "techniques").then(|| {
        let file = root().join(format!(
            "techniques/{}/{}/technique.toml",
            parts[1], parts[2]
        ));
        let mut sets = vec![format!("techniques.{}={}", parts[1], parts[2])];
        sets.extend(
            std::fs::read_to_string(file)
                .map(|t| plait_graph::techniques::required_choices(&t))
                .unwrap_or_default(),
        );
        sets
    })
}

/// `--set` before each of `sets`.
fn set_flags(sets: Vec<String>) -> Vec<String> {
    sets.into_iter()
        .flat_map(|s| ["--set".to_string(), s])
        .collect()
}

/// The `plait check` arguments that read `rel`: a technique's files through
/// the base pipeline with it chosen, anything else through every pipeline.
fn check_args(rel: &str, pipelines: &[String]) -> Vec<String> {
    let mut args = vec!["check".to_string()];
    match technique_of(rel) {
        Some(sets) => {
            args.push(BASE.to_string());
            args.extend(set_flags(sets));
        }
        None => args.extend(pipelines.iter().cloned()),
    }
    args
}

/// A tiny render that reads `rel` (its technique chosen, if it has one).
fn render_args(rel: &str) -> Vec<String> {
    let mut args: Vec<String> = [
        "render", BASE, "--size", "32x24", "--scene", SCENE, "--out", "out.png",
    ]
    .map(String::from)
    .to_vec();
    if let Some(sets) = technique_of(rel) {
        args.extend(set_flags(sets));
    }
    args
}

/// A finished run: its exit code (`None`: killed by a signal) and stderr.
struct Ran {
    code: Option<i32>,
    stderr: String,
}

/// `plait ARGS` from `library` with it as the whole search path, killed
/// after `HANG`.
fn run(library: &Path, args: &[String]) -> Ran {
    let mut child = Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(library)
        .env("PLAIT_PATH", library)
        // A panic's first lines are enough to find it.
        .env("RUST_BACKTRACE", "0")
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run plait");
    let stderr = child.stderr.take().expect("stderr");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = std::io::Read::read_to_string(&mut std::io::BufReader::new(stderr), &mut s);
        s
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break Some(status);
        }
        if start.elapsed() > HANG {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let stderr = reader.join().expect("stderr reader");
    match status {
        Some(s) => Ran {
            code: s.code(),
            stderr,
        },
        None => Ran {
            code: None,
            stderr: format!("hung for over {HANG:?}\n{stderr}"),
        },
    }
}

/// Whether `bad` is unreadable on its own: not UTF-8, or TOML that does not
/// parse. Then nothing but that file can be blamed, so the error must name
/// it. (Damage that leaves a file well-formed — a module emptied, a binding
/// dropped — may rightly be reported where the file is used: at the import,
/// or at the slot the shader no longer binds.)
fn unreadable(rel: &str, bad: &[u8]) -> bool {
    match std::str::from_utf8(bad) {
        Err(_) => true,
        Ok(text) => rel.ends_with(".toml") && text.parse::<toml::Table>().is_err(),
    }
}

/// Whether `stderr` points at a line and column of some file (`x.toml:3:1`).
fn located(stderr: &str) -> bool {
    stderr.split([' ', '\n']).any(|word| {
        let mut parts = word.trim_end_matches(':').rsplitn(3, ':');
        let (col, line, file) = (parts.next(), parts.next(), parts.next());
        let number = |s: Option<&str>| {
            s.is_some_and(|s| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()))
        };
        number(col)
            && number(line)
            && file.is_some_and(|f| f.ends_with(".toml") || f.ends_with(".wgsl"))
    })
}

/// What is wrong with a damaged run, if anything.
fn verdict(rel: &str, must_name: bool, ran: &Ran) -> Option<String> {
    let panicked = ran.stderr.contains("panicked at");
    match ran.code {
        Some(0) if !panicked => None,
        Some(2) if panicked => Some("exit 2 after a panic".into()),
        Some(2) if must_name && !ran.stderr.contains(rel) => {
            Some("the file is unreadable, but the error does not name it".into())
        }
        // An unreadable file (not UTF-8) is named without a line.
        Some(2) if !located(&ran.stderr) && !ran.stderr.contains(rel) => {
            Some("no error names a file:line:col or the damaged file".into())
        }
        Some(2) => None,
        Some(code) => Some(format!(
            "exit {code}{}",
            if panicked { ", a panic" } else { "" }
        )),
        None => Some("killed (signal or hang)".into()),
    }
}

/// A command line for a message: the list of every pipeline shortened.
fn shown(args: &[String]) -> String {
    if args.len() > 4 {
        format!("{} <every pipeline>", args[0])
    } else {
        args.join(" ")
    }
}

/// Counts of one worker's runs.
#[derive(Default)]
struct Tally {
    checks: usize,
    renders: usize,
    refused: usize,
    failures: Vec<String>,
}

/// One damage of one file, and whether it is rendered too.
struct Job {
    rel: String,
    damage: Damage,
    render: bool,
}

fn run_jobs(jobs: &[Job], pipelines: &[String]) -> Tally {
    let library = library_copy();
    let dir = library.path();
    let mut tally = Tally::default();
    for job in jobs {
        let path = dir.join(&job.rel);
        let original = std::fs::read(&path).expect("the copy");
        let bad = damaged(&original, job.damage, job.rel.ends_with(".wgsl"));
        if bad == original {
            continue;
        }
        let must_name = unreadable(&job.rel, &bad);
        std::fs::write(&path, &bad).expect("damage the copy");
        let mut runs = vec![check_args(&job.rel, pipelines)];
        if job.render {
            runs.push(render_args(&job.rel));
        }
        for args in &runs {
            let ran = run(dir, args);
            if args[0] == "render" {
                tally.renders += 1;
            } else {
                tally.checks += 1;
            }
            tally.refused += usize::from(ran.code == Some(2));
            if let Some(why) = verdict(&job.rel, must_name, &ran) {
                let tail: String = ran
                    .stderr
                    .lines()
                    .take(6)
                    .collect::<Vec<_>>()
                    .join("\n    ");
                tally.failures.push(format!(
                    "{} {:?}: `plait {}`: {why}\n    {tail}",
                    job.rel,
                    job.damage,
                    shown(args)
                ));
            }
        }
        std::fs::write(&path, &original).expect("restore the copy");
    }
    tally
}

/// Every file, every damage; the renders a seeded sample.
fn jobs(files: &[String], seed: u64, mutants: u64) -> Vec<Job> {
    let mut rng = Rng(seed);
    let mut jobs = Vec::new();
    for rel in files {
        let mut damages = vec![Damage::Half, Damage::Empty];
        damages.extend((0..mutants).map(|_| Damage::Mutant(rng.next())));
        for damage in damages {
            jobs.push(Job {
                rel: rel.clone(),
                damage,
                render: false,
            });
        }
    }
    for _ in 0..RENDERS.min(jobs.len()) {
        let i = rng.below(jobs.len());
        jobs[i].render = true;
    }
    jobs
}

#[test]
fn no_damaged_library_file_panics_check_or_render() {
    let files = library_files();
    let pipelines: Vec<String> = files
        .iter()
        .filter(|f| f.starts_with("pipelines/"))
        .cloned()
        .collect();
    assert!(files.len() > 100 && pipelines.len() > 10, "{files:?}");
    // Undamaged, every run is accepted, so a refusal below is the damage's.
    let clean = library_copy();
    for args in [
        check_args("shaders/lib/frame.wgsl", &pipelines),
        render_args(BASE),
    ] {
        let ran = run(clean.path(), &args);
        assert_eq!(
            ran.code,
            Some(0),
            "plait {}: {}",
            args.join(" "),
            ran.stderr
        );
    }
    let seed = env_number("PLAIT_DAMAGE_SEED", 41);
    let jobs = jobs(&files, seed, env_number("PLAIT_DAMAGE_MUTANTS", 2));
    // Two workers, each on its own copy (the machine this runs on has two cores).
    let start = Instant::now();
    let half = jobs.len().div_ceil(2);
    let tallies: Vec<Tally> = std::thread::scope(|s| {
        let workers: Vec<_> = jobs
            .chunks(half)
            .map(|chunk| s.spawn(|| run_jobs(chunk, &pipelines)))
            .collect();
        workers
            .into_iter()
            .map(|w| w.join().expect("worker"))
            .collect()
    });
    let sum = |f: fn(&Tally) -> usize| tallies.iter().map(f).sum::<usize>();
    let failures: Vec<&String> = tallies.iter().flat_map(|t| &t.failures).collect();
    eprintln!(
        "{} files, {} damages (seed {seed}): {} checks, {} renders, {} refused with exit 2, {} failures, {:.0} s",
        files.len(),
        jobs.len(),
        sum(|t| t.checks),
        sum(|t| t.renders),
        sum(|t| t.refused),
        failures.len(),
        start.elapsed().as_secs_f64()
    );
    assert!(
        failures.is_empty(),
        "{} damaged runs failed:\n{}",
        failures.len(),
        failures
            .iter()
            .map(|f| f.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// A chosen technique's file emptied (still valid TOML) is refused at that
/// file: before, the choice was dropped without a word and the error
/// surfaced elsewhere ("output `final` is not written by any pass").
#[test]
fn an_emptied_technique_file_is_an_error_at_that_file() {
    let library = library_copy();
    let rel = "techniques/tone_mapping/reinhard/technique.toml";
    std::fs::write(library.path().join(rel), "").expect("empty it");
    let args: Vec<String> = ["check", BASE, "--set", "techniques.tone_mapping=reinhard"]
        .map(String::from)
        .to_vec();
    let ran = run(library.path(), &args);
    assert_eq!(ran.code, Some(2), "{}", ran.stderr);
    assert!(
        ran.stderr.contains(&format!(
            "{rel}:1:1: a technique file needs a [technique] table"
        )),
        "{}",
        ran.stderr
    );
}
