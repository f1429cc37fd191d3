//! The frame's standard inputs (group 0 of every pass), computed from the scene.

use glam::{Mat4, Vec3};
use plait_hair::scene::{Background, Camera, LightKind, Scene};
use plait_hair::{Aabb, Strands};

/// Mirrors `struct Frame` in `shaders/lib/frame.wgsl`; every member is 16-byte
/// aligned so the Rust and WGSL layouts agree without padding rules.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    pub camera_view_proj: [[f32; 4]; 4],
    pub camera_view: [[f32; 4]; 4],
    pub camera_inv_view_proj: [[f32; 4]; 4],
    pub light_view_proj: [[f32; 4]; 4],
    pub light_view: [[f32; 4]; 4],
    pub light_inv_view_proj: [[f32; 4]; 4],
    pub camera_position: [f32; 4],
    pub light_direction: [f32; 4],
    pub light_position: [f32; 4],
    pub light_color: [f32; 4],
    pub hair_color: [f32; 4],
    pub hair_shading: [f32; 4],
    pub background: [f32; 4],
    pub ambient: [f32; 4],
    pub screen_size: [f32; 4],
    pub jitter: [f32; 4],
    pub near_far: [f32; 4],
    /// x: mean alpha over every vertex (strand alpha × material alpha ×
    /// strand coverage while coverage is on) — occupancy order's ᾱ only with
    /// `mean_alpha = "frame"`; by default it measures ᾱ per pixel on the GPU
    /// (alpha_sum pass); y: strands; z: segments; w: the mean alpha without
    /// coverage.
    pub hair_stats: [f32; 4],
    /// The comparison conventions every visibility provider shares
    /// (docs/design.md, "In front of"): x = self-shadow bias in light linear
    /// depth, y = 1 to jitter light-map lookups by up to half a texel
    /// (Sintorn & Assarsson 2009 Fig. 9), 0 for exact texel lookups;
    /// z = 1 when strands weigh by their pixel coverage.
    pub conventions: [f32; 4],
    /// World-from-rest matrix of the head (and every opaque vertex whose
    /// `head` weight is 1) at this frame's time: the scene's `[animation]`,
    /// the identity for a still head.
    pub head_model: [[f32; 4]; 4],
    /// `head_model` one frame earlier (velocities, simulation collisions).
    pub head_model_previous: [[f32; 4]; 4],
    /// The hair's bounding sphere (xyz centre, w radius, world units) as the
    /// frame poses it: how big the groom looks from a view
    /// (`plait::geometry::lod` derives its strand count from it).
    pub hair_sphere: [f32; 4],
    /// x: the strands' mean width (thickness, world units) over every
    /// vertex — what the depth-only self-shadow maps (modified shadow map,
    /// TressFX), which keep no strand's width, take each strand crossed to
    /// be, to block its share of a light texel (issue 47); y: the widest
    /// strand across the camera's view, in pixels, over every vertex in
    /// front of the eye (the CPU's strands: [`FrameUniforms::draws_wide_strands`]);
    /// z: the widest across the light's view, in its normalized device
    /// units (2 across the map: [`FrameUniforms::draws_wide_light_strands`]);
    /// w unused.
    pub hair_width: [f32; 4],
}

/// Hair nearer the light than a point by at most this much (world units) is
/// not "in front of" it: the point's own fragment and strand never shadow it.
/// About one strand's thickness in the scenes plait ships.
pub const SELF_SHADOW_BIAS: f32 = 0.01;

/// Size of `FrameUniforms` in bytes (also checked against the WGSL struct by a test).
pub const FRAME_UNIFORMS_SIZE: u64 = std::mem::size_of::<FrameUniforms>() as u64;

fn v4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

impl FrameUniforms {
    /// Standard inputs for rendering `scene` at `size`, with light maps fitted to
    /// the hair (occluders) and the whole scene (receivers).
    pub fn new(
        scene: &Scene,
        strands: &Strands,
        scene_bounds: Aabb,
        size: (u32, u32),
        frame_index: u32,
    ) -> Self {
        Self::seen_from(
            &scene.camera,
            scene,
            strands,
            scene_bounds,
            size,
            frame_index,
        )
    }

