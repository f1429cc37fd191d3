//! `renderer = "plait"` in a path-traced reference: plait's own GPU path
//! tracer (`pipelines/physical/path_traced.toml`: Chiang et al. 2016 fibres,
//! Lambertian meshes, next-event estimation to the key light) renders the
//! reference instead of Mitsuba 3, with the file's samples, depth, seeds and
//! fibre, on the scene and size every variant renders. Its two seeds make
//! the mean and the noise estimate as Mitsuba's do (`cache::of_seeds`), and
//! its wall time stands in the reference's row, so one run beside a Mitsuba
//! run says how the two path tracers compare in time. Not cached: its image
//! depends on plait's own shaders, which every run builds afresh.

use std::ops::Range;
use std::path::PathBuf;
use std::time::Instant;

use toml::Spanned;

use super::path_traced::{PathTraced, PathTracedError};
use super::{AbError, ScenePlan};
use crate::session::SessionError;
use plait_passes::path_trace::{MAX_DEPTH, MAX_SPP};

/// The path tracer's pipeline, as a library file (the checkout's, or the
/// built-in copy of an installed `plait`).
const PIPELINE: &str = "pipelines/physical/path_traced.toml";

pub(super) fn pipeline() -> PathBuf {
    plait_assets::find(PIPELINE).unwrap_or_else(|| PathBuf::from(PIPELINE))
}

/// The file's values the GPU path tracer cannot take, at their place in
/// the file: its pass's bounds (`plait_passes::path_trace`), and no
/// unbounded depth (Mitsuba's −1: the GPU's paths end at `MAX_DEPTH`).
pub(super) fn check(
    spp: &Spanned<u32>,
    max_depth: &Spanned<i32>,
    seeds: &Spanned<Vec<u32>>,
    at: &dyn Fn(Option<Range<usize>>, String) -> PathTracedError,
) -> Result<(), PathTracedError> {
    if i64::from(*spp.get_ref()) > MAX_SPP {
        return Err(at(
            Some(spp.span()),
            format!("renderer \"plait\" takes at most {MAX_SPP} spp per seed"),
        ));
    }
    let depth = i64::from(*max_depth.get_ref());
    if !(1..=MAX_DEPTH).contains(&depth) {
        return Err(at(
            Some(max_depth.span()),
            format!(
                "renderer \"plait\" takes a max_depth from 1 to {MAX_DEPTH} (no -1: its paths are bounded)"
            ),
        ));
    }
    if let Some(seed) = seeds.get_ref().iter().find(|&&s| s > i32::MAX as u32) {
        return Err(at(
            Some(seeds.span()),
            format!("renderer \"plait\" takes seeds up to {}: {seed}", i32::MAX),
        ));
    }
    Ok(())
}

/// The `--set`s that make the path tracer render `spec` with `seed`: its
/// samples, depth and seed, and the fibre as the chiang params.
pub(super) fn sets(spec: &PathTraced, seed: u32) -> Vec<String> {
    let f = &spec.fibre;
    vec![
        format!("params.spp={}", spec.spp),
        format!("params.max_depth={}", spec.max_depth),
        format!("params.seed={seed}"),
        format!("params.chiang_beta_m={}", f.longitudinal_roughness),
        format!("params.chiang_beta_n={}", f.azimuthal_roughness),
        format!("params.chiang_tilt={}", f.scale_tilt_degrees),
        format!("params.chiang_eta={}", f.eta),
    ]
}

/// One scene's reference: each seed rendered at `size` (the run's size
/// times `supersample`), its linear radiance read and filtered down, the
/// two combined. A frame whose loops were cut or whose buffers dropped
/// paths is an error (`Prepared::render` checks), never a darker truth.
pub(super) fn reference(
    spec: &PathTraced,
    scene: &ScenePlan,
    (size, supersample): ((u32, u32), u32),
    gpu: &plait_gpu::Gpu,
) -> Result<super::cache::Reference, AbError> {
    let pipeline = pipeline();
    let start = Instant::now();
    let mut images = Vec::new();
    for seed in spec.seeds {
        let what = || {
            format!(
                "the path-traced reference (renderer \"plait\", {}) on scene {}, seed {seed}",
                pipeline.display(),
                scene.name
            )
        };
        let error = |source: SessionError| AbError::Render {
            what: what(),
            source,
        };
        let prepared =
            crate::session::prepare(gpu, &pipeline, &sets(spec, seed), &scene.data, size)
                .map_err(error)?;
        prepared.render().map_err(error)?;
        let texels = prepared
            .read_resource(crate::linear::RADIANCE)
            .map_err(|e| error(e.into()))?;
        let image = crate::linear::to_f32_image(&texels);
        images.push(super::cache::filtered_seed(
            scene,
            &pipeline,
            &image,
            supersample,
        )?);
    }
    let seconds = start.elapsed().as_secs_f64();
    Ok(super::cache::of_seeds(
        spec,
        scene,
        [&images[0], &images[1]],
        seconds,
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bounds the file is checked against are the pass's own: a value
    /// the file lets through is one the pipeline takes.
    #[test]
    fn the_bounds_are_the_path_trace_pass_params() {
        let library = plait_passes::library_for(&[]);
        let spec = library
            .types
            .get("path_trace")
            .expect("the path_trace pass type")
            .spec();
        let range = |name: &str| match spec.params.iter().find(|p| p.name == name) {
            Some(plait_graph::ParamSpec {
                ty: plait_graph::ParamType::Int { min, max },
                ..
            }) => (*min, *max),
            other => panic!("{name}: an int param, not {other:?}"),
        };
        assert_eq!(range("spp"), (1, MAX_SPP));
        assert_eq!(range("max_depth"), (1, MAX_DEPTH));
        assert_eq!(range("seed"), (0, i64::from(i32::MAX)));
    }
}
