//! What an A/B run will do, decided before any GPU work: the variants (each
//! pipeline at every point of the sweeps, then the reference), each loaded
//! and checked, and the scenes, each loaded once.

use std::path::{Path, PathBuf};

use indexmap::IndexMap;
use plait_graph::CompileOptions;

use super::AbError;
use crate::session::{SceneData, compile_checked_in, resolve_pipeline};

/// A `--set` key and the values it takes, one variant each:
/// `params.slices=32,64,128` or `techniques.self_shadow=occupancy,exact`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SweepSpec {
    pub key: String,
    pub values: Vec<String>,
}

/// Why a `--sweep` argument is not `KEY=V1,V2,…`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct SweepSyntaxError(pub(super) String);

impl SweepSpec {
    /// `KEY=V1,V2,…`: a key without spaces, then distinct, non-empty values.
    pub fn parse(text: &str) -> Result<Self, SweepSyntaxError> {
        let bad = |message: String| Err(SweepSyntaxError(message));
        let Some((key, values)) = text.split_once('=') else {
            return bad(format!(
                "`{text}` is not KEY=V1,V2,… (e.g. params.slices=32,64,128)"
            ));
        };
        let key = key.trim();
        if key.is_empty() || key.contains(char::is_whitespace) {
            return bad(format!(
                "`{text}`: the key before `=` must be a --set key such as params.slices"
            ));
        }
        let values: Vec<String> = values.split(',').map(|v| v.trim().to_string()).collect();
        if values.iter().any(String::is_empty) {
            return bad(format!("`{text}`: empty value in the comma-separated list"));
        }
        let mut seen = std::collections::HashSet::new();
        if let Some(dup) = values.iter().find(|v| !seen.insert(v.as_str())) {
            return bad(format!("`{text}`: value `{dup}` is listed twice"));
        }
        Ok(SweepSpec {
            key: key.to_string(),
            values,
        })
    }
}

/// `--camera-distance F1,F2,…`: every scene (and the reference) rendered
/// with its camera moved along its view ray to F times its distance from
/// its target ([`plait_hair::Camera::dollied`]), F finite, > 0, at most
/// [`plait_hair::camera::MAX_CAMERA_DISTANCE`], each listed once.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraDistances(pub Vec<f64>);

impl CameraDistances {
    /// `1,2,4,8`: distinct factors, each a valid camera distance. The
    /// message says what is wrong with which value (clap names the flag).
    pub fn parse(text: &str) -> Result<Self, SweepSyntaxError> {
        let bad = |message: String| Err(SweepSyntaxError(message));
        let mut factors = Vec::new();
        for item in text.split(',').map(str::trim) {
            if item.is_empty() {
                return bad(format!(
                    "`{text}`: empty value in the comma-separated list (e.g. 1,2,4,8)"
                ));
            }
            let Ok(f) = item.parse::<f64>() else {
                return bad(format!("`{item}` is not a number (e.g. 1,2,4,8)"));
            };
            if let Err(why) = plait_hair::camera::check_camera_distance(f) {
                return bad(format!("factor {why}"));
            }
            if factors.contains(&f) {
                return bad(format!("`{text}`: factor {item} is listed twice"));
            }
            factors.push(f);
        }
        Ok(CameraDistances(factors))
    }
}

