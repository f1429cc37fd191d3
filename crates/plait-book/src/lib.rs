//! plait's book: the hand-written guide of `book/`, plus a page per
//! technique and per gallery pipeline generated from their files, built with
//! mdBook (as a library, so the book builds with the crate versions of
//! `Cargo.lock`) and checked — every link and image resolves, nothing is
//! loaded from the network — by [`check`]; [`browser`] opens every page in
//! headless Chromium.
//!
//! Nothing on a generated page is typed by hand: descriptions, papers,
//! params, memory and files come from `technique.toml` and the pipeline
//! files; ranges from the pass library (`plait passes --json`); pictures and
//! schedules from the `plait` binary; measured rows from the tables
//! `scripts/gallery.sh` writes into the gallery page.

pub mod browser;
pub mod check;
mod context;
mod error;
mod figures;
pub mod live;
pub mod measured;
mod params;
mod pipeline_page;
mod plait_cmd;
pub mod published;
pub mod runnable;
mod stage;
mod technique_page;

use std::path::{Path, PathBuf};

pub use context::DEFAULT_PIPELINE;
pub use error::BookError;
pub use figures::FigureSettings;
pub use plait_cmd::Plait;

/// The gallery page whose marked tables are the last measurement run.
pub const GALLERY_PAGE: &str = "book/src/guide/gallery.md";

/// What to build, and where.
#[derive(Clone, Debug)]
pub struct Options {
    /// The repository root (holds `book/`, `pipelines/`, `techniques/`).
    pub repo: PathBuf,
    /// The staged book (emptied and rewritten).
    pub stage: PathBuf,
    /// Where the HTML goes (`target/book`).
    pub out: PathBuf,
    /// The `plait` binary that makes the figures.
    pub plait: PathBuf,
    pub figures: FigureSettings,
    /// The live view's site (`bash scripts/web.sh`), copied into the book
    /// under `live/`; every technique and gallery page then links to it
    /// ([`live`]). `None`: the book without it.
    pub live: Option<PathBuf>,
}

/// A generated page: its path under `src/` and what it documents.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Generated {
    Technique {
        point: String,
        name: String,
        page: String,
    },
    Pipeline {
        file: String,
        page: String,
    },
}

/// The built book.
#[derive(Clone, Debug)]
pub struct Built {
    pub out: PathBuf,
    pub generated: Vec<Generated>,
}

/// Stages, generates and builds the book.
pub fn build(opts: &Options) -> Result<Built, BookError> {
    let src = stage::prepare(&opts.repo, &opts.stage)?;
    let plait = Plait {
        exe: opts.plait.clone(),
        repo: opts.repo.clone(),
    };
    let roots = plait_graph::techniques::TechniqueRoots::at(opts.repo.join("techniques"));
    let catalog = plait_graph::techniques::catalog(&roots).map_err(|errors| {
        BookError::content(
            opts.repo.join("techniques"),
            plait_graph::Errors(errors).to_string(),
        )
    })?;
    let mut ctx = context::Context {
        repo: opts.repo.clone(),
        pipelines: context::gallery(&opts.repo)?,
        pass_params: context::pass_params(&plait)?,
        runs: measured::read(&opts.repo.join(GALLERY_PAGE))?,
        figures: figures::Figures::new(&plait, &src, opts.figures.clone())?,
        live: opts.live.is_some(),
    };

    let mut generated = Vec::new();
    let mut technique_toc = String::new();
    let mut point = String::new();
    let contracts = plait_graph::techniques::wgsl_points(&[])
        .map_err(|e| BookError::content("techniques", e.to_string()))?;
    for info in &catalog {
        if info.point != point {
            point = info.point.clone();
            let intro = format!("techniques/{point}.md");
            let contract = contracts.iter().find(|c| c.point == point);
            let mut page = point_page(&point, &catalog);
            if let Some(c) = contract {
                page.push_str(&contract_section(c)?);
            }
            write(&src.join(&intro), &page)?;
            technique_toc.push_str(&format!("- [{point}]({intro})\n"));
        }
        let page = technique_page::page_path(&info.point, &info.name);
        write(&src.join(&page), &technique_page::write(info, &mut ctx)?)?;
        technique_toc.push_str(&format!("  - [{}]({page})\n", info.name));
        generated.push(Generated::Technique {
            point: info.point.clone(),
            name: info.name.clone(),
            page,
        });
    }
    let mut pipeline_toc = String::new();
    for p in ctx.pipelines.clone() {
        write(&src.join(&p.page), &pipeline_page::write(&p, &mut ctx)?)?;
        pipeline_toc.push_str(&format!("- [{}]({})\n", p.file_name, p.page));
        generated.push(Generated::Pipeline {
            file: p.file_name.clone(),
            page: p.page.clone(),
        });
    }
    fill_summary(&src, &technique_toc, &pipeline_toc)?;
    fill_choice_points(&src, &catalog)?;
    write_published(&opts.repo, &src)?;
    fill_default_frame(&src, &opts.stage, &plait)?;
    run_mdbook(&opts.stage, &opts.out)?;
    if let Some(site) = &opts.live {
        live::copy_site(site, &opts.out)?;
    }
    Ok(Built {
        out: opts.out.clone(),
        generated,
    })
}

