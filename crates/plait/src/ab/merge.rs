//! `plait ab merge`: the shards of one plan ([`shard`](super::shard)) joined
//! into the report one run would write — the same rows in the same order,
//! the same images and metrics — except that each row's times come from
//! the machine of its shard, which the report says (`Run::shard`,
//! `Report::shards`) instead of presenting them as ratios from one run.
//!
//! The one number a shard cannot know is a scene's difference-map scale
//! (the largest difference over all its rows): the merge takes it over the
//! joined rows and redraws each difference map at that scale from the
//! images the shards wrote, checking that the comparison it recomputes
//! gives the shard's metrics.

use std::path::{Path, PathBuf};

use plait_compare::report::{Report, SceneResult};

use super::shard::{SHARD_FILE, SHARD_SCHEMA, ShardMarker};

/// Why shards do not merge. Every variant names the directories.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    #[error("no shard directory to merge")]
    Nothing,
    #[error(
        "{}: no {SHARD_FILE}: not a finished shard (half-written, still running, or not a `plait ab --shard` directory)",
        .0.display()
    )]
    Unfinished(PathBuf),
    #[error("{}: reading {name}", dir.display())]
    Read {
        dir: PathBuf,
        name: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{}: {name} is not a shard's file", dir.display())]
    Parse {
        dir: PathBuf,
        name: String,
        #[source]
        source: serde_json::Error,
    },
    #[error("{}: shard schema {found}, this plait reads {SHARD_SCHEMA}", dir.display())]
    Schema { dir: PathBuf, found: String },
    #[error(
        "{} and {} are shards of different plans (fingerprints {} and {}): same pipelines, files, flags and plait needed",
        a.display(), b.display(), &fa[..12], &fb[..12]
    )]
    DifferentPlans {
        a: PathBuf,
        b: PathBuf,
        fa: String,
        fb: String,
    },
    #[error("{} and {} are both shard {index}", a.display(), b.display())]
    Duplicate {
        index: usize,
        a: PathBuf,
        b: PathBuf,
    },
    #[error("shard {missing} of {count} is missing (given: {given})")]
    Missing {
        missing: usize,
        count: usize,
        given: String,
    },
    #[error("{}: {what}", dir.display())]
    Inconsistent { dir: PathBuf, what: String },
    #[error(
        "scene {scene}: the reference image of {} differs from {}'s (file {file}): the shards' rows were measured against different truths (different GPUs or drivers?)",
        a.display(), b.display()
    )]
    ReferenceDiffers {
        scene: String,
        file: String,
        a: PathBuf,
        b: PathBuf,
    },
    #[error("{}: {what}", dir.display())]
    Image {
        dir: PathBuf,
        what: String,
        #[source]
        source: image::ImageError,
    },
    #[error("{}: {what}", dir.display())]
    Compare {
        dir: PathBuf,
        what: String,
        #[source]
        source: plait_compare::CompareError,
    },
    #[error("writing the merged report")]
    Write(#[source] super::AbError),
}

/// One shard directory, read.
struct Part {
    dir: PathBuf,
    marker: ShardMarker,
    report: Report,
}

