//! Shader composition with naga_oil: `#import plait::frame`, `#ifdef`, params as defines.
//!
//! Library modules live in `shaders/lib/`. Like the pass types' own shaders
//! they are read at run time from the library search path (`PLAIT_PATH`, or
//! the checkout plait was built from) so an edit needs no rebuild, with the
//! copies compiled into the binary as fallback ([`library_source`]); a pass
//! shader anywhere on disk can import them. Errors carry the shader's path and
//! naga's diagnostic with line and column.

use std::borrow::Cow;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use naga_oil::compose::{
    ComposableModuleDescriptor, Composer, NagaModuleDescriptor, ShaderDefValue, ShaderLanguage,
    ShaderType,
};

/// A WGSL module importable by every shader, as `(file name, source)`.
pub const LIBRARY_MODULES: &[(&str, &str)] = &[
    (
        "shaders/lib/frame.wgsl",
        include_str!("../../../shaders/lib/frame.wgsl"),
    ),
    (
        "shaders/lib/kajiya_kay.wgsl",
        include_str!("../../../shaders/lib/kajiya_kay.wgsl"),
    ),
    (
        "shaders/lib/marschner.wgsl",
        include_str!("../../../shaders/lib/marschner.wgsl"),
    ),
    (
        "shaders/lib/shadow.wgsl",
        include_str!("../../../shaders/lib/shadow.wgsl"),
    ),
    (
        "shaders/lib/hair_map.wgsl",
        include_str!("../../../shaders/lib/hair_map.wgsl"),
    ),
    (
        "shaders/lib/occupancy.wgsl",
        include_str!("../../../shaders/lib/occupancy.wgsl"),
    ),
    (
        "shaders/lib/visibility/none.wgsl",
        include_str!("../../../shaders/lib/visibility/none.wgsl"),
    ),
    (
        "shaders/lib/visibility/modified_shadow_map.wgsl",
        include_str!("../../../shaders/lib/visibility/modified_shadow_map.wgsl"),
    ),
    (
        "shaders/lib/visibility/occupancy.wgsl",
        include_str!("../../../shaders/lib/visibility/occupancy.wgsl"),
    ),
    (
        "shaders/lib/visibility/deep_opacity.wgsl",
        include_str!("../../../shaders/lib/visibility/deep_opacity.wgsl"),
    ),
    (
        "shaders/lib/visibility/opacity_shadow_maps.wgsl",
        include_str!("../../../shaders/lib/visibility/opacity_shadow_maps.wgsl"),
    ),
    (
        "shaders/lib/visibility/density_clustering.wgsl",
        include_str!("../../../shaders/lib/visibility/density_clustering.wgsl"),
    ),
    (
        "shaders/lib/visibility/exact.wgsl",
        include_str!("../../../shaders/lib/visibility/exact.wgsl"),
    ),
    (
        "shaders/lib/self_shadow.wgsl",
        include_str!("../../../shaders/lib/self_shadow.wgsl"),
    ),
    (
        "shaders/lib/transparency/depth_peel.wgsl",
        include_str!("../../../shaders/lib/transparency/depth_peel.wgsl"),
    ),
    (
        "shaders/lib/transparency/fragment_list.wgsl",
        include_str!("../../../shaders/lib/transparency/fragment_list.wgsl"),
    ),
    (
        "shaders/lib/transparency/weighted_average.wgsl",
        include_str!("../../../shaders/lib/transparency/weighted_average.wgsl"),
    ),
    (
        "shaders/lib/transparency/coverage.wgsl",
        include_str!("../../../shaders/lib/transparency/coverage.wgsl"),
    ),
];

/// The module that picks a visibility provider by define; providers are
/// added to the composer before it.
const SELF_SHADOW_MODULE: &str = "shaders/lib/self_shadow.wgsl";

/// Visibility provider modules of the library that are not in
/// [`LIBRARY_MODULES`]: files in `shaders/lib/visibility/` on the search path
/// or among the built-in copies.
pub fn extra_providers() -> Vec<PathBuf> {
    plait_assets::list("shaders/lib/visibility", "wgsl")
        .into_iter()
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            !LIBRARY_MODULES
                .iter()
                .any(|(known, _)| known.strip_prefix("shaders/lib/visibility/") == Some(name))
        })
        .collect()
}