/// A choice point's page: its contract and the techniques that fill it.
fn point_page(point: &str, catalog: &[plait_graph::techniques::TechniqueInfo]) -> String {
    let mut md = format!(
        "# The `{point}` choice point\n\n\
         A pipeline picks one technique here with `{point} = \"NAME\"` in its `[techniques]` \
         table, or `--set techniques.{point}=NAME`. `plait techniques` lists the same.\n\n\
         | technique | what | source | memory |\n|---|---|---|---|\n"
    );
    for t in catalog.iter().filter(|t| t.point == point) {
        md.push_str(&format!(
            "| [{}]({point}/{}.md) | {} | {} | {} |\n",
            t.name,
            t.name,
            params::cell(&t.description),
            params::cell(&t.source),
            params::cell(&t.memory)
        ));
    }
    md
}

/// A WGSL point's contract, from its point file: the function, the
/// selector, the binding range, the slots and the params any provider may
/// use (what `docs/design.md` once kept by hand).
fn contract_section(c: &plait_graph::techniques::WgslPoint) -> Result<String, BookError> {
    let mut md = format!(
        "\n## Contract (`techniques/{0}/point.toml`)\n\n\
         Each technique's provider is the WGSL module `{1}::NAME` defining `{2}`; \
         shading code calls `{3}` from the generated `{4}`, which picks the one the \
         `{5}` param names (default `{6}`). {7}\n\n",
        c.point,
        c.providers,
        c.signature(),
        c.call,
        c.module,
        c.param,
        c.default.value,
        c.doc
    );
    if let Some(a) = &c.also {
        md.push_str(&format!(
            "Each provider also defines `fn {}({}) -> {}`, called as `{}`: {}\n\n",
            a.function, a.arguments, a.returns, a.call, a.doc
        ));
    }
    if let Some(o) = &c.optional {
        md.push_str(&format!(
            "A provider may define `fn {}({}) -> {}` (listed in its `provides`), called as `{}`: {}\n\n",
            o.function, o.arguments, o.returns, o.call, o.doc
        ));
    }
    if let Some(b) = &c.contract.bindings {
        let (first, last) = b.value;
        md.push_str(&format!(
            "Its providers' bindings: group 1, {first}–{last}.\n\n"
        ));
    }
    if !c.contract.inputs.is_empty() {
        md.push_str("| slot a provider may bind | kind | access | formats | what |\n|---|---|---|---|---|\n");
        for s in &c.contract.inputs {
            md.push_str(&format!(
                "| `{}` | {:?} | {} | {} | {} |\n",
                s.name,
                s.kind,
                s.access,
                s.formats,
                params::cell(&s.doc)
            ));
        }
        md.push('\n');
    }
    let all = c
        .contract
        .all_params()
        .map_err(|e| BookError::content("techniques", e.to_string()))?;
    if !all.is_empty() {
        md.push_str("| param a provider may read | type | default | what |\n|---|---|---|---|\n");
        for p in &all {
            let default = p
                .spec
                .default
                .as_ref()
                .map_or(String::new(), |d| d.to_string());
            // A param the point leaves unbounded (its technique may bound
            // it, `[param_ranges]`) reads as a number, not ±f64::MAX.
            let ty = match p.spec.ty {
                plait_graph::ParamType::Float { min, max }
                    if min == f64::MIN && max == f64::MAX =>
                {
                    "number".to_owned()
                }
                ref t => t.to_string(),
            };
            md.push_str(&format!(
                "| `{}` | {ty} | {default} | {} |\n",
                p.spec.name,
                params::cell(&p.spec.doc)
            ));
        }
    }
    Ok(md)
}

