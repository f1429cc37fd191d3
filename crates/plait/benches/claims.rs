//! The papers' speed claims, side by side in one run:
//! `cargo bench -p plait --bench claims [-- --repeats N --write]`.
//!
//! Each claim compares two pipelines on a scene at a size. Every pipeline is
//! prepared once, rendered once to warm up, then rendered in interleaved
//! rounds (every pipeline once per round), so a drift of the machine's speed
//! falls on both sides of a ratio alike. It prints, per claim, the median GPU
//! frame times, their ratio, the spread of the per-round ratios, the paper's
//! ratio, and whether the claim holds: plait's ratio points the way the
//! paper's does. `--write` writes the table between the
//! `<!-- claims:speed -->` markers of book/src/guide/claims.md: the book's speed figures
//! are this output, never typed by hand.
//! A benchmark, not a test: nothing here fails on a slow machine.

mod support;

use std::path::PathBuf;

use plait::gpu::Gpu;
use plait::session::{Prepared, SceneData, prepare, repo_root};
use support::timing::{arg, median};

/// "`faster` is faster than `slower`" — or, with `expect_slower`, a claim
/// that `faster` costs more (occupancy against DOM-3).
struct Claim {
    /// Who claims it, where.
    source: &'static str,
    /// What is claimed, in the paper's words.
    text: &'static str,
    scene: &'static str,
    size: (u32, u32),
    /// The pipeline the claim says is faster, and the slower one.
    faster: &'static str,
    slower: &'static str,
    /// slower / faster in the paper, where it gives times.
    paper_ratio: Option<(f64, &'static str)>,
}

const CLAIMS: &[Claim] = &[
    Claim {
        source: "Sintorn & Assarsson 2009 §4, Fig. 2",
        text: "occupancy-order blending is much faster than depth peeling",
        scene: "small",
        size: (256, 192),
        faster: "occupancy",
        slower: "depth_peeling",
        paper_ratio: Some((12.7, "51 vs 4 fps at ~112 layers")),
    },
    Claim {
        source: "Sintorn & Assarsson 2009 §4, Fig. 2",
        text: "occupancy-order blending is much faster than depth peeling",
        scene: "stray",
        size: (256, 192),
        faster: "occupancy",
        slower: "depth_peeling",
        paper_ratio: Some((12.7, "51 vs 4 fps at ~112 layers")),
    },
    Claim {
        source: "Sintorn & Assarsson 2009 §4",
        text: "deep opacity maps (3 layers) cost a little less than occupancy maps",
        scene: "default",
        size: (320, 240),
        faster: "deep_opacity",
        slower: "occupancy",
        paper_ratio: Some((41.0 / 33.5, "41 vs 33.5 ms")),
    },
    Claim {
        source: "Yuksel & Keyser 2008 Fig. 1",
        text: "deep opacity maps (3 layers) are faster than opacity shadow maps (16)",
        scene: "default",
        size: (320, 240),
        faster: "deep_opacity",
        slower: "opacity_shadow_maps",
        paper_ratio: Some((114.0 / 81.0, "114 vs 81 fps")),
    },
    Claim {
        source: "Halén & Wester 2007 §3.3.2",
        text: "the modified shadow map is cheaper than occupancy maps",
        scene: "default",
        size: (320, 240),
        faster: "modified_shadow_map",
        slower: "occupancy",
        paper_ratio: None,
    },
    Claim {
        source: "plait (tests/claims.rs reference on stray)",
        text: "per-pixel lists sorted exactly are faster than depth peeling",
        scene: "stray",
        size: (256, 192),
        faster: "linked_list",
        slower: "depth_peeling",
        paper_ratio: None,
    },
    Claim {
        source: "AMD TressFX 4.1 ShortCut, as measured by O3DE's AtomTressFX gem",
        text: "ShortCut (3 nearest depths, the rest weighted) is about twice as fast as per-pixel linked lists",
        scene: "default",
        size: (960, 720),
        faster: "shortcut",
        slower: "linked_list",
        paper_ratio: Some((2.0, "≈ 2×")),
    },
];

/// One pipeline on one scene at one size, and its timed frames.
struct Run<'g> {
    key: (&'static str, &'static str, (u32, u32)),
    prepared: Prepared<'g>,
    ms: Vec<f64>,
}