/// Everything an A/B run is asked to do.
#[derive(Clone, Debug)]
pub struct AbOptions {
    /// The variants' pipeline files.
    pub pipelines: Vec<PathBuf>,
    /// The ground truth every image is compared with; rendered with `sets`
    /// but never swept.
    pub reference: PathBuf,
    /// Scene files; none = the built-in scene.
    pub scenes: Vec<PathBuf>,
    /// `--set key=value` for every variant and the reference.
    pub sets: Vec<String>,
    /// None, one (a variant per value) or two (a grid of every combination).
    pub sweeps: Vec<SweepSpec>,
    /// Timed frames per variant after one warm-up frame.
    pub repeats: u32,
    /// Timed frames of the reference, when fewer than `repeats`: the first
    /// that many repeats render it (a reference far slower than the
    /// variants — supersampled depth peeling — whose own time is only a
    /// ratio of its own; its image is one frame whatever this says).
    pub reference_repeats: Option<u32>,
    pub size: (u32, u32),
    /// The reference is rendered this many times larger in each dimension
    /// and box-filtered down to `size` (1 = not supersampled).
    pub supersample: u32,
    /// The command that asked for the run (`argv`), for the provenance.
    pub command: Vec<String>,
    /// An animated sequence per variant and scene for the temporal metric
    /// (`--frames N --fps F`), or none.
    pub sequence: Option<Sequence>,
    /// `--camera-distance`: each scene at each of these camera distances
    /// (factors of the scene's own), or empty: each scene as it is.
    pub camera_distances: Vec<f64>,
    /// `--hair-color`: each scene once per colour, every strand recoloured
    /// (before the camera distances), or empty: each scene's own colours.
    pub hair_colors: Vec<super::HairColor>,
}

/// Frames 0..frames of each scene's animation at fps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sequence {
    pub frames: u32,
    pub fps: f32,
}

impl AbOptions {
    /// The size a variant renders at: `size`, times `supersample` for the reference.
    pub fn render_size(&self, is_reference: bool) -> (u32, u32) {
        let k = if is_reference {
            self.supersample.max(1)
        } else {
            1
        };
        (self.size.0 * k, self.size.1 * k)
    }

    /// `pipelines` against `reference` on the built-in scene at 960×720,
    /// five repeats, no `--set`, no sweep.
    pub fn new(pipelines: Vec<PathBuf>, reference: PathBuf) -> Self {
        AbOptions {
            pipelines,
            reference,
            scenes: Vec::new(),
            sets: Vec::new(),
            sweeps: Vec::new(),
            repeats: 5,
            reference_repeats: None,
            size: (960, 720),
            supersample: 1,
            command: Vec::new(),
            sequence: None,
            camera_distances: Vec::new(),
            hair_colors: Vec::new(),
        }
    }
}

/// One pipeline at one point of the sweeps, or the reference.
#[derive(Clone, Debug)]
pub struct VariantPlan {
    /// Unique, usable in file names (`occupancy@64`).
    pub id: String,
    /// For people (`occupancy [params.slices=64]`).
    pub label: String,
    pub pipeline: PathBuf,
    /// The run's `--set`s, then this variant's sweep values.
    pub sets: Vec<String>,
    /// Its value of each sweep, in the order of the sweeps.
    pub sweep_values: IndexMap<String, String>,
    pub is_reference: bool,
}

/// A scene, loaded once for every variant (once per camera distance).
pub struct ScenePlan {
    /// Unique, usable in file names (the file's stem, `default` for the
    /// built-in one; `small@d2` at camera distance 2).
    pub name: String,
    /// `None` for the built-in scene.
    pub path: Option<PathBuf>,
    /// With `--camera-distance`: the scene's name without the distance,
    /// and the factor its camera was moved back by.
    pub distance: Option<(String, f64)>,
    /// With `--hair-color`: the colour every strand was given.
    pub hair_color: Option<super::HairColor>,
    pub data: SceneData,
}

/// A checked A/B run, ready for [`run`](super::run()).
pub struct Plan {
    pub options: AbOptions,
    /// The reference pipeline as resolved (a path that exists).
    pub reference: PathBuf,
    /// The variants, the reference last.
    pub variants: Vec<VariantPlan>,
    pub scenes: Vec<ScenePlan>,
    /// A path-traced reference instead of a pipeline (its file has a
    /// `[path_traced]` table); its images, one per scene, are filled in by
    /// [`render_references`](super::render_references) before the run.
    pub path_traced: Option<super::PathTraced>,
    pub path_traced_images: Vec<super::references::Rendered>,
    /// The run's one library, read with every variant's own `techniques/`:
    /// two pipelines whose folders declare one module are an error naming
    /// both files, and every variant compiles and builds with it.
    pub library: std::sync::Arc<plait_gpu::PassLibrary>,
}