fn write(path: &Path, text: &str) -> Result<(), BookError> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(BookError::io(dir))?;
    }
    std::fs::write(path, text).map_err(BookError::io(path))
}

/// Puts the generated tables of contents at their markers of `SUMMARY.md`;
/// a marker missing is an error (the pages would be built but unreachable).
fn fill_summary(src: &Path, techniques: &str, pipelines: &str) -> Result<(), BookError> {
    let path = src.join("SUMMARY.md");
    let text = std::fs::read_to_string(&path).map_err(BookError::io(&path))?;
    let mut out = text.clone();
    for (marker, toc) in [
        ("<!-- generated:techniques -->", techniques),
        ("<!-- generated:pipelines -->", pipelines),
    ] {
        if !out.contains(marker) {
            return Err(BookError::content(&path, format!("no `{marker}` line")));
        }
        out = out.replace(marker, toc.trim_end());
    }
    write(&path, &out)
}

/// The guide page whose list of choice points and techniques is generated.
pub const CHOICE_POINTS_PAGE: &str = "guide/techniques.md";
const CHOICE_POINTS_MARKER: &str = "<!-- generated:choice-points -->";

/// Puts the table of every choice point and its techniques at its marker,
/// from the catalog: a hand-kept list drifted (it once left out
/// `compute_raster`).
fn fill_choice_points(
    src: &Path,
    catalog: &[plait_graph::techniques::TechniqueInfo],
) -> Result<(), BookError> {
    let path = src.join(CHOICE_POINTS_PAGE);
    let text = std::fs::read_to_string(&path).map_err(BookError::io(&path))?;
    if !text.contains(CHOICE_POINTS_MARKER) {
        return Err(BookError::content(
            &path,
            format!("no `{CHOICE_POINTS_MARKER}` line"),
        ));
    }
    let mut table = String::from("| choice point | techniques |\n|---|---|\n");
    let mut points: Vec<&str> = catalog.iter().map(|t| t.point.as_str()).collect();
    points.dedup();
    for point in points {
        let names: Vec<String> = catalog
            .iter()
            .filter(|t| t.point == point)
            .map(|t| {
                format!(
                    "[`{}`](../{})",
                    t.name,
                    technique_page::page_path(point, &t.name)
                )
            })
            .collect();
        table.push_str(&format!(
            "| [`{point}`](../techniques/{point}.md) | {} |\n",
            names.join(" · ")
        ));
    }
    write(&path, &text.replace(CHOICE_POINTS_MARKER, table.trim_end()))
}

