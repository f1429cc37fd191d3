//! Writing a [`MitsubaScene`] as a folder: `scene.xml` (Mitsuba 3's scene
//! format, version 3.0.0), `hair_K.txt` (Mitsuba's `bsplinecurve` files: one
//! control point `x y z radius` a line, strands separated by an empty line),
//! `mesh_K.obj` and `plait.json`.
//!
//! The XML leaves samples per pixel, maximum path depth and seed as
//! `$spp`, `$max_depth` and `$seed` with defaults, so `render.py` sets them
//! when it loads the file and the folder is the same for every render.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::{Vec3, Vec4};

use super::{ExportError, HairGroup, MitsubaMesh, MitsubaScene};

/// What [`MitsubaScene::write`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// `DIR/scene.xml`.
    pub scene_xml: PathBuf,
    /// Every file, `scene.xml` first.
    pub files: Vec<PathBuf>,
}

impl MitsubaScene {
    /// Writes the folder `dir` (created if missing; files of an earlier
    /// export with the same names are replaced).
    pub fn write(&self, dir: &Path) -> Result<Written, ExportError> {
        let io = |path: &Path| {
            let path = path.to_path_buf();
            move |error| ExportError::Io { path, error }
        };
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let mut files = vec![dir.join("scene.xml")];
        for (k, g) in self.hair.iter().enumerate() {
            let path = dir.join(format!("hair_{k}.txt"));
            std::fs::write(&path, curve_file(g)).map_err(io(&path))?;
            files.push(path);
        }
        for (k, m) in self.meshes.iter().enumerate() {
            let path = dir.join(format!("mesh_{k}.obj"));
            std::fs::write(&path, obj_file(m)).map_err(io(&path))?;
            files.push(path);
        }
        let json = dir.join("plait.json");
        std::fs::write(&json, self.sidecar()).map_err(io(&json))?;
        files.push(json);
        std::fs::write(&files[0], self.xml()).map_err(io(&files[0]))?;
        Ok(Written {
            scene_xml: files[0].clone(),
            files,
        })
    }

    /// `scene.xml`.
    pub fn xml(&self) -> String {
        let mut x = String::from("<scene version=\"3.0.0\">\n");
        x += "  <default name=\"spp\" value=\"64\"/>\n";
        x += "  <default name=\"max_depth\" value=\"16\"/>\n";
        x += "  <default name=\"seed\" value=\"0\"/>\n";
        // hide_emitters: a ray that hits nothing returns 0 and alpha 0;
        // render.py adds the background (radiance) where alpha < 1, so the
        // background seen and the ambient that lights can differ, as in plait.
        x += "  <integrator type=\"path\">\n    <integer name=\"max_depth\" value=\"$max_depth\"/>\n";
        x += "    <boolean name=\"hide_emitters\" value=\"true\"/>\n  </integrator>\n";
        x += &self.sensor_xml();
        x += &self.light_xml();
        if self.ambient != Vec3::ZERO {
            let _ = writeln!(
                x,
                "  <emitter type=\"constant\">\n    {}\n  </emitter>",
                rgb("radiance", self.ambient)
            );
        }
        for (k, g) in self.hair.iter().enumerate() {
            x += &self.hair_xml(k, g);
        }
        for (k, m) in self.meshes.iter().enumerate() {
            let _ = writeln!(
                x,
                "  <shape type=\"obj\" id=\"mesh_{k}\">\n    <string name=\"filename\" value=\"mesh_{k}.obj\"/>\n    <!-- plait mesh \"{}\" -->\n    <bsdf type=\"twosided\"><bsdf type=\"diffuse\">{}</bsdf></bsdf>\n  </shape>",
                xml_text(&m.name),
                rgb("reflectance", m.albedo)
            );
        }
        x + "</scene>\n"
    }

