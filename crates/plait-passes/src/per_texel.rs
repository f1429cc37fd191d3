//! Size checks for light-map buffers that hold a fixed number of u32 words per
//! texel of a map they go with (occupancy bits, slab counts, deep opacity
//! layers, opacity shadow map slices, density clusters, exact fragment lists):
//! a wrong size would make the shaders index the wrong texel, so `plait check`
//! refuses it (`PassType::check_sizes`) before any GPU work.

use plait_graph::{ResolvedResource, ResourceDesc, ScheduledPass};

/// The buffer bound to `buffer_slot` must hold `k · multiple` u32 words per
/// texel of the texture bound to `texture_slot`, with 1 ≤ k·multiple ≤ `max`.
/// Returns the words per texel (or `None` when a slot is unbound).
pub fn check_words(
    pass: &ScheduledPass,
    resources: &[ResolvedResource],
    buffer_slot: &str,
    texture_slot: &str,
    multiple: u64,
    max: u64,
) -> Result<Option<u64>, String> {
    let desc = |slot: &str| {
        pass.reads
            .iter()
            .chain(pass.writes.iter())
            .find(|b| b.slot == slot)
            // A culled pass may name resources the schedule dropped.
            .and_then(|b| resources.get(b.resource))
            .map(|r| (r.name.clone(), r.desc.clone()))
    };
    let (
        Some((buffer_name, ResourceDesc::Buffer { size })),
        Some((_, ResourceDesc::Texture { width, height, .. })),
    ) = (desc(buffer_slot), desc(texture_slot))
    else {
        return Ok(None);
    };
    let per_texel = 4 * width as u64 * height as u64;
    let words = size / per_texel;
    if size == 0
        || !size.is_multiple_of(per_texel)
        || !words.is_multiple_of(multiple)
        || words > max
        || words == 0
    {
        return Err(format!(
            "buffer `{buffer_name}` (slot `{buffer_slot}`) has {size} bytes; it needs a multiple of {multiple} u32 words (at most {max}) per texel of the {width}x{height} map, i.e. a multiple of {} bytes",
            per_texel * multiple
        ));
    }
    Ok(Some(words))
}