/// The generated page of published figures (`published::stale::page`); the
/// stale ones are said on stderr too, so whoever builds the book sees them.
fn write_published(repo: &Path, src: &Path) -> Result<(), BookError> {
    for f in published::stale::freshness(repo)? {
        if f.is_stale() {
            eprintln!(
                "book: figure `{}` ({}) was measured at {} before {} later commit(s) to what it \
                 measures; re-check it with `bash scripts/bench.sh --check {}`",
                f.id,
                f.page,
                &f.commit[..f.commit.len().min(10)],
                f.changed_since.len(),
                f.id
            );
        }
    }
    write(&src.join(PUBLISHED_PAGE), &published::stale::page(repo)?)
}

/// The generated page listing every published figure and its freshness.
pub const PUBLISHED_PAGE: &str = "guide/published.md";

/// The guide page that shows the default render's per-pass table, and its
/// marker.
pub const DEFAULT_FRAME_PAGE: &str = "guide/first-render.md";
const DEFAULT_FRAME_MARKER: &str = "<!-- generated:default-frame -->";
/// The pipeline `scripts/render.sh` renders (issue 43), not `plait
/// render`'s own default (`pipelines/occupancy.toml`).
pub const DEFAULT_FRAME_PIPELINE: &str = "pipelines/default.toml";

/// Puts the per-pass table of `plait render` (the default pipeline on the
/// built-in scene, as `scripts/render.sh` runs it) at its marker: measured
/// on the machine that builds the book, whose adapter the table's first line
/// names, never typed by hand.
fn fill_default_frame(src: &Path, stage: &Path, plait: &Plait) -> Result<(), BookError> {
    let path = src.join(DEFAULT_FRAME_PAGE);
    let text = std::fs::read_to_string(&path).map_err(BookError::io(&path))?;
    if !text.contains(DEFAULT_FRAME_MARKER) {
        return Err(BookError::content(
            &path,
            format!("no `{DEFAULT_FRAME_MARKER}` line"),
        ));
    }
    // Outside `src/`, so mdBook does not copy the picture into the site.
    let png = stage.join("default-frame.png");
    let table = plait.run(&[
        "render".into(),
        DEFAULT_FRAME_PIPELINE.into(),
        "--out".into(),
        png.display().to_string(),
    ])?;
    // Its last line names the picture, a path of this machine's stage.
    let table: Vec<&str> = table.lines().filter(|l| !l.starts_with("wrote ")).collect();
    let table = table.join("\n");
    let block = format!(
        "```text\n$ plait render {DEFAULT_FRAME_PIPELINE}   # what bash scripts/render.sh runs\n{}\n```",
        table.trim_end()
    );
    write(&path, &text.replace(DEFAULT_FRAME_MARKER, &block))
}

fn run_mdbook(stage: &Path, out: &Path) -> Result<(), BookError> {
    let config_path = stage.join("book.toml");
    let mut config =
        mdbook_driver::config::Config::from_disk(&config_path).map_err(BookError::MdBook)?;
    config.build.build_dir = out.to_path_buf();
    let book = mdbook_driver::MDBook::load_with_config(stage, config).map_err(BookError::MdBook)?;
    book.build().map_err(BookError::MdBook)
}

#[cfg(test)]
mod tests {
    /// The point page's contract comes from the point file: its range, its
    /// slots and its params, the `[params_from]` ones included.
    #[test]
    fn a_point_page_lists_its_contract_from_the_point_file() {
        let points = plait_graph::techniques::wgsl_points(&[]).expect("the point files");
        let shading = points
            .iter()
            .find(|p| p.point == "shading")
            .expect("shading");
        let md = super::contract_section(shading).expect("a contract");
        for want in [
            "## Contract (`techniques/shading/point.toml`)",
            "`fn hair_direct(",
            "group 1, 20–29",
            "| `marschner_m` | Texture | sampled | rgba16float |",
            "| `chiang_beta_m` | number | 0.3 |",
            "| `marschner_shift_r` | number -45 … 45 | -7.5 |",
            "defining `fn hair_direct(",
        ] {
            assert!(md.contains(want), "no `{want}` in\n{md}");
        }
    }
}
