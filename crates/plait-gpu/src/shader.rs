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
        "shaders/lib/cube.wgsl",
        include_str!("../../../shaders/lib/cube.wgsl"),
    ),
    (
        "shaders/lib/sh.wgsl",
        include_str!("../../../shaders/lib/sh.wgsl"),
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
        "shaders/lib/hair_bounds.wgsl",
        include_str!("../../../shaders/lib/hair_bounds.wgsl"),
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
        "shaders/lib/shading/kajiya_kay.wgsl",
        include_str!("../../../shaders/lib/shading/kajiya_kay.wgsl"),
    ),
    (
        "shaders/lib/shading/marschner.wgsl",
        include_str!("../../../shaders/lib/shading/marschner.wgsl"),
    ),
    (
        "shaders/lib/shading/marschner_reference.wgsl",
        include_str!("../../../shaders/lib/shading/marschner_reference.wgsl"),
    ),
    (
        "shaders/lib/hair_direct.wgsl",
        include_str!("../../../shaders/lib/hair_direct.wgsl"),
    ),
    (
        "shaders/lib/lighting/ambient.wgsl",
        include_str!("../../../shaders/lib/lighting/ambient.wgsl"),
    ),
    (
        "shaders/lib/lighting/irradiance_maps.wgsl",
        include_str!("../../../shaders/lib/lighting/irradiance_maps.wgsl"),
    ),
    (
        "shaders/lib/lighting/environment_reference.wgsl",
        include_str!("../../../shaders/lib/lighting/environment_reference.wgsl"),
    ),
    (
        "shaders/lib/hair_environment.wgsl",
        include_str!("../../../shaders/lib/hair_environment.wgsl"),
    ),
    (
        "shaders/lib/occlusion/none.wgsl",
        include_str!("../../../shaders/lib/occlusion/none.wgsl"),
    ),
    (
        "shaders/lib/occlusion/per_vertex.wgsl",
        include_str!("../../../shaders/lib/occlusion/per_vertex.wgsl"),
    ),
    (
        "shaders/lib/hair_occlusion.wgsl",
        include_str!("../../../shaders/lib/hair_occlusion.wgsl"),
    ),
    (
        "shaders/lib/strand_coverage.wgsl",
        include_str!("../../../shaders/lib/strand_coverage.wgsl"),
    ),
    (
        "shaders/lib/hair_fragment.wgsl",
        include_str!("../../../shaders/lib/hair_fragment.wgsl"),
    ),
];

/// A choice point answered in WGSL: every technique of the point supplies a
/// provider module `MODULE::NAME` (file `DIR/NAME.wgsl`) defining one
/// function, and a selector module imports the one the pass's param names
/// (`#ifdef PARAM_NAME`). A new provider is a WGSL file plus its import line
/// in the selector, never a line of Rust: files on the search path beyond the
/// built-in list are found by [`extra_providers`].
pub struct ProviderPoint {
    /// Folder of the provider files, e.g. `shaders/lib/visibility`.
    pub dir: &'static str,
    /// The module that picks a provider by define; providers are added to the
    /// composer before it.
    pub selector: &'static str,
    /// Module path prefix: `plait::visibility` → `plait::visibility::NAME`.
    pub module: &'static str,
    /// The function every provider defines, and its WGSL signature.
    pub function: &'static str,
    pub params: &'static str,
    pub returns: &'static str,
}

/// Self-shadowing (`visibility`), key-light shading (`shading`), light from
/// the rest of the environment (`lighting`), per-vertex occlusion (`occlusion`).
pub const PROVIDER_POINTS: &[ProviderPoint] = &[
    ProviderPoint {
        dir: "shaders/lib/visibility",
        selector: "shaders/lib/self_shadow.wgsl",
        module: "plait::visibility",
        function: "hair_visibility",
        params: "world: vec3<f32>",
        returns: "f32",
    },
    ProviderPoint {
        dir: "shaders/lib/shading",
        selector: "shaders/lib/hair_direct.wgsl",
        module: "plait::shading",
        function: "hair_direct",
        params: "tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>",
        returns: "vec3<f32>",
    },
    ProviderPoint {
        dir: "shaders/lib/lighting",
        selector: "shaders/lib/hair_environment.wgsl",
        module: "plait::lighting",
        function: "hair_environment",
        params: "world: vec3<f32>, tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>",
        returns: "vec3<f32>",
    },
    ProviderPoint {
        dir: "shaders/lib/occlusion",
        selector: "shaders/lib/hair_occlusion.wgsl",
        module: "plait::occlusion",
        function: "vertex_occlusion",
        params: "vertex_index: u32",
        returns: "f32",
    },
];

