//! Strands wider than a light texel (issue 47) in the self-shadow maps that
//! weigh a strand by its share of a light texel (occupancy, slabs, deep
//! opacity, opacity shadow maps, density clusters, exact's depth lists:
//! every light-view hair pass through `plait::hair_map::map_texel`). Those
//! passes draw hair from the light as one-texel lines, and a strand's share
//! of its texel is its width across the light in texels, at most 1: a
//! strand wider than a texel blocks one texel across its width, and the
//! texels beside it that it also covers miss it. Every camera-view hair draw
//! (the shaded hair, the camera maps, the compute rasterizer) draws such a
//! segment at its width instead (`plait::strand_coverage`, "the quad draw"),
//! so only the light maps need this count: each frame says how many segments
//! its light maps hold narrower than they are, never silently.

use std::sync::Mutex;

use glam::{Mat4, Vec3, Vec4};
use plait_gpu::frame::FrameUniforms;
use plait_graph::{ResourceDesc, Schedule, View};
use plait_hair::Strands;

/// The slot of the light's hair depth range texture every pass through
/// `map_texel` binds (written by `depth_range`, read by the others): its
/// width is the map's texels across (`map_texel`'s `m.size.x`).
const RANGE_SLOT: &str = "range";

/// The hair as the frame's count needs it: per vertex its position, tangent
/// and thickness, per segment its first vertex, and the light maps' texels
/// across; and the last count with the light it was made for (the light
/// rarely moves between frames, and a count walks every hair vertex).
pub struct WideCount {
    points: Vec<(Vec3, Vec3, f32)>,
    segments: Vec<u32>,
    texels: u32,
    last: Mutex<Option<(LightKey, (usize, usize))>>,
}

/// What a count depends on besides the hair: the light's matrix, direction
/// and position.
type LightKey = ([[f32; 4]; 4], [f32; 4], [f32; 4]);

fn light_key(frame: &FrameUniforms) -> LightKey {
    (
        frame.light_view_proj,
        frame.light_direction,
        frame.light_position,
    )
}

impl WideCount {
    /// For a schedule with a light-view hair pass that weighs strands by
    /// their share of a light texel, with strand coverage on (wisps' strips
    /// block whole texels, as coverage off does: `None` for them too).
    pub fn new(schedule: &Schedule, strands: &Strands, wisps: bool) -> Option<Self> {
        if wisps || !crate::session::strand_coverage(schedule) {
            return None;
        }
        let texels = light_map_texels(schedule)?;
        let (vertices, indices) = strands.line_list();
        let points = vertices
            .iter()
            .map(|v| (Vec3::from(v.position), Vec3::from(v.tangent), v.thickness))
            .collect();
        let segments = indices.chunks(2).map(|s| s[0]).collect();
        Some(WideCount {
            points,
            segments,
            texels,
            last: Mutex::new(None),
        })
    }

    /// How many segments are wider than a light texel from the frame's
    /// light (either end, as `segment_is_wide` asks of a pixel), of how many.
    pub fn count(&self, frame: &FrameUniforms) -> (usize, usize) {
        let key = light_key(frame);
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((k, counted)) = *last
            && k == key
        {
            return counted;
        }
        // Each vertex once: most end one segment and start the next.
        let widths: Vec<f32> = self
            .points
            .iter()
            .map(|&(p, t, w)| light_width_texels(frame, p, t, w, self.texels))
            .collect();
        let wide = self
            .segments
            .iter()
            .filter(|&&i| {
                let (a, b) = (widths[i as usize], widths[i as usize + 1]);
                a >= 0.0 && b >= 0.0 && a.max(b) > 1.0
            })
            .count();
        let counted = (wide, self.segments.len());
        *last = Some((key, counted));
        counted
    }

    /// The frame's note, when any segment is wider than a light texel.
    pub fn note(&self, frame: &FrameUniforms) -> Option<String> {
        let (wide, total) = self.count(frame);
        let texels = self.texels;
        (wide > 0).then(|| {
            format!(
                "self_shadow: {wide} of {total} hair segments are wider than a texel of the {texels}-texel light maps: each blocks one texel across its width (share at most 1), and the texels beside it miss it; the camera-view draws draw them at their width"
            )
        })
    }
}

/// The texels across of the light maps that weigh strands by their share:
/// the `range` texture of the schedule's first light-view hair pass that
/// binds one (they all bind the same).
fn light_map_texels(schedule: &Schedule) -> Option<u32> {
    schedule
        .passes
        .iter()
        .filter(|p| p.view == Some(View::Light) && p.draw == Some(plait_graph::Draw::Hair))
        .flat_map(|p| p.reads.iter().chain(p.writes.iter()))
        .filter(|b| b.slot == RANGE_SLOT)
        .find_map(|b| match &b.resolved(&schedule.resources)?.desc {
            ResourceDesc::Texture { width, .. } => Some(*width),
            _ => None,
        })
}

/// `plait::hair_map::map_width` on the CPU, in texels of a `texels`-wide
/// light map: the strand's width across the light (towards a directional
/// light's direction, or a spot's position); −1 behind the light.
pub fn light_width_texels(
    frame: &FrameUniforms,
    world: Vec3,
    tangent: Vec3,
    thickness: f32,
    texels: u32,
) -> f32 {
    let direction = Vec4::from(frame.light_direction);
    let to_light = if direction.w > 0.5 {
        (Vec4::from(frame.light_position).truncate() - world).normalize_or_zero()
    } else {
        direction.truncate()
    };
    let mut side = tangent.cross(to_light);
    if side.length_squared() < 1e-12 {
        let up = if to_light.y.abs() > 0.9 {
            Vec3::X
        } else {
            Vec3::Y
        };
        side = up.cross(to_light);
    }
    let side = side.normalize_or_zero();
    let view_proj = Mat4::from_cols_array_2d(&frame.light_view_proj);
    let a = view_proj * world.extend(1.0);
    let b = view_proj * (world + side * thickness).extend(1.0);
    if a.w <= 0.0 || b.w <= 0.0 {
        return -1.0;
    }
    let map = (b.truncate().truncate() / b.w - a.truncate().truncate() / a.w) * 0.5;
    map.length() * texels as f32
}
