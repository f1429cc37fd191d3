//! Every WGSL file under `shaders/` is composed (naga_oil) and validated (naga)
//! the way plait composes it at run time. The test fails when it finds no
//! shaders (wgpu once had a shader test that silently validated nothing) and
//! lists every failure with naga's diagnostic.

use std::collections::BTreeSet;
use std::path::Path;

use indexmap::IndexMap;
use plait_gpu::pass::PassType;
use plait_gpu::{Define, ShaderLibrary};
use plait_graph::{Location, ParamSpec, ParamType, PassShape, ScheduledPass, Value};
use plait_tests::{files_with_ext, rel, repo_root};

fn library() -> ShaderLibrary {
    ShaderLibrary::new(&plait_gpu::library::Library::read(&[]).expect("the library is found"))
        .unwrap_or_else(|e| {
            panic!(
                "composing the shader library failed in {}:\n{}",
                e.path.display(),
                e.message
            )
        })
}

/// A value for a param: its default, else the smallest valid one.
fn some_value(p: &ParamSpec) -> Value {
    if let Some(v) = &p.default {
        return v.clone();
    }
    match &p.ty {
        ParamType::Int { min, .. } => Value::Int(*min),
        ParamType::Float { min, .. } => Value::Float(*min),
        ParamType::Bool => Value::Bool(false),
        ParamType::Enum(options) => Value::Str(options.first().cloned().unwrap_or_default()),
        ParamType::Str => Value::Str(String::new()),
        ParamType::Vec3 => Value::List(vec![Value::Float(0.0); 3]),
    }
}

/// Param sets a pass of this type can have that change its defines: the
/// defaults, then each value of each enum (and each bool) param in turn.
fn param_variants(params: &[ParamSpec]) -> Vec<IndexMap<String, Value>> {
    let base: IndexMap<String, Value> = params
        .iter()
        .map(|p| (p.name.clone(), some_value(p)))
        .collect();
    let mut out = vec![base.clone()];
    for p in params {
        let values: Vec<Value> = match &p.ty {
            ParamType::Enum(options) => options.iter().map(|o| Value::Str(o.clone())).collect(),
            ParamType::Bool => vec![Value::Bool(false), Value::Bool(true)],
            _ => continue,
        };
        for v in values {
            let mut m = base.clone();
            m.insert(p.name.clone(), v);
            if !out.contains(&m) {
                out.push(m);
            }
        }
    }
    out
}

fn scheduled_pass(
    type_name: &str,
    shape: PassShape,
    view: Option<&str>,
    params: IndexMap<String, Value>,
) -> ScheduledPass {
    ScheduledPass {
        name: format!("test_{type_name}"),
        type_name: type_name.into(),
        type_id: None,
        shape,
        view: view.and_then(plait_graph::View::from_name),
        draw: None,
        reads: vec![],
        writes: vec![],
        params,
        shader: None,
        shader_location: None,
        raster: Default::default(),
        blend_writes: Vec::new(),
        location: Location::Builtin,
        technique: None,
        run_once: false,
    }
}

