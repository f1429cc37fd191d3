//! Techniques: a pipeline's `[techniques]` table names one technique per
//! choice point, and one key swaps it:
//!
//! ```toml
//! [techniques]
//! self_shadow = "deep_opacity"
//! transparency = "weighted_average"
//! ```
//!
//! A technique is a folder of data, `techniques/<point>/<name>/`: its
//! `technique.toml` (found in layers: [`roots`]) holds its params, resources
//! and passes (merged into the pipeline, which may tune them:
//! the pipeline's own keys win), and the contract it fulfils:
//!
//! ```toml
//! [technique]
//! point = "self_shadow"            # the choice point it fills
//! description = "…"
//! source = "Yuksel & Keyser 2008 §3"
//! memory = "…"                     # a formula, for `plait techniques`
//! includes = ["../light_range.toml"]  # shared fragments, relative to this file
//!
//! [technique.exports]              # what every pass that `uses` the point receives
//! reads = { vis_range = "light_range", vis_layers = "light_dom" }
//! params = { self_shadow = "deep_opacity" }
//! ```
//!
//! A pass consumes a choice point with `uses = ["self_shadow"]`: the chosen
//! technique's exports are merged into its `reads` and `params` (the pass's
//! own entries win). No pass in a pipeline file names a technique's maps, so
//! every combination of choices composes without a new file.

use std::path::{Path, PathBuf};

use crate::error::{Error, ErrorKind, Location, Spanned};
use crate::load::{Entry, Node, Table, merge, parse_file};
use crate::schedule::ChosenTechnique;
use crate::suggest::{did_you_mean, nearest_first};
use crate::value::Value;

/// The folder technique files live in, under the first ancestor of the
/// pipeline's folder that has one.
pub const TECHNIQUES_DIR: &str = "techniques";

/// Keys of a technique file's `[technique]` table.
const TECHNIQUE_KEYS: &[&str] = &[
    "point",
    "description",
    "source",
    "memory",
    "includes",
    "exports",
    "engine",
    "provides",
    "requires",
    "adapter",
];
/// Top-level tables a technique file may hold.
const FILE_KEYS: &[&str] = &["technique", "params", "param_ranges", "resources", "passes"];
/// What exports may carry.
const EXPORT_KEYS: &[&str] = &["reads", "params"];

mod catalog;
mod exports;
mod param_scope;
pub mod point_contract;
pub mod point_file;
mod point_optional;
mod requires;
pub use requires::required_choices;
mod roots;
pub mod technique_keys;

pub use catalog::{TechniqueInfo, catalog};
use exports::{PointExports, give_exports};
pub use param_scope::ENGINE_PARAMS;
pub(crate) use param_scope::{check_param_names, explain_unchosen_sets};
pub use point_contract::{PointContract, PointParam};
pub use point_file::{POINT_FILE, PointFile, WgslPoint, wgsl_points};
pub use point_optional::{OptionalFunction, argument_names};
pub use roots::{Located, TECHNIQUE_FILE, TechniqueRoots, located_error};
pub(crate) use technique_keys::check_param_ranges;

/// The folder whose `techniques/` is `pipeline`'s own (see
/// [`techniques_beside`]), resolved; `None` for a built-in pipeline or one
/// with no `techniques/` beside it. Its WGSL is part of the shader library a
/// session reads for that pipeline (`plait_gpu::library::Library::read`).
pub fn own_root(pipeline: &Path) -> Option<PathBuf> {
    if plait_assets::is_builtin(pipeline) {
        return None;
    }
    let own = techniques_beside(pipeline)?;
    let root = own
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    Some(root.canonicalize().unwrap_or_else(|_| root.to_path_buf()))
}

