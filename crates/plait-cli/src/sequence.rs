//! `plait render --frames N --fps F --out DIR`: an animated sequence.
//!
//! Frame i is at time i / fps (the scene's `[animation]`, `frame.jitter.z`).
//! DIR receives `0000.png` … (one image per frame), `animation.png` (an
//! animated PNG preview, at most 480 pixels wide) and `frames.json` (every
//! frame's GPU time and the per-pass medians). Everything is written into a
//! temporary folder beside DIR and renamed into place at the end, so an
//! error or an interrupt leaves no half-written sequence.
//!
//! The preview is APNG through the `png` crate rather than GIF through
//! `image`: lossless 24-bit colour (GIF's 256-colour palette bands the hair's
//! gradients and dithers its shadows), streamed frame by frame so a long
//! sequence is never held in memory, and the crate is already in the tree
//! through `image`'s PNG support.

use std::io::{BufWriter, IsTerminal};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use plait::frames::{median_report, render_sequence};
use plait::session::{SceneData, prepare_compiled};
use plait::source::PipelineSource;
use plait_gpu::{FrameReport, Gpu};
use plait_hair::scene::Scene;

use crate::output::PendingDir;
use crate::render_cmd::Rendered;

/// The widest preview frame; larger renders are scaled down for it.
const PREVIEW_WIDTH: u32 = 480;

/// What a sequence run needs from the command line.
pub struct SequenceArgs<'a> {
    pub pipeline: &'a Path,
    pub sets: &'a [String],
    pub scene: &'a Scene,
    pub scene_path: Option<&'a Path>,
    pub size: (u32, u32),
    pub frames: u32,
    pub fps: f32,
    pub out: &'a Path,
    pub json: bool,
}

/// `--fps`: a positive number of frames per second, at most 1000.
pub fn parse_fps(text: &str) -> Result<f32, String> {
    let fps: f32 = text
        .trim()
        .parse()
        .map_err(|_| format!("`{text}` is not a number of frames per second (e.g. 30)"))?;
    if !(fps.is_finite() && fps > 0.0 && fps <= 1000.0) {
        return Err(format!("`{text}`: frames per second must be in (0, 1000]"));
    }
    Ok(fps)
}

/// `0000.png` …: at least four digits, more when the sequence needs them.
fn frame_name(index: u32, frames: u32) -> String {
    let digits = frames.saturating_sub(1).to_string().len().max(4);
    format!("{index:0digits$}.png")
}

/// The animated preview, written as frames arrive.
struct Preview {
    writer: png::Writer<BufWriter<std::fs::File>>,
    size: (u32, u32),
}

impl Preview {
    fn create(path: &Path, render: (u32, u32), frames: u32, fps: f32) -> Result<Self> {
        let scale = (PREVIEW_WIDTH as f32 / render.0 as f32).min(1.0);
        let size = (
            ((render.0 as f32 * scale).round() as u32).max(1),
            ((render.1 as f32 * scale).round() as u32).max(1),
        );
        let file =
            std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?;
        let mut encoder = png::Encoder::new(BufWriter::new(file), size.0, size.1);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_animated(frames, 0)?;
        // The delay in milliseconds (APNG's u16 fraction), at least 1 ms.
        let delay_ms = (1000.0 / fps).round().clamp(1.0, u16::MAX as f32) as u16;
        encoder.set_frame_delay(delay_ms, 1000)?;
        Ok(Preview {
            writer: encoder.write_header()?,
            size,
        })
    }

    fn push(&mut self, image: &image::RgbaImage) -> Result<()> {
        let frame = if image.dimensions() == self.size {
            std::borrow::Cow::Borrowed(image)
        } else {
            std::borrow::Cow::Owned(image::imageops::resize(
                image,
                self.size.0,
                self.size.1,
                image::imageops::FilterType::Triangle,
            ))
        };
        self.writer.write_image_data(frame.as_raw())?;
        Ok(())
    }

    fn finish(self) -> Result<()> {
        self.writer.finish()?;
        Ok(())
    }
}

/// A bar on standard error when it is a terminal; nothing otherwise (the
/// table or JSON on standard output stays clean).
fn progress(frames: u32) -> Option<indicatif::ProgressBar> {
    std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(frames as u64);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{bar:40.cyan/blue} frame {pos}/{len} {elapsed_precise} (ETA {eta}) {msg}",
        ) {
            bar.set_style(style);
        }
        bar
    })
}