    /// [`FrameUniforms::new`] with `camera` in place of the scene's (an
    /// animated dolly: `Scene::camera_at`); the light is fitted as ever.
    pub fn seen_from(
        camera: &Camera,
        scene: &Scene,
        strands: &Strands,
        scene_bounds: Aabb,
        size: (u32, u32),
        frame_index: u32,
    ) -> Self {
        let hair_bounds = strands.bounds();
        let mean_alpha = if strands.alpha.is_empty() {
            1.0
        } else {
            // Summed in f64: the mean of N equal alphas is that alpha exactly,
            // whatever N (an f32 sum drifts with the count).
            (strands.alpha.iter().map(|&a| a as f64).sum::<f64>() / strands.alpha.len() as f64)
                as f32
        };
        let aspect = size.0 as f32 / size.1.max(1) as f32;
        let view = camera.view();
        let proj = camera.projection(aspect);
        let view_proj = proj * view;
        let seen = SeenWidths::of(strands, view_proj, Vec3::from(camera.eye), size);
        let light = LightFrustum::fit(scene, hair_bounds, scene_bounds);
        let to_light = scene.light.direction_to_light();
        let (light_dir_w, light_pos) = match &scene.light.kind {
            LightKind::Directional { .. } => (0.0, Vec3::ZERO),
            LightKind::Spot { position, .. } => (1.0, Vec3::from(*position)),
        };
        // As plait::hair_map's map_view: towards a directional light, or a
        // spot's position.
        let light_eye = if light_dir_w > 0.5 {
            light_pos.extend(1.0)
        } else {
            to_light.extend(0.0)
        };
        let widest_light = widest_ndc(strands, light.projection * light.view, light_eye);
        let light_color = Vec3::from(scene.light.color) * scene.light.intensity;
        let m = &scene.material;
        // w tells the shaders to read `background_image` instead of the colour.
        let (background, background_is_image) = match &scene.background {
            Background::Color(c) => (Vec3::from(*c), 0.0),
            Background::Image(_) => (Vec3::ZERO, 1.0),
        };
        FrameUniforms {
            camera_view_proj: view_proj.to_cols_array_2d(),
            camera_view: view.to_cols_array_2d(),
            camera_inv_view_proj: view_proj.inverse().to_cols_array_2d(),
            light_view_proj: (light.projection * light.view).to_cols_array_2d(),
            light_view: light.view.to_cols_array_2d(),
            light_inv_view_proj: (light.projection * light.view).inverse().to_cols_array_2d(),
            camera_position: v4(Vec3::from(camera.eye), 1.0),
            light_direction: v4(to_light, light_dir_w),
            light_position: v4(light_pos, 1.0),
            light_color: v4(light_color, 1.0),
            hair_color: v4(Vec3::from(m.color), m.alpha),
            hair_shading: [m.diffuse, m.specular, m.specular_exponent, m.specular_shift],
            background: v4(background, background_is_image),
            ambient: v4(Vec3::splat(scene.ambient), 1.0),
            screen_size: [
                size.0 as f32,
                size.1 as f32,
                1.0 / size.0 as f32,
                1.0 / size.1 as f32,
            ],
            jitter: [0.0, 0.0, 0.0, frame_index as f32],
            near_far: [camera.near, camera.far, light.near, light.far],
            conventions: [
                SELF_SHADOW_BIAS / (light.far - light.near).max(1e-6),
                1.0,
                1.0,
                0.0,
            ],
            hair_stats: [
                (seen.covered_alpha * scene.material.alpha).clamp(0.0, 1.0),
                strands.strand_count() as f32,
                strands.segment_count() as f32,
                (mean_alpha * scene.material.alpha).clamp(0.0, 1.0),
            ],
            head_model: Mat4::IDENTITY.to_cols_array_2d(),
            head_model_previous: Mat4::IDENTITY.to_cols_array_2d(),
            hair_sphere: hair_sphere(hair_bounds),
            hair_width: [mean_thickness(strands), seen.widest, widest_light, 0.0],
        }
    }

