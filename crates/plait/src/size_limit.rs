//! `--size` too large for the adapter. Resources sized from the screen
//! (`size = "screen"`, `"${screen_width} * …"`) grow with `--size`, and
//! past the adapter's texture or storage-binding limit the pipeline no
//! longer compiles. The errors then name a technique file's resource, which
//! is not what the user changed: when the same pipeline fits at a tiny size,
//! the flag is what to change, so the message names `--size`, the largest
//! size of the same shape that fits, and what overflows
//! ([`SessionError::Size`]). The session's compile for an adapter
//! ([`crate::adapter::compile_on`]) asks this itself, so every front end
//! (render, frames, ab, the viewer) words a too-large size the same way.

use std::path::Path;

use plait_gpu::Gpu;
use plait_graph::{CompileOptions, Errors, Pipeline, Schedule};

use crate::session::SessionError;
use crate::source::PipelineSource;

/// Fails naming `--size` when `size` is what keeps `pipeline` (with `sets`)
/// from fitting `gpu`'s limits; any other problem is left to the render,
/// which reports it with its file and line. For a pipeline loaded already
/// whose compile failed, [`explain_on`].
pub fn check(
    pipeline: &Path,
    sets: &[String],
    size: (u32, u32),
    gpu: &Gpu,
) -> Result<(), SessionError> {
    let Ok(loaded) = plait_graph::load(pipeline, sets) else {
        return Ok(());
    };
    explain_on(&loaded, &PipelineSource::new(pipeline, sets), size, gpu)
}

/// After `loaded` failed to compile for `gpu` at `size`: the `--size` error
/// when the size is at fault, `Ok` (the compile's own errors stand) when not.
pub fn explain_on(
    loaded: &Pipeline,
    source: &PipelineSource,
    size: (u32, u32),
    gpu: &Gpu,
) -> Result<(), SessionError> {
    let on = format!("on {}", gpu.adapter_name());
    explain(loaded, source, size, &on, &|s| {
        crate::session::gpu_options(gpu, s)
    })
}

/// [`check`] without a GPU, against WebGPU's default limits (`plait ab`).
pub fn check_default_limits(
    pipeline: &Path,
    sets: &[String],
    size: (u32, u32),
) -> Result<(), SessionError> {
    let Ok(loaded) = plait_graph::load(pipeline, sets) else {
        return Ok(());
    };
    explain_default_limits(&loaded, &PipelineSource::new(pipeline, sets), size)
}

/// [`explain_on`] against WebGPU's default limits (`plait graph`).
pub fn explain_default_limits(
    loaded: &Pipeline,
    source: &PipelineSource,
    size: (u32, u32),
) -> Result<(), SessionError> {
    explain(
        loaded,
        source,
        size,
        "within WebGPU's default limits",
        &|s| CompileOptions {
            screen: s,
            ..CompileOptions::default()
        },
    )
}

/// `options(size)` gives the limits; `on` names them in the message
/// (`on llvmpipe`, `within WebGPU's default limits`). Only the pipeline
/// files are compiled here (no shaders): limits are theirs. A bounded
/// buffer still at its technique's default is lowered to fit, as the render
/// does ([`crate::overflow::compile_fitting`]): only what the user set, or
/// what cannot fit at all, is the flag's fault.
fn explain(
    loaded: &Pipeline,
    source: &PipelineSource,
    size: (u32, u32),
    on: &str,
    options: &dyn Fn((u32, u32)) -> CompileOptions,
) -> Result<(), SessionError> {
    let registry = source.library.registry();
    let with = |extra: &[String], opts: &CompileOptions| -> Result<Schedule, Errors> {
        if extra.is_empty() {
            plait_graph::compile(loaded, &registry, opts)
        } else {
            plait_graph::compile(&source.load(extra)?, &registry, opts)
        }
    };
    let compile = |s: (u32, u32)| -> Result<(), Errors> {
        crate::overflow::compile_fitting(&with, &[], &options(s)).map(|_| ())
    };
    let pipeline = &source.path;
    let Err(errors) = compile(size) else {
        return Ok(());
    };
    if compile((1, 1)).is_err() {
        // Too large at any size, or wrong in another way: not the flag's fault.
        return Ok(());
    }
    let (w, h) = largest_fitting(size, |s| compile(s).is_ok());
    let overflows: Vec<String> = errors.0.iter().map(|e| format!("  {e}")).collect();
    Err(SessionError::Size(format!(
        "--size {}x{} is too large for {} {on}: the largest size of this shape it fits is {w}x{h}; at {}x{}:\n{}",
        size.0,
        size.1,
        pipeline.display(),
        size.0,
        size.1,
        overflows.join("\n")
    )))
}

/// The largest size with `size`'s aspect ratio (width from 1 to `size.0`,
/// height in proportion, at least 1) that `fits`, by bisection: memory
/// grows with the size, so what fits at one width fits at every smaller one.
/// `fits` must hold at width 1.
fn largest_fitting(size: (u32, u32), fits: impl Fn((u32, u32)) -> bool) -> (u32, u32) {
    let shape = |w: u32| {
        let h = (u64::from(w) * u64::from(size.1) / u64::from(size.0)).max(1);
        (w, h as u32)
    };
    let (mut lo, mut hi) = (1, size.0);
    while lo < hi {
        let mid = lo + (hi - lo).div_ceil(2);
        if fits(shape(mid)) {
            lo = mid;
        } else {
            hi = mid - 1;
        }
    }
    shape(lo)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_finds_the_largest_size_of_the_shape() {
        // A pretend limit of 1,000,000 texels.
        let fits = |(w, h): (u32, u32)| u64::from(w) * u64::from(h) <= 1_000_000;
        assert_eq!(largest_fitting((8192, 8192), fits), (1000, 1000));
        assert_eq!(largest_fitting((4000, 2000), fits), (1414, 707));
        assert_eq!(largest_fitting((3, 2), |_| true), (3, 2));
        assert_eq!(largest_fitting((500, 1), |(w, _)| w <= 7), (7, 1));
    }
}
