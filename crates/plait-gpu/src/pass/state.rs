//! Fixed-function state of a raster or fullscreen pass: chosen in Rust by a
//! pass type ([`RasterState`]), or written in TOML (`depth`, `blend`, `cull`
//! of [`plait_graph::raster_decl`]) and turned into a [`RasterState`] here,
//! with the checks that need the pass's targets.

use plait_graph::raster_decl::{
    Blend, BlendComponent, BlendFactor, BlendOp, BlendPreset, Compare, Cull, RasterDecl,
};
use plait_graph::{Access, Format, Location, ResolvedResource, ResourceDesc, ScheduledPass};

/// Depth test and write of a raster pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DepthMode {
    /// Test and write (the usual opaque pass).
    TestWrite(wgpu::CompareFunction),
    /// Test against a depth target read by the pass, never write it.
    TestOnly(wgpu::CompareFunction),
}

impl DepthMode {
    pub fn compare(self) -> wgpu::CompareFunction {
        match self {
            DepthMode::TestWrite(c) | DepthMode::TestOnly(c) => c,
        }
    }
}

/// Fixed-function state of a raster pass that its Rust module chooses.
#[derive(Clone, Debug, PartialEq)]
pub struct RasterState {
    pub cull_mode: Option<wgpu::Face>,
    /// Used when the pass has a depth attachment.
    pub depth: DepthMode,
    /// Blend per colour target, in target order; missing entries replace.
    pub blend: Vec<Option<wgpu::BlendState>>,
    pub clear_color: wgpu::Color,
    pub clear_depth: f32,
    pub alpha_to_coverage: bool,
    /// Channels written per colour target, in target order; missing entries write all.
    pub write_mask: Vec<wgpu::ColorWrites>,
    /// Keep colour targets' contents even where the schedule says this pass
    /// writes them first (the second draw of a pass that draws twice).
    pub load_colors: bool,
}

impl Default for RasterState {
    fn default() -> Self {
        RasterState {
            cull_mode: None,
            depth: DepthMode::TestWrite(wgpu::CompareFunction::Less),
            blend: Vec::new(),
            clear_color: wgpu::Color::TRANSPARENT,
            clear_depth: 1.0,
            alpha_to_coverage: false,
            write_mask: Vec::new(),
            load_colors: false,
        }
    }
}

/// A named blend state (the presets of pipeline files), for Rust pass types
/// too, so a preset means the same everywhere; `None` for `replace`.
pub fn blend_preset(preset: BlendPreset) -> Option<wgpu::BlendState> {
    blend_state(Blend::Preset(preset))
}

/// The wgpu blend state of a TOML blend (`None`: replace).
pub fn blend_state(blend: Blend) -> Option<wgpu::BlendState> {
    let (color, alpha) = blend.components()?;
    Some(wgpu::BlendState {
        color: blend_component(color),
        alpha: blend_component(alpha),
    })
}

fn blend_component(c: BlendComponent) -> wgpu::BlendComponent {
    use wgpu::BlendFactor as W;
    let factor = |f: BlendFactor| match f {
        BlendFactor::Zero => W::Zero,
        BlendFactor::One => W::One,
        BlendFactor::Src => W::Src,
        BlendFactor::OneMinusSrc => W::OneMinusSrc,
        BlendFactor::SrcAlpha => W::SrcAlpha,
        BlendFactor::OneMinusSrcAlpha => W::OneMinusSrcAlpha,
        BlendFactor::Dst => W::Dst,
        BlendFactor::OneMinusDst => W::OneMinusDst,
        BlendFactor::DstAlpha => W::DstAlpha,
        BlendFactor::OneMinusDstAlpha => W::OneMinusDstAlpha,
    };
    // WebGPU requires both factors to be `one` for min and max.
    let (src, dst) = match c.op {
        BlendOp::Min | BlendOp::Max => (W::One, W::One),
        _ => (factor(c.src), factor(c.dst)),
    };
    wgpu::BlendComponent {
        src_factor: src,
        dst_factor: dst,
        operation: match c.op {
            BlendOp::Add => wgpu::BlendOperation::Add,
            BlendOp::Subtract => wgpu::BlendOperation::Subtract,
            BlendOp::ReverseSubtract => wgpu::BlendOperation::ReverseSubtract,
            BlendOp::Min => wgpu::BlendOperation::Min,
            BlendOp::Max => wgpu::BlendOperation::Max,
        },
    }
}

pub fn compare_function(c: Compare) -> wgpu::CompareFunction {
    use wgpu::CompareFunction as W;
    match c {
        Compare::Never => W::Never,
        Compare::Less => W::Less,
        Compare::Equal => W::Equal,
        Compare::LessEqual => W::LessEqual,
        Compare::Greater => W::Greater,
        Compare::NotEqual => W::NotEqual,
        Compare::GreaterEqual => W::GreaterEqual,
        Compare::Always => W::Always,
    }
}

/// Whether a colour target of `format` can be blended at all. 32-bit floats
/// can (natively with `FLOAT32_BLENDABLE`, else in 16 bits with a note);
/// integer formats never can.
fn blendable(format: Format) -> bool {
    !matches!(
        format,
        Format::R32Uint | Format::Rg32Uint | Format::Rgba32Uint | Format::Depth32Float
    )
}