fn read_json<T: serde::de::DeserializeOwned>(dir: &Path, name: &str) -> Result<T, MergeError> {
    let text = std::fs::read_to_string(dir.join(name)).map_err(|source| MergeError::Read {
        dir: dir.to_path_buf(),
        name: name.into(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|source| MergeError::Parse {
        dir: dir.to_path_buf(),
        name: name.into(),
        source,
    })
}

fn read_part(dir: &Path) -> Result<Part, MergeError> {
    if !dir.join(SHARD_FILE).is_file() {
        return Err(MergeError::Unfinished(dir.to_path_buf()));
    }
    let marker: ShardMarker = read_json(dir, SHARD_FILE)?;
    if marker.schema != SHARD_SCHEMA {
        return Err(MergeError::Schema {
            dir: dir.to_path_buf(),
            found: marker.schema,
        });
    }
    let report = read_json(dir, "report.json")?;
    Ok(Part {
        dir: dir.to_path_buf(),
        marker,
        report,
    })
}

/// Every shard of one plan, each once, in index order.
fn read_all(dirs: &[PathBuf]) -> Result<Vec<Part>, MergeError> {
    let mut parts = dirs
        .iter()
        .map(|d| read_part(d))
        .collect::<Result<Vec<_>, _>>()?;
    let first = parts.first().ok_or(MergeError::Nothing)?;
    let (fingerprint, count) = (first.marker.fingerprint.clone(), first.marker.shard.count);
    for p in &parts[1..] {
        if p.marker.fingerprint != fingerprint || p.marker.shard.count != count {
            return Err(MergeError::DifferentPlans {
                a: first.dir.clone(),
                b: p.dir.clone(),
                fa: fingerprint,
                fb: p.marker.fingerprint.clone(),
            });
        }
    }
    parts.sort_by_key(|p| p.marker.shard.index);
    for w in parts.windows(2) {
        if w[0].marker.shard.index == w[1].marker.shard.index {
            return Err(MergeError::Duplicate {
                index: w[0].marker.shard.index,
                a: w[0].dir.clone(),
                b: w[1].dir.clone(),
            });
        }
    }
    if let Some(missing) =
        (0..count).find(|&i| parts.get(i).is_none_or(|p| p.marker.shard.index != i))
    {
        let given: Vec<String> = parts
            .iter()
            .map(|p| format!("{} = shard {}", p.dir.display(), p.marker.shard.index))
            .collect();
        return Err(MergeError::Missing {
            missing,
            count,
            given: given.join(", "),
        });
    }
    Ok(parts)
}

/// Join the shards in `dirs` into one report in `out` (an existing, empty
/// directory the caller owns): `report.json`, `report.html`, `report.md`
/// and every file they name.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<Report, MergeError> {
    let parts = read_all(dirs)?;
    let first = &parts[0];
    let variants = serde_json::to_value(&first.report.variants).ok();
    for p in &parts[1..] {
        if serde_json::to_value(&p.report.variants).ok() != variants {
            return Err(MergeError::Inconsistent {
                dir: p.dir.clone(),
                what: format!("its variants differ from {}'s", first.dir.display()),
            });
        }
    }
    let mut report = first.report.clone();
    report.shards = parts.iter().map(|p| p.marker.shard.clone()).collect();
    let mut taken: Vec<String> = Vec::new();
    let joined = first
        .marker
        .scenes
        .iter()
        .map(|name| join_scene(&parts, name, &mut taken))
        .collect::<Result<Vec<_>, _>>()?;
    // Every unit exactly once: a shard that rendered what it did not claim,
    // or two that rendered the same, is caught before anything is written.
    let mut expected = first.marker.units.clone();
    let mut got = taken.clone();
    expected.sort();
    got.sort();
    if expected != got {
        return Err(MergeError::Inconsistent {
            dir: first.dir.clone(),
            what: format!(
                "the shards' rows {got:?} are not the plan's units {expected:?} each once"
            ),
        });
    }
    report.scenes = Vec::new();
    for (mut scene, home, sources) in joined {
        write_scene_files(&mut scene, home, &sources, out)?;
        report.scenes.push(scene);
    }
    for v in &report.variants {
        if let Some(svg) = &v.graph_svg {
            copy(&first.dir, svg, out)?;
        }
    }
    super::run::write_report(out, &report, &graphs(&report, out)).map_err(MergeError::Write)?;
    Ok(report)
}

/// The schedule pictures the HTML embeds, read back from `out`.
fn graphs(report: &Report, out: &Path) -> Vec<(String, String)> {
    report
        .variants
        .iter()
        .filter_map(|v| {
            let svg = std::fs::read_to_string(out.join(v.graph_svg.as_ref()?)).ok()?;
            Some((v.id.clone(), svg))
        })
        .collect()
}

fn copy(dir: &Path, name: &str, out: &Path) -> Result<(), MergeError> {
    std::fs::copy(dir.join(name), out.join(name))
        .map(|_| ())
        .map_err(|source| MergeError::Read {
            dir: dir.to_path_buf(),
            name: name.into(),
            source,
        })
}

/// Scene `name`'s rows from every shard, in the plan's variant order, with
/// the shard holding its reference and each row's shard; `taken` gains
/// each row's unit id. The shards' references must agree byte for byte.
#[allow(clippy::type_complexity)]
fn join_scene<'p>(
    parts: &'p [Part],
    name: &str,
    taken: &mut Vec<String>,
) -> Result<(SceneResult, &'p Part, Vec<&'p Part>), MergeError> {
    let holding: Vec<(&Part, &SceneResult)> = parts
        .iter()
        .filter_map(|p| Some((p, p.report.scenes.iter().find(|s| s.name == name)?)))
        .collect();
    let Some(&(home, template)) = holding.first() else {
        return Err(MergeError::Inconsistent {
            dir: parts[0].dir.clone(),
            what: format!("no shard holds scene {name}"),
        });
    };
    // Every shard measured against the same reference, byte for byte.
    let reference_files =
        std::iter::once(&template.reference_image).chain(&template.reference_linear_image);
    for file in reference_files {
        let bytes = std::fs::read(home.dir.join(file)).map_err(|source| MergeError::Read {
            dir: home.dir.clone(),
            name: file.to_string(),
            source,
        })?;
        for (p, _) in &holding[1..] {
            if std::fs::read(p.dir.join(file)).ok().as_ref() != Some(&bytes) {
                return Err(MergeError::ReferenceDiffers {
                    scene: name.into(),
                    file: file.to_string(),
                    a: p.dir.clone(),
                    b: home.dir.clone(),
                });
            }
        }
    }
    let mut scene = template.clone();
    scene.runs = Vec::new();
    let mut sources = Vec::new();
    for v in &parts[0].report.variants {
        for (p, s) in &holding {
            for run in s.runs.iter().filter(|r| r.variant == v.id) {
                taken.push(format!("{name}/{}", run.variant));
                scene.runs.push(run.clone());
                sources.push(*p);
            }
        }
    }
    Ok((scene, home, sources))
}

