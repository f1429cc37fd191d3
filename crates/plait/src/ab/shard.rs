//! A share of an A/B run (`plait ab --shard I/N`), for runs that outgrow one
//! machine; [`merge`](super::merge()) joins the shards into one report.
//!
//! The work units are the report's rows: every (scene, variant) pair of the
//! [`Plan`], the reference included, in the plan's order (scenes in the
//! order given, each with its variants, the reference last). Unit `u` of
//! that list belongs to shard `u mod N`: the plan is the same on every
//! machine given the same command and files, so is the split.
//!
//! A unit is measured against its scene's reference, rendered in the same
//! process: the reference is rendered again by every shard holding a unit
//! of that scene (its row belongs to one shard only). Rendering it once and
//! shipping it would need the comparison, the visibility probes and the
//! temporal metric to run at merge time from files; duplicating it costs
//! one extra render per scene and shard, and lets the merge check that
//! every shard saw the same truth (byte-identical reference images).
//!
//! A shard writes its partial `report.json`, the files its rows name, and
//! last `shard.json`: the plan's fingerprint, its index, the machine, the
//! units. A directory without `shard.json` is a half-written shard.

use std::path::Path;

use plait_compare::report::{Provenance, Report, ShardInfo};
use plait_gpu::Gpu;
use serde::{Deserialize, Serialize};
use sha2::Digest as _;

use super::{AbError, Plan, Step};

/// `shard.json`'s schema.
pub const SHARD_SCHEMA: &str = "plait-ab-shard/1";
/// The file that marks a finished shard.
pub const SHARD_FILE: &str = "shard.json";

/// Shard `index` of `count` (0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

/// Why a shard index (from `--shard` or the environment) is unusable.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct ShardSyntaxError(pub String);

impl Shard {
    /// `I/N`: 0 ≤ I < N.
    pub fn parse(text: &str) -> Result<Self, ShardSyntaxError> {
        let bad = |m: String| Err(ShardSyntaxError(m));
        let Some((i, n)) = text.split_once('/') else {
            return bad(format!(
                "`{text}` is not I/N (e.g. 0/3: the first of three)"
            ));
        };
        let (Ok(index), Ok(count)) = (i.trim().parse::<usize>(), n.trim().parse::<usize>()) else {
            return bad(format!(
                "`{text}`: I and N must be whole numbers (e.g. 0/3)"
            ));
        };
        Shard::new(index, count).map_err(|e| ShardSyntaxError(format!("`{text}`: {e}")))
    }

    pub fn new(index: usize, count: usize) -> Result<Self, ShardSyntaxError> {
        if count == 0 {
            return Err(ShardSyntaxError("there must be at least one shard".into()));
        }
        if index >= count {
            return Err(ShardSyntaxError(format!(
                "shard index {index} is out of range 0..{count} (shards count from 0)"
            )));
        }
        Ok(Shard { index, count })
    }

