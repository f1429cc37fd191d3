//! The first phases of a binding plan: each slot matched to the shader
//! binding of its name or, in a data-only raster pass, settled as an
//! attachment; then the rules on a pass's targets as a whole.

use plait_graph::{
    Access, Binding, Error as GraphError, ErrorKind, PassShape, ResolvedResource, ResourceDesc,
    ResourceKind, ScheduledPass, SlotRef,
};

use super::Planner;
use crate::reflect::{BindingKind, ShaderBinding};

impl Planner<'_> {
    /// Check every live slot against its binding and settle the accesses of
    /// a data-only pass from the shader. Returns how many colour targets
    /// were settled.
    pub(super) fn settle_slots(&mut self) -> usize {
        let mut color_targets = 0;
        for (slot, b) in SlotRef::all(self.pass) {
            let Some(res) = b.resolved(self.resources) else {
                // A culled pass's binding to a resource nothing live uses.
                continue;
            };
            let name = self.binding_of(&b.slot);
            let bound = self.group1.iter().find(|s| s.name == name).cloned();
            match bound {
                None if self.dynamic_slots => {
                    if let Some(access) = self.settle_unbound(slot, b, res) {
                        color_targets += usize::from(access == Access::ColorTarget);
                        self.plan.settled.push((slot, access));
                    }
                }
                // A slot every hair draw takes, which this shader does not read.
                None if b.shared => {}
                None => {
                    if !matches!(b.access, Access::ColorTarget | Access::DepthTarget) {
                        let message = format!(
                            "the shader declares no binding named `{}` for this slot",
                            b.slot
                        );
                        self.error(&b.location, message);
                    }
                }
                Some(sb) => {
                    check_binding(&sb, b, res, self.pass, slot.is_write(), &mut self.errors);
                    if self.dynamic_slots {
                        self.plan.settled.push((slot, binding_access(&sb)));
                    }
                }
            }
        }
        color_targets
    }

    /// A data-only pass's slot the shader does not bind: an attachment of a
    /// raster pass (depth if it is a depth texture, else a colour target it
    /// writes), or an error.
    fn settle_unbound(
        &mut self,
        slot: SlotRef,
        b: &Binding,
        res: &ResolvedResource,
    ) -> Option<Access> {
        let is_depth =
            matches!(res.desc, ResourceDesc::Texture { format, .. } if format.is_depth());
        if !self.is_raster() || res.desc.kind() != ResourceKind::Texture {
            let message = format!("slot `{}` is not a binding of the shader", b.slot);
            self.error(&b.location, message);
            None
        } else if is_depth {
            Some(Access::DepthTarget)
        } else if slot.is_write() {
            Some(Access::ColorTarget)
        } else {
            let message = format!(
                "slot `{}` is read but the shader declares no binding of that name",
                b.slot
            );
            self.error(&b.location, message);
            None
        }
    }

    /// One depth target at most, and a data-only raster pass writes
    /// something: a target, its depth, or storage.
    pub(super) fn check_targets(&mut self, color_targets: usize) {
        // A depth texture the shader does not bind is the depth test's
        // target; a second one (a shadow map the shader stopped using) would
        // be silently dropped, so it is refused at its slot.
        let pass = self.pass;
        let depth_slots: Vec<&Binding> = self
            .plan
            .settled
            .iter()
            .filter(|(_, a)| *a == Access::DepthTarget)
            .filter_map(|(s, _)| s.get(pass))
            .collect();
        if let [first, extra, ..] = depth_slots.as_slice() {
            let message = format!(
                "slot `{}` is a depth texture the shader does not bind, so it would be a second depth target (`{}` is the first): bind it in the shader or drop it",
                extra.slot, first.slot
            );
            self.error(&extra.location, message);
        }
        // (A culled pass's writes may name resources the schedule dropped.)
        let all_writes_live = pass
            .writes
            .iter()
            .all(|b| b.resolved(self.resources).is_some());
        let writes_depth = self
            .plan
            .settled
            .iter()
            .any(|(s, a)| s.is_write() && *a == Access::DepthTarget);
        if self.dynamic_slots
            && self.is_raster()
            && all_writes_live
            && color_targets == 0
            && !writes_depth
            && !self.plan.writes_storage
        {
            let shape = if self.shape == PassShape::Fullscreen {
                "fullscreen"
            } else {
                "raster"
            };
            let message = format!("a {shape} pass must write at least one target");
            self.error(&pass.location, message);
        }
    }
}

/// The access a slot bound to shader binding `sb` has.
fn binding_access(sb: &ShaderBinding) -> Access {
    match sb.kind {
        BindingKind::Uniform { .. } => Access::Uniform,
        BindingKind::Texture { .. } => Access::Sampled,
        _ if sb.writes() => Access::StorageWrite,
        _ => Access::StorageRead,
    }
}

/// A slot bound to shader binding `sb`: resource kind, format, samples,
/// layers, and writes through a slot declared under `reads`.
fn check_binding(
    sb: &ShaderBinding,
    b: &plait_graph::Binding,
    res: &ResolvedResource,
    pass: &ScheduledPass,
    is_write: bool,
    errors: &mut Vec<GraphError>,
) {
    let err = |message: String| {
        GraphError::new(
            b.location.clone(),
            ErrorKind::Pass {
                pass: pass.name.clone(),
                message,
            },
        )
    };
    if sb.resource_kind() != Some(res.desc.kind()) {
        errors.push(err(format!(
            "slot `{}` is bound to {} `{}`, but the shader declares it as {:?}",
            b.slot,
            res.desc.kind(),
            res.name,
            sb.kind
        )));
        return;
    }
    if let ResourceDesc::Texture {
        format,
        samples,
        layers,
        ..
    } = res.desc
    {
        if let Err(why) = sb.accepts_format(format) {
            errors.push(GraphError::new(
                b.location.clone(),
                ErrorKind::FormatMismatch {
                    resource: res.name.clone(),
                    declared: format.to_string(),
                    pass: pass.name.clone(),
                    slot: b.slot.clone(),
                    accepted: why,
                },
            ));
        }
        let (multi, arrayed) = match sb.kind {
            BindingKind::Texture {
                multisampled,
                arrayed,
                ..
            } => (multisampled, arrayed),
            BindingKind::StorageTexture { arrayed, .. } => (false, arrayed),
            _ => (false, false),
        };
        if multi != (samples > 1) {
            errors.push(err(format!(
                "`{}` has {samples} samples but the shader's `{}` is {}multisampled",
                res.name,
                b.slot,
                if multi { "" } else { "not " }
            )));
        }
        if arrayed != (layers > 1) {
            errors.push(err(format!(
                "`{}` has {layers} layers but the shader's `{}` is {}an array texture",
                res.name,
                b.slot,
                if arrayed { "" } else { "not " }
            )));
        }
    }
    if sb.writes() && !is_write {
        errors.push(err(format!(
            "the shader writes `{}`; bind it under `writes`, not `reads`",
            b.slot
        )));
    }
}