    /// The key light: `directional` (irradiance) or, for a spot light,
    /// `point` (radiant intensity; [`super::MitsubaLight::Point`]).
    fn light_xml(&self) -> String {
        match self.light {
            super::MitsubaLight::Directional {
                direction,
                irradiance,
            } => format!(
                "  <emitter type=\"directional\">\n    <vector name=\"direction\" value=\"{}\"/>\n    {}\n  </emitter>\n",
                v3(direction),
                rgb("irradiance", irradiance)
            ),
            super::MitsubaLight::Point {
                position,
                intensity,
            } => format!(
                "  <emitter type=\"point\">\n    <point name=\"position\" value=\"{}\"/>\n    {}\n  </emitter>\n",
                v3(position),
                rgb("intensity", intensity)
            ),
        }
    }

    /// The camera: Mitsuba's `look_at` frame, the same vertical field of
    /// view and clip planes; the box filter makes a pixel the mean over its
    /// square, centred where plait's rasterizer samples it (x + ½, y + ½).
    fn sensor_xml(&self) -> String {
        let c = &self.camera;
        format!(
            "  <sensor type=\"perspective\">\n    <string name=\"fov_axis\" value=\"y\"/>\n    <float name=\"fov\" value=\"{}\"/>\n    <float name=\"near_clip\" value=\"{}\"/>\n    <float name=\"far_clip\" value=\"{}\"/>\n    <transform name=\"to_world\">\n      <lookat origin=\"{}\" target=\"{}\" up=\"{}\"/>\n    </transform>\n    <sampler type=\"independent\">\n      <integer name=\"sample_count\" value=\"$spp\"/>\n      <integer name=\"seed\" value=\"$seed\"/>\n    </sampler>\n    <film type=\"hdrfilm\">\n      <integer name=\"width\" value=\"{}\"/>\n      <integer name=\"height\" value=\"{}\"/>\n      <string name=\"pixel_format\" value=\"rgba\"/>\n      <string name=\"component_format\" value=\"float32\"/>\n      <rfilter type=\"box\"/>\n    </film>\n  </sensor>\n",
            c.fov_y_degrees,
            c.near,
            c.far,
            v3(c.eye),
            v3(c.target),
            v3(c.up),
            c.size.0,
            c.size.1
        )
    }

    fn hair_xml(&self, k: usize, g: &HairGroup) -> String {
        let f = &self.fibre;
        let hair = format!(
            "<bsdf type=\"hair\">\n      <float name=\"longitudinal_roughness\" value=\"{}\"/>\n      <float name=\"azimuthal_roughness\" value=\"{}\"/>\n      <float name=\"scale_tilt\" value=\"{}\"/>\n      <float name=\"int_ior\" value=\"{}\"/>\n      <float name=\"ext_ior\" value=\"1\"/>\n      {}\n    </bsdf>",
            f.longitudinal_roughness,
            f.azimuthal_roughness,
            mitsuba_scale_tilt(f.scale_tilt_degrees),
            f.eta,
            rgb("sigma_a", g.sigma_a)
        );
        let bsdf = if g.alpha < 1.0 {
            format!(
                "<bsdf type=\"mask\">\n    <float name=\"opacity\" value=\"{}\"/>\n    {hair}\n    </bsdf>",
                g.alpha
            )
        } else {
            hair
        };
        format!(
            "  <shape type=\"bsplinecurve\" id=\"hair_{k}\">\n    <!-- colour {} alpha {}: {} strands -->\n    <string name=\"filename\" value=\"hair_{k}.txt\"/>\n    {bsdf}\n  </shape>\n",
            v3(g.color),
            g.alpha,
            g.strands.len()
        )
    }

    /// `plait.json`: the background (render.py adds it where camera rays
    /// miss), the image size, the hair groups and the notes.
    fn sidecar(&self) -> String {
        let groups: Vec<_> = self
            .hair
            .iter()
            .enumerate()
            .map(|(k, g)| {
                serde_json::json!({
                    "shape": format!("hair_{k}"),
                    "color": g.color.to_array(),
                    "alpha": g.alpha,
                    "sigma_a": g.sigma_a.to_array(),
                    "strands": g.strands.len(),
                })
            })
            .collect();
        let json = serde_json::json!({
            "background": self.background.to_array(),
            "size": [self.camera.size.0, self.camera.size.1],
            "hair_groups": groups,
            "notes": self.notes,
        });
        serde_json::to_string_pretty(&json).unwrap_or_default() + "\n"
    }
}

