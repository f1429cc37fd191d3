//! Visibility probes: what a pipeline's self-shadowing technique says about
//! light reaching points along rays from the light — the curves of Figure 5 of
//! Sintorn & Assarsson 2009, and the numbers `plait ab` compares between
//! variants.
//!
//! The probe is data: the variant file is extended by one data-only compute
//! pass (`shaders/visibility_probe.wgsl`) that imports the provider the
//! variant's shading pass names, binds the same `vis_*` maps and params, and
//! writes one visibility per (ray, depth). Outputs become the probe buffer, so
//! every pass the probe does not need (the camera, the image) is culled.

use std::fmt::Write;

use glam::Vec3;
use plait_compare::report::{Visibility, VisibilityCurve};
use plait_gpu::Gpu;
use plait_graph::Value;

use crate::session::{SceneData, SessionError, check_pipeline, gpu_options};
use crate::source::PipelineSource;

/// Rays on a uv grid of the light map, sampled at evenly spaced light depths.
#[derive(Clone, Debug)]
pub struct ProbeGrid {
    pub uv0: [f32; 2],
    pub uv1: [f32; 2],
    pub rays: (u32, u32),
    pub depths: u32,
    /// Light NDC depth of the first and last sample.
    pub depth_range: (f32, f32),
}

impl ProbeGrid {
    /// A grid over the hair seen from the light, its depths spanning the hair.
    pub fn through_hair(scene: &SceneData, rays: (u32, u32), depths: u32) -> Self {
        let frame = scene.frame((1, 1), 0);
        let m = glam::Mat4::from_cols_array_2d(&frame.light_view_proj);
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for c in scene.strands.bounds().corners() {
            let p = m.project_point3(c);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        let uv = |x: f32, y: f32| {
            [
                (x * 0.5 + 0.5).clamp(0.0, 1.0),
                (0.5 - y * 0.5).clamp(0.0, 1.0),
            ]
        };
        ProbeGrid {
            uv0: uv(lo.x, hi.y),
            uv1: uv(hi.x, lo.y),
            rays,
            depths: depths.max(2),
            depth_range: (lo.z.clamp(0.0, 1.0), hi.z.clamp(0.0, 1.0)),
        }
    }

    pub fn ray_count(&self) -> usize {
        (self.rays.0 * self.rays.1) as usize
    }

    /// Light NDC depth of sample `d`.
    pub fn depth(&self, d: u32) -> f32 {
        let t = d as f32 / (self.depths - 1).max(1) as f32;
        self.depth_range.0 + (self.depth_range.1 - self.depth_range.0) * t
    }

    /// uv of ray `r` on the light map.
    pub fn ray_uv(&self, r: u32) -> [f32; 2] {
        let (x, y) = (r % self.rays.0, r / self.rays.0);
        let f = |a: f32, b: f32, i: u32, n: u32| a + (b - a) * (i as f32 + 0.5) / n as f32;
        [
            f(self.uv0[0], self.uv1[0], x, self.rays.0),
            f(self.uv0[1], self.uv1[1], y, self.rays.1),
        ]
    }
}

/// A pipeline's visibility along every probe ray.
#[derive(Clone, Debug)]
pub struct Probed {
    /// The provider the pipeline's shading pass uses (`occupancy`, `exact`…).
    pub visibility: String,
    /// `values[ray * depths + d]`.
    pub values: Vec<f32>,
}

fn literal(v: &Value) -> String {
    match v {
        Value::Str(s) => format!("{s:?}"),
        Value::Float(f) => format!("{f:?}"),
        Value::List(items) => format!(
            "[{}]",
            items.iter().map(literal).collect::<Vec<_>>().join(", ")
        ),
        other => other.to_string(),
    }
}

/// Probe the self-shadowing of `source`'s pipeline (with its sets) on
/// `scene`; `None` when no pass of it has a visibility provider (a
/// `visibility` param). The probe compiles and builds with `source.library`
/// and reads no library of its own, so `plait ab` probes every variant with
/// the one library its run rendered them with. `source.extra_outputs` are
/// not probed (the probe's one output is its buffer).
pub fn probe_visibility(
    gpu: &Gpu,
    source: &PipelineSource,
    scene: &SceneData,
    size: (u32, u32),
    grid: &ProbeGrid,
) -> Result<Option<Probed>, SessionError> {
    probe_with(gpu, source, scene, size, grid, VISIBILITY_PROBE)
}

/// The built-in probe shader: the provider's `self_shadow(world)`.
const VISIBILITY_PROBE: &str = "shaders/visibility_probe.wgsl";

/// As [`probe_visibility`], with another probe shader: one of the same
/// layout (`probe_out`, `probe_params`) evaluating something else of the
/// provider at each probe point — e.g. its optional strand count
/// (`tests/fixtures/strands_probe.wgsl`). `shader` is found like any shader
/// a pipeline names (next to the pipeline, at its checkout's root, on the
/// library search path of `source.library`).
pub fn probe_with(
    gpu: &Gpu,
    source: &PipelineSource,
    scene: &SceneData,
    size: (u32, u32),
    grid: &ProbeGrid,
    shader: &str,
) -> Result<Option<Probed>, SessionError> {
    let Some((visibility, mut prepared)) = build_probe(gpu, source, scene, size, grid, shader)?
    else {
        return Ok(None);
    };
    // Like with like: every provider and the reference read the texel the
    // point falls in (no Fig. 9 jitter, which is for shading), with the one
    // "in front of" convention of the frame (docs/design.md).
    prepared.set_frame(&scene.frame(size, 0).with_light_jitter(false));
    prepared.render()?;
    let values = read_probe(&prepared)?;
    Ok(Some(Probed { visibility, values }))
}

/// A pipeline's visibility along every probe ray, frame after frame of the
/// scene's animation.
#[derive(Clone, Debug)]
pub struct ProbedSequence {
    pub visibility: String,
    /// `frames[t][ray * depths + d]`.
    pub frames: Vec<Vec<f32>>,
}

/// Probe the self-shadowing of `source`'s pipeline (compiled with
/// `source.library`, as [`probe_visibility`]) at frames `0..frames` of the
/// scene's animation at `fps` (the hair and the light's frustum where they
/// are in each frame); `None` without a visibility provider.
pub fn probe_sequence(
    gpu: &Gpu,
    source: &PipelineSource,
    scene: &SceneData,
    size: (u32, u32),
    grid: &ProbeGrid,
    frames: u32,
    fps: f32,
) -> Result<Option<ProbedSequence>, SessionError> {
    let Some((visibility, mut prepared)) =
        build_probe(gpu, source, scene, size, grid, VISIBILITY_PROBE)?
    else {
        return Ok(None);
    };
    let mut values = Vec::with_capacity(frames as usize);
    for index in 0..frames {
        let frame = prepared.pose_frame(scene, size, index, fps)?;
        prepared.set_frame(&frame.with_light_jitter(false));
        prepared.render()?;
        values.push(read_probe(&prepared)?);
    }
    Ok(Some(ProbedSequence {
        visibility,
        frames: values,
    }))
}

fn read_probe(prepared: &crate::session::Prepared<'_>) -> Result<Vec<f32>, SessionError> {
    let bytes = prepared.read_buffer("probe_out")?;
    Ok(bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect())
}

/// The variant extended by the probe pass, built: its provider's name and
/// the prepared pipeline; `None` without a provider. Compiled and built with
/// `source.library`: the probe reads no library of its own.
fn build_probe<'g>(
    gpu: &'g Gpu,
    source: &PipelineSource,
    scene: &SceneData,
    size: (u32, u32),
    grid: &ProbeGrid,
    shader: &str,
) -> Result<Option<(String, crate::session::Prepared<'g>)>, SessionError> {
    let opts = gpu_options(gpu, size);
    let (library, pipeline, sets) = (&source.library, source.path.as_path(), &source.sets[..]);
    let variant = crate::session::compile_checked_in(library, pipeline, sets, &opts)?;
    // Capacities the session lowered to fit the adapter, kept: the probe
    // pipeline draws no pass that counts into them (its one output is
    // `probe_out`), so it could not lower them itself, yet their resources
    // are still declared and checked against the limits.
    let fitted: Vec<String> = variant
        .overflow
        .iter()
        .filter(|c| c.grows)
        .map(|c| format!("params.{}={}", c.param, c.value))
        .collect();
    let sets = &[sets, fitted.as_slice()].concat();
    let shading = variant
        .passes
        .iter()
        .filter(|p| p.params.contains_key("self_shadow"))
        .max_by_key(|p| p.name == "hair");
    let Some(shading) = shading else {
        return Ok(None);
    };
    let Some(visibility) = shading.params["self_shadow"].as_str().map(str::to_owned) else {
        return Ok(None);
    };
    // The self_shadow point's slots, as its point file declares them.
    let slots: Vec<String> = plait_passes::visibility::slots(library)
        .into_iter()
        .map(|s| s.name)
        .collect();
    let reads: Vec<String> = shading
        .reads
        .iter()
        .filter(|b| slots.contains(&b.slot))
        .map(|b| format!("{} = {:?}", b.slot, b.resource_name))
        .collect();
    // Only the providers' params: the probe samples self-shadowing as the
    // shading pass sees it, not the pass's own (transparency) params, which
    // its shader would not read.
    let provider_params: Vec<String> = plait_passes::hair_fragment::shading_params(library)
        .into_iter()
        .map(|p| p.name)
        .collect();
    let mut params: Vec<String> = shading
        .params
        .iter()
        .filter(|(k, _)| provider_params.iter().any(|n| n == *k))
        .map(|(k, v)| format!("{k} = {}", literal(v)))
        .collect();
    params.extend([
        format!("probe_uv0 = [{:?}, {:?}]", grid.uv0[0], grid.uv0[1]),
        format!("probe_uv1 = [{:?}, {:?}]", grid.uv1[0], grid.uv1[1]),
        format!("probe_rays_x = {:?}", grid.rays.0 as f32),
        format!("probe_rays_y = {:?}", grid.rays.1 as f32),
        format!("probe_depths = {:?}", grid.depths as f32),
        format!("probe_depth0 = {:?}", grid.depth_range.0),
        format!("probe_depth1 = {:?}", grid.depth_range.1),
    ]);
    let file_name = pipeline
        .file_name()
        .and_then(|f| f.to_str())
        .unwrap_or("pipeline.toml");
    // `shader` is found like any shader a pipeline names: next to it, at its
    // checkout's root, or on the library search path (built-in copy last).
    let mut text = String::new();
    let _ = write!(
        text,
        "[pipeline]\nname = \"probe\"\nextends = {file_name:?}\noutputs = [\"probe_out\"]\n\n\
         [resources.probe_out]\nkind = \"buffer\"\nsize = {bytes}\n\n\
         [passes.visibility_probe]\ntype = \"compute\"\nshader = {shader:?}\nreads = {{ {reads} }}\n\
         writes = {{ probe_out = \"probe_out\" }}\nparams = {{ {params} }}\n",
        bytes = grid.ray_count() * grid.depths as usize * 4,
        reads = reads.join(", "),
        params = params.join(", "),
    );
    let probe_path = pipeline.with_file_name(format!(
        "{}.probe.toml",
        file_name.trim_end_matches(".toml")
    ));
    let compile = |extra: &[String]| {
        let loaded = plait_graph::load_str(&probe_path, &text, &[sets, extra].concat())?;
        check_pipeline(library, &loaded, &opts)
    };
    let mut schedule = compile(&[])?;
    // The session chose the carried values, not the user: they stay growable.
    for c in &mut schedule.overflow {
        c.grows |= variant
            .overflow
            .iter()
            .any(|v| v.grows && v.param == c.param);
    }
    // The reference's bounded buffers hold everything, as when it renders.
    let probe = PipelineSource::with_library(&probe_path, &[], library.clone());
    let prepared = crate::overflow::prepare_holding(gpu, schedule, &compile, &probe, scene, size)?;
    Ok(Some((visibility, prepared)))
}

