//! The data-only pass types: a WGSL file and a few lines of TOML, no Rust.
//!
//! `fullscreen` draws one triangle over its colour targets (the pass's
//! `writes` that the shader does not bind, in file order); `raster` draws the
//! scene's hair or opaque geometry (`draw`) from the light or the camera
//! (`view`) into its colour and depth targets, with the state its TOML sets
//! (`depth`, `blend`, `cull`); `compute` dispatches one thread per texel of
//! its first written texture (or per 4 bytes of its first written buffer).
//! Every other slot is matched by name to a shader binding in group 1, checked
//! with naga's reflection when the pipeline is loaded; a `params` uniform is
//! filled from the pass params by member name.
//!
//! A raster pass's storage writes respect its depth test whatever the shader
//! does (the engine's `depth_guard`); `plait check` refuses a data-only pass
//! whose depth target would make that impossible on some adapter.

use plait_gpu::pass::PassType;
use plait_graph::{PassShape, PassTypeSpec};

/// One data-only pass type of `shape`.
pub struct DataOnly {
    pub name: &'static str,
    pub shape: PassShape,
    pub description: &'static str,
}

pub const FULLSCREEN: DataOnly = DataOnly {
    name: "fullscreen",
    shape: PassShape::Fullscreen,
    description: "A WGSL fragment shader over the whole target; slots are the shader's bindings; `blend` per colour target.",
};

pub const RASTER: DataOnly = DataOnly {
    name: "raster",
    shape: PassShape::Raster,
    description: "A WGSL vertex + fragment shader drawing `draw` from `view`; slots are the shader's bindings, other textures its targets; `depth`, `blend`, `cull`, `alpha_to_coverage` and `loads` set its state.",
};

pub const COMPUTE: DataOnly = DataOnly {
    name: "compute",
    shape: PassShape::Compute,
    description: "A WGSL compute shader; slots are the shader's bindings.",
};

// The three data-only types are found by the library like every Rust pass type.
inventory::submit! { crate::RustPassType(|_| Box::new(FULLSCREEN)) }
inventory::submit! { crate::RustPassType(|_| Box::new(RASTER)) }
inventory::submit! { crate::RustPassType(|_| Box::new(COMPUTE)) }

impl PassType for DataOnly {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec::data_only(self.name, self.shape, self.description)
    }
    fn shader(&self) -> Option<&str> {
        None
    }
}