fn describe(defines: &[(String, Define)]) -> String {
    if defines.is_empty() {
        return "no defines".into();
    }
    defines
        .iter()
        .map(|(k, v)| format!("{k}={v:?}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Every shader file, relative to the checkout (`shaders/passes/x.wgsl`).
fn shader_files() -> Vec<String> {
    let dir = repo_root().join("shaders");
    let files: Vec<String> = files_with_ext(&dir, "wgsl")
        .iter()
        .map(|p| rel(p))
        .collect();
    assert!(
        !files.is_empty(),
        "found no .wgsl files under {}: shader validation would test nothing",
        dir.display()
    );
    files
}

#[test]
fn every_shader_composes_and_validates() {
    let root = repo_root();
    let files = shader_files();
    let passes = plait_passes::read_library(&[]);
    let mut shaders = library();
    let mut failures: Vec<String> = Vec::new();
    let mut compositions = 0;

    // Library modules: ShaderLibrary::new() composed each one above (a parse,
    // import or contract error would have panicked there). No list names
    // them, so the test is that discovery finds every module of the checkout:
    // each file under shaders/lib/, and each file of shaders/ or techniques/
    // declaring `#define_import_path`, is a module of the library, read from
    // the checkout.
    let found = plait_gpu::library::Library::read(&[]).expect("the library is found");
    let keys: BTreeSet<&str> = found.modules.iter().map(|m| m.key.as_str()).collect();
    let mut module_files: Vec<String> = files_with_ext(&root.join("techniques"), "wgsl")
        .iter()
        .map(|p| rel(p))
        .chain(files.iter().cloned())
        .collect();
    module_files.sort();
    for f in &module_files {
        let text = std::fs::read_to_string(root.join(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
        let declares = text
            .lines()
            .any(|l| l.trim_start().starts_with("#define_import_path"));
        if f.starts_with("shaders/lib/") && !declares {
            failures.push(format!(
                "{f}: a file in shaders/lib/ without `#define_import_path`, so no shader can import it"
            ));
        }
        if declares && !keys.contains(f.as_str()) {
            failures.push(format!(
                "{f}: declares a module, but the shader library did not find it"
            ));
        }
    }
    for m in &found.modules {
        if m.key.ends_with(".wgsl") && !module_files.contains(&m.key) {
            failures.push(format!(
                "{}: a library module that is not in this checkout (read from {})",
                m.key,
                m.path.display()
            ));
        }
    }
    // Every point file found providers (one declared twice fails discovery).
    for point in &found.points {
        assert!(
            !point.providers.is_empty(),
            "{}: no provider found",
            point.contract.point
        );
    }

    for f in files.iter().filter(|f| !f.starts_with("shaders/lib/")) {
        let path = root.join(f);
        let source =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {f}: {e}"));
        // The define sets this file is composed with at run time.
        let mut variants: Vec<Vec<(String, Define)>> = Vec::new();
        if f.starts_with("shaders/passes/") {
            let users: Vec<&dyn PassType> = passes
                .types
                .values()
                .map(|t| t.as_ref())
                .filter(|t| t.shader().is_some_and(|p| p == f))
                .collect();
            if users.is_empty() {
                // Still validated, but a pass shader no type uses is probably a mistake.
                eprintln!(
                    "note: {f} is not the shader of any registered pass type; validating it without defines"
                );
                variants.push(vec![]);
            }
            for t in users {
                let spec = t.spec();
                let views: &[Option<&str>] = if spec.shape == PassShape::Raster {
                    &[Some("camera"), Some("light")]
                } else {
                    &[None]
                };
                for view in views {
                    for params in param_variants(&spec.params) {
                        let defines =
                            t.defines(&scheduled_pass(&spec.name, spec.shape, *view, params));
                        if !variants.contains(&defines) {
                            variants.push(defines);
                        }
                    }
                }
            }
        } else {
            // Data-only shaders (`shaders/*.wgsl`): the `fullscreen`/`compute`
            // types pass no defines for a pass without params.
            variants.push(vec![]);
        }
        for defines in variants {
            compositions += 1;
            if let Err(e) = shaders.compose(Path::new(f), &source, &defines) {
                failures.push(format!("{f} ({}):\n{}", describe(&defines), e.message));
            }
        }
    }

    // Pass types whose built-in shader path does not exist on disk.
    for t in passes.types.values() {
        if let Some(p) = t.shader()
            && !root.join(p).is_file()
        {
            failures.push(format!(
                "pass type `{}` names shader {p}, which is not a file in the checkout",
                t.spec().name
            ));
        }
    }

    assert!(
        failures.is_empty(),
        "{} shader problem(s):\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
    eprintln!(
        "validated {} shader files in {compositions} compositions",
        files.len()
    );
}

/// The test above must be able to fail: a broken shader is reported with its
/// file name and a line number.
#[test]
fn a_broken_shader_is_reported_with_file_and_line() {
    let mut shaders = library();
    let source = "#import plait::frame::frame\n\n@fragment\nfn fs_main() -> @location(0) vec4<f32> {\n    return frame.nonexistent;\n}\n";
    let err = shaders
        .compose(Path::new("shaders/broken.wgsl"), source, &[])
        .expect_err("an invalid shader must not compose");
    assert!(
        err.message.contains("broken.wgsl"),
        "message does not name the file:\n{}",
        err.message
    );
    assert!(
        err.message.contains(":5:"),
        "message does not give line 5:\n{}",
        err.message
    );
}
