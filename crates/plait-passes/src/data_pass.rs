//! Pass types declared in TOML next to their WGSL (`shaders/passes/*.toml`,
//! format in [`plait_graph::pass_type_file`]): single-draw passes whose Rust
//! would only restate slots, params and state — the shadow map, occupancy,
//! slab, opacity shadow map, deep opacity and depth list maps, and the
//! fullscreen resolves and composes. Rust stays for what data cannot say:
//! loops (depth range's two draws, depth peeling, k-means) and state chosen
//! by a param (hair shading's blend).

use std::path::Path;

use plait_gpu::pass::PassType;
use plait_graph::pass_type_file::{self, PassTypeFile, check_words_per_texel};
use plait_graph::{
    Error, ErrorKind, Errors, Location, PassTypeSpec, RasterDecl, ResolvedResource, ScheduledPass,
};

/// The library folder of the pass-type files: every `*.toml` in it is a pass
/// type (search path first, then the built-in copies). No list names them.
pub const PASS_TYPE_DIR: &str = "shaders/passes";

/// A pass type read from a pass-type file.
pub struct DataPassType {
    file: PassTypeFile,
    /// Library path of its shader (`shaders/passes/occupancy.wgsl`).
    shader: String,
}

impl DataPassType {
    /// Parse the pass-type file at `path` (on disk or built in); its shader is
    /// the file it names beside it, which must exist there.
    pub fn load(path: &Path) -> Result<DataPassType, Errors> {
        let text = plait_assets::read_to_string(path).map_err(|e| {
            Errors(vec![Error::new(
                Location::Path {
                    path: path.to_owned(),
                },
                ErrorKind::Schema(format!("cannot read file: {e}")),
            )])
        })?;
        let file = pass_type_file::parse(path, &text)?;
        let shader = format!("{PASS_TYPE_DIR}/{}", file.shader.value);
        // The file beside this one is on the search path too, so looking the
        // library path up finds it (or an earlier folder's copy, as for any
        // library file).
        if plait_assets::find(&shader).is_none() {
            return Err(Errors(vec![Error::new(
                file.shader.location.clone(),
                ErrorKind::Schema(format!(
                    "shader `{}` is neither beside this file nor in {PASS_TYPE_DIR}/ on the library search path",
                    file.shader.value
                )),
            )]));
        }
        Ok(DataPassType { file, shader })
    }
}

impl PassType for DataPassType {
    fn spec(&self) -> PassTypeSpec {
        self.file.spec.clone()
    }
    fn shader(&self) -> Option<&str> {
        Some(&self.shader)
    }
    fn raster_decl(&self, pass: &ScheduledPass) -> RasterDecl {
        self.file.raster.overridden_by(&pass.raster)
    }
    fn check_sizes(
        &self,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
    ) -> Result<(), String> {
        self.file
            .words_per_texel
            .iter()
            .try_for_each(|w| check_words_per_texel(w, pass, resources).map(|_| ()))
    }
}

/// Every pass-type file of the library, parsed, with the errors of the
/// broken ones (named by file, line and column; compile reports them, so a
/// broken file on `PLAIT_PATH` fails `plait check` rather than plait).
pub fn discover() -> (Vec<DataPassType>, Vec<Error>) {
    let mut types = Vec::new();
    let mut errors = Vec::new();
    for path in plait_assets::list(PASS_TYPE_DIR, "toml") {
        match DataPassType::load(&path) {
            Ok(t) => types.push(t),
            Err(e) => errors.extend(e.0),
        }
    }
    (types, errors)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pass_type_file_of_the_checkout_is_found_and_parses() {
        let (types, errors) = discover();
        assert!(errors.is_empty(), "{}", Errors(errors));
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders/passes");
        let on_disk: Vec<String> = std::fs::read_dir(&dir)
            .expect("shaders/passes exists")
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|n| n.ends_with(".toml"))
            .collect();
        assert!(!on_disk.is_empty());
        assert_eq!(types.len(), on_disk.len(), "one pass type per file");
    }

    #[test]
    fn a_pass_type_whose_shader_is_missing_is_an_error_at_its_key() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("lost.toml");
        std::fs::write(
            &path,
            "[pass_type]\nname = \"lost\"\nshape = \"compute\"\nsource = \"-\"\ndescription = \"-\"\nshader = \"nowhere.wgsl\"\n",
        )
        .expect("write");
        let e = DataPassType::load(&path)
            .err()
            .expect("refused")
            .to_string();
        assert!(e.contains("lost.toml:6:10"), "{e}");
        assert!(
            e.contains("`nowhere.wgsl` is neither beside this file"),
            "{e}"
        );
    }
}
