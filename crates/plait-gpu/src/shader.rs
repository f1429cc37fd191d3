//! Shader composition with naga_oil: `#import plait::frame`, `#ifdef`, params as defines.
//!
//! Library modules are found, not listed ([`crate::library`]): every WGSL
//! file of `shaders/` and `techniques/` declaring `#define_import_path`, read
//! at run time from the library search path (`PLAIT_PATH`, or the checkout
//! plait was built from) so an edit needs no rebuild, with the copies
//! compiled into the binary as fallback; a pass shader anywhere on disk can
//! import them. Errors carry the shader's path and
//! naga's diagnostic with line and column.

use std::borrow::Cow;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use plait_graph::techniques::WgslPoint;

use naga_oil::compose::{
    ComposableModuleDescriptor, Composer, NagaModuleDescriptor, ShaderDefValue, ShaderLanguage,
    ShaderType,
};

/// Checked by composing a call to the provider's function (and to its
/// `[wgsl.also]` function, when the point has one), so a missing function
/// or a wrong signature is an error that names the provider's file before
/// any pass uses it.
fn check_contract(
    composer: &mut Composer,
    point: &WgslPoint,
    name: &str,
    path: &Path,
    source: &str,
) -> Result<(), ShaderError> {
    let main = (
        point.function.as_str(),
        point.arguments.as_str(),
        point.returns.as_str(),
    );
    check_function(composer, point, name, path, source, main)?;
    if let Some(a) = &point.also {
        let also = (
            a.function.as_str(),
            a.arguments.as_str(),
            a.returns.as_str(),
        );
        check_function(composer, point, name, path, source, also)?;
    }
    Ok(())
}

/// One function of a point's contract: `(name, arguments, return type)`.
fn check_function(
    composer: &mut Composer,
    point: &WgslPoint,
    name: &str,
    path: &Path,
    source: &str,
    (function, arguments, returns): (&str, &str, &str),
) -> Result<(), ShaderError> {
    let argument_names = plait_graph::techniques::argument_names(arguments).join(", ");
    let probe = format!(
        "#import {}::{name}::{function}\n\
         fn plait_contract({arguments}) -> {returns} {{ return {function}({argument_names}); }}\n",
        point.providers,
    );
    // The error points at the provider's function, or at the top of the file
    // when it has none.
    let (line, column) = source
        .lines()
        .enumerate()
        .find_map(|(i, l)| {
            let at = l.find(&format!("fn {function}("))?;
            Some((i + 1, at + 1))
        })
        .unwrap_or((1, 1));
    let missing = |detail: String| ShaderError {
        path: path.to_owned(),
        message: format!(
            "{}:{line}:{column}: {} provider `{name}` must define `fn {function}({arguments}) -> {returns}` (the contract in {}):\n{detail}",
            path.display(),
            point.point,
            point.file,
        ),
    };
    // No such function in the text: refused before composing. naga_oil
    // panics (naga's GLSL writer, unreachable) composing a module that
    // declares an acceleration structure and no function — a ray-traced
    // provider cut short — where it should report the missing function.
    if !source.contains(&format!("fn {function}(")) {
        return Err(missing(format!("no `fn {function}(` in the file")));
    }
    composer
        .make_naga_module(NagaModuleDescriptor {
            source: &probe,
            file_path: &format!("the contract of {}", path.display()),
            shader_type: ShaderType::Wgsl,
            shader_defs: HashMap::new(),
            additional_imports: &[],
        })
        .map(|_| ())
        .map_err(|e| missing(e.emit_to_string(composer)))
}

/// The text of a library file (a pass type's shader,
/// `shaders/passes/occupancy.wgsl`): the copy on the search path when there
/// is one, so edits apply without a rebuild, else the built-in copy. Returns
/// the path messages should name.
pub fn library_file(name: &str) -> Result<(PathBuf, Cow<'static, str>), ShaderError> {
    let Some(path) = plait_assets::find(name) else {
        return Err(ShaderError {
            message: format!(
                "{name}: no such file on the library search path ({}) nor among the built-in copies",
                plait_assets::SEARCH_PATH_VAR
            ),
            path: PathBuf::from(name),
        });
    };
    match plait_assets::read_to_string(&path) {
        Ok(text) => Ok((path, text)),
        Err(e) => Err(ShaderError {
            message: format!("{}: cannot read file: {e}", path.display()),
            path,
        }),
    }
}

/// Read a shader a pipeline names (`shader = "…"`): from disk, or a built-in
/// copy (`<built-in>/shaders/…`).
pub fn read_shader_file(path: &Path) -> std::io::Result<Cow<'static, str>> {
    plait_assets::read_to_string(path)
}

/// A shader that failed to parse, compose or validate.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{message}")]
pub struct ShaderError {
    pub path: PathBuf,
    /// naga's diagnostic, naming the file, line and column.
    pub message: String,
}

/// A define passed to a shader: `#ifdef NAME` / `#if NAME == 3`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Define {
    Bool(bool),
    Int(i32),
    UInt(u32),
}

/// The composer with plait's library modules loaded.
pub struct ShaderLibrary {
    composer: Composer,
}

impl ShaderLibrary {
    /// The composer with the modules of `library` added, each provider
    /// checked against its point's contract.
    pub fn new(library: &crate::library::Library) -> Result<Self, ShaderError> {
        let mut composer = Composer::default().with_capabilities(naga::valid::Capabilities::all());
        composer.validate = true;
        for module in &library.modules {
            let file_path = module.path.display().to_string();
            let added = composer.add_composable_module(ComposableModuleDescriptor {
                source: &module.source,
                file_path: &file_path,
                language: ShaderLanguage::Wgsl,
                as_name: None,
                additional_imports: &[],
                shader_defs: HashMap::new(),
            });
            if let Err(e) = added {
                return Err(ShaderError {
                    message: e.emit_to_string(&composer),
                    path: module.path.clone(),
                });
            }
        }
        for point in &library.points {
            for (name, path) in &point.providers {
                let source = library
                    .modules
                    .iter()
                    .find(|m| &m.path == path)
                    .map_or("", |m| m.source.as_str());
                check_contract(&mut composer, &point.contract, name, path, source)?;
            }
        }
        Ok(ShaderLibrary { composer })
    }

    /// Compose and validate a shader. `path` is only used in messages.
    pub fn compose(
        &mut self,
        path: &Path,
        source: &str,
        defines: &[(String, Define)],
    ) -> Result<naga::Module, ShaderError> {
        let shader_defs = defines
            .iter()
            .map(|(k, v)| {
                let v = match *v {
                    Define::Bool(b) => ShaderDefValue::Bool(b),
                    Define::Int(i) => ShaderDefValue::Int(i),
                    Define::UInt(u) => ShaderDefValue::UInt(u),
                };
                (k.clone(), v)
            })
            .collect();
        let file_path = path.display().to_string();
        self.composer
            .make_naga_module(NagaModuleDescriptor {
                source,
                file_path: &file_path,
                shader_type: ShaderType::Wgsl,
                shader_defs,
                additional_imports: &[],
            })
            .map_err(|e| ShaderError {
                path: path.to_owned(),
                message: e.emit_to_string(&self.composer),
            })
    }
}