    /// From a batch system's environment, when it sets one (`get` reads a
    /// variable): a Slurm job array (`SLURM_ARRAY_TASK_ID`, its
    /// `SLURM_ARRAY_TASK_MIN`, `_STEP` and `_COUNT`: `--array=1-8` and
    /// `--array=0-14:2` work, an id list with gaps does not) or a Kubernetes
    /// Indexed Job (`JOB_COMPLETION_INDEX`, the count from `count` or
    /// `PLAIT_SHARD_COUNT`, since Kubernetes does not pass it to the pod).
    pub fn from_env(
        get: &dyn Fn(&str) -> Option<String>,
        count: Option<usize>,
    ) -> Result<Option<Self>, ShardSyntaxError> {
        let number = |name: &str| -> Result<Option<usize>, ShardSyntaxError> {
            get(name)
                .map(|v| {
                    v.trim()
                        .parse::<usize>()
                        .map_err(|_| ShardSyntaxError(format!("{name}={v} is not a whole number")))
                })
                .transpose()
        };
        if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
            let min = number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let step = number("SLURM_ARRAY_TASK_STEP")?.unwrap_or(1).max(1);
            let n = count.or(number("SLURM_ARRAY_TASK_COUNT")?).ok_or_else(|| {
                ShardSyntaxError("SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not; give --shard I/N".into())
            })?;
            let offset = id.checked_sub(min).filter(|o| o % step == 0);
            let Some(offset) = offset else {
                return Err(ShardSyntaxError(format!(
                    "SLURM_ARRAY_TASK_ID={id} is not SLURM_ARRAY_TASK_MIN={min} plus a multiple of the step {step}; use a contiguous array such as --array=0-{}",
                    n.saturating_sub(1)
                )));
            };
            return Shard::new(offset / step, n)
                .map(Some)
                .map_err(|e| ShardSyntaxError(format!("from SLURM_ARRAY_TASK_ID={id}: {e}")));
        }
        if let Some(index) = number("JOB_COMPLETION_INDEX")? {
            let n = match count {
                Some(n) => n,
                None => number("PLAIT_SHARD_COUNT")?.ok_or_else(|| {
                    ShardSyntaxError("JOB_COMPLETION_INDEX is set: give the number of shards with --shard-count N or PLAIT_SHARD_COUNT".into())
                })?,
            };
            return Shard::new(index, n)
                .map(Some)
                .map_err(|e| ShardSyntaxError(format!("from JOB_COMPLETION_INDEX={index}: {e}")));
        }
        Ok(None)
    }

    /// Whether unit `position` (in [`units`] order) is this shard's.
    fn owns(&self, position: usize) -> bool {
        position % self.count == self.index
    }

    /// The variants this shard renders on scene `scene` (indices into
    /// [`Plan::variants`], in order): its units there, and the reference
    /// when it has any (the truth they are measured against).
    pub(super) fn variants_of(&self, plan: &Plan, scene: usize) -> Vec<usize> {
        let n = plan.variants.len();
        let mut chosen: Vec<usize> = (0..n).filter(|&v| self.owns(scene * n + v)).collect();
        let reference = plan.reference_index();
        if !chosen.is_empty() && !chosen.contains(&reference) {
            chosen.push(reference);
            chosen.sort_unstable();
        }
        chosen
    }

    /// Whether the row of variant `variant` on scene `scene` is this shard's.
    pub(super) fn owns_unit(&self, plan: &Plan, scene: usize, variant: usize) -> bool {
        self.owns(scene * plan.variants.len() + variant)
    }

    /// [`Plan::step_count`] for this shard's share.
    pub fn step_count(&self, plan: &Plan) -> u64 {
        let per_variant =
            plan.step_count() / (plan.scenes.len() * plan.variants.len()).max(1) as u64;
        let variants: usize = (0..plan.scenes.len())
            .map(|s| self.variants_of(plan, s).len())
            .sum();
        variants as u64 * per_variant
    }
}

/// Every unit of `plan` in order: `scene/variant`.
pub fn units(plan: &Plan) -> Vec<String> {
    plan.scenes
        .iter()
        .flat_map(|s| {
            plan.variants
                .iter()
                .map(move |v| format!("{}/{}", s.name, v.id))
        })
        .collect()
}

/// `shard.json`: what a finished shard did, and of which plan.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ShardMarker {
    pub schema: String,
    /// SHA-256 of everything the plan is made of ([`fingerprint`]).
    pub fingerprint: String,
    pub shard: ShardInfo,
    /// The plan's scenes in order (the merged report's order).
    pub scenes: Vec<String>,
    /// Every unit of the plan, in order ([`units`]).
    pub units: Vec<String>,
    /// The units this shard rendered.
    pub mine: Vec<String>,
}

/// What the plan is made of, hashed: two shards merge only when their
/// fingerprints agree. The options (minus the command line, which differs
/// by `--shard`), the variants, the scenes, and the hash of every file the
/// pipelines, shaders and scenes are read from.
#[derive(Serialize)]
struct Fingerprinted<'a> {
    plait_version: &'a str,
    size: [u32; 2],
    repeats: u32,
    reference_repeats: Option<u32>,
    supersample: u32,
    sequence: Option<(u32, String)>,
    camera_distances: &'a [f64],
    hair_colors: Vec<(&'a str, [f32; 3])>,
    sweeps: Vec<(&'a str, &'a [String])>,
    sets: &'a [String],
    reference: &'a str,
    variants: Vec<(&'a str, String, &'a [String])>,
    scenes: Vec<&'a str>,
    pipelines: &'a [plait_compare::report::PipelineProvenance],
    builtin_shaders: &'a [plait_compare::report::FileHash],
    scene_files: &'a [plait_compare::report::FileHash],
}

pub fn fingerprint(plan: &Plan, p: &Provenance) -> String {
    let o = &plan.options;
    let f = Fingerprinted {
        plait_version: &p.plait_version,
        size: p.size,
        repeats: p.repeats,
        reference_repeats: o.reference_repeats,
        supersample: o.supersample,
        sequence: o.sequence.map(|s| (s.frames, s.fps.to_string())),
        camera_distances: &o.camera_distances,
        hair_colors: o
            .hair_colors
            .iter()
            .map(|c| (c.name.as_str(), c.rgb))
            .collect(),
        sweeps: o
            .sweeps
            .iter()
            .map(|s| (s.key.as_str(), s.values.as_slice()))
            .collect(),
        sets: &p.sets,
        reference: &p.reference,
        variants: plan
            .variants
            .iter()
            .map(|v| {
                (
                    v.id.as_str(),
                    v.pipeline.display().to_string(),
                    v.sets.as_slice(),
                )
            })
            .collect(),
        scenes: plan.scenes.iter().map(|s| s.name.as_str()).collect(),
        pipelines: &p.pipelines,
        builtin_shaders: &p.builtin_shaders,
        scene_files: &p.scenes,
    };
    let json = serde_json::to_vec(&f).unwrap_or_default();
    sha2::Sha256::digest(&json)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The machine's host name, for the list of where times were measured.
pub fn machine_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .or_else(|| std::env::var("COMPUTERNAME").ok())
        .unwrap_or_else(|| "unknown".into())
}

