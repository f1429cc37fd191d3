//! The last phase of a binding plan: what feeds each group-1 binding of the
//! shader — a slot, a params uniform or a scene buffer — and the bindings
//! plait cannot feed.

use plait_graph::{Error as GraphError, ErrorKind};

use super::{BindingSource, PlannedBinding, Planner};
use crate::pass::pass_type::SCENE_BINDINGS;
use crate::reflect::{self, BindingKind, ShaderBinding};

impl Planner<'_> {
    /// Every shader binding needs a slot, a params uniform or a scene buffer.
    pub(super) fn group1_sources(&mut self) {
        for sb in std::mem::take(&mut self.group1) {
            let Some(source) = self.source_of(&sb) else {
                continue;
            };
            match &sb.kind {
                BindingKind::Sampler { .. } => {
                    let message = format!(
                        "sampler `{}` belongs in group 0 (import plait::frame)",
                        sb.name
                    );
                    self.error(&self.pass.location, message);
                }
                BindingKind::StorageTexture { format: None, .. } => {
                    let message =
                        format!("storage texture `{}` has an unsupported format", sb.name);
                    self.error(&self.pass.location, message);
                }
                _ => {}
            }
            self.plan.bindings.push(PlannedBinding {
                binding: sb.binding,
                name: sb.name.clone(),
                kind: sb.kind.clone(),
                source,
            });
        }
    }

    /// What feeds `sb`, or `None` after reporting why nothing can.
    fn source_of(&mut self, sb: &ShaderBinding) -> Option<BindingSource> {
        let pass = self.pass;
        let slot = pass
            .reads
            .iter()
            .chain(pass.writes.iter())
            .find(|s| self.binding_of(&s.slot) == sb.name);
        if let Some(s) = slot {
            // A culled pass's slot may name a dropped resource: nothing
            // to bind (the plan of a culled pass is checked, never built).
            let resource = s.resource?;
            return Some(BindingSource::Slot {
                resource,
                format: self.texture(Some(resource)).map(|(f, _)| f),
            });
        }
        if is_params(sb) {
            let packed = reflect::params_layout(self.module, &sb.name)
                .ok_or_else(|| format!("`{}` must be a uniform struct", sb.name))
                .and_then(|(size, members)| reflect::pack_params(size, &members, &pass.params));
            return match packed {
                Ok(bytes) => Some(BindingSource::Params(bytes)),
                Err(message) => {
                    self.error(&pass.location, message);
                    None
                }
            };
        }
        if SCENE_BINDINGS.contains(&sb.name.as_str()) {
            if sb.writes() {
                // Bound by name it is read-only: a writer must say so in
                // the file, so the graph orders it before the hair draws.
                let message = format!(
                    "the shader writes scene resource `{}`; bind it under `writes` (`writes = {{ {0} = \"{0}\" }}`)",
                    sb.name
                );
                self.error(&pass.location, message);
                return None;
            }
            return Some(BindingSource::Scene(sb.name.clone()));
        }
        self.errors.push(GraphError::new(
            pass.location.clone(),
            ErrorKind::MissingBinding {
                pass: pass.name.clone(),
                binding: sb.name.clone(),
                group: sb.group,
                index: sb.binding,
            },
        ));
        None
    }
}

/// A uniform filled from the pass params by member name: `params`, or a
/// module's own such as `visibility_params`.
fn is_params(b: &ShaderBinding) -> bool {
    matches!(b.kind, BindingKind::Uniform { .. }) && b.name.ends_with("params")
}