fn main() {
    let repeats: usize = arg("--repeats")
        .and_then(|s| s.parse().ok())
        .unwrap_or(3)
        .max(1);
    let root = repo_root();
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    if !gpu.capabilities.timestamps {
        eprintln!(
            "{} has no timestamp queries: no GPU times to compare",
            gpu.adapter_name()
        );
        std::process::exit(1);
    }
    let mut scenes: Vec<(&str, SceneData)> = Vec::new();
    for claim in CLAIMS {
        if !scenes.iter().any(|(n, _)| *n == claim.scene) {
            let path = root.join(format!("examples/scenes/{}.toml", claim.scene));
            let data = SceneData::load(Some(&path)).unwrap_or_else(|e| panic!("{e}"));
            scenes.push((claim.scene, data));
        }
    }
    let scene = |name: &str| &scenes.iter().find(|(n, _)| *n == name).expect("loaded").1;
    let mut runs: Vec<Run> = Vec::new();
    for claim in CLAIMS {
        for pipeline in [claim.faster, claim.slower] {
            let key = (claim.scene, pipeline, claim.size);
            if runs.iter().any(|r| r.key == key) {
                continue;
            }
            let path: PathBuf = root.join(format!("pipelines/{pipeline}.toml"));
            let prepared = prepare(&gpu, &path, &[], scene(claim.scene), claim.size)
                .unwrap_or_else(|e| panic!("{pipeline} on {}: {e}", claim.scene));
            // Warm-up: pipelines, run-once passes and the first upload.
            prepared.render().unwrap_or_else(|e| panic!("{e}"));
            runs.push(Run {
                key,
                prepared,
                ms: Vec::new(),
            });
        }
    }
    for round in 0..repeats {
        eprintln!("round {} of {repeats}", round + 1);
        for run in &mut runs {
            let frame = run.prepared.render().unwrap_or_else(|e| panic!("{e}"));
            run.ms.push(frame.report.total_gpu_ms.unwrap_or(f64::NAN));
        }
    }
    let table = table(&gpu, repeats, &runs);
    println!("{table}");
    if std::env::args().any(|a| a == "--write") {
        let page = root.join("book/src/guide/claims.md");
        write_between_markers(&page, "claims:speed", &table)
            .unwrap_or_else(|e| panic!("{}: {e}", page.display()));
        eprintln!("wrote the table into {}", page.display());
    }
}

fn table(gpu: &Gpu, repeats: usize, runs: &[Run]) -> String {
    let find = |key| runs.iter().find(|r| r.key == key).expect("rendered");
    let mut out = format!(
        "`cargo bench -p plait --bench claims -- --repeats {repeats}` on {}: median GPU frame \
         time of {repeats} interleaved rounds; the ratio is slower / faster, its range over the \
         rounds in brackets.\n\n\
         | claim (paper) | scene, size | faster ms | slower ms | plait's ratio | paper's ratio | holds? |\n\
         |---|---|---:|---:|---:|---:|---|\n",
        gpu.adapter_name()
    );
    for c in CLAIMS {
        let fast = find((c.scene, c.faster, c.size));
        let slow = find((c.scene, c.slower, c.size));
        let (f, s) = (median(&fast.ms), median(&slow.ms));
        let ratio = s / f;
        let per_round: Vec<f64> = slow.ms.iter().zip(&fast.ms).map(|(s, f)| s / f).collect();
        let lo = per_round.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = per_round.iter().copied().fold(0.0, f64::max);
        let paper = c
            .paper_ratio
            .map(|(r, how)| format!("{r:.2}× ({how})"))
            .unwrap_or_else(|| "—".into());
        // Holds: plait's ratio points the paper's way in every round. Where
        // the paper gives times, say whether the size agrees too (within 2×).
        let holds = match (lo > 1.0, c.paper_ratio) {
            (false, _) => "**no**".to_string(),
            (true, Some((r, _))) if (ratio / r).max(r / ratio) <= 2.0 => "yes".into(),
            (true, Some(_)) => "in direction, not in size".into(),
            (true, None) => "yes".into(),
        };
        out += &format!(
            "| {} ({}): {} < {} | {}, {}×{} | {f:.0} | {s:.0} | {ratio:.2}× [{lo:.2}–{hi:.2}] | {paper} | {holds} |\n",
            c.text, c.source, c.faster, c.slower, c.scene, c.size.0, c.size.1
        );
    }
    out
}

/// Replace what stands between `<!-- NAME -->` and `<!-- /NAME -->` in `path`.
fn write_between_markers(path: &std::path::Path, name: &str, body: &str) -> Result<(), String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let (open, close) = (format!("<!-- {name} -->"), format!("<!-- /{name} -->"));
    let start = text
        .find(&open)
        .ok_or_else(|| format!("no {open} marker"))?
        + open.len();
    let end = text[start..]
        .find(&close)
        .ok_or_else(|| format!("no {close} marker after {open}"))?
        + start;
    let new = format!("{}\n{}{}", &text[..start], body, &text[end..]);
    let tmp = path.with_extension("md.tmp");
    std::fs::write(&tmp, new).map_err(|e| e.to_string())?;
    std::fs::rename(&tmp, path).map_err(|e| e.to_string())
}