impl Plan {
    /// Resolve the pipelines, lay out the variants, load and check every one
    /// (shaders included, with naga) and load the scenes — every error a
    /// user can cause, before any GPU work.
    pub fn new(options: AbOptions) -> Result<Self, AbError> {
        if options.pipelines.is_empty() {
            return Err(AbError::NoPipelines);
        }
        if options.repeats == 0 {
            return Err(AbError::NoRepeats);
        }
        if let Some(n) = options.reference_repeats
            && !(1..=options.repeats).contains(&n)
        {
            return Err(AbError::ReferenceRepeats {
                reference: n,
                repeats: options.repeats,
            });
        }
        if options.sweeps.len() > 2 {
            return Err(AbError::TooManySweeps(options.sweeps.len()));
        }
        if let [a, b] = options.sweeps.as_slice()
            && a.key == b.key
        {
            return Err(AbError::SweptTwice(a.key.clone()));
        }
        let mut taken = Vec::new();
        let mut variants = Vec::new();
        let points = grid_points(&options.sweeps);
        for given in &options.pipelines {
            let pipeline = resolve_pipeline(Some(given));
            // A built-in copy (`<built-in>/pipelines/…`) exists for plait only.
            if !plait_assets::exists(&pipeline) {
                return Err(AbError::MissingPipeline(given.clone()));
            }
            let base = stem(&pipeline);
            for point in &points {
                let mut sets = options.sets.clone();
                sets.extend(point.iter().map(|(k, v)| format!("{k}={v}")));
                let (id, label) = if point.is_empty() {
                    (base.clone(), base.clone())
                } else {
                    let values: Vec<&str> = point.iter().map(|(_, v)| *v).collect();
                    let settings: Vec<String> =
                        point.iter().map(|(k, v)| format!("{k}={v}")).collect();
                    (
                        format!("{base}@{}", values.join("@")),
                        format!("{base} [{}]", settings.join(", ")),
                    )
                };
                variants.push(VariantPlan {
                    id: unique(sanitize(&id), &mut taken),
                    label,
                    pipeline: pipeline.clone(),
                    sets,
                    sweep_values: point
                        .iter()
                        .map(|(k, v)| (k.to_string(), v.to_string()))
                        .collect(),
                    is_reference: false,
                });
            }
        }
        let reference = resolve_pipeline(Some(&options.reference));
        if !plait_assets::exists(&reference) {
            return Err(AbError::MissingReference(options.reference.clone()));
        }
        // The run's one library, read with every variant's own `techniques/`
        // (a path-traced reference is no pipeline): the path tracer's
        // standard fibre is its shading point's.
        let pipelines: Vec<&std::path::Path> = variants
            .iter()
            .map(|v| v.pipeline.as_path())
            .chain((!super::path_traced::is_path_traced(&reference)).then_some(reference.as_path()))
            .collect();
        let library = plait_passes::library_for(&pipelines);
        let path_traced = super::path_traced::load_if_path_traced(&reference, &options, &library)?;
        variants.push(VariantPlan {
            id: unique("reference".into(), &mut taken),
            label: if options.supersample > 1 {
                format!(
                    "{} (reference, {}× supersampled)",
                    stem(&reference),
                    options.supersample
                )
            } else {
                format!("{} (reference)", stem(&reference))
            },
            pipeline: reference.clone(),
            sets: options.sets.clone(),
            sweep_values: IndexMap::new(),
            is_reference: true,
        });

        let compile = CompileOptions {
            screen: options.size,
            ..CompileOptions::default()
        };
        for v in variants
            .iter()
            .filter(|v| !(v.is_reference && path_traced.is_some()))
        {
            let compile = CompileOptions {
                screen: options.render_size(v.is_reference),
                ..compile.clone()
            };
            compile_checked_in(&library, &v.pipeline, &v.sets, &compile).map_err(|source| {
                AbError::Pipeline {
                    path: v.pipeline.clone(),
                    what: what_of(v),
                    source,
                }
            })?;
        }

        let scenes = super::scenes::load(&options)?;
        match &path_traced {
            // plait's own path tracer: its pipeline, with the file's values,
            // checked like every variant before any GPU work.
            Some(spec) if spec.renderer == "plait" => {
                let pipeline = super::plait_reference::pipeline();
                let sets = super::plait_reference::sets(spec, spec.seeds[0]);
                let compile = CompileOptions {
                    screen: options.render_size(true),
                    ..compile
                };
                compile_checked_in(&library, &pipeline, &sets, &compile).map_err(|source| {
                    AbError::Pipeline {
                        path: pipeline.clone(),
                        what: format!(
                            " (the path-traced reference {}: renderer = \"plait\")",
                            spec.file.display()
                        ),
                        source,
                    }
                })?;
            }
            Some(spec) => super::path_traced::check_scenes(spec, &options, &scenes)?,
            None => {}
        }
        Ok(Plan {
            options,
            reference,
            variants,
            scenes,
            path_traced,
            path_traced_images: Vec::new(),
            library,
        })
    }

