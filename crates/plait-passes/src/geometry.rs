//! The `geometry` point: which strands a hair draw rasterizes, and for how
//! many of the groom's strands each one stands (`strand_weight(strand_id)`,
//! `techniques/geometry/point.toml`). Every pass that draws hair uses it
//! without asking (the point file's `draws = ["hair"]`), so its params are
//! the library's shared params, taken by every hair draw whatever its type.

use plait_graph::{ParamSpec, SlotSpec};

/// The providers, by param value: every module `plait::geometry::NAME` found.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("geometry")
}

/// The providers' optional input slots, taken by every pass drawing hair
/// (`techniques/geometry/point.toml`, `[inputs]`).
pub fn slots(library: &plait_gpu::PassLibrary) -> Vec<SlotSpec> {
    crate::points::slots(library, "geometry")
}

/// Params of the providers (filled into `geometry_params` by member name).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    crate::points::params(library, "geometry")
}
