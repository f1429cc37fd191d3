//! Where techniques are found. A technique is a folder,
//! `techniques/<point>/<name>/`, holding `technique.toml` and the WGSL it
//! names; the engine lists the folders itself (no registry). Technique
//! folders are looked for in layers, nearest first:
//!
//! 1. the `techniques/` beside the pipeline (its folder's or an ancestor's):
//!    the pipeline's own library, whose names shadow the layers below;
//! 2. the `techniques/` of each folder of the search path (`PLAIT_PATH`, or
//!    the checkout plait was built from), so a folder dropped there is a
//!    choice for an installed binary without a rebuild — two of these
//!    folders claiming one `<point>/<name>` is an error, not a silent pick;
//! 3. the copies built into the binary, last.
//!
//! `.toml` files directly in a point's folder are fragments that techniques
//! `includes`; a folder at a point without `technique.toml` is an error
//! wherever it is looked at.

use std::path::{Path, PathBuf};

use crate::error::{Error, ErrorKind, Location};

use super::TECHNIQUES_DIR;

/// The file that makes a folder a technique.
pub const TECHNIQUE_FILE: &str = "technique.toml";

/// The layers techniques are looked up in, nearest first.
#[derive(Clone, Debug, Default)]
pub struct TechniqueRoots {
    /// The pipeline's own folder, if it has one (shadows the rest).
    own: Option<PathBuf>,
    /// The search path's folders, in order.
    search: Vec<PathBuf>,
    /// The built-in copies (`<built-in>/techniques`), when built in.
    builtin: Option<PathBuf>,
}

/// Where `<point>/<name>` is, or why it is not.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Located {
    /// Its `technique.toml`.
    Found(PathBuf),
    /// No layer has a folder of that name.
    Missing,
    /// The nearest folder of that name has no `technique.toml`.
    NoTechniqueFile(PathBuf),
    /// Two folders of the search path claim the name.
    Twice(PathBuf, PathBuf),
}

impl TechniqueRoots {
    /// The layers for `pipeline` (see the module docs).
    pub fn for_pipeline(pipeline: &Path) -> Self {
        let own = (!plait_assets::is_builtin(pipeline))
            .then(|| super::techniques_beside(pipeline))
            .flatten();
        let mut search: Vec<PathBuf> = Vec::new();
        for dir in plait_assets::search_path() {
            let t = dir.join(TECHNIQUES_DIR);
            if t.is_dir()
                && !same_folder(own.as_deref(), &t)
                && !search.iter().any(|s| same_folder(Some(s), &t))
            {
                search.push(t);
            }
        }
        let builtin = Path::new(plait_assets::BUILTIN_ROOT).join(TECHNIQUES_DIR);
        let builtin = plait_assets::is_dir(&builtin).then_some(builtin);
        TechniqueRoots {
            own,
            search,
            builtin,
        }
    }

    /// The pipeline's own folder (if any) over the search path's folders,
    /// with no built-in copies (tests, tools that know their folders).
    pub fn new(own: Option<PathBuf>, search: Vec<PathBuf>) -> Self {
        TechniqueRoots {
            own,
            search,
            builtin: None,
        }
    }

    /// One folder alone (`plait techniques --dir`, tests).
    pub fn at(dir: PathBuf) -> Self {
        TechniqueRoots {
            own: Some(dir),
            ..Self::default()
        }
    }

    /// Every layer, nearest first.
    pub fn layers(&self) -> impl Iterator<Item = &PathBuf> {
        self.own.iter().chain(&self.search).chain(&self.builtin)
    }

    pub fn is_empty(&self) -> bool {
        self.layers().next().is_none()
    }

    /// The choice points (sub-folders of any layer), sorted.
    pub fn points(&self) -> Vec<String> {
        let mut all: Vec<String> = self
            .layers()
            .flat_map(|root| names(root, plait_assets::is_dir))
            .collect();
        all.sort();
        all.dedup();
        all
    }

    /// The techniques of `point` in any layer (folders with a
    /// `technique.toml`), sorted.
    pub fn choices(&self, point: &str) -> Vec<String> {
        let mut all: Vec<String> = self
            .layers()
            .flat_map(|root| {
                let dir = root.join(point);
                names(&dir, |p| plait_assets::exists(&p.join(TECHNIQUE_FILE)))
            })
            .collect();
        all.sort();
        all.dedup();
        all
    }