    /// The variants rendered on the GPU: all of them, but a path-traced reference.
    pub fn gpu_variants(&self) -> impl Iterator<Item = &VariantPlan> {
        let path_traced = self.path_traced.is_some();
        self.variants
            .iter()
            .filter(move |v| !(v.is_reference && path_traced))
    }

    /// Where the reference is in [`Plan::variants`].
    pub fn reference_index(&self) -> usize {
        self.variants
            .iter()
            .position(|v| v.is_reference)
            .unwrap_or(self.variants.len() - 1)
    }

    /// How many progress steps [`run`](super::run()) reports: per scene and
    /// variant, build, warm-up, each repeat, compare and probe.
    pub fn step_count(&self) -> u64 {
        let per_variant = 4 + self.options.repeats as u64 + self.options.sequence.map_or(0, |_| 1);
        // A path-traced reference is only compared and probed on the run.
        let (on_gpu, path_traced) = match self.path_traced {
            Some(_) => (self.variants.len() as u64 - 1, 2),
            None => (self.variants.len() as u64, 0),
        };
        // The repeats a reference on the GPU skips.
        let skipped = match self.path_traced {
            Some(_) => 0,
            None => (self.options.repeats - self.repeats_of(self.reference_index())) as u64,
        };
        self.scenes.len() as u64 * (on_gpu * per_variant + path_traced - skipped)
    }

    /// The timed repeats of variant `index`: `repeats`, or
    /// `reference_repeats` for the reference.
    pub fn repeats_of(&self, index: usize) -> u32 {
        match self.options.reference_repeats {
            Some(n) if self.variants[index].is_reference => n,
            _ => self.options.repeats,
        }
    }
}

/// How an error names a variant beyond its file: ` (--sweep k=v)`, ` (--reference)`.
fn what_of(v: &VariantPlan) -> String {
    if v.is_reference {
        return " (--reference)".into();
    }
    if v.sweep_values.is_empty() {
        return String::new();
    }
    let sweeps: Vec<String> = v
        .sweep_values
        .iter()
        .map(|(k, x)| format!("--sweep {k}={x}"))
        .collect();
    format!(" ({})", sweeps.join(" "))
}

/// Every point of the sweeps, the first sweep outermost (so a grid reads
/// row by row); one empty point without sweeps.
fn grid_points(sweeps: &[SweepSpec]) -> Vec<Vec<(&str, &str)>> {
    let mut points: Vec<Vec<(&str, &str)>> = vec![Vec::new()];
    for sweep in sweeps {
        points = points
            .into_iter()
            .flat_map(|point| {
                sweep.values.iter().map(move |value| {
                    let mut next = point.clone();
                    next.push((sweep.key.as_str(), value.as_str()));
                    next
                })
            })
            .collect();
    }
    points
}

