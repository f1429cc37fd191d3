//! Scene resources: buffers the scene provides, named in a pass's `reads` and
//! `writes` like declared resources but never declared (their sizes are the
//! scene's, not the pipeline's). They let simulation and guide interpolation
//! be ordinary compute passes of the graph (Halén & Wester 2007 §5.5: the
//! guides are simulated, the drawn strands rebuilt from them every frame).
//!
//! - A raster pass with `draw = "hair"` reads `hair_vertices` and
//!   `hair_indices` without naming them, so a pass that writes the vertices
//!   runs before every hair draw and is live whenever one is.
//! - Their contents persist from frame to frame (the scene owns them, the
//!   engine never clears them): `guide_positions` and `guide_previous` are the
//!   simulation's state.
//! - Writing a read-only one is an error at the slot that names it.

/// One buffer the scene provides.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneResource {
    pub name: &'static str,
    /// Passes may bind it under `writes`.
    pub writable: bool,
    /// Layout and meaning, for listings and messages.
    pub doc: &'static str,
}

/// Every scene resource, in a fixed order (their ids follow the declared ones).
pub const SCENE_RESOURCES: &[SceneResource] = &[
    SceneResource {
        name: "hair_vertices",
        writable: true,
        doc: "the drawn hair: one StrandVertex (48 B: position, thickness, tangent, alpha, colour, strand id) per point",
    },
    SceneResource {
        name: "hair_indices",
        writable: false,
        doc: "line-list indices of the drawn hair, two u32 per segment",
    },
    SceneResource {
        name: "guide_rest",
        writable: false,
        doc: "guide points at rest, vec4 per point: xyz, w = rest length of the segment to the previous point (0 at the root)",
    },
    SceneResource {
        name: "guide_strands",
        writable: false,
        doc: "per guide strand: vec2<u32> first point, point count",
    },
    SceneResource {
        name: "guide_positions",
        writable: true,
        doc: "guide points now, vec4 per point (w unused); persists between frames, starts at rest",
    },
    SceneResource {
        name: "guide_previous",
        writable: true,
        doc: "guide points one step ago, vec4 per point (Verlet state); persists, starts at rest",
    },
    SceneResource {
        name: "strand_guides",
        writable: false,
        doc: "per drawn strand: vec4<u32>(guide 0, 1, 2, first point), vec4<f32>(weights, scale), vec4<f32>(rest root, point count)",
    },
    SceneResource {
        name: "head_colliders",
        writable: false,
        doc: "ellipsoids the hair collides with, at rest: vec4 centre, vec4 radii each (none: one with radii 0)",
    },
    SceneResource {
        name: "head_sdf",
        writable: false,
        doc: "the head mesh's signed distance field at rest, f32s: origin xyz, cell, dims xyz (u32 bits), 1 if present (0: no head mesh), then the distances, x fastest",
    },
    SceneResource {
        name: "opaque_vertices",
        writable: false,
        doc: "the meshes' vertices (head at rest, ground, [[meshes]]): 10 f32 each (40 B: position, normal, albedo, 1 for the head's), what the acceleration structure's triangles index",
    },
    SceneResource {
        name: "opaque_indices",
        writable: false,
        doc: "the meshes' triangle indices into opaque_vertices, three u32 per triangle, mesh after mesh",
    },
    SceneResource {
        name: "opaque_meshes",
        writable: false,
        doc: "per mesh, in the structure's instance order: vec4<u32>(first index in opaque_indices, index count, 1 for the head, 0)",
    },
];

/// The scene resources a `draw = "hair"` pass reads without naming them.
pub const DRAWN_HAIR: &[&str] = &["hair_vertices", "hair_indices"];

/// The scene resource named `name` and its index in [`SCENE_RESOURCES`].
pub fn scene_resource(name: &str) -> Option<(usize, &'static SceneResource)> {
    SCENE_RESOURCES
        .iter()
        .enumerate()
        .find(|(_, r)| r.name == name)
}
