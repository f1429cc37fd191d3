//! Strands wider than a pixel (issue 47) where a pipeline does not draw them
//! at their width: the compute rasterizer (`compute_raster`'s `tile_blend`
//! pass) draws every segment as a one-pixel line whose coverage stops at 1.
//! Every raster hair draw through `plait::hair_fragment` (and the camera
//! maps and mean alpha beside it) draws a segment wider than a pixel as a
//! quad of its width instead (`plait::strand_coverage`, "the quad draw"), so
//! only the compute rasterizer needs this count: each frame says how many
//! segments it drew narrower than they are, never silently.

use glam::{Mat4, Vec3, Vec4};
use plait_gpu::frame::{FrameUniforms, strand_width_pixels};
use plait_graph::Schedule;
use plait_hair::Strands;

/// The pass type that rasterizes lines in a compute shader.
const COMPUTE_RASTER: &str = "tile_blend";

/// The hair as the frame's count needs it: per vertex its position, tangent
/// and thickness, and per segment its first vertex.
pub struct WideCount {
    points: Vec<(Vec3, Vec3, f32)>,
    segments: Vec<u32>,
}

impl WideCount {
    /// For a schedule with the compute rasterizer and strand coverage on
    /// (wisps are drawn at their width: `None` for them too).
    pub fn new(schedule: &Schedule, strands: &Strands, wisps: bool) -> Option<Self> {
        let rasterizes = schedule
            .passes
            .iter()
            .any(|p| p.type_name == COMPUTE_RASTER);
        if !rasterizes || wisps || !crate::session::strand_coverage(schedule) {
            return None;
        }
        let (vertices, indices) = strands.line_list();
        let points = vertices
            .iter()
            .map(|v| (Vec3::from(v.position), Vec3::from(v.tangent), v.thickness))
            .collect();
        let segments = indices.chunks(2).map(|s| s[0]).collect();
        Some(WideCount { points, segments })
    }

    /// How many segments are wider than a pixel from the frame's camera
    /// (either end: the rule of `segment_is_wide` in
    /// `shaders/lib/strand_coverage.wgsl`), of how many.
    pub fn count(&self, frame: &FrameUniforms) -> (usize, usize) {
        let width = |i: u32| {
            let (p, t, w) = self.points[i as usize];
            width_pixels(frame, p, t, w)
        };
        let wide = self
            .segments
            .iter()
            .filter(|&&i| {
                let (a, b) = (width(i), width(i + 1));
                a >= 0.0 && b >= 0.0 && a.max(b) > 1.0
            })
            .count();
        (wide, self.segments.len())
    }

    /// The frame's note, when any segment is wider than a pixel.
    pub fn note(&self, frame: &FrameUniforms) -> Option<String> {
        let (wide, total) = self.count(frame);
        (wide > 0).then(|| {
            format!(
                "compute_raster: {wide} of {total} hair segments are wider than a pixel from this camera and are drawn as one-pixel lines (coverage at most 1: narrower than they are); the raster transparency techniques draw them at their width"
            )
        })
    }
}

/// The strand's width across the frame's view in pixels
/// (`plait_gpu::frame::strand_width_pixels`, the shader's on the CPU); −1
/// behind the eye.
pub fn width_pixels(frame: &FrameUniforms, world: Vec3, tangent: Vec3, thickness: f32) -> f32 {
    let view_proj = Mat4::from_cols_array_2d(&frame.camera_view_proj);
    let eye = Vec4::from(frame.camera_position).truncate();
    let half = glam::Vec2::new(frame.screen_size[0], frame.screen_size[1]) * 0.5;
    strand_width_pixels(world, tangent, thickness, view_proj, eye, half).unwrap_or(-1.0)
}
