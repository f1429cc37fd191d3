//! The scene's hair: read from its file or generated, with follow strands
//! and placement applied, and the camera and light given as `"fit"` fitted to
//! its bounds.

use std::path::PathBuf;

use glam::Vec3;

use super::{HairSource, Light, Scene, SceneError};
use crate::asset::Asset;
use crate::groom::Missing;
use crate::strands::{Aabb, Strands};

impl Scene {
    /// The strands to render: the file's or the generated groom, with its
    /// follow strands, the default look where a `.tfx` file has none
    /// (`crate::groom::dress`), placed by its transform.
    pub fn strands(&self) -> Result<Strands, SceneError> {
        let (mut strands, origin, missing) = match &self.hair.source {
            HairSource::File(path) => {
                let (asset, _warnings) = Asset::read_with(path, &self.hair.usd)
                    .map_err(|e| self.hair.named_here(e.into()))?;
                let strands = asset.strands();
                check_albedo(&strands).map_err(|message| {
                    self.hair.named_here(SceneError::Invalid {
                        path: path.clone(),
                        message,
                    })
                })?;
                (strands, path.clone(), missing_look(&asset))
            }
            HairSource::Procedural(spec) => (
                crate::groom::generate(spec),
                PathBuf::from("<procedural groom>"),
                Missing::default(),
            ),
        };
        let invalid = |message: String| SceneError::Invalid {
            path: origin.clone(),
            message,
        };
        if let Some(follow) = &self.hair.follow {
            follow
                .check_size(&strands)
                .map_err(|m| invalid(format!("hair.{m}")))?;
            strands = follow.apply(&strands);
        }
        // After the follow strands, which count toward the density that sets
        // the default width; before the transform, which scales it.
        crate::groom::dress(&mut strands, missing);
        if let Some(transform) = &self.hair.transform {
            transform.apply(&mut strands).map_err(invalid)?;
        }
        Ok(strands)
    }

    /// [`Scene::strands`], then the camera and light given as `"fit"` are
    /// fitted to the hair (and head): what a renderer calls.
    pub fn load_hair(&mut self) -> Result<Strands, SceneError> {
        let strands = self.strands()?;
        self.frame(strands.bounds());
        Ok(strands)
    }

    /// Fits the camera and light given as `"fit"` to `hair` (the head and
    /// the `[[meshes]]` are added; the ground only widens the depth range).
    pub fn frame(&mut self, hair: Aabb) {
        let head = self
            .head
            .as_ref()
            .map(|h| {
                let (c, r) = (Vec3::from(h.center), Vec3::from(h.radii));
                Aabb::new(c - r, c + r)
            })
            .unwrap_or(Aabb::EMPTY);
        let subject = hair.union(&head).union(&self.file_mesh_bounds());
        if let Some(fit) = &self.framing.camera {
            self.camera = fit.camera(subject, subject.union(&self.opaque_bounds()));
        }
        if self.framing.light {
            let fitted = Light::fitted(&self.camera, self.light.intensity);
            self.light.kind = fitted.kind;
        }
    }
}

impl super::Hair {
    /// `error` (reading the hair file) prefixed with where the scene names
    /// the file, when a scene file did.
    fn named_here(&self, error: SceneError) -> SceneError {
        match &self.declared_at {
            Some(at) => SceneError::HairFile {
                at: at.clone(),
                error: Box::new(error),
            },
            None => error,
        }
    }
}

/// A strand's colour is its fibre's albedo (`docs/formats.md`, "Light and
/// units"): a channel outside [0, 1] would reflect more light than it
/// receives, so a file's colours are refused as the scene's albedos are,
/// naming the first strand and point at fault.
fn check_albedo(strands: &Strands) -> Result<(), String> {
    for (strand, range) in strands.ranges().enumerate() {
        for point in range.clone() {
            let c = strands.color[point];
            if !c.is_finite() || c.min_element() < 0.0 || c.max_element() > 1.0 {
                return Err(format!(
                    "strand {strand}, point {}: colour {:?} is not an albedo; every channel must be finite and within [0, 1] (docs/formats.md, \"Light and units\")",
                    point - range.start,
                    c.to_array()
                ));
            }
        }
    }
    Ok(())
}

/// What a file leaves out of the look (`crate::groom::dress`): a `.tfx`
/// file's absent thickness and colour arrays, a USD stage's absent `widths`
/// and `displayColor` (on every prim read); nothing for a `.hair` file,
/// whose header states defaults for both.
fn missing_look(asset: &Asset) -> Missing {
    match asset {
        Asset::Tfx(file) => Missing {
            thickness: file.strand_thickness.is_none(),
            color: file.vertex_color.is_none(),
        },
        Asset::Usd(groom) => Missing {
            thickness: groom.lacks_widths(),
            color: groom.lacks_colors(),
        },
        Asset::Hair(_) => Missing::default(),
    }
}