/// The state a TOML raster declaration gives `pass` (whose slot accesses are
/// settled), or every problem with it, each where it was written: a blend for
/// a slot that is not a colour target or whose format cannot blend, a depth
/// test without a depth input, a depth write into a target the pass only reads.
/// `decl` is the pass's over its type's ([`PassType::raster_decl`]), whose
/// blends compile resolved to writes ([`ScheduledPass::blend_writes`]).
///
/// [`PassType::raster_decl`]: super::PassType::raster_decl
pub fn from_decl(
    decl: &RasterDecl,
    pass: &ScheduledPass,
    resources: &[ResolvedResource],
) -> Result<RasterState, Vec<(Location, String)>> {
    let mut errors = Vec::new();
    let mut state = RasterState::default();
    // The colour targets drawn into (an `X_resolve` only receives samples),
    // as indices into `pass.writes`, in attachment order.
    let targets: Vec<usize> = (0..pass.writes.len())
        .filter(|&i| pass.writes[i].access == Access::ColorTarget && !pass.is_resolve(i))
        .collect();
    // A culled pass may bind resources the schedule dropped: what they would
    // have been is unknown, so they are not held against it.
    let dropped = |b: &plait_graph::Binding| b.resolved(resources).is_none();
    let any_dropped = pass.reads.iter().chain(pass.writes.iter()).any(dropped);
    for (k, (slot, blend)) in decl.blend.iter().enumerate() {
        let write = pass.blend_writes.get(k).copied().flatten();
        if write.is_some_and(|w| dropped(&pass.writes[w])) {
            continue;
        }
        let Some(index) = write.and_then(|w| targets.iter().position(|&t| t == w)) else {
            let names: Vec<&str> = targets
                .iter()
                .map(|&t| pass.writes[t].slot.as_str())
                .collect();
            errors.push((
                blend.location.clone(),
                format!(
                    "`blend.{slot}`: `{slot}` is not a colour target of this pass{}",
                    if names.is_empty() {
                        " (it has none)".to_owned()
                    } else {
                        format!(
                            "{} (colour targets: {})",
                            plait_graph::suggest::did_you_mean(slot, names.iter().copied()),
                            names.join(", ")
                        )
                    }
                ),
            ));
            continue;
        };
        let Some(res) = pass.writes[targets[index]].resolved(resources) else {
            continue;
        };
        if let ResourceDesc::Texture { format, .. } = res.desc
            && blend.components().is_some()
            && !blendable(format)
        {
            errors.push((
                blend.location.clone(),
                format!(
                    "`blend.{slot}`: `{}` is {format}, which cannot be blended (integer formats have no blending); use `replace`, a float format, or atomics on a storage buffer",
                    res.name
                ),
            ));
            continue;
        }
        if state.blend.len() <= index {
            state.blend.resize(index + 1, None);
        }
        state.blend[index] = blend_state(blend.value);
    }
    let depth_target = pass
        .writes
        .iter()
        .map(|b| (b, true))
        .chain(pass.reads.iter().map(|b| (b, false)))
        .find(|(b, _)| b.access == Access::DepthTarget);
    if let Some(depth) = &decl.depth {
        let compare = compare_function(depth.compare);
        match (depth_target, depth.write) {
            (None, _) if any_dropped => {}
            (None, _) => errors.push((
                depth.location.clone(),
                "a depth test needs a depth input: bind a depth32float texture under `reads` (tested only) or `writes` (tested and written)".into(),
            )),
            (Some((b, false)), Some(true)) => errors.push((
                depth.location.clone(),
                format!(
                    "`write = true`, but the depth target `{}` is bound under `reads`; bind it under `writes` to write it",
                    b.slot
                ),
            )),
            (Some((_, written)), write) => {
                state.depth = if write.unwrap_or(written) {
                    DepthMode::TestWrite(compare)
                } else {
                    DepthMode::TestOnly(compare)
                };
            }
        }
    }
    if let Some(cull) = &decl.cull {
        state.cull_mode = match cull.value {
            Cull::None => None,
            Cull::Front => Some(wgpu::Face::Front),
            Cull::Back => Some(wgpu::Face::Back),
        };
    }
    if let Some(a2c) = &decl.alpha_to_coverage
        && a2c.value
    {
        // wgpu accepts alpha to coverage only with more than one sample.
        let samples = targets
            .first()
            .and_then(|&t| pass.writes[t].resolved(resources))
            .map(|r| match r.desc {
                ResourceDesc::Texture { samples, .. } => samples,
                ResourceDesc::Buffer { .. } | ResourceDesc::AccelerationStructure => 1,
            });
        match samples {
            Some(n) if n > 1 => state.alpha_to_coverage = true,
            None if any_dropped => {}
            _ => errors.push((
                a2c.location.clone(),
                "`alpha_to_coverage = true` needs a multisampled colour target: give the resource written under the pass's first colour slot `samples = 4`".into(),
            )),
        }
    }
    if errors.is_empty() {
        Ok(state)
    } else {
        Err(errors)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_the_usual_blend_states() {
        assert_eq!(blend_preset(BlendPreset::Replace), None);
        assert_eq!(
            blend_preset(BlendPreset::Over),
            Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING)
        );
        assert_eq!(
            blend_preset(BlendPreset::Alpha),
            Some(wgpu::BlendState::ALPHA_BLENDING)
        );
        let additive = blend_preset(BlendPreset::Additive).expect("blends");
        assert_eq!(additive.color, additive.alpha);
        assert_eq!(additive.color.src_factor, wgpu::BlendFactor::One);
        assert_eq!(additive.color.dst_factor, wgpu::BlendFactor::One);
        let under = blend_preset(BlendPreset::Under).expect("blends");
        assert_eq!(under.color.src_factor, wgpu::BlendFactor::OneMinusDstAlpha);
        assert_eq!(under.color.dst_factor, wgpu::BlendFactor::One);
    }
}