    /// The frame's time in seconds (`jitter.z`) and the head's pose now and
    /// one frame earlier (`head_model`, `head_model_previous`).
    pub fn with_motion(mut self, time: f32, head_model: Mat4, head_model_previous: Mat4) -> Self {
        self.jitter[2] = time;
        self.head_model = head_model.to_cols_array_2d();
        self.head_model_previous = head_model_previous.to_cols_array_2d();
        self
    }

    /// Whether light-map lookups are jittered (shading: yes, against
    /// silhouette aliasing; measuring visibility: no, so every provider and
    /// the reference read the same texel).
    pub fn with_light_jitter(mut self, on: bool) -> Self {
        self.conventions[1] = if on { 1.0 } else { 0.0 };
        self
    }

    /// Whether strands thinner than a pixel weigh by the part of it they
    /// cover (`plait::strand_coverage::strand_coverage`; on by
    /// default). Off, every strand covers its pixels wholly, as before; the
    /// mean fragment alpha follows.
    pub fn with_strand_coverage(mut self, on: bool) -> Self {
        if (self.conventions[2] > 0.5) != on {
            self.conventions[2] = if on { 1.0 } else { 0.0 };
            self.hair_stats.swap(0, 3);
        }
        self
    }

    /// Whether a camera hair draw needs its quad draw of strands wider than
    /// a pixel (`plait::strand_coverage`, "the quad draw") for the hair as
    /// the CPU holds it: coverage on and some vertex at least
    /// [`WIDE_MARGIN`] of a pixel wide. The line draw drops a segment the
    /// GPU finds wider than a pixel whatever the CPU decided, so the margin
    /// keeps a rounding difference between the two from losing it; hair a
    /// pass moves or makes on the GPU is not the CPU's, and always draws it
    /// (`Renderer`).
    pub fn draws_wide_strands(&self) -> bool {
        self.conventions[2] > 0.5 && self.hair_width[1] >= WIDE_MARGIN
    }

    /// [`FrameUniforms::draws_wide_strands`] for a light-view hair pass
    /// whose maps are at most `texels` across (plait::hair_map's map_view:
    /// a strand is wide past one texel of its map): the widest strand
    /// across the light, in texels of the larger side, against the same
    /// margin. Conservative on a map that is not square.
    pub fn draws_wide_light_strands(&self, texels: u32) -> bool {
        self.conventions[2] > 0.5 && 0.5 * self.hair_width[2] * texels as f32 >= WIDE_MARGIN
    }

    pub fn camera_view_proj(&self) -> Mat4 {
        Mat4::from_cols_array_2d(&self.camera_view_proj)
    }
}

/// The light's view and projection, fitted tightly to the hair so the light
/// maps spend their texels on it (Halén & Wester 2007 §5.7):
/// x/y cover the occluders (the hair), depth runs from the nearest object of
/// the scene to the farthest receiver so hair shadows reach the ground and
/// opaque objects between the light and the hair shadow it.
#[derive(Clone, Copy, Debug)]
pub struct LightFrustum {
    pub view: Mat4,
    pub projection: Mat4,
    /// Distances from the light along its axis, in world units.
    pub near: f32,
    pub far: f32,
}

