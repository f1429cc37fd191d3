//! The shader library, found rather than listed.
//!
//! A *library module* is any WGSL file under `shaders/` or `techniques/`
//! (search path first, then the built-in copies) that declares
//! `#define_import_path`. naga_oil needs modules added after the modules they
//! import, so the order comes from their `#import` lines; an `#import` that
//! no module provides is an error at its line and column. A choice point
//! answered in WGSL is declared by `techniques/<point>/point.toml`
//! ([`plait_graph::techniques::wgsl_point`]); its providers are the modules
//! named `<providers>::<name>`, and its selector module is generated from the
//! providers found. Nothing here lists a file: a module dropped into a
//! technique folder on `PLAIT_PATH` is part of the library on the next load.
//!
//! The library is a value ([`Library::read`]), read once per session from the
//! search path and the loaded pipelines' own `techniques/` folders; nothing
//! here caches it. A front end that reloads (the viewer, `render --watch`)
//! reads a new one.

use std::collections::{BTreeMap, HashMap};
use std::path::PathBuf;

use plait_graph::techniques::{POINT_FILE, WgslPoint, wgsl_points};

use crate::shader::ShaderError;

/// The folders whose WGSL files may be library modules.
const MODULE_FOLDERS: &[&str] = &["shaders", "techniques"];

/// One module of the library.
#[derive(Clone, Debug)]
pub struct LibraryModule {
    /// Its library path (`shaders/lib/frame.wgsl`), the same wherever it is
    /// read from; for a generated selector, its point file's and the module.
    pub key: String,
    /// Where it was read from (the point file, for a generated selector).
    pub path: PathBuf,
    /// Its import path (`plait::frame`).
    pub name: String,
    pub source: String,
    imports: Vec<Import>,
}

/// An `#import` line: the path as written and where.
#[derive(Clone, Debug)]
struct Import {
    path: String,
    line: usize,
    column: usize,
}

/// A point answered in WGSL with the providers found for it.
#[derive(Clone, Debug)]
pub struct ProviderPoint {
    pub contract: WgslPoint,
    /// Provider name (the param value) and its module's file, sorted by name.
    pub providers: Vec<(String, PathBuf)>,
}

/// The whole library, modules in the order naga_oil must receive them.
#[derive(Clone, Debug, Default)]
pub struct Library {
    pub modules: Vec<LibraryModule>,
    pub points: Vec<ProviderPoint>,
    /// The loaded pipelines' own folders it was read with (their
    /// `techniques/` before the search path's), resolved.
    pub own_roots: Vec<PathBuf>,
}

/// Every file the library read with `own_roots` is made of, as `(library
/// path, where it is read from)`: what the viewer and `render --watch` watch.
pub fn library_files(own_roots: &[PathBuf]) -> Vec<(String, PathBuf)> {
    let mut files: Vec<(String, PathBuf)> = MODULE_FOLDERS
        .iter()
        .flat_map(|f| list_tree(own_roots, f, "wgsl"))
        .collect();
    files.extend(
        list_tree(own_roots, plait_graph::techniques::TECHNIQUES_DIR, "toml")
            .into_iter()
            .filter(|(key, _)| key.ends_with(&format!("/{POINT_FILE}"))),
    );
    files
}

/// The files of `folder` with extension `ext`, nearest copy of each: a
/// loaded pipeline's own `techniques/` (under `own_roots`) before the search
/// path's, the built-in copies last.
///
/// A pipeline's own copy of a file shadows the search path's. Two pipelines'
/// own folders holding the same file are both kept, so a module both declare
/// is an error naming the two files, not a silent pick of the first.
fn list_tree(own_roots: &[PathBuf], folder: &str, ext: &str) -> Vec<(String, PathBuf)> {
    let mut found = plait_assets::list_tree(folder, ext);
    if folder != plait_graph::techniques::TECHNIQUES_DIR {
        return found;
    }
    let mut own: Vec<(String, PathBuf)> = Vec::new();
    // Two own roots may be one folder written two ways: each file once.
    let mut seen: std::collections::HashSet<PathBuf> = std::collections::HashSet::new();
    for root in own_roots {
        for (key, path) in plait_assets::list_tree_in(std::slice::from_ref(root), folder, ext) {
            if plait_assets::is_builtin(&path) {
                continue;
            }
            let resolved = path.canonicalize().unwrap_or_else(|_| path.clone());
            if seen.insert(resolved) {
                own.push((key, path));
            }
        }
    }
    found.retain(|(key, _)| !own.iter().any(|(k, _)| k == key));
    own.extend(found);
    own
}