    /// The nearest layer's point file of `point` (`<point>/point.toml`),
    /// parsed, if any layer has one.
    pub fn point_file(&self, point: &str) -> Option<Result<super::PointFile, Vec<Error>>> {
        let path = self
            .layers()
            .map(|root| root.join(point).join(super::POINT_FILE))
            .find(|p| plait_assets::exists(p))?;
        Some(match plait_assets::read_to_string(&path) {
            Ok(text) => super::point_file::parse(point, &path, &text).map_err(|e| e.0),
            Err(e) => Err(vec![Error::new(
                Location::Path { path },
                ErrorKind::Io(e.to_string()),
            )]),
        })
    }

    /// The points every pipeline has, listed in its `[techniques]` or not:
    /// those whose point file `draws` a geometry (every pass drawing it uses
    /// them). A broken point file is reported when the point is chosen.
    pub fn implied_points(&self) -> Vec<String> {
        self.points()
            .into_iter()
            .filter(|p| matches!(self.point_file(p), Some(Ok(f)) if !f.draws.is_empty()))
            .collect()
    }

    /// Where the technique `name` of `point` is.
    pub fn locate(&self, point: &str, name: &str) -> Located {
        let folder = |root: &Path| root.join(point).join(name);
        let has_folder = |root: &Path| plait_assets::is_dir(&folder(root));
        let nearest = |root: &Path| {
            let file = folder(root).join(TECHNIQUE_FILE);
            if plait_assets::exists(&file) {
                Located::Found(file)
            } else {
                Located::NoTechniqueFile(folder(root))
            }
        };
        if let Some(own) = self.own.as_deref().filter(|r| has_folder(r)) {
            return nearest(own);
        }
        let claims: Vec<&PathBuf> = self.search.iter().filter(|r| has_folder(r)).collect();
        match claims.as_slice() {
            [] => {}
            [one] => return nearest(one),
            [a, b, ..] => return Located::Twice(folder(a), folder(b)),
        }
        match self.builtin.as_deref().filter(|r| has_folder(r)) {
            Some(b) => nearest(b),
            None => Located::Missing,
        }
    }

    /// What is wrong with the folders as laid out: technique folders without
    /// `technique.toml`, names two search-path folders claim. For
    /// `plait techniques` and `plait check`.
    pub fn problems(&self) -> Vec<Error> {
        let mut out = Vec::new();
        for point in self.points() {
            let mut names: Vec<String> = self
                .layers()
                .flat_map(|root| names(&root.join(&point), plait_assets::is_dir))
                .collect();
            names.sort();
            names.dedup();
            for name in names {
                if let Some(e) = located_error(&self.locate(&point, &name), &point, &name) {
                    out.push(e);
                }
            }
        }
        out
    }
}

/// The error for a lookup that found no technique file, at `location` if
/// given (the `[techniques]` entry), else at the folder.
pub fn located_error(found: &Located, point: &str, name: &str) -> Option<Error> {
    let (at, message) = match found {
        Located::Found(_) | Located::Missing => return None,
        Located::NoTechniqueFile(folder) => (
            folder.clone(),
            format!(
                "the technique folder {} has no {TECHNIQUE_FILE}: a technique is a folder holding {TECHNIQUE_FILE} and the WGSL it names",
                folder.display()
            ),
        ),
        Located::Twice(a, b) => (
            a.clone(),
            format!(
                "two folders of the search path claim the {point} technique `{name}`: {} and {}; rename one (or drop a folder from PLAIT_PATH)",
                a.display(),
                b.display()
            ),
        ),
    };
    Some(Error::new(
        Location::Path { path: at },
        ErrorKind::Schema(message),
    ))
}

fn same_folder(a: Option<&Path>, b: &Path) -> bool {
    let canon = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    a.is_some_and(|a| canon(a) == canon(b))
}

/// The entry names of `dir` that `keep` accepts.
fn names(dir: &Path, keep: impl Fn(&Path) -> bool) -> Vec<String> {
    plait_assets::read_dir(dir)
        .into_iter()
        .filter(|p| keep(p))
        .filter_map(|p| p.file_name().and_then(|s| s.to_str()).map(str::to_owned))
        .collect()
}
