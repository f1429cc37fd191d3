//! `depth_lists`: exact self-shadowing, the ground truth — every hair
//! fragment's light depth stored per light texel (Sintorn & Assarsson 2009
//! §3, Fig. 5: the exact number of fragments in front, which the occupancy
//! order of §3.2 estimates).
//!
//! One hair draw from the light; each fragment takes a place in its texel's
//! list with `atomicAdd` on the texel's counter and stores its linear light
//! depth there (f32 bits). A list holds `capacity` depths (the `lists` buffer's
//! words per texel); fragments past it are dropped, counted in `overflow`
//! ([0] dropped fragments, [1] texels that overflowed) so a render can say
//! whether the truth is exact. The provider `plait::visibility::exact` counts
//! the stored depths in front of a point: visibility = exp(-w · n), n exact.
//! No sorting is needed — only a count.
//!
//! Memory: 512² × capacity × 4 B (96 MiB at capacity 96) + 1 MiB counters —
//! a reference, not a real-time method.

use plait_gpu::pass::{BuiltinShader, PassType};
use plait_graph::{Access, Format, PassShape, PassTypeSpec, ResolvedResource, ScheduledPass};

use crate::per_texel::check_words;
use crate::spec_util::{DEPTH, buffer, texture};

pub struct DepthLists;

/// The longest list the provider reads.
pub const MAX_CAPACITY: u64 = 1024;

impl PassType for DepthLists {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            name: "depth_lists".into(),
            description: "Every hair fragment's linear depth per texel (capacity from the buffer size), with counters and an overflow count.".into(),
            source: "Sintorn & Assarsson 2009 §3, Fig. 5".into(),
            shape: PassShape::Raster,
            inputs: vec![
                texture("range", Access::Sampled, &[Format::Rg32Float], "depth range of the same view: gives the map size"),
                texture("depth", Access::DepthTarget, DEPTH, "opaque depth of the same view, tested not written"),
            ],
            outputs: vec![
                buffer("lists", Access::StorageWrite, "capacity × f32 depths per texel"),
                buffer("counts", Access::StorageWrite, "fragments per texel (may exceed capacity)"),
                buffer("overflow", Access::StorageWrite, "[0] dropped fragments, [1] overflowing texels"),
            ],
            params: vec![],
            dynamic_slots: false,
            needs_shader: false,
            required_features: vec![],
        }
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some((
            "shaders/passes/depth_lists.wgsl",
            include_str!("../../../shaders/passes/depth_lists.wgsl"),
        ))
    }
    fn check_sizes(
        &self,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
    ) -> Result<(), String> {
        check_words(pass, resources, "lists", "range", 1, MAX_CAPACITY)?;
        check_words(pass, resources, "counts", "range", 1, 1)?;
        Ok(())
    }
}