/// Mitsuba's `scale_tilt` for plait's cuticle tilt α (degrees, > 0: the
/// scales point to the tip, so R leaves towards the root — Marschner et al.
/// 2003's shift, plait's `marschner` and `chiang`): −α.
///
/// Why negated: Mitsuba 3's `hair` BSDF (as pbrt-v3's and pbrt-v4's hair
/// code) rotates the eye's θ by −2α for R, which moves the R lobe by +2α
/// towards the fibre's local y axis, and at a `bsplinecurve` hit that axis
/// runs from the curve's first control point to its last — the root to the
/// tip, as [`curve_file`] writes a strand. So a positive `scale_tilt` there
/// puts R on the tip's side (`scripts/mitsuba/tilt_side.py` measures it:
/// +9.8° at +4, −13.3° at −4).
pub(super) fn mitsuba_scale_tilt(alpha_degrees: f32) -> f32 {
    -alpha_degrees
}

/// A curve file for `bsplinecurve`: `x y z radius` per control point (`{}`
/// prints an f32 so that it reads back to the same f32), the control points
/// of [`through_points`] for each strand.
///
/// Why a B-spline and not `linearcurve`, which is plait's polyline as it is:
/// at a `linearcurve` hit Mitsuba 3.9.1 leaves dp_du zero and builds the
/// shading frame from the normal alone, while its `hair` BSDF takes the
/// frame's second axis as the fibre's axis, so each fibre was shaded about
/// an axis that ignores the strand. At a `bsplinecurve` hit dp_du runs
/// around the curve, so the frame's second axis (normal × dp_du) is the
/// curve's tangent (`scripts/mitsuba/frame_probe.py`).
///
/// The file ends with [`terminator`]: one segment of radius 0 after the
/// last strand, so that no segment with a surface is the file's last.
fn curve_file(g: &HairGroup) -> String {
    let mut s = String::new();
    let mut last = None;
    for (i, strand) in g.strands.iter().enumerate() {
        if i > 0 {
            s.push('\n');
        }
        for c in through_points(strand) {
            let _ = writeln!(s, "{} {} {} {}", c.x, c.y, c.z, c.w);
            last = Some(c);
        }
    }
    if let Some(tip) = last {
        s.push('\n');
        for c in terminator(tip) {
            let _ = writeln!(s, "{} {} {} {}", c.x, c.y, c.z, c.w);
        }
    }
    s
}

/// Four control points at `tip`'s position with radius 0: a segment with
/// no surface, which no ray can hit, written after a file's last strand.
///
/// Why: Mitsuba 3.9.1's `bsplinecurve` maps a hit to the global curve
/// parameter v = (segment + u) / segments in f32, and its `partials()`
/// takes segment = floor(v × segments) without clamping. A hit within
/// ~3·10⁻⁴ of the end of the file's last segment (the last strand's tip,
/// with a few thousand segments in the file) rounds v to 1.0 and reads the
/// segment index one past the end: Dr.Jit's debug mode reports
/// "out-of-bounds read from position 5984 in an array of size 5984", and
/// without it `llvm_ad_rgb` segfaults (the built-in scene, 512 spp; the
/// reproducer is `scripts/mitsuba/tip_crash.py`). With this segment last,
/// the out-of-range read can happen only on a hit of a radius-0 segment.
/// The strands' segments keep their indices (`prim_index`) and the scene
/// its bounding box; the export's notes say it.
pub(super) fn terminator(tip: Vec4) -> [Vec4; 4] {
    [tip.truncate().extend(0.0); 4]
}