impl Library {
    /// Find, read and order the library (see the module docs): the search
    /// path as it is now, with the `techniques/` of each of `own_roots` (the
    /// loaded pipelines' own folders, [`plait_graph::techniques::own_root`])
    /// before it.
    pub fn read(own_roots: &[PathBuf]) -> Result<Library, ShaderError> {
        read_library(own_roots)
    }

    /// The value names of the point whose param is `param` (`visibility`):
    /// the providers found.
    pub fn providers(&self, param: &str) -> Vec<String> {
        self.points
            .iter()
            .find(|p| p.contract.param == param)
            .map(|p| p.providers.iter().map(|(n, _)| n.clone()).collect())
            .unwrap_or_default()
    }
}

fn read_library(own_roots: &[PathBuf]) -> Result<Library, ShaderError> {
    let mut found: BTreeMap<String, LibraryModule> = BTreeMap::new();
    for folder in MODULE_FOLDERS {
        for (key, path) in list_tree(own_roots, folder, "wgsl") {
            let source = plait_assets::read_to_string(&path)
                .map_err(|e| ShaderError {
                    message: format!("{}: cannot read file: {e}", path.display()),
                    path: path.clone(),
                })?
                .into_owned();
            let Some(name) = import_path(&source) else {
                continue;
            };
            if let Some(first) = found.get(&name) {
                let at = |source: &str| import_path_line(source).unwrap_or(1);
                return Err(ShaderError {
                    message: format!(
                        "{}:{}:1: declares `#define_import_path {name}`, which {}:{}:1 declares too: \
                         one module per import path",
                        path.display(),
                        at(&source),
                        first.path.display(),
                        at(&first.source),
                    ),
                    path,
                });
            }
            let imports = imports(&source);
            found.insert(
                name.clone(),
                LibraryModule {
                    key,
                    path,
                    name,
                    source,
                    imports,
                },
            );
        }
    }
    let mut technique_roots = own_roots.to_vec();
    technique_roots.extend(plait_assets::search_path());
    let points = provider_points(&found, &technique_roots)?;
    for point in &points {
        let names: Vec<String> = point.providers.iter().map(|(n, _)| n.clone()).collect();
        // The providers whose module defines the optional function, if the
        // point has one (`[wgsl.optional]`).
        let with_optional: Vec<String> = match &point.contract.optional {
            Some(o) => names
                .iter()
                .filter(|n| {
                    found
                        .get(&format!("{}::{n}", point.contract.providers))
                        .is_some_and(|m| m.source.contains(&format!("fn {}(", o.function)))
                })
                .cloned()
                .collect(),
            None => Vec::new(),
        };
        let source = point.contract.selector_source(&names, &with_optional);
        let path = point_path(&point.contract);
        if let Some(clash) = found.get(&point.contract.module) {
            return Err(ShaderError {
                message: format!(
                    "{}: the selector `{}` is generated from this file, but {} declares it too; \
                     delete that file",
                    path.display(),
                    point.contract.module,
                    clash.path.display()
                ),
                path,
            });
        }
        found.insert(
            point.contract.module.clone(),
            LibraryModule {
                key: format!(
                    "{}/{}/{POINT_FILE} (generates {})",
                    plait_graph::techniques::TECHNIQUES_DIR,
                    point.contract.point,
                    point.contract.module
                ),
                imports: imports(&source),
                path,
                name: point.contract.module.clone(),
                source,
            },
        );
    }
    Ok(Library {
        modules: dependency_order(found)?,
        points,
        own_roots: own_roots.to_vec(),
    })
}

fn point_path(point: &WgslPoint) -> PathBuf {
    match &point.file {
        plait_graph::Location::Path { path } | plait_graph::Location::File { path, .. } => {
            path.clone()
        }
        other => PathBuf::from(other.to_string()),
    }
}