impl LightFrustum {
    pub fn fit(scene: &Scene, occluders: Aabb, receivers: Aabb) -> Self {
        let all = occluders.union(&receivers);
        let radius = all.extent().length().max(1e-3);
        let to_light = scene.light.direction_to_light().normalize_or(Vec3::Y);
        let (eye, forward) = match &scene.light.kind {
            LightKind::Directional { .. } => {
                (occluders.center() + to_light * radius * 2.0, -to_light)
            }
            LightKind::Spot { position, .. } => {
                let p = Vec3::from(*position);
                (p, (occluders.center() - p).normalize_or(-to_light))
            }
        };
        let up = if forward.cross(Vec3::Y).length_squared() < 1e-6 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        let view = Mat4::look_to_rh(eye, forward, up);
        let to_view = |p: Vec3| view.transform_point3(p);
        let occ: Vec<Vec3> = occluders.corners().into_iter().map(to_view).collect();
        let rec: Vec<Vec3> = receivers.corners().into_iter().map(to_view).collect();
        // Anything nearer the light than the hair can shadow it, opaque objects
        // included: the near plane takes every receiver too, or an opaque
        // occluder in front of the hair would be clipped out of the shadow map.
        // Both planes stand a thousandth of the scene's size beyond the
        // nearest and farthest point: a face square to the light (the ground
        // under a light straight down) lies wholly at one depth, and on the
        // far plane itself rounding put it outside the map, unshadowed
        // (tests/light_frustum.rs).
        let margin = 1e-3 * radius;
        let near = (occ
            .iter()
            .chain(rec.iter())
            .map(|p| -p.z)
            .fold(f32::INFINITY, f32::min)
            - margin)
            .max(1e-3);
        let far = (rec
            .iter()
            .chain(occ.iter())
            .map(|p| -p.z)
            .fold(0.0, f32::max)
            + margin)
            .max(near + 1e-3);
        let projection = match &scene.light.kind {
            LightKind::Directional { .. } => {
                let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
                for p in &occ {
                    lo = lo.min(*p);
                    hi = hi.max(*p);
                }
                // A small margin keeps strands on the border inside the map.
                let pad = (hi - lo).max_element() * 0.02;
                Mat4::orthographic_rh(lo.x - pad, hi.x + pad, lo.y - pad, hi.y + pad, near, far)
            }
            LightKind::Spot { cone_degrees, .. } => {
                let fitted = occ
                    .iter()
                    .map(|p| (p.x.abs().max(p.y.abs()) / (-p.z).max(1e-3)).atan())
                    .fold(0.0, f32::max)
                    * 2.0
                    * 1.04;
                let fov = fitted.min(cone_degrees.to_radians()).max(1e-3);
                Mat4::perspective_rh(fov, 1.0, near, far)
            }
        };
        LightFrustum {
            view,
            projection,
            near,
            far,
        }
    }
}

/// The strands' widths as the camera sees them at one size, from one walk
/// over every vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeenWidths {
    /// The mean strand alpha weighted by strand coverage, the CPU mirror of
    /// `strand_coverage` in `shaders/lib/strand_coverage.wgsl`: the part of
    /// a pixel each vertex's strand covers (at most 1), times its alpha,
    /// averaged over vertices (summed in f64). Order-based blending's ᾱ
    /// (Sintorn & Assarsson 2009 §3.4) is the alpha fragments actually carry.
    pub covered_alpha: f32,
    /// The widest strand across the view, in pixels, over the vertices in
    /// front of the eye; 0 without any.
    pub widest: f32,
}

/// A vertex this much of a pixel wide or wider makes a camera hair draw
/// draw its quads ([`FrameUniforms::draws_wide_strands`]): the GPU calls a
/// segment wide above 1, and its f32 arithmetic differs from the CPU's by
/// far less than this.
pub const WIDE_MARGIN: f32 = 0.9;

impl SeenWidths {
    pub fn of(strands: &Strands, view_proj: Mat4, eye: Vec3, size: (u32, u32)) -> Self {
        if strands.points.is_empty() {
            return SeenWidths {
                covered_alpha: 1.0,
                widest: 0.0,
            };
        }
        let tangents = strands.tangents();
        let half = glam::Vec2::new(size.0 as f32, size.1 as f32) * 0.5;
        let mut sum = 0.0f64;
        let mut widest = 0.0f32;
        for (i, &p) in strands.points.iter().enumerate() {
            let alpha = strands.alpha.get(i).copied().unwrap_or(1.0) as f64;
            let thickness = strands.thickness.get(i).copied().unwrap_or(1.0);
            let width = strand_width_pixels(p, tangents[i], thickness, view_proj, eye, half);
            // Behind the eye the line is clipped anyway: coverage 1 as in WGSL.
            sum += alpha * width.map_or(1.0, |w| w.min(1.0)) as f64;
            widest = widest.max(width.unwrap_or(0.0));
        }
        SeenWidths {
            covered_alpha: (sum / strands.points.len() as f64) as f32,
            widest,
        }
    }
}

/// `strand_width_pixels` of `shaders/lib/strand_coverage.wgsl` on the CPU:
/// the width across the view, in pixels (`half` = half the screen size), of
/// a strand of `thickness` at `p` along `tangent`; `None` behind the eye.
pub fn strand_width_pixels(
    p: Vec3,
    tangent: Vec3,
    thickness: f32,
    view_proj: Mat4,
    eye: Vec3,
    half: glam::Vec2,
) -> Option<f32> {
    side_ndc(p, tangent, thickness, view_proj, eye.extend(1.0)).map(|v| (v * half).length())
}