/// Control points (position, radius) of the uniform cubic B-spline that
/// passes through every point of `strand` in order: n points give n + 2
/// control points, n − 1 segments, segment i running from point i to point
/// i + 1 (so Mitsuba's `prim_index` is plait's segment index). Each point is
/// (C[i] + 4 C[i+1] + C[i+2]) / 6; the ends are natural (no curvature:
/// C[0] = 2 C[1] − C[2], which puts C[1] on the first point), and the
/// interior is the tridiagonal system solved by Thomas's algorithm. Between
/// points the curve bends where plait's polyline has corners:
/// `direct_probe.py` measures how far from the polyline, in fibre radii. A
/// strand of one point has no segment and is written as it is (Mitsuba then
/// refuses the file: fewer than four control points).
pub(super) fn through_points(strand: &[(Vec3, f32)]) -> Vec<Vec4> {
    let p: Vec<Vec4> = strand.iter().map(|(q, r)| q.extend(*r)).collect();
    let n = p.len();
    if n < 2 {
        return p;
    }
    // c[1] = p[0], c[n] = p[n-1]; unknowns c[2..n-1] from rows i = 1..n-2:
    // c[i] + 4 c[i+1] + c[i+2] = 6 p[i].
    let mut c = vec![Vec4::ZERO; n + 2];
    c[1] = p[0];
    c[n] = p[n - 1];
    let m = n - 2;
    let (mut diag, mut rhs) = (vec![4.0f32; m], vec![Vec4::ZERO; m]);
    for k in 0..m {
        rhs[k] = 6.0 * p[k + 1];
    }
    if m > 0 {
        rhs[0] -= c[1];
        rhs[m - 1] -= c[n];
    }
    for k in 1..m {
        let w = 1.0 / diag[k - 1];
        diag[k] -= w;
        rhs[k] = rhs[k] - w * rhs[k - 1];
    }
    for k in (0..m).rev() {
        let next = if k + 1 < m { c[k + 3] } else { Vec4::ZERO };
        c[k + 2] = (rhs[k] - next) / diag[k];
    }
    c[0] = 2.0 * c[1] - c[2];
    c[n + 1] = 2.0 * c[n] - c[n - 1];
    // A sharp taper (a tip of radius 0 after a thick point) makes the exact
    // spline's radius negative, which Mitsuba cannot draw: 0 there, and
    // `plan` notes how many strands ([`radius_dips_below_zero`]).
    for k in &mut c {
        k.w = k.w.max(0.0);
    }
    c
}

/// Whether the exact spline through `strand`'s radii has a control radius
/// below 0 (then [`through_points`] writes 0 there).
pub(super) fn radius_dips_below_zero(strand: &[(Vec3, f32)]) -> bool {
    let mut unclamped = strand.to_vec();
    // The same solve on the radii alone, as positions (the solve is per
    // component), so the clamp in through_points cannot hide the dip.
    for (p, r) in &mut unclamped {
        *p = Vec3::new(*r, 0.0, 0.0);
        *r = 1.0;
    }
    through_points(&unclamped).iter().any(|c| c.x < 0.0)
}

/// A Wavefront OBJ with per-vertex normals (1-based indices).
fn obj_file(m: &MitsubaMesh) -> String {
    let mut s = format!("# plait mesh {}\n", m.name);
    for p in &m.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    for n in &m.normals {
        let _ = writeln!(s, "vn {} {} {}", n.x, n.y, n.z);
    }
    for t in m.indices.chunks_exact(3) {
        let [a, b, c] = [t[0] + 1, t[1] + 1, t[2] + 1];
        let _ = writeln!(s, "f {a}//{a} {b}//{b} {c}//{c}");
    }
    s
}

fn v3(v: Vec3) -> String {
    format!("{}, {}, {}", v.x, v.y, v.z)
}

fn rgb(name: &str, v: Vec3) -> String {
    format!("<rgb name=\"{name}\" value=\"{}\"/>", v3(v))
}

/// Text safe inside an XML comment or attribute.
fn xml_text(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace("--", "- -")
}
