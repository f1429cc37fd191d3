//! Pass types declared in TOML next to their WGSL (`shaders/passes/*.toml`,
//! format in [`plait_graph::pass_type_file`]): single-draw passes whose Rust
//! would only restate slots, params and state — the shadow map, occupancy,
//! slab, opacity shadow map, deep opacity and depth list maps, and the
//! fullscreen resolves and composes. Rust stays for what data cannot say:
//! loops (depth range's two draws, depth peeling, k-means) and state chosen
//! by a param (hair shading's blend).

use plait_gpu::pass::{BuiltinShader, PassType};
use plait_graph::pass_type_file::{self, PassTypeFile, check_words_per_texel};
use plait_graph::{Errors, PassTypeSpec, RasterDecl, ResolvedResource, ScheduledPass};

/// The pass-type files compiled into plait, and the shaders they name.
pub const FILES: &[BuiltinShader] = &[
    plait_gpu::builtin_shader!("passes/shadow_map.toml"),
    plait_gpu::builtin_shader!("passes/occupancy.toml"),
    plait_gpu::builtin_shader!("passes/slab.toml"),
    plait_gpu::builtin_shader!("passes/occupancy_slabs.toml"),
    plait_gpu::builtin_shader!("passes/deep_opacity.toml"),
    plait_gpu::builtin_shader!("passes/opacity_shadow_maps.toml"),
    plait_gpu::builtin_shader!("passes/depth_lists.toml"),
    plait_gpu::builtin_shader!("passes/compose.toml"),
    plait_gpu::builtin_shader!("passes/alpha_sum.toml"),
    plait_gpu::builtin_shader!("passes/compose_hair_over.toml"),
    plait_gpu::builtin_shader!("passes/weighted_average_resolve.toml"),
    plait_gpu::builtin_shader!("passes/fragment_list_resolve.toml"),
    // Environment lighting (Xing et al. 2012 §3, §5).
    plait_gpu::builtin_shader!("passes/environment_cube.toml"),
    plait_gpu::builtin_shader!("passes/irradiance_maps.toml"),
    plait_gpu::builtin_shader!("passes/sh_project.toml"),
    plait_gpu::builtin_shader!("passes/sh_kernel.toml"),
    plait_gpu::builtin_shader!("passes/sh_irradiance_maps.toml"),
    plait_gpu::builtin_shader!("passes/marschner_tables.toml"),
];

const SHADERS: &[BuiltinShader] = &[
    plait_gpu::builtin_shader!("passes/shadow_map.wgsl"),
    plait_gpu::builtin_shader!("passes/occupancy.wgsl"),
    plait_gpu::builtin_shader!("passes/slice_counts.wgsl"),
    plait_gpu::builtin_shader!("passes/occupancy_slabs.wgsl"),
    plait_gpu::builtin_shader!("passes/deep_opacity.wgsl"),
    plait_gpu::builtin_shader!("passes/depth_lists.wgsl"),
    plait_gpu::builtin_shader!("passes/compose.wgsl"),
    plait_gpu::builtin_shader!("passes/alpha_sum.wgsl"),
    plait_gpu::builtin_shader!("passes/compose_hair_over.wgsl"),
    plait_gpu::builtin_shader!("passes/weighted_average_resolve.wgsl"),
    plait_gpu::builtin_shader!("passes/fragment_list_resolve.wgsl"),
    plait_gpu::builtin_shader!("passes/environment_cube.wgsl"),
    plait_gpu::builtin_shader!("passes/irradiance_maps.wgsl"),
    plait_gpu::builtin_shader!("passes/sh_project.wgsl"),
    plait_gpu::builtin_shader!("passes/sh_kernel.wgsl"),
    plait_gpu::builtin_shader!("passes/sh_irradiance_maps.wgsl"),
    plait_gpu::builtin_shader!("passes/marschner_tables.wgsl"),
];

/// A pass type read from a pass-type file.
pub struct DataPassType {
    file: PassTypeFile,
    shader: BuiltinShader,
}

impl DataPassType {
    /// Parse a built-in pass-type file; its shader must be built in too.
    pub fn builtin((path, text): BuiltinShader) -> Result<DataPassType, Errors> {
        let file = pass_type_file::parse(path.as_ref(), text)?;
        let dir = path.rsplit_once('/').map_or("", |(d, _)| d);
        let shader_path = format!("{dir}/{}", file.shader.value);
        let Some(&shader) = SHADERS.iter().find(|(p, _)| *p == shader_path) else {
            return Err(Errors(vec![plait_graph::Error::new(
                file.shader.location.clone(),
                plait_graph::ErrorKind::Schema(format!(
                    "shader {shader_path} is not among the built-in pass shaders (plait_passes::data_pass::SHADERS)"
                )),
            )]));
        };
        Ok(DataPassType { file, shader })
    }
}

impl PassType for DataPassType {
    fn spec(&self) -> PassTypeSpec {
        self.file.spec.clone()
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some(self.shader)
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

/// Every built-in pass-type file, parsed. A broken built-in file is a bug in
/// plait, not in a user's pipeline: the test below keeps them parseable, and
/// the message names the file, line and column.
pub fn builtin_types() -> Vec<DataPassType> {
    FILES
        .iter()
        .map(|&f| {
            DataPassType::builtin(f)
                .unwrap_or_else(|e| panic!("built-in pass-type file {}:\n{e}", f.0))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_pass_type_file_parses_and_is_listed() {
        let types = builtin_types();
        assert_eq!(types.len(), FILES.len());
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders/passes");
        let on_disk: Vec<String> = std::fs::read_dir(&dir)
            .expect("shaders/passes exists")
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|n| n.ends_with(".toml"))
            .collect();
        assert!(!on_disk.is_empty());
        for name in on_disk {
            assert!(
                FILES
                    .iter()
                    .any(|(p, _)| *p == format!("shaders/passes/{name}")),
                "shaders/passes/{name} is not listed in plait_passes::data_pass::FILES"
            );
        }
    }
}
