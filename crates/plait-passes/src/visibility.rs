//! Visibility providers: every self-shadowing technique answers one WGSL
//! question, `hair_visibility(world) -> f32`, from its own light maps. A
//! shading pass imports `plait::self_shadow` (generated from
//! `techniques/self_shadow/point.toml`), which picks the provider its
//! `self_shadow` param names, and binds the provider's maps under the `vis_*`
//! slots. Adding a provider is a WGSL module in its technique's folder (no
//! shading pass changes, no import line; `plait::self_shadow::tressfx` was
//! added so); maps or params no provider has used yet are declared here.

use plait_graph::{Access, Format, ParamSpec, SlotSpec};

use crate::spec_util::{DEPTH, SlotExt, buffer, choice, float, texture};

/// The providers, by param value: every module `plait::self_shadow::NAME`
/// found (`techniques/self_shadow/tressfx/self_shadow.wgsl` →
/// `self_shadow = "tressfx"`), so a provider that needs no maps or params
/// beyond those below is WGSL alone.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("self_shadow")
}

/// The optional input slots any provider may need.
pub fn slots() -> Vec<SlotSpec> {
    vec![
        texture(
            "vis_depth",
            Access::Sampled,
            DEPTH,
            "modified_shadow_map, tressfx: nearest hair depth from the light",
        )
        .optional(),
        texture(
            "vis_range",
            Access::Sampled,
            &[Format::Rg32Float],
            "occupancy: light-view depth range",
        )
        .optional(),
        buffer(
            "vis_bits",
            Access::StorageRead,
            "occupancy: light-view occupancy bits",
        )
        .optional(),
        buffer(
            "vis_slabs",
            Access::StorageRead,
            "occupancy: light-view slab counts",
        )
        .optional(),
        buffer(
            "vis_layers",
            Access::StorageRead,
            "deep_opacity: fragment count per layer after z0 (Yuksel & Keyser 2008 §3)",
        )
        .optional(),
        buffer(
            "vis_slices",
            Access::StorageRead,
            "opacity_shadow_maps: fragment count per uniform slice (Halén & Wester 2007 §5.7)",
        )
        .optional(),
        buffer(
            "vis_clusters",
            Access::StorageRead,
            "density_clustering: k-means stages of (count, Σz, Σz²) per cluster (Mertens et al. 2004)",
        )
        .optional(),
        buffer(
            "vis_lists",
            Access::StorageRead,
            "exact: every fragment's light depth per texel (Sintorn & Assarsson 2009 Fig. 5)",
        )
        .optional(),
        buffer(
            "vis_counts",
            Access::StorageRead,
            "exact: fragments per light texel",
        )
        .optional(),
        buffer(
            "vis_toward",
            Access::StorageRead,
            "density_volume: per voxel, the strands between its centre and the light (Jansson et al. 2019)",
        )
        .optional(),
        buffer(
            "vis_box",
            Access::StorageRead,
            "density_volume: the volume's box, resolution and march step",
        )
        .optional(),
    ]
}

/// Params of the providers (filled into `visibility_params` by name).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    vec![
        choice(
            "self_shadow",
            "none",
            &providers(library)
                .iter()
                .map(String::as_str)
                .collect::<Vec<_>>(),
            "self-shadowing technique (visibility provider) used for hair shadows",
        ),
        float(
            "density",
            40.0,
            0.0,
            1e6,
            "modified_shadow_map, tressfx: extinction per world unit behind the first strand (tressfx: shadow_weight / fiber spacing)",
        ),
        float(
            "shadow_weight",
            0.05,
            0.0,
            100.0,
            "occupancy, deep_opacity, opacity_shadow_maps, density_clustering, exact, tressfx: opacity w added per hair fragment in front (§3.3; tressfx: w = -ln(1 - α))",
        ),
        float(
            "shadow_opaque",
            0.0,
            0.0,
            1.0,
            "exact: 1 = fibres opaque to light, T = product of (1 - share) over the fibres in front (a path tracer's single scattering); 0 = exp(-shadow_weight * sum of shares); between: their mix",
        ),
        float(
            "layer_size",
            0.05,
            1e-6,
            1e6,
            "deep_opacity: first layer thickness in world units (layer k is k times as thick)",
        ),
    ]
}
