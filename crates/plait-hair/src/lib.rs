//! Strand geometry for plait (issue 3).
//!
//! - [`hair_file`]: Cem Yuksel's binary `.hair` format, read and written exactly.
//! - [`Strands`]: the renderable model (points, per-point thickness, alpha,
//!   color), its bounds, and its GPU line-list layout [`StrandVertex`].
//! - [`mesh`]: opaque geometry (head ellipsoid, ground plane).
//! - [`groom`]: deterministic procedural grooms, guide strands with barycentric
//!   interpolation (Halén & Wester 2007 §2.5), stray strands
//!   (Sintorn & Assarsson 2009 Fig. 4/5).
//! - [`scene`]: the TOML scene file every pipeline renders, light frustum
//!   fitting (Halén & Wester 2007 §5.7).

pub mod groom;
pub mod hair_file;
pub mod mesh;
pub mod rng;
pub mod scene;
mod strands;

pub use groom::{GroomSpec, HeadShape, ScalpRegion, Style, generate};
pub use hair_file::{HairError, HairFile, HairWarning};
pub use mesh::{Mesh, MeshVertex};
pub use scene::{
    Background, Camera, Ground, HairMaterial, HairSource, Head, Light, LightKind, Scene, SceneError,
};
pub use strands::{Aabb, StrandVertex, Strands};
