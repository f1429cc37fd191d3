//! Flags several commands share, parsed in one place.

use clap::Args;

/// `--set key=value` in one place for every command.
#[derive(Args, Clone, Debug, Default)]
pub struct SetArgs {
    /// Override a key of the pipeline file (repeatable; the key must exist),
    /// e.g. `--set params.slices=64` or `--set passes.hair.params.shadow_weight=0.3`.
    /// `techniques.POINT=NAME` swaps a technique, e.g.
    /// `--set techniques.self_shadow=occupancy_no_slab`; `plait techniques`
    /// lists the points and their techniques.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

/// `--scene NAME`: a path, or a scene found by name like a pipeline
/// (`plait::session::resolve_scene`: `--scene small.toml` from anywhere).
pub fn parse_scene(text: &str) -> Result<std::path::PathBuf, std::convert::Infallible> {
    Ok(plait::session::resolve_scene(std::path::Path::new(text)))
}

/// `--size 960x720` (`960X720` too: the README's `WxH` with either x).
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{text}` is not WIDTHxHEIGHT (e.g. 960x720)");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(format!("`{text}`: width and height must be 1..=16384"));
    }
    Ok((w, h))
}