/// The widest strand over every vertex, in the normalized device units of
/// `view_proj` seen from `eye` (a position, w = 1, or the unit direction
/// towards it, w = 0); 0 without hair or with every vertex behind the eye.
fn widest_ndc(strands: &Strands, view_proj: Mat4, eye: glam::Vec4) -> f32 {
    let tangents = strands.tangents();
    strands
        .points
        .iter()
        .enumerate()
        .filter_map(|(i, &p)| {
            let thickness = strands.thickness.get(i).copied().unwrap_or(1.0);
            side_ndc(p, tangents[i], thickness, view_proj, eye)
        })
        .map(|v| v.length())
        .fold(0.0, f32::max)
}

/// `view_side_pixels` of `shaders/lib/strand_coverage.wgsl` on the CPU, in
/// normalized device units: the image of the strand's width along the side
/// across it and the view ray; `None` behind the eye. `eye` as in
/// [`widest_ndc`].
fn side_ndc(
    p: Vec3,
    tangent: Vec3,
    thickness: f32,
    view_proj: Mat4,
    eye: glam::Vec4,
) -> Option<glam::Vec2> {
    let to_eye = if eye.w > 0.5 {
        (eye.truncate() - p).normalize_or_zero()
    } else {
        eye.truncate()
    };
    let mut side = tangent.cross(to_eye);
    if side.length_squared() < 1e-12 {
        let up = if to_eye.y.abs() > 0.9 {
            Vec3::X
        } else {
            Vec3::Y
        };
        side = up.cross(to_eye);
    }
    let side = side.normalize_or_zero();
    let a = view_proj * p.extend(1.0);
    let b = view_proj * (p + side * thickness).extend(1.0);
    if a.w <= 0.0 || b.w <= 0.0 {
        return None;
    }
    Some(b.truncate().truncate() / b.w - a.truncate().truncate() / a.w)
}

/// The sphere around `bounds` (its centre, half its diagonal); a point for
/// no hair.
/// The mean strand thickness over every vertex (summed in f64, as the mean
/// alpha), 0 without hair.
fn mean_thickness(strands: &Strands) -> f32 {
    if strands.thickness.is_empty() {
        return 0.0;
    }
    (strands.thickness.iter().map(|&t| t as f64).sum::<f64>() / strands.thickness.len() as f64)
        as f32
}