/// Run `shard`'s share of `plan` into `dir`: its partial `report.json`, the
/// files its rows name, then `shard.json` (written last: the marker of a
/// finished shard).
pub fn run_shard(
    plan: &Plan,
    shard: Shard,
    gpu: &Gpu,
    dir: &Path,
    progress: &mut dyn FnMut(Step<'_>) -> std::io::Result<()>,
) -> Result<(Report, ShardMarker), AbError> {
    let (mut report, _graphs) = super::run::render(plan, gpu, dir, Some(shard), progress)?;
    let info = ShardInfo {
        index: shard.index,
        count: shard.count,
        machine: machine_name(),
        adapter: report.provenance.adapter.clone(),
        unix_time: report.provenance.unix_time,
    };
    report.shards = vec![info.clone()];
    let all = units(plan);
    let marker = ShardMarker {
        schema: SHARD_SCHEMA.into(),
        fingerprint: fingerprint(plan, &report.provenance),
        shard: info,
        scenes: plan.scenes.iter().map(|s| s.name.clone()).collect(),
        mine: all
            .iter()
            .enumerate()
            .filter(|(u, _)| shard.owns(*u))
            .map(|(_, id)| id.clone())
            .collect(),
        units: all,
    };
    write_json(dir, "report.json", &report)?;
    write_json(dir, SHARD_FILE, &marker)?;
    Ok((report, marker))
}

/// `value` as pretty JSON in `dir/name`.
pub(super) fn write_json<T: Serialize>(dir: &Path, name: &str, value: &T) -> Result<(), AbError> {
    let text = serde_json::to_string_pretty(value).map_err(AbError::Json)?;
    std::fs::write(dir.join(name), text).map_err(|source| AbError::Write {
        name: name.into(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shard_syntax() {
        assert_eq!(Shard::parse("2/3"), Ok(Shard { index: 2, count: 3 }));
        for bad in ["3/3", "0/0", "1", "a/3", "-1/3", "1/3/4", ""] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        assert!(
            Shard::parse("3/3")
                .unwrap_err()
                .0
                .contains("out of range 0..3")
        );
    }

    fn env(vars: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let vars: Vec<(String, String)> = vars
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        move |name| vars.iter().find(|(k, _)| k == name).map(|(_, v)| v.clone())
    }

    /// Slurm ids may start anywhere and step; Kubernetes needs a count.
    #[test]
    fn shard_from_the_environment() {
        let slurm = env(&[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ]);
        assert_eq!(
            Shard::from_env(&slurm, None),
            Ok(Some(Shard { index: 2, count: 4 }))
        );
        let slurm = env(&[
            ("SLURM_ARRAY_TASK_ID", "8"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ]);
        assert_eq!(
            Shard::from_env(&slurm, None),
            Ok(Some(Shard { index: 7, count: 8 }))
        );
        let gap = env(&[
            ("SLURM_ARRAY_TASK_ID", "9"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ]);
        assert!(
            Shard::from_env(&gap, None)
                .unwrap_err()
                .0
                .contains("SLURM_ARRAY_TASK_ID=9")
        );
        let k8s = env(&[("JOB_COMPLETION_INDEX", "1"), ("PLAIT_SHARD_COUNT", "3")]);
        assert_eq!(
            Shard::from_env(&k8s, None),
            Ok(Some(Shard { index: 1, count: 3 }))
        );
        assert_eq!(
            Shard::from_env(&k8s, Some(2)),
            Ok(Some(Shard { index: 1, count: 2 }))
        );
        let k8s = env(&[("JOB_COMPLETION_INDEX", "1")]);
        assert!(
            Shard::from_env(&k8s, None)
                .unwrap_err()
                .0
                .contains("--shard-count")
        );
        let out = env(&[("JOB_COMPLETION_INDEX", "3"), ("PLAIT_SHARD_COUNT", "3")]);
        assert!(Shard::from_env(&out, None).is_err());
        assert_eq!(Shard::from_env(&env(&[]), None), Ok(None));
    }
}
