//! The `geometry` point: which strands a hair draw rasterizes, and for how
//! many of the groom's strands each one stands (`strand_weight(strand_id)`,
//! `techniques/geometry/point.toml`). Every pass that draws hair uses it
//! without asking (the point file's `draws = ["hair"]`), so its params are
//! the library's shared params, taken by every hair draw whatever its type.

use plait_graph::ParamSpec;

use crate::spec_util::{choice, float};

/// The providers, by param value: every module `plait::geometry::NAME` found.
pub fn providers() -> Vec<String> {
    plait_gpu::library::providers("geometry")
}

/// Params of the providers (filled into `geometry_params` by member name).
pub fn params() -> Vec<ParamSpec> {
    vec![
        choice(
            "geometry",
            "strands",
            &providers().iter().map(String::as_str).collect::<Vec<_>>(),
            "which strands a hair draw rasterizes, and how wide each is (geometry provider)",
        ),
        float(
            "lod_screen_fraction",
            0.5,
            0.001,
            1.0,
            "lod: the groom's height on screen (fraction of the screen height) from which every strand is drawn; below it the strand count falls in proportion",
        ),
    ]
}