/// Keep names usable as file names.
pub(super) fn sanitize(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_' | '@' | '=') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

pub(super) fn unique(id: String, taken: &mut Vec<String>) -> String {
    let mut candidate = id.clone();
    let mut n = 2;
    while taken.contains(&candidate) {
        candidate = format!("{id}-{n}");
        n += 1;
    }
    taken.push(candidate.clone());
    candidate
}

pub(super) fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "pipeline".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_syntax() {
        let s = SweepSpec::parse("params.slices=32, 64,128").unwrap();
        assert_eq!(s.key, "params.slices");
        assert_eq!(s.values, ["32", "64", "128"]);
        assert!(SweepSpec::parse("params.slices").is_err());
        assert!(SweepSpec::parse("=1,2").is_err());
        assert!(SweepSpec::parse("k=1,,2").is_err());
        assert!(SweepSpec::parse("k=1,1").is_err());
        assert_eq!(
            CameraDistances::parse("1, 2,4.5").unwrap(),
            CameraDistances(vec![1.0, 2.0, 4.5])
        );
        for bad in [
            "", "1,,2", "1,x", "0", "-1", "nan", "inf", "1e9", "1,2,1", "2,2.0",
        ] {
            assert!(CameraDistances::parse(bad).is_err(), "{bad}");
        }
        let t = SweepSpec::parse("techniques.self_shadow=occupancy,exact").unwrap();
        assert_eq!(t.values, ["occupancy", "exact"]);
    }

    #[test]
    fn names_are_file_names_and_unique() {
        assert_eq!(sanitize("forward@a b/c"), "forward@a_b_c");
        let mut taken = vec![];
        assert_eq!(unique("a".into(), &mut taken), "a");
        assert_eq!(unique("a".into(), &mut taken), "a-2");
    }

    #[test]
    fn two_sweeps_give_every_combination_row_by_row() {
        let sweeps = [
            SweepSpec::parse("params.a=1,2").unwrap(),
            SweepSpec::parse("techniques.t=x,y,z").unwrap(),
        ];
        let points = grid_points(&sweeps);
        assert_eq!(points.len(), 6);
        assert_eq!(points[0], [("params.a", "1"), ("techniques.t", "x")]);
        assert_eq!(points[2], [("params.a", "1"), ("techniques.t", "z")]);
        assert_eq!(points[3], [("params.a", "2"), ("techniques.t", "x")]);
        assert_eq!(grid_points(&sweeps[..1]).len(), 2);
        assert_eq!(grid_points(&[]), [Vec::<(&str, &str)>::new()]);
    }

    fn options() -> AbOptions {
        let root = crate::session::repo_root();
        let mut o = AbOptions::new(
            vec![root.join("pipelines/forward.toml")],
            root.join("pipelines/forward.toml"),
        );
        o.scenes = vec![root.join("examples/scenes/small.toml")];
        o.size = (64, 48);
        o
    }

    /// Variants of a grid, named and set up before any GPU work.
    #[test]
    fn a_grid_plans_a_variant_per_combination_then_the_reference() {
        let mut o = options();
        o.sets = vec!["params.light_size=256".into()];
        o.sweeps = vec![
            SweepSpec::parse("params.hair_density=10,40").unwrap(),
            SweepSpec::parse("params.light_size=128,256,512").unwrap(),
        ];
        let plan = Plan::new(o).expect("plan");
        assert_eq!(plan.variants.len(), 2 * 3 + 1);
        let v = &plan.variants[4];
        assert_eq!(v.id, "forward@40@256");
        assert_eq!(
            v.label,
            "forward [params.hair_density=40, params.light_size=256]"
        );
        assert_eq!(
            v.sets,
            [
                "params.light_size=256",
                "params.hair_density=40",
                "params.light_size=256"
            ]
        );
        assert_eq!(v.sweep_values["params.hair_density"], "40");
        let reference = &plan.variants[plan.reference_index()];
        assert!(reference.is_reference && reference.sweep_values.is_empty());
        assert_eq!(reference.sets, ["params.light_size=256"]);
        assert_eq!(plan.scenes[0].name, "small");
        assert_eq!(plan.step_count(), 7 * (4 + 5));
    }

    /// Each scene once per camera distance, named by it, its camera that
    /// many times as far from the target; the variants untouched.
    #[test]
    fn camera_distances_plan_each_scene_at_each_distance() {
        let mut o = options();
        o.camera_distances = vec![1.0, 2.5, 8.0];
        let plan = Plan::new(o).expect("plan");
        assert_eq!(plan.variants.len(), 2);
        let names: Vec<&str> = plan.scenes.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["small@d1", "small@d2.5", "small@d8"]);
        let gap = |s: &ScenePlan| {
            let c = &s.data.scene.camera;
            (glam::Vec3::from(c.eye) - glam::Vec3::from(c.target)).length()
        };
        let base = gap(&plan.scenes[0]);
        for (scene, d) in plan.scenes.iter().zip([1.0f32, 2.5, 8.0]) {
            assert_eq!(scene.distance, Some(("small".into(), d as f64)));
            assert!((gap(scene) - d * base).abs() < 1e-4 * d, "{}", scene.name);
        }
        assert_eq!(plan.step_count(), 3 * 2 * (4 + 5));
    }

    /// Each scene once per hair colour (every strand recoloured, opacity
    /// kept), each of those once per camera distance, named by both.
    #[test]
    fn hair_colours_plan_each_scene_in_each_colour() {
        let mut o = options();
        let blond = super::super::HairColor::parse("blond=0.85,0.65,0.40").unwrap();
        let black = super::super::HairColor::parse("black=0.02,0.02,0.02").unwrap();
        o.hair_colors = vec![blond.clone(), black.clone()];
        o.camera_distances = vec![1.0, 2.0];
        let plan = Plan::new(o).expect("plan");
        let names: Vec<&str> = plan.scenes.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "small@blond@d1",
                "small@blond@d2",
                "small@black@d1",
                "small@black@d2"
            ]
        );
        let own = SceneData::load(Some(&plan.scenes[0].path.clone().unwrap())).unwrap();
        for (scene, color) in plan.scenes.iter().zip([&blond, &blond, &black, &black]) {
            assert_eq!(scene.hair_color.as_ref(), Some(color));
            let strands = &scene.data.strands;
            assert!(!strands.color.is_empty());
            assert!(strands.color.iter().all(|c| c.to_array() == color.rgb));
            assert_eq!(strands.alpha, own.strands.alpha, "opacity kept");
        }
        assert_ne!(own.strands.color[0].to_array(), blond.rgb);
    }

    #[test]
    fn bad_plans_fail_naming_what_is_wrong() {
        let mut o = options();
        o.sweeps = vec![
            SweepSpec::parse("params.a=1").unwrap(),
            SweepSpec::parse("params.b=1").unwrap(),
            SweepSpec::parse("params.c=1").unwrap(),
        ];
        assert!(matches!(Plan::new(o), Err(AbError::TooManySweeps(3))));
        let mut o = options();
        o.sweeps = vec![
            SweepSpec::parse("params.light_size=128").unwrap(),
            SweepSpec::parse("params.light_size=256").unwrap(),
        ];
        assert!(matches!(Plan::new(o), Err(AbError::SweptTwice(k)) if k == "params.light_size"));
        // A value the pipeline refuses names the sweep point.
        let mut o = options();
        o.sweeps = vec![
            SweepSpec::parse("params.light_size=128").unwrap(),
            SweepSpec::parse("params.no_such_param=1,2").unwrap(),
        ];
        let e = Plan::new(o).err().expect("unknown param");
        let text = format!("{e}: {}", std::error::Error::source(&e).expect("source"));
        assert!(
            text.contains("(--sweep params.light_size=128 --sweep params.no_such_param=1)")
                && text.contains("no_such_param"),
            "{text}"
        );
        let mut o = options();
        o.reference = "pipelines/missing.toml".into();
        assert_eq!(
            Plan::new(o).err().expect("missing").to_string(),
            "--reference pipelines/missing.toml: no such file"
        );
        let mut o = options();
        o.scenes = vec!["nope.toml".into()];
        assert!(
            Plan::new(o)
                .err()
                .expect("missing scene")
                .to_string()
                .starts_with("--scene nope.toml")
        );
    }
}