pub fn run(args: &SequenceArgs<'_>) -> Result<()> {
    if crate::output::image_format(args.out, "--out").is_ok() {
        bail!(
            "--out {}: with --frames, --out is a folder for {} … and animation.png",
            args.out.display(),
            frame_name(0, args.frames)
        );
    }
    let pending = PendingDir::create(args.out, "frames.json", "frame sequence")?;
    // Pipeline and scene files are read before the device opens; the one
    // compile is for the device (its capabilities and limits).
    let source = PipelineSource::new(args.pipeline, args.sets);
    let loaded = source.load(&[])?;
    let data = SceneData::new(args.scene.clone())?;
    let gpu = Gpu::new()?;
    let schedule = plait::adapter::compile_on(&gpu, &loaded, &source, args.size)?;
    let mut prepared = prepare_compiled(&gpu, schedule, &source, &data, args.size)?;
    let dir = pending.dir().to_path_buf();
    let mut preview =
        Preview::create(&dir.join("animation.png"), args.size, args.frames, args.fps)?;
    let bar = progress(args.frames);
    let mut last = None;
    let frames = render_sequence(
        &mut prepared,
        &data,
        args.size,
        args.frames,
        args.fps,
        |index, frame, image| -> Result<()> {
            let name = frame_name(index, args.frames);
            let bytes = crate::output::encode_image(&image, image::ImageFormat::Png)?;
            std::fs::write(dir.join(&name), bytes).with_context(|| format!("writing {name}"))?;
            preview.push(&image)?;
            if let Some(bar) = &bar {
                bar.set_message(
                    frame
                        .report
                        .total_gpu_ms
                        .map(|ms| format!("{ms:.0} ms GPU"))
                        .unwrap_or_default(),
                );
                bar.inc(1);
            }
            last = Some(image);
            Ok(())
        },
    )?;
    preview.finish()?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let reports: Vec<FrameReport> = frames.into_iter().map(|f| f.report).collect();
    let median = median_report(&reports).context("no frames rendered")?;
    let rendered = Rendered {
        schedule: prepared.schedule().clone(),
        // Each counter's worst frame, so a sequence that dropped says so.
        dropped: plait::overflow::dropped_lines(&median),
        report: median,
        image: last.context("no frames rendered")?,
        adapter: gpu.adapter_name().to_owned(),
        backend: gpu.backend_name(),
        notes: prepared.notes().to_vec(),
        linear: None,
    };
    let json = sequence_json(args, &rendered, &reports);
    std::fs::write(
        dir.join("frames.json"),
        serde_json::to_string_pretty(&json)?,
    )
    .context("writing frames.json")?;
    pending.commit()?;
    for note in &rendered.notes {
        eprintln!("note: {note}");
    }
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&json)?)?;
    } else {
        crate::render_cmd::print_table(
            args.pipeline,
            args.scene_path,
            &rendered,
            args.out,
            "median frame",
        )?;
        outln!(
            "GPU times are medians over {} frames at {} fps; {} … {} and animation.png in {}",
            args.frames,
            args.fps,
            frame_name(0, args.frames),
            frame_name(args.frames - 1, args.frames),
            args.out.display()
        )?;
    }
    Ok(())
}

/// `frames.json` (and `--json`): the single-frame report of the medians,
/// plus the sequence and every frame's total.
fn sequence_json(
    args: &SequenceArgs<'_>,
    median: &Rendered,
    reports: &[FrameReport],
) -> serde_json::Value {
    let mut json = crate::render_cmd::report_json(args.pipeline, args.scene_path, median, args.out);
    let per_frame: Vec<serde_json::Value> = reports
        .iter()
        .enumerate()
        .map(|(i, r)| {
            serde_json::json!({
                "index": i,
                "time": i as f32 / args.fps,
                "image": frame_name(i as u32, args.frames),
                "total_gpu_ms": r.total_gpu_ms,
            })
        })
        .collect();
    json["sequence"] = serde_json::json!({
        "frames": args.frames,
        "fps": args.fps,
        "scene": args.scene_path.map(|p| p.display().to_string()),
        "preview": "animation.png",
        "gpu_ms": "medians over the frames",
        "per_frame": per_frame,
    });
    json
}

/// The default `--out` of a sequence.
pub fn default_out() -> PathBuf {
    PathBuf::from("frames")
}
