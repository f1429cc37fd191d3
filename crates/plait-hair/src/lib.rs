//! Strand geometry for plait (issue 3).
//!
//! - [`hair_file`]: Cem Yuksel's binary `.hair` format, read and written exactly.
//! - [`Strands`]: the renderable model (points, per-point thickness, alpha,
//!   color), its bounds, and its GPU line-list layout [`StrandVertex`].
//! - [`mesh`]: opaque geometry (head ellipsoid, ground plane).
//! - [`mesh_file`]: mesh files a scene names (`[[meshes]]`: glTF 2.0),
//!   read with every count bounded first, and written (`.glb`).
//! - [`sdf`]: a mesh's signed distance field, the head mesh's collider.
//! - [`groom`]: deterministic procedural grooms, guide strands with barycentric
//!   interpolation (Halén & Wester 2007 §2.5), stray strands
//!   (Sintorn & Assarsson 2009 Fig. 4/5).
//! - [`tfx`]: AMD TressFX's binary `.tfx` format (versions 3 and 4), read and
//!   written; [`usd`]: `BasisCurves` grooms in USD (`.usda`, `.usdc`,
//!   `.usdz`), read and written; [`asset`] tells the formats apart.
//! - [`guides`]: guide strands and the binding of every rendered strand to
//!   them, the CPU reference of GPU guide interpolation.
//! - [`follow`]: follow strands around guide strands, as TressFX makes them.
//! - [`transform`]: placing a groom (scale, rotation, translation).
//! - [`environment`]: the light around the scene (an HDR/EXR/PNG image or
//!   the procedural sky) and CPU references of the irradiance maps
//!   (Xing et al. 2012 §3, §5).
//! - [`animation`]: keyframed motion of the head (the scene's `[animation]`).
//! - [`scene`]: the TOML scene file every pipeline renders; [`camera`] (a
//!   look-at camera or one fitted to the hair), [`light`] (light frustum
//!   fitting, Halén & Wester 2007 §5.7), [`hair_source`] (the `[hair]` table).

pub mod animation;
pub mod asset;
pub mod camera;
pub mod curve;
pub mod environment;
pub mod follow;
pub mod groom;
pub mod guides;
pub mod hair_file;
pub mod hair_source;
pub mod light;
pub mod mesh;
pub mod mesh_file;
pub mod rng;
pub mod scene;
pub mod sculpted_head;
pub mod sdf;
mod strands;
pub mod tfx;
pub mod transform;
pub mod usd;
pub mod wisps;

pub use asset::{Asset, AssetError, Format};
pub use environment::{Environment, EnvironmentError, EnvironmentImage};
pub use follow::FollowStrands;
pub use groom::{GroomSpec, HeadShape, ScalpRegion, Style, generate};
pub use hair_file::{HairError, HairFile, HairWarning};
pub use mesh::{Mesh, MeshVertex};
pub use scene::{
    Background, Camera, CameraFit, Framing, Ground, Hair, HairMaterial, HairSource, Head, Light,
    LightKind, Scene, SceneError,
};
pub use strands::{Aabb, StrandVertex, Strands};
pub use tfx::{TfxError, TfxFile, TfxWarning};
pub use transform::{Scale, Transform};
pub use usd::{UsdError, UsdGroom, UsdOptions};