/// A joined scene's files into `out`: the reference's (from `home`), each
/// row's from its shard, the difference maps redrawn at the scene's scale
/// (the largest difference over all its rows, as one run takes it).
fn write_scene_files(
    scene: &mut SceneResult,
    home: &Part,
    sources: &[&Part],
    out: &Path,
) -> Result<(), MergeError> {
    for file in std::iter::once(&scene.reference_image).chain(&scene.reference_linear_image) {
        copy(&home.dir, file, out)?;
    }
    let references = scene_refs(scene);
    let max_diff = scene
        .runs
        .iter()
        .map(|r| r.metrics.max_abs_diff)
        .fold(0.0, f64::max);
    let scale = plait_compare::heatmap::nice_scale(max_diff);
    for (run, p) in scene.runs.iter_mut().zip(sources) {
        for file in [&run.image, &run.flip_image]
            .into_iter()
            .chain(&run.linear_image)
        {
            copy(&p.dir, file, out)?;
        }
        if run.diff_scale == scale {
            copy(&p.dir, &run.diff_image, out)?;
        } else {
            redraw_diff(&p.dir, &references, run, scale, out)?;
        }
    }
    Ok(())
}

/// The reference's display and linear image names of a scene.
fn scene_refs(scene: &SceneResult) -> (String, Option<String>) {
    (
        scene.reference_image.clone(),
        scene.reference_linear_image.clone(),
    )
}

/// `run`'s difference map at `scale`, from the images its shard wrote (the
/// comparison recomputed, and checked to give the shard's metrics).
fn redraw_diff(
    dir: &Path,
    (reference, reference_linear): &(String, Option<String>),
    run: &mut plait_compare::report::Run,
    scale: f64,
    out: &Path,
) -> Result<(), MergeError> {
    let image_error = |what: String| {
        let dir = dir.to_path_buf();
        move |source| MergeError::Image { dir, what, source }
    };
    let open =
        |name: &str| image::open(dir.join(name)).map_err(image_error(format!("reading {name}")));
    let reference_png = open(reference)?.to_rgba8();
    let test_png = open(&run.image)?.to_rgba8();
    let linears = match (reference_linear, &run.linear_image) {
        (Some(r), Some(t)) => Some((open(r)?.to_rgba32f(), open(t)?.to_rgba32f())),
        _ => None,
    };
    let c = plait_compare::compare_linear(
        &reference_png,
        &test_png,
        linears.as_ref().map(|(r, t)| (r, t)),
    )
    .map_err(|source| MergeError::Compare {
        dir: dir.to_path_buf(),
        what: format!("comparing {} with {reference}", run.image),
        source,
    })?;
    if c.metrics != run.metrics {
        return Err(MergeError::Inconsistent {
            dir: dir.to_path_buf(),
            what: format!(
                "{} recompared with {reference} gives {:?}, its report says {:?}",
                run.image, c.metrics, run.metrics
            ),
        });
    }
    run.diff_scale = scale;
    plait_compare::heatmap::heatmap(&c.abs_diff, c.width, c.height, scale as f32)
        .save_with_format(out.join(&run.diff_image), image::ImageFormat::Png)
        .map_err(image_error(format!(
            "writing {} to the merged report",
            run.diff_image
        )))
}
