//! `plait view`: the flags; the window is `plait_view`.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use plait::session::resolve_pipeline;

use crate::args::{SetArgs, parse_scene, parse_size};

#[derive(Args)]
pub struct ViewArgs {
    /// Pipeline file (default: pipelines/occupancy.toml). Saving it, the
    /// scene or any shader it uses reloads it.
    pipeline: Option<PathBuf>,
    /// Scene file (default: the built-in scene).
    #[arg(long, value_parser = parse_scene)]
    scene: Option<PathBuf>,
    /// Render size, `WIDTHxHEIGHT` (small: every frame is rendered).
    #[arg(long, value_parser = parse_size, default_value = "400x300")]
    size: (u32, u32),
    /// Start with this texture or buffer in the resource inspector.
    #[arg(long, value_name = "RESOURCE")]
    inspect: Option<String>,
    /// Write the pipeline's output to this PNG and quit (after --after-frames
    /// frames of the current state and --after-reloads reloads).
    #[arg(long, value_name = "FILE.png")]
    screenshot: Option<PathBuf>,
    /// Frames rendered since the last (re)build before the screenshot.
    #[arg(long, default_value_t = 1, requires = "screenshot")]
    after_frames: u32,
    /// Successful reloads (after a saved file or an edited param) to wait for
    /// before counting frames for the screenshot.
    #[arg(long, default_value_t = 0, requires = "screenshot")]
    after_reloads: u32,
    #[command(flatten)]
    set: SetArgs,
}

pub fn run(args: ViewArgs) -> Result<()> {
    // A bad screenshot path fails now, not after the window has rendered.
    if let Some(path) = &args.screenshot {
        if !path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png"))
        {
            anyhow::bail!(
                "--screenshot {}: the screenshot is a PNG; name it `….png`",
                path.display()
            );
        }
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty());
        if let Some(dir) = dir.filter(|d| !d.is_dir()) {
            anyhow::bail!(
                "--screenshot {}: no folder {}",
                path.display(),
                dir.display()
            );
        }
    }
    let screenshot = args.screenshot.map(|path| plait_view::Screenshot {
        path,
        after_frames: args.after_frames,
        after_reloads: args.after_reloads,
    });
    plait_view::run(plait_view::ViewOptions {
        pipeline: resolve_pipeline(args.pipeline.as_deref()),
        scene: args.scene,
        size: args.size,
        sets: args.set.sets,
        inspect: args.inspect,
        screenshot,
    })?;
    Ok(())
}