/// The techniques folder beside `pipeline`: its own folder's, or an
/// ancestor's — relative to the working directory when it is below it, so
/// messages name `techniques/…` as a user would.
pub(crate) fn techniques_beside(pipeline: &Path) -> Option<PathBuf> {
    let dir = pipeline.parent().unwrap_or(Path::new(""));
    let absolute = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
    let found = absolute
        .ancestors()
        .map(|a| a.join(TECHNIQUES_DIR))
        .find(|t| t.is_dir())?;
    let cwd = std::env::current_dir()
        .ok()
        .and_then(|c| std::fs::canonicalize(c).ok());
    Some(
        match cwd.and_then(|c| found.strip_prefix(c).ok().map(Path::to_path_buf)) {
            Some(relative) => relative,
            None => found,
        },
    )
}

/// `dir/name` with `..` taken off lexically (`occupancy/../light_range.toml`
/// is `light_range.toml`), so messages and watched files name the file once.
fn lexical_join(dir: &Path, name: &str) -> PathBuf {
    use std::path::Component;
    let mut out = PathBuf::new();
    for c in dir.join(name).components() {
        match c {
            Component::ParentDir
                if matches!(out.components().next_back(), Some(Component::Normal(_))) =>
            {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

fn schema(location: &Location, message: String) -> Error {
    Error::new(location.clone(), ErrorKind::Schema(message))
}

fn table<'a>(node: &'a Spanned<Node>, key: &str) -> Option<&'a Table> {
    match &node.value {
        Node::Table(t) => match &t.get(key)?.value.value {
            Node::Table(inner) => Some(inner),
            _ => None,
        },
        _ => None,
    }
}

fn technique_table(node: &Spanned<Node>) -> Option<&Table> {
    table(node, "technique")
}

/// A technique file with its `includes` (and theirs) merged under it.
pub(crate) fn read_technique(path: &Path) -> Result<Spanned<Node>, Vec<Error>> {
    read_with_includes(path, &mut Vec::new())
}

fn read_with_includes(path: &Path, chain: &mut Vec<PathBuf>) -> Result<Spanned<Node>, Vec<Error>> {
    chain.push(path.to_path_buf());
    let text = plait_assets::read_to_string(path).map_err(|e| {
        vec![Error::new(
            Location::Path {
                path: path.to_path_buf(),
            },
            ErrorKind::Io(e.to_string()),
        )]
    })?;
    let tree = parse_file(path, &text).map_err(|e| e.0)?;
    let mut errors = Vec::new();
    let Node::Table(top) = &tree.value else {
        return Ok(tree);
    };
    for (key, entry) in top {
        if !FILE_KEYS.contains(&key.as_str()) {
            errors.push(schema(
                &entry.key,
                format!(
                    "a technique file holds [technique], [params], [resources] and [passes]; `{key}` is not one of them{}",
                    did_you_mean(key, FILE_KEYS.iter().copied())
                ),
            ));
        }
    }
    let Some(technique) = technique_table(&tree) else {
        // A shared fragment: data only.
        return if errors.is_empty() {
            Ok(tree)
        } else {
            Err(errors)
        };
    };
    for (key, entry) in technique {
        if !TECHNIQUE_KEYS.contains(&key.as_str()) {
            errors.push(schema(
                &entry.key,
                format!(
                    "[technique] has no key `{key}`{} (keys: {})",
                    did_you_mean(key, TECHNIQUE_KEYS.iter().copied()),
                    TECHNIQUE_KEYS.join(", ")
                ),
            ));
        }
    }
    let mut merged: Option<Spanned<Node>> = None;
    if let Some(includes) = technique.get("includes") {
        let Node::List(items) = &includes.value.value else {
            errors.push(schema(
                &includes.value.location,
                "`includes` must be a list of file names".into(),
            ));
            return Err(errors);
        };
        for item in items {
            let Node::Scalar(Value::Str(name)) = &item.value else {
                errors.push(schema(
                    &item.location,
                    "`includes` must list file names".into(),
                ));
                continue;
            };
            let included = lexical_join(path.parent().unwrap_or(Path::new("")), name);
            if chain.contains(&included) {
                errors.push(schema(
                    &item.location,
                    format!("`includes` loops back to {}", included.display()),
                ));
                continue;
            }
            if let Err(e) = plait_assets::read_to_string(&included) {
                errors.push(Error::new(
                    item.location.clone(),
                    ErrorKind::ReadFile {
                        path: included,
                        reason: e.to_string(),
                    },
                ));
                continue;
            }
            match read_with_includes(&included, chain) {
                Ok(fragment) => match &mut merged {
                    Some(m) => merge(m, fragment),
                    None => merged = Some(fragment),
                },
                Err(e) => errors.extend(e),
            }
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    Ok(match merged {
        Some(mut base) => {
            merge(&mut base, tree);
            base
        }
        None => tree,
    })
}

/// Replace the `[techniques]` table of `root` (the pipeline after `extends`
/// and `--set`) by the chosen techniques' data, and give every pass that
/// `uses` a choice point that point's exports. Technique files read are added
/// to `files`.
pub(crate) fn apply_techniques(
    root: &mut Spanned<Node>,
    pipeline_path: &Path,
    files: &mut Vec<PathBuf>,
    errors: &mut Vec<Error>,
) -> Vec<ChosenTechnique> {
    let mut chosen_list = Vec::new();
    let Node::Table(top) = &mut root.value else {
        return chosen_list;
    };
    let chosen = top.shift_remove("techniques");
    let mut exports: Vec<PointExports> = Vec::new();
    let mut combined: Option<Spanned<Node>> = None;
    // Points joined to every draw of a geometry (`draws`): unchosen, their
    // WGSL default applies, so a pass may `uses` one without a choice.
    let mut implicit: Vec<String> = Vec::new();
    if let Some(entry) = &chosen {
        let Node::Table(points_table) = &entry.value.value else {
            errors.push(schema(
                &entry.value.location,
                "[techniques] maps each choice point to a technique name, e.g. `self_shadow = \"occupancy\"`".into(),
            ));
            return chosen_list;
        };
        let roots = TechniqueRoots::for_pipeline(pipeline_path);
        if roots.is_empty() {
            errors.push(schema(
                &entry.key,
                format!(
                    "no `{TECHNIQUES_DIR}/` folder beside {} or above it, so no technique can be found",
                    pipeline_path.display()
                ),
            ));
            return chosen_list;
        }
        implicit = roots
            .points()
            .into_iter()
            .filter(
                |p| matches!(roots.point_file(p), Some(Ok(f)) if !f.draws.is_empty() || f.implicit),
            )
            .collect();
        let mut chooser = Chooser {
            known_points: roots.points(),
            roots,
            files,
            errors: &mut *errors,
            chosen: Vec::new(),
            exports: Vec::new(),
            combined: None,
            owners: Vec::new(),
            trees: Vec::new(),
        };
        for (point, choice) in points_table {
            chooser.choose(point, choice);
        }
        let refused = requires::check(&chooser.roots, &chooser.trees);
        chooser.errors.extend(refused);
        (chosen_list, exports, combined) = (chooser.chosen, chooser.exports, chooser.combined);
    }
    if !errors.is_empty() {
        return chosen_list;
    }
    // The pipeline's own keys win over the techniques'.
    if let Some(mut base) = combined {
        let pipeline = std::mem::replace(
            root,
            Spanned::new(Node::Table(Table::new()), base.location.clone()),
        );
        merge(&mut base, pipeline);
        *root = base;
    }
    give_exports(root, &exports, &implicit, chosen.is_some(), errors);
    chosen_list
}

/// What reading the chosen techniques of `[techniques]` one by one gathers.
struct Chooser<'a> {
    roots: TechniqueRoots,
    known_points: Vec<String>,
    files: &'a mut Vec<PathBuf>,
    errors: &'a mut Vec<Error>,
    chosen: Vec<ChosenTechnique>,
    exports: Vec<PointExports>,
    /// The techniques' data (without `[technique]`), merged in choice order.
    combined: Option<Spanned<Node>>,
    /// Which technique defined each resource and pass, to refuse two of them
    /// defining the same name: (section, `point/name`, item, where its key
    /// is written).
    owners: Vec<(String, String, String, Location)>,
    /// Each chosen technique's file, for `[technique.requires]`.
    trees: Vec<requires::Chosen>,
}

impl Chooser<'_> {
    /// Reads the technique chosen for `point`, checks it against its point
    /// and gathers its exports and data.
    fn choose(&mut self, point: &str, choice: &Entry) {
        let Some((name, path)) = self.locate(point, choice) else {
            return;
        };
        let tree = match read_technique(&path) {
            Ok(t) => t,
            Err(mut e) => {
                self.errors.append(&mut e);
                return;
            }
        };
        self.files.push(path.clone());
        self.chosen.push(ChosenTechnique {
            point: point.to_owned(),
            name: name.clone(),
            path: path.clone(),
            params: table(&tree, "params")
                .map(|t| t.keys().cloned().collect())
                .unwrap_or_default(),
            ranges: technique_keys::ranges(&tree, self.errors),
            engine: technique_table(&tree)
                .map(|t| technique_keys::engine(t, self.errors))
                .unwrap_or_default(),
            adapter: technique_table(&tree)
                .map(|t| technique_keys::adapter(t, self.errors))
                .unwrap_or_default(),
        });
        let Some(technique) = technique_table(&tree) else {
            // Without it the choice would vanish: no exports, no check of
            // what the point promises (an emptied file once turned into
            // "output `final` is not written" at the pipeline).
            self.errors.push(schema(
                &tree.location,
                format!(
                    "a technique file needs a [technique] table (`point = \"{point}\"`, description, source, memory); this one has none"
                ),
            ));
            return;
        };
        self.check_point_key(technique, &tree, point);
        let (reads, params) = self.read_exports(technique);
        self.trees.push(requires::Chosen {
            point: point.to_owned(),
            name: name.clone(),
            at: choice.value.location.clone(),
            tree: tree.clone(),
        });
        let mut draws = Vec::new();
        match self.roots.point_file(point) {
            Some(Ok(promise)) => {
                self.errors
                    .extend(point_file::check_writes(&promise, point, name, &tree));
                if let Some(wgsl) = &promise.wgsl {
                    self.errors.extend(point_contract::check_technique(
                        wgsl,
                        name,
                        &tree,
                        (reads.as_ref(), params.as_ref()),
                    ));
                }
                draws = promise.draws.into_iter().map(|d| d.value).collect();
            }
            Some(Err(mut e)) => self.errors.append(&mut e),
            None => {}
        }
        self.exports.push(PointExports {
            point: point.to_owned(),
            reads,
            params,
            draws,
        });
        self.claim_names(&tree, point, name);
        let Node::Table(mut t) = tree.value else {
            return;
        };
        t.shift_remove("technique");
        t.shift_remove("param_ranges");
        let data = Spanned::new(Node::Table(t), tree.location);
        match &mut self.combined {
            Some(c) => merge(c, data),
            None => self.combined = Some(data),
        }
    }

    /// The technique named for `point` and its file, or `None` once the
    /// point, the name or the folder is reported.
    fn locate<'c>(&mut self, point: &str, choice: &'c Entry) -> Option<(&'c String, PathBuf)> {
        if !self.known_points.iter().any(|p| p == point) {
            let known_points = &self.known_points;
            self.errors.push(schema(
                &choice.key,
                format!(
                    "no choice point `{point}`{} (points: {})",
                    did_you_mean(point, known_points.iter().map(String::as_str)),
                    known_points.join(", ")
                ),
            ));
            return None;
        }
        let Node::Scalar(Value::Str(name)) = &choice.value.value else {
            self.errors.push(schema(
                &choice.value.location,
                format!("techniques.{point} names a technique: a string"),
            ));
            return None;
        };
        match self.roots.locate(point, name) {
            Located::Found(path) => Some((name, path)),
            Located::Missing => {
                let valid = self.roots.choices(point);
                let ranked = nearest_first(name, valid.iter().map(String::as_str));
                self.errors.push(schema(
                    &choice.value.location,
                    format!(
                        "no {point} technique `{name}`{} (choices: {})",
                        did_you_mean(name, valid.iter().map(String::as_str)),
                        ranked.join(" | ")
                    ),
                ));
                None
            }
            other => {
                let mut e = located_error(&other, point, name).expect("not found");
                // Reported at the choice, naming the folder.
                e.location = choice.value.location.clone();
                self.errors.push(e);
                None
            }
        }
    }

    /// Checks that `[technique] point` names the point the folder is under.
    fn check_point_key(&mut self, technique: &Table, tree: &Spanned<Node>, point: &str) {
        match technique.get("point").map(|e| &e.value) {
            Some(Spanned {
                value: Node::Scalar(Value::Str(p)),
                ..
            }) if p == point => {}
            Some(other) => self.errors.push(schema(
                &other.location,
                format!("this technique fills the choice point `{point}` (it is in {TECHNIQUES_DIR}/{point}/); write `point = \"{point}\"`"),
            )),
            None => self.errors.push(schema(
                &tree.location,
                format!("[technique] needs `point = \"{point}\"`"),
            )),
        }
    }

    /// The `reads` and `params` tables of `[technique.exports]`, reporting
    /// anything else there.
    fn read_exports(&mut self, technique: &Table) -> (Option<Table>, Option<Table>) {
        let (mut reads, mut params) = (None, None);
        let Some(e) = technique.get("exports") else {
            return (reads, params);
        };
        let Node::Table(t) = &e.value.value else {
            self.errors
                .push(schema(&e.value.location, "exports must be a table".into()));
            return (reads, params);
        };
        for (key, x) in t {
            let slot = match &x.value.value {
                Node::Table(inner) => Some(inner.clone()),
                _ => {
                    self.errors.push(schema(
                        &x.value.location,
                        format!("exports.{key} must be a table"),
                    ));
                    None
                }
            };
            match key.as_str() {
                "reads" => reads = slot,
                "params" => params = slot,
                _ => self.errors.push(schema(
                    &x.key,
                    format!(
                        "exports has `reads` and `params`; not `{key}`{}",
                        did_you_mean(key, EXPORT_KEYS.iter().copied())
                    ),
                )),
            }
        }
        (reads, params)
    }

    /// Records the params, resources and passes technique `point/name`
    /// defines, reporting any another technique defined first.
    fn claim_names(&mut self, tree: &Spanned<Node>, point: &str, name: &str) {
        // Two techniques may not define the same param, resource or pass:
        // they share the pipeline's one table of each, so the second would
        // silently retune the first (a new technique's `slabs = 9` once
        // changed occupancy's slab count, exit 0). The pipeline's own keys
        // still tune any technique's.
        for section in ["params", "resources", "passes"] {
            let Some(t) = table(tree, section) else {
                continue;
            };
            for (item, e) in t {
                // One fragment included by two chosen techniques (the density
                // volume of self_shadow and ambient_occlusion) defines its
                // names once: the same key at the same place is one item.
                let shared = |at: &Location| *at == e.key;
                if let Some((_, other, _, _)) = self
                    .owners
                    .iter()
                    .find(|(s, _, i, at)| s == section && i == item && !shared(at))
                {
                    let hint = if section == "params" {
                        format!(
                            "; technique params share the pipeline's [params] table, so give this one a name of its own (e.g. `{name}_{item}`)"
                        )
                    } else {
                        String::new()
                    };
                    self.errors.push(schema(
                        &e.key,
                        format!(
                            "{section}.{item} is defined by technique `{other}` too: two techniques cannot define the same name{hint}"
                        ),
                    ));
                } else {
                    self.owners.push((
                        section.to_owned(),
                        format!("{point}/{name}"),
                        item.clone(),
                        e.key.clone(),
                    ));
                }
            }
        }
    }
}
