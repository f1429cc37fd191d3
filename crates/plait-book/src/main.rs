//! `plait-book`: builds the book (`bash scripts/book.sh` runs this) and
//! checks it: links, images, no network loads; `--browser` also opens every
//! page in headless Chromium; `--screenshots DIR` writes pictures of the
//! index and one technique page to look at.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Parser;

#[derive(Parser)]
#[command(about = "Build plait's book: the guide plus a generated page per technique and pipeline")]
struct Args {
    /// The `plait` binary that makes the pictures.
    #[arg(long)]
    plait: PathBuf,
    /// Where the HTML goes (given twice, the last wins: scripts/book.sh passes
    /// the build folder's first).
    #[arg(long, default_value = "target/book", overrides_with = "out")]
    out: PathBuf,
    /// The staged book (a copy of book/ plus the generated pages).
    #[arg(long, default_value = "target/book-src", overrides_with = "stage")]
    stage: PathBuf,
    /// Size of the pictures, WIDTHxHEIGHT.
    #[arg(long, default_value = "256x192")]
    size: String,
    /// Open every page in headless Chromium too.
    #[arg(long)]
    browser: bool,
    /// Write screenshots of the index and a technique page here.
    #[arg(long, value_name = "DIR")]
    screenshots: Option<PathBuf>,
    /// The live view's site (`bash scripts/web.sh` builds it): copied into
    /// the book under live/, linked from every technique and gallery page.
    #[arg(long, value_name = "DIR")]
    live: Option<PathBuf>,
}

fn main() -> Result<()> {
    let args = Args::parse();
    let repo = std::env::current_dir()?;
    let (w, h) = args
        .size
        .split_once(['x', 'X'])
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .with_context(|| format!("--size {}: expected WIDTHxHEIGHT", args.size))?;
    let abs = |p: &PathBuf| {
        if p.is_absolute() {
            p.clone()
        } else {
            repo.join(p)
        }
    };
    let opts = plait_book::Options {
        repo: repo.clone(),
        stage: abs(&args.stage),
        out: abs(&args.out),
        plait: abs(&args.plait),
        figures: plait_book::FigureSettings {
            scenes: vec!["small.toml".into(), "stray.toml".into()],
            size: (w, h),
        },
        live: args.live.as_ref().map(abs),
    };
    let built = plait_book::build(&opts)?;
    let problems = plait_book::check::check(&built.out);
    for p in &problems {
        eprintln!("book: {p}");
    }
    if !problems.is_empty() {
        bail!("{} problems in the built book", problems.len());
    }
    let pages = plait_book::check::pages(&built.out);
    if args.browser {
        let problems = plait_book::browser::check_pages(&built.out, &pages)?;
        for p in &problems {
            eprintln!("browser: {p}");
        }
        if !problems.is_empty() {
            bail!("{} problems in the browser", problems.len());
        }
        println!(
            "browser: {} pages opened in Chromium, no problem",
            pages.len()
        );
    }
    if let Some(dir) = args.screenshots {
        std::fs::create_dir_all(&dir)?;
        for (page, name) in [
            ("index.html", "index.png"),
            ("techniques/self_shadow/deep_opacity.html", "technique.png"),
        ] {
            plait_book::browser::screenshot(&built.out, page, &dir.join(name))?;
            println!("wrote {}", dir.join(name).display());
        }
    }
    println!(
        "{} pages ({} generated), links and images checked: {}",
        pages.len(),
        built.generated.len(),
        built.out.join("index.html").display()
    );
    Ok(())
}