impl ProviderPoint {
    /// The point by its folder's last component (`visibility`, `shading`, …).
    pub fn named(name: &str) -> Option<&'static ProviderPoint> {
        PROVIDER_POINTS
            .iter()
            .find(|p| p.dir.rsplit('/').next() == Some(name))
    }

    /// Provider names, by param value: the built-in modules, then files on
    /// the search path (`tressfx.wgsl` → `visibility = "tressfx"`).
    pub fn providers(&self) -> Vec<String> {
        let prefix = format!("{}/", self.dir);
        let built_in = LIBRARY_MODULES.iter().filter_map(|(path, _)| {
            path.strip_prefix(prefix.as_str())?
                .strip_suffix(".wgsl")
                .map(str::to_owned)
        });
        let extra = extra_providers(self)
            .into_iter()
            .filter_map(|p| p.file_stem().and_then(|s| s.to_str()).map(str::to_owned));
        built_in.chain(extra).collect()
    }

    fn signature(&self) -> String {
        format!("fn {}({}) -> {}", self.function, self.params, self.returns)
    }

    /// Checked by composing a call to the provider's function, so a missing
    /// function or a wrong signature is an error that names the provider's
    /// file before any pass uses it.
    fn check_contract(&self, composer: &mut Composer, path: &Path) -> Result<(), ShaderError> {
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        let args: Vec<&str> = self
            .params
            .split(',')
            .filter_map(|p| p.split(':').next())
            .map(str::trim)
            .collect();
        let probe = format!(
            "#import {}::{name}::{}\n\
             fn plait_contract({}) -> {} {{ return {}({}); }}\n",
            self.module,
            self.function,
            self.params,
            self.returns,
            self.function,
            args.join(", ")
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
                    "{} provider `{name}` must define `{}`:\n{}",
                    self.dir.rsplit('/').next().unwrap_or(""),
                    self.signature(),
                    e.emit_to_string(composer)
                ),
            })
    }
}

/// Provider modules of `point` that are not in [`LIBRARY_MODULES`]: files in
/// its folder on the search path or among the built-in copies.
pub fn extra_providers(point: &ProviderPoint) -> Vec<PathBuf> {
    let prefix = format!("{}/", point.dir);
    plait_assets::list(point.dir, "wgsl")
        .into_iter()
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            !LIBRARY_MODULES
                .iter()
                .any(|(known, _)| known.strip_prefix(prefix.as_str()) == Some(name))
        })
        .collect()
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
                message: format!("{}: cannot read file: {e}", path.display()),
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
            if let Some(point) = PROVIDER_POINTS.iter().find(|p| p.selector == *name) {
                // Providers beyond the built-in list go in before the selector
                // that imports them.
                for path in extra_providers(point) {
                    let source = plait_assets::read_to_string(&path).map_err(|e| ShaderError {
                        message: format!("{}: cannot read file: {e}", path.display()),
                        path: path.clone(),
                    })?;
                    add(&mut composer, path, &source)?;
                }
            }
            let (path, source) = library_source(name, builtin)?;
            add(&mut composer, path, &source)?;
        }
        for point in PROVIDER_POINTS {
            let prefix = format!("{}/", point.dir);
            let providers = LIBRARY_MODULES
                .iter()
                .filter(|(name, _)| name.starts_with(prefix.as_str()))
                .map(|(name, _)| PathBuf::from(name))
                .chain(extra_providers(point));
            for path in providers {
                point.check_contract(&mut composer, &path)?;
            }
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
