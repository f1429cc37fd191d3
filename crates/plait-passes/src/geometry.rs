//! The `geometry` point: which strands a hair draw rasterizes, and for how
//! many of the groom's strands each one stands (`strand_weight(strand_id)`,
//! `techniques/geometry/point.toml`). Every pass that draws hair uses it
//! without asking (the point file's `draws = ["hair"]`), so its params are
//! the library's shared params, taken by every hair draw whatever its type.

use plait_graph::{Access, Format, ParamSpec, SlotSpec};

use crate::spec_util::{SlotExt, choice, float, int, texture};

/// `wisp_count` when a pipeline does not set it.
pub const WISP_COUNT_DEFAULT: i64 = 300;

/// `wisp_lod_screen_fraction` when a pipeline does not set it: the wisps'
/// level of detail starts where `lod`'s default does.
pub const WISP_LOD_SCREEN_FRACTION_DEFAULT: f64 = 0.5;

/// The providers, by param value: every module `plait::geometry::NAME` found.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("geometry")
}

/// The providers' optional input slots, taken by every pass drawing hair.
pub fn slots() -> Vec<SlotSpec> {
    vec![
        texture(
            "wisp_texture",
            Access::Sampled,
            &[Format::Rgba16Float],
            "wisps: the strand texture and its mip chain side by side (Halén & Wester 2007 §2.3–2.4)",
        )
        .optional(),
    ]
}

/// Params of the providers (filled into `geometry_params` by member name).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    vec![
        choice(
            "geometry",
            "strands",
            &providers(library)
                .iter()
                .map(String::as_str)
                .collect::<Vec<_>>(),
            "which strands a hair draw rasterizes, and how wide each is (geometry provider)",
        ),
        float(
            "lod_screen_fraction",
            0.5,
            0.001,
            1.0,
            "lod: the groom's height on screen (fraction of the screen height) from which every strand is drawn; below it the strand count falls in proportion",
        ),
        int(
            "wisp_count",
            WISP_COUNT_DEFAULT,
            1,
            4096,
            "wisps: how many wisps relaxation dart throwing spreads over the scalp (at most one per strand root; O(n²) at load)",
        ),
        float(
            "wisp_lod_screen_fraction",
            WISP_LOD_SCREEN_FRACTION_DEFAULT,
            0.0,
            1.0,
            "wisps: the groom's height on screen (fraction of the screen height) from which every wisp is drawn; below it fewer, wider wisps (Halén & Wester 2007 §2.4); 0 draws every wisp always",
        ),
        float(
            "wisp_width",
            0.15,
            1e-4,
            10.0,
            "wisps: a wisp's width across the view (model units)",
        ),
    ]
}