/// Each point file with the modules `<providers>::<name>` found for it; its
/// default must be one of them.
fn provider_points(
    found: &BTreeMap<String, LibraryModule>,
    technique_roots: &[PathBuf],
) -> Result<Vec<ProviderPoint>, ShaderError> {
    let contracts = wgsl_points(technique_roots).map_err(|e| ShaderError {
        path: e
            .0
            .first()
            .map(|e| PathBuf::from(e.location.to_string()))
            .unwrap_or_default(),
        message: e.to_string(),
    })?;
    let mut points = Vec::new();
    for contract in contracts {
        let prefix = format!("{}::", contract.providers);
        let providers: Vec<(String, PathBuf)> = found
            .values()
            .filter_map(|m| {
                let name = m.name.strip_prefix(&prefix)?;
                (!name.contains("::")).then(|| (name.to_owned(), m.path.clone()))
            })
            .collect();
        for (name, path) in &providers {
            let module = found.values().find(|m| m.path == *path);
            if let Some(m) = module {
                check_bindings(&contract, name, path, &m.source)?;
            }
        }
        let default = &contract.default;
        if !providers.iter().any(|(n, _)| *n == default.value) {
            let names: Vec<&str> = providers.iter().map(|(n, _)| n.as_str()).collect();
            return Err(ShaderError {
                path: point_path(&contract),
                message: format!(
                    "{}: default provider `{}` has no module `{}{}` on the search path{} \
                     (providers found: {})",
                    default.location,
                    default.value,
                    prefix,
                    default.value,
                    plait_graph::suggest::did_you_mean(&default.value, names.iter().copied()),
                    if names.is_empty() {
                        "none".into()
                    } else {
                        names.join(", ")
                    }
                ),
            });
        }
        points.push(ProviderPoint {
            contract,
            providers,
        });
    }
    Ok(points)
}

/// Every group-1 binding provider `name` declares lies in its point's
/// `bindings` (`techniques/<point>/point.toml`, `[point]`): the points share
/// group 1 of every shading pass, so a binding outside its range could
/// collide with another point's. An error at the binding's line and column.
fn check_bindings(
    contract: &WgslPoint,
    name: &str,
    path: &std::path::Path,
    source: &str,
) -> Result<(), ShaderError> {
    let Some(range) = &contract.contract.bindings else {
        return Ok(());
    };
    let (first, last) = range.value;
    for (i, line) in source.lines().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        let number = |attr: &str| -> Option<(usize, u32)> {
            let at = code.find(attr)?;
            let rest = &code[at + attr.len()..];
            let n = rest.split(')').next()?.trim().parse().ok()?;
            Some((at, n))
        };
        let (Some((_, 1)), Some((at, binding))) = (number("@group("), number("@binding(")) else {
            continue;
        };
        if binding < first || binding > last {
            return Err(ShaderError {
                path: path.to_owned(),
                message: format!(
                    "{}:{}:{}: {} provider `{name}` declares @group(1) @binding({binding}), outside the point's bindings {first}–{last} ({}): the points share group 1, so its bindings must lie in its point's range",
                    path.display(),
                    i + 1,
                    at + 1,
                    contract.point,
                    range.location
                ),
            });
        }
    }
    Ok(())
}

/// The module's `#define_import_path`, if it declares one.
fn import_path(source: &str) -> Option<String> {
    source.lines().find_map(|l| {
        let rest = l.trim_start().strip_prefix("#define_import_path")?;
        let name = rest.split_whitespace().next()?;
        Some(name.to_owned())
    })
}

/// The 1-based line of the `#define_import_path` directive.
fn import_path_line(source: &str) -> Option<usize> {
    let line = source
        .lines()
        .position(|l| l.trim_start().starts_with("#define_import_path"))?;
    Some(line + 1)
}

/// Every `#import` line: the module path (`plait::frame::{a, b}` →
/// `plait::frame`; `x as y` → `x`), with its 1-based line and column.
fn imports(source: &str) -> Vec<Import> {
    source
        .lines()
        .enumerate()
        .filter_map(|(i, line)| {
            let start = line.len() - line.trim_start().len();
            let rest = line[start..].strip_prefix("#import")?;
            let lead = rest.len() - rest.trim_start().len();
            let rest = rest.trim_start();
            let end = rest
                .find(|c: char| c.is_whitespace() || c == '{' || c == ',')
                .unwrap_or(rest.len());
            let path = rest[..end].trim_end_matches("::");
            (!path.is_empty()).then(|| Import {
                path: path.to_owned(),
                line: i + 1,
                column: start + "#import".len() + lead + 1,
            })
        })
        .collect()
}

/// The module an import path refers to: the longest module name it starts
/// with (`plait::frame::frame` → `plait::frame`).
fn resolve<'m>(path: &str, names: &'m [String]) -> Option<&'m str> {
    names
        .iter()
        .filter(|n| path == n.as_str() || path.starts_with(&format!("{n}::")))
        .max_by_key(|n| n.len())
        .map(String::as_str)
}