/// The contract of a visibility provider (`shaders/lib/visibility/NAME.wgsl`,
/// module `plait::visibility::NAME`): it defines
/// `fn hair_visibility(world: vec3<f32>) -> f32`. Checked by composing a
/// call to it, so a missing function or a wrong signature is an error that
/// names the provider's file before any pass uses it.
fn check_provider_contract(composer: &mut Composer, path: &Path) -> Result<(), ShaderError> {
    let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    let probe = format!(
        "#import plait::visibility::{name}::hair_visibility\n\
         fn plait_contract(world: vec3<f32>) -> f32 {{ return hair_visibility(world); }}\n"
    );
    composer
        .make_naga_module(NagaModuleDescriptor {
            source: &probe,
            file_path: &format!("the contract of {}", path.display()),
            shader_type: ShaderType::Wgsl,
            shader_defs: HashMap::new(),
            additional_imports: &[],
        })
        .map(|_| ())
        .map_err(|e| ShaderError {
            path: path.to_owned(),
            message: format!(
                "visibility provider `{name}` must define `fn hair_visibility(world: vec3<f32>) -> f32`:\n{}",
                e.emit_to_string(composer)
            ),
        })
}

/// The text of a library file compiled into plait (a library module, a pass
/// type's shader): the copy on the search path when there is one, so edits
/// apply without a rebuild, else the built-in `text`. Returns the path
/// messages should name.
pub fn library_source(
    name: &'static str,
    text: &'static str,
) -> Result<(PathBuf, Cow<'static, str>), ShaderError> {
    match plait_assets::find_on_disk(name) {
        Some(path) => match std::fs::read_to_string(&path) {
            Ok(text) => Ok((path, Cow::Owned(text))),
            Err(e) => Err(ShaderError {
                message: format!("cannot read shader {}: {e}", path.display()),
                path,
            }),
        },
        None => Ok((PathBuf::from(name), Cow::Borrowed(text))),
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
    /// Digest of the library modules' texts as read: part of every pipeline
    /// cache key, since an edited module changes every shader importing it.
    digest: u64,
}

impl ShaderLibrary {
    pub fn new() -> Result<Self, ShaderError> {
        let mut composer = Composer::default().with_capabilities(naga::valid::Capabilities::all());
        composer.validate = true;
        // Library modules import each other; naga_oil needs them added in dependency
        // order, and LIBRARY_MODULES is kept in that order.
        let mut digest = std::hash::DefaultHasher::new();
        let mut add = |composer: &mut Composer, path: PathBuf, source: &str| {
            std::hash::Hash::hash(source, &mut digest);
            let file_path = path.display().to_string();
            composer
                .add_composable_module(ComposableModuleDescriptor {
                    source,
                    file_path: &file_path,
                    language: ShaderLanguage::Wgsl,
                    as_name: None,
                    additional_imports: &[],
                    shader_defs: HashMap::new(),
                })
                .map(|_| ())
                .map_err(|e| ShaderError {
                    message: e.emit_to_string(composer),
                    path,
                })
        };
        for (name, builtin) in LIBRARY_MODULES {
            if *name == SELF_SHADOW_MODULE {
                // Visibility providers beyond the built-in list: a new one is
                // a WGSL file in shaders/lib/visibility/ plus its import line
                // in self_shadow.wgsl, never a line of Rust. They go in before
                // the module that imports them.
                for path in extra_providers() {
                    let source = plait_assets::read_to_string(&path).map_err(|e| ShaderError {
                        message: format!("cannot read shader {}: {e}", path.display()),
                        path: path.clone(),
                    })?;
                    add(&mut composer, path, &source)?;
                }
            }
            let (path, source) = library_source(name, builtin)?;
            add(&mut composer, path, &source)?;
        }
        let providers = LIBRARY_MODULES
            .iter()
            .filter(|(name, _)| name.starts_with("shaders/lib/visibility/"))
            .map(|(name, _)| PathBuf::from(name))
            .chain(extra_providers());
        for path in providers {
            check_provider_contract(&mut composer, &path)?;
        }
        Ok(ShaderLibrary {
            composer,
            digest: std::hash::Hasher::finish(&digest),
        })
    }

    /// Digest of the library modules as read (see the field).
    pub fn library_digest(&self) -> u64 {
        self.digest
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