fn hair_sphere(bounds: Aabb) -> [f32; 4] {
    if !(bounds.min.is_finite() && bounds.max.is_finite()) {
        return [0.0; 4];
    }
    let centre = (bounds.min + bounds.max) * 0.5;
    v4(centre, (bounds.max - bounds.min).length() * 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::mem::offset_of;

    /// `FrameUniforms` and `struct Frame` of `shaders/lib/frame.wgsl` name the
    /// same members at the same offsets, and have the same size (naga's
    /// layout of the composed library module).
    #[test]
    fn the_wgsl_frame_struct_matches_frame_uniforms() {
        let source = "#import plait::frame::frame\n@fragment\nfn fs_main() -> @location(0) vec4<f32> {\n    return frame.ambient;\n}\n";
        let module = crate::modules::Shaders::read(&[])
            .compose(std::path::Path::new("frame_layout.wgsl"), source, &[])
            .unwrap_or_else(|e| panic!("{e}"));
        let (_, var) = module
            .global_variables
            .iter()
            .find(|(_, v)| v.space == naga::AddressSpace::Uniform)
            .expect("the frame uniform");
        let naga::TypeInner::Struct { members, span } = &module.types[var.ty].inner else {
            panic!("frame is a struct");
        };
        let wgsl: Vec<(String, usize)> = members
            .iter()
            .map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize))
            .collect();
        macro_rules! rust_members {
            ($($field:ident),* $(,)?) => {
                vec![$((stringify!($field).to_owned(), offset_of!(FrameUniforms, $field))),*]
            };
        }
        let rust: Vec<(String, usize)> = rust_members![
            camera_view_proj,
            camera_view,
            camera_inv_view_proj,
            light_view_proj,
            light_view,
            light_inv_view_proj,
            camera_position,
            light_direction,
            light_position,
            light_color,
            hair_color,
            hair_shading,
            background,
            ambient,
            screen_size,
            jitter,
            near_far,
            hair_stats,
            conventions,
            head_model,
            head_model_previous,
            hair_sphere,
            hair_width,
        ];
        assert_eq!(wgsl, rust);
        assert_eq!(*span as u64, FRAME_UNIFORMS_SIZE);
    }

    /// A strand of thickness t at distance 5 under a 90° camera 100 pixels
    /// high is 10 t pixels wide: `widest` is the widest vertex, strands behind
    /// the eye do not count, and the quad draw is wanted from `WIDE_MARGIN`
    /// of a pixel up, only with coverage on.
    #[test]
    fn the_widest_strand_decides_the_quad_draw() {
        let view = Mat4::look_at_rh(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y);
        let proj = Mat4::perspective_rh(std::f32::consts::FRAC_PI_2, 1.0, 0.1, 100.0);
        let eye = Vec3::new(0.0, 0.0, 5.0);
        let strand = |x: f32, z: f32| [Vec3::new(x, -1.0, z), Vec3::new(x, 1.0, z)];
        let mut strands = Strands::new();
        strands.push_strand(&strand(0.0, 0.0), |t| 0.02 + 0.06 * t, |_| 1.0, Vec3::ONE);
        strands.push_strand(&strand(1.0, 0.0), |_| 0.05, |_| 1.0, Vec3::ONE);
        // Behind the eye: clipped, whatever its width.
        strands.push_strand(&strand(0.0, 6.0), |_| 10.0, |_| 1.0, Vec3::ONE);
        let seen = SeenWidths::of(&strands, proj * view, eye, (100, 100));
        assert!((seen.widest - 0.8).abs() < 1e-3, "{seen:?}");
        // Coverage min(width, 1) of each vertex, 1 behind the eye.
        let mean = (0.2 + 0.8 + 0.5 * 1.0198 + 0.5 * 1.0198 + 2.0) / 6.0;
        assert!(
            (seen.covered_alpha - mean).abs() < 2e-3,
            "{seen:?} against {mean}"
        );
        let mut frame: FrameUniforms = bytemuck::Zeroable::zeroed();
        frame.conventions[2] = 1.0;
        frame.hair_width[1] = seen.widest;
        assert!(!frame.draws_wide_strands(), "0.8 px is under the margin");
        frame.hair_width[1] = WIDE_MARGIN;
        assert!(frame.draws_wide_strands());
        frame.conventions[2] = 0.0;
        assert!(
            !frame.draws_wide_strands(),
            "coverage off: no segment is wide"
        );
    }

    /// From a directional light (w = 0: the direction towards it) through
    /// an orthographic frustum 4 units across, a strand 0.02 thick is 0.01
    /// of the normalized device units: 2.56 texels of a 512-texel map (its
    /// quads drawn), 0.64 of a 128-texel one (not).
    #[test]
    fn the_widest_strand_from_the_light_is_measured_in_its_maps_texels() {
        let view = Mat4::look_at_rh(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y);
        let proj = Mat4::orthographic_rh(-2.0, 2.0, -2.0, 2.0, 0.1, 10.0);
        let mut strands = Strands::new();
        let points = [Vec3::new(0.5, -1.0, 0.0), Vec3::new(0.5, 1.0, 0.0)];
        strands.push_strand(&points, |_| 0.02, |_| 1.0, Vec3::ONE);
        let widest = widest_ndc(&strands, proj * view, Vec3::Z.extend(0.0));
        assert!((widest - 0.01).abs() < 1e-5, "{widest}");
        let mut frame: FrameUniforms = bytemuck::Zeroable::zeroed();
        frame.conventions[2] = 1.0;
        frame.hair_width[2] = widest;
        assert!(frame.draws_wide_light_strands(512));
        assert!(!frame.draws_wide_light_strands(128));
        frame.conventions[2] = 0.0;
        assert!(!frame.draws_wide_light_strands(512), "coverage off");
    }
}