/// Modules after the modules they import; an unknown import or a cycle is
/// an error naming the file, line and column.
fn dependency_order(
    mut found: BTreeMap<String, LibraryModule>,
) -> Result<Vec<LibraryModule>, ShaderError> {
    let names: Vec<String> = found.keys().cloned().collect();
    let mut deps: HashMap<String, Vec<String>> = HashMap::new();
    for m in found.values() {
        let mut d = Vec::new();
        for import in &m.imports {
            match resolve(&import.path, &names) {
                Some(n) => d.push(n.to_owned()),
                None => {
                    let prefix = import.path.rsplit_once("::").map_or("", |(p, _)| p);
                    return Err(ShaderError {
                        message: format!(
                            "{}:{}:{}: `#import {}`: no module on the search path provides it{} \
                             (a module declares `#define_import_path`)",
                            m.path.display(),
                            import.line,
                            import.column,
                            import.path,
                            plait_graph::suggest::did_you_mean(
                                prefix,
                                names.iter().map(String::as_str)
                            ),
                        ),
                        path: m.path.clone(),
                    });
                }
            }
        }
        deps.insert(m.name.clone(), d);
    }
    // Depth-first, in name order so the order (and the library digest) is
    // the same on every run.
    let mut order = Vec::new();
    let mut state: HashMap<String, bool> = HashMap::new(); // false: on the stack
    fn visit(
        name: &str,
        deps: &HashMap<String, Vec<String>>,
        state: &mut HashMap<String, bool>,
        order: &mut Vec<String>,
        stack: &mut Vec<String>,
    ) -> Result<(), Vec<String>> {
        match state.get(name) {
            Some(true) => return Ok(()),
            Some(false) => {
                let from = stack.iter().position(|s| s == name).unwrap_or(0);
                let mut cycle = stack[from..].to_vec();
                cycle.push(name.to_owned());
                return Err(cycle);
            }
            None => {}
        }
        state.insert(name.to_owned(), false);
        stack.push(name.to_owned());
        for d in &deps[name] {
            visit(d, deps, state, order, stack)?;
        }
        stack.pop();
        state.insert(name.to_owned(), true);
        order.push(name.to_owned());
        Ok(())
    }
    for name in &names {
        visit(name, &deps, &mut state, &mut order, &mut Vec::new()).map_err(|cycle| {
            let path = found[&cycle[0]].path.clone();
            ShaderError {
                message: format!(
                    "{}: modules import each other in a cycle: {}",
                    path.display(),
                    cycle.join(" → ")
                ),
                path,
            }
        })?;
    }
    Ok(order.into_iter().filter_map(|n| found.remove(&n)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn module(name: &str, source: &str) -> (String, LibraryModule) {
        (
            name.to_owned(),
            LibraryModule {
                key: format!("{name}.wgsl"),
                path: PathBuf::from(format!("{name}.wgsl")),
                name: name.to_owned(),
                source: source.to_owned(),
                imports: imports(source),
            },
        )
    }

    #[test]
    fn imports_are_read_with_their_place() {
        let found = imports(
            "#define_import_path a\n  #import plait::frame::{frame, light_lookup}\n#import b::c as d\n#import e\n",
        );
        let got: Vec<(&str, usize, usize)> = found
            .iter()
            .map(|i| (i.path.as_str(), i.line, i.column))
            .collect();
        assert_eq!(
            got,
            vec![("plait::frame", 2, 11), ("b::c", 3, 9), ("e", 4, 9)]
        );
        assert_eq!(
            import_path("// x\n#define_import_path plait::x\n").as_deref(),
            Some("plait::x")
        );
    }

    #[test]
    fn modules_come_after_what_they_import() {
        let found: BTreeMap<_, _> = [
            module("a", "#import c::f\n#import b::{g}\n"),
            module("b", "#import c::f\n"),
            module("c", ""),
        ]
        .into_iter()
        .collect();
        let order: Vec<String> = dependency_order(found)
            .expect("orders")
            .into_iter()
            .map(|m| m.name)
            .collect();
        assert_eq!(order, ["c", "b", "a"]);
    }

    #[test]
    fn an_import_no_module_provides_is_an_error_at_its_line() {
        let found: BTreeMap<_, _> = [
            module("plait::frame", ""),
            module("a", "\n#import plait::fram::frame\n"),
        ]
        .into_iter()
        .collect();
        let e = dependency_order(found).unwrap_err();
        assert!(
            e.message
                .starts_with("a.wgsl:2:9: `#import plait::fram::frame`"),
            "{}",
            e.message
        );
        assert!(
            e.message.contains("did you mean `plait::frame`"),
            "{}",
            e.message
        );
    }

    #[test]
    fn a_cycle_is_an_error() {
        let found: BTreeMap<_, _> = [module("a", "#import b::x\n"), module("b", "#import a::y\n")]
            .into_iter()
            .collect();
        let e = dependency_order(found).unwrap_err();
        assert!(e.message.contains("a → b → a"), "{}", e.message);
    }
}