/// Visibility of a variant against the reference along the probe rays: the
/// mean and max |ΔV| over the samples of rays that pass through hair (the
/// reference sees less than full light somewhere along them), and the curves
/// of the four rays through the most hair.
pub fn visibility_error(grid: &ProbeGrid, reference: &Probed, variant: &Probed) -> Visibility {
    let depths = grid.depths as usize;
    let rays = grid.ray_count();
    let ray = |values: &[f32], r: usize| values[r * depths..(r + 1) * depths].to_vec();
    let through_hair: Vec<usize> = (0..rays)
        .filter(|&r| ray(&reference.values, r).iter().any(|&v| v < 0.999))
        .collect();
    let (mut sum, mut max, mut count) = (0.0f64, 0.0f64, 0usize);
    for &r in &through_hair {
        for (a, b) in ray(&reference.values, r)
            .iter()
            .zip(ray(&variant.values, r))
        {
            let e = (*a as f64 - b as f64).abs();
            sum += e;
            max = max.max(e);
            count += 1;
        }
    }
    let mut darkest = through_hair.clone();
    darkest.sort_by(|&a, &b| {
        reference.values[(a + 1) * depths - 1].total_cmp(&reference.values[(b + 1) * depths - 1])
    });
    let curves = darkest
        .iter()
        .take(4)
        .map(|&r| {
            let uv = grid.ray_uv(r as u32);
            VisibilityCurve {
                light_uv: uv,
                depth: (0..grid.depths).map(|d| grid.depth(d) as f64).collect(),
                exact: ray(&reference.values, r)
                    .iter()
                    .map(|&v| v as f64)
                    .collect(),
                approx: ray(&variant.values, r).iter().map(|&v| v as f64).collect(),
            }
        })
        .collect();
    Visibility {
        provider: variant.visibility.clone(),
        reference_provider: reference.visibility.clone(),
        rays_through_hair: through_hair.len(),
        curves,
        mean_abs_error: if count > 0 { sum / count as f64 } else { 0.0 },
        max_abs_error: max,
    }
}
