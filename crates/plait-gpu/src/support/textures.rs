//! What a schedule's textures need of their formats, as the pool creates
//! them: usages per slot, copies, sample counts, layers.

use plait_graph::{Access, ResourceDesc, Schedule, ScheduledPass};
use wgpu::TextureUsages as U;

use super::check::problem;
use super::{AdapterSupport, Problem};
use crate::pool::texture_format;

/// What every texture needs whatever reads it: copies (readback, histories)
/// for single-sampled ones, the sample count for multisampled ones.
pub(super) fn resource_problems(
    schedule: &Schedule,
    support: &AdapterSupport,
    out: &mut Vec<Problem>,
) {
    for r in schedule.resources.iter().filter(|r| !r.scene) {
        let ResourceDesc::Texture {
            format,
            samples,
            layers,
            ..
        } = r.desc
        else {
            continue;
        };
        let tf = texture_format(format);
        let features = support.format(format);
        let mut add = |what: String, missing: String| {
            out.push(problem(None, &r.location, Some(&r.name), what, missing))
        };
        if samples > 1 {
            if !features.flags.sample_count_supported(samples) {
                add(
                    format!("texture `{}` ({format}, {samples} samples)", r.name),
                    format!(
                        "Sample count {samples} is not supported by format {tf:?} on this adapter (it supports {:?})",
                        features.flags.supported_sample_counts()
                    ),
                );
            }
        } else {
            let missing = (U::COPY_SRC | U::COPY_DST) - features.allowed_usages;
            if !missing.is_empty() {
                add(
                    format!(
                        "texture `{}` ({format}), which the engine copies (readback, histories)",
                        r.name
                    ),
                    usages_not_allowed(missing, tf),
                );
            }
        }
        if layers > support.limits.max_texture_array_layers {
            add(
                format!("texture `{}` ({layers} layers)", r.name),
                format!(
                    "the adapter's max_texture_array_layers is {}",
                    support.limits.max_texture_array_layers
                ),
            );
        }
    }
}

/// wgpu's words for a texture created with usages its format does not allow.
fn usages_not_allowed(missing: U, tf: wgpu::TextureFormat) -> String {
    let webgpu = tf
        .guaranteed_format_features(wgpu::Features::empty())
        .allowed_usages;
    let downlevel = if webgpu.contains(missing) {
        " due to downlevel restrictions"
    } else {
        ""
    };
    format!("Texture usages {missing:?} are not allowed on a texture of type {tf:?}{downlevel}")
}

/// The usages a pass's slots give their textures (as the pool creates them).
pub(super) fn usage_problems(
    pass: &ScheduledPass,
    schedule: &Schedule,
    support: &AdapterSupport,
    out: &mut Vec<Problem>,
) {
    for b in pass.reads.iter().chain(&pass.writes) {
        let Some(r) = b.resolved(&schedule.resources).filter(|r| !r.scene) else {
            continue;
        };
        let ResourceDesc::Texture {
            format, samples, ..
        } = r.desc
        else {
            continue;
        };
        let (mut usage, verb) = match b.access {
            Access::Sampled => (U::TEXTURE_BINDING, "samples"),
            Access::StorageRead | Access::StorageWrite => {
                (U::STORAGE_BINDING, "binds as a storage texture")
            }
            // Targets are sampleable too (the pool's rule: a pass may read back what it drew).
            Access::ColorTarget => (U::RENDER_ATTACHMENT | U::TEXTURE_BINDING, "renders into"),
            Access::DepthTarget => (
                U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
                "uses as its depth target",
            ),
            Access::Uniform => continue,
        };
        // A multisampled target is only rendered into (the pool's rule).
        if samples > 1 {
            usage &= match b.access {
                Access::Sampled => U::TEXTURE_BINDING,
                _ => U::RENDER_ATTACHMENT,
            };
        }
        let missing = usage - support.format(format).allowed_usages;
        if !missing.is_empty() {
            out.push(problem(
                Some(pass),
                &b.location,
                Some(&r.name),
                format!("{verb} `{}` ({format}, slot `{}`)", r.name, b.slot),
                usages_not_allowed(missing, texture_format(format)),
            ));
        }
    }
}
