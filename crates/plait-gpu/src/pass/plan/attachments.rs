//! The attachments and clears of a binding plan, which follow from the
//! accesses as settled: colour targets (with their MSAA resolves), the depth
//! target, and the storage buffers that start the pass zeroed.

use plait_graph::{Access, Binding, SlotRef};

use super::{ColorTarget, DepthTarget, Planner};

impl<'a> Planner<'a> {
    /// Fill the plan's colours, clears and depth target.
    pub(super) fn attachments(&mut self) {
        let settled: Vec<(SlotRef, Access, &'a Binding)> = SlotRef::all(self.pass)
            .map(|(slot, b)| (slot, self.access_of(slot, b.access), b))
            .collect();
        // In the order of `pass.writes`, so `Binding::resolves` indexes it.
        let writes: Vec<(Access, &Binding)> = settled
            .iter()
            .filter(|(s, _, _)| s.is_write())
            .map(|&(_, a, b)| (a, b))
            .collect();
        // An `X_resolve` paired (at compile) with a colour target `X`.
        let is_resolve = |b: &Binding| {
            b.resolves
                .and_then(|x| writes.get(x))
                .is_some_and(|(a, _)| *a == Access::ColorTarget)
        };
        for (i, &(a, b)) in writes.iter().enumerate() {
            match a {
                Access::ColorTarget if !is_resolve(b) => self.color_target(i, b, &writes),
                // Storage textures are not zeroed: clearing one needs
                // CLEAR_TEXTURE, which core WebGPU lacks; their kernels write
                // every texel (the lighting maps, the environment cube).
                Access::StorageWrite if !b.loads && self.texture(b.resource).is_none() => {
                    self.plan.clears.extend(b.resource)
                }
                // Nothing would fill a storage texture with its `clear`.
                Access::StorageWrite if !b.loads && self.clear_of(b.resource).is_some() => {
                    let message = format!(
                        "slot `{}` writes `{}` as a storage texture first in the frame, but `clear = …` applies only where a colour or depth target is cleared; write it from a raster pass first or drop `clear`",
                        b.slot, b.resource_name
                    );
                    self.error(&b.location, message);
                }
                _ => {}
            }
        }
        // Written depth first: a pass that writes depth tests against it.
        let depth = settled
            .iter()
            .filter(|(_, a, _)| *a == Access::DepthTarget)
            .min_by_key(|(s, _, _)| !s.is_write());
        self.plan.depth = depth.and_then(|&(slot, _, b)| {
            let (format, samples) = self.texture(b.resource)?;
            Some(DepthTarget {
                slot: b.slot.clone(),
                resource: b.id(),
                format,
                samples,
                written: slot.is_write(),
                loads: b.loads,
                clear: self.clear_of(b.resource),
            })
        });
    }

    /// A colour target (write `index`), with the `<slot>_resolve` target its
    /// samples resolve into if the pass writes one.
    fn color_target(&mut self, index: usize, b: &Binding, writes: &[(Access, &Binding)]) {
        let Some((format, samples)) = self.texture(b.resource) else {
            if b.resolved(self.resources).is_some() {
                let message = format!("colour target `{}` is not a texture", b.slot);
                self.error(&b.location, message);
            }
            return;
        };
        let resolve = writes
            .iter()
            .find(|(_, r)| r.resolves == Some(index))
            .map(|(_, r)| *r);
        if let Some(r) = resolve {
            self.check_resolve(b, r, format, samples);
        }
        self.plan.colors.push(ColorTarget {
            slot: b.slot.clone(),
            resource: b.id(),
            format,
            samples,
            loads: b.loads,
            clear: self.clear_of(b.resource),
            resolve: resolve.and_then(|r| r.resource),
        });
    }

    /// wgpu resolves only a multisampled target into a single-sampled one of
    /// the same format: say so at load, not as a validation error mid-frame.
    fn check_resolve(
        &mut self,
        b: &Binding,
        r: &Binding,
        format: plait_graph::Format,
        samples: u32,
    ) {
        let Some((resolve_format, resolve_samples)) = self.texture(r.resource) else {
            return;
        };
        if samples >= 2 && resolve_samples == 1 && resolve_format == format {
            return;
        }
        let name = |b: &Binding| b.resolved(self.resources).map_or("?", |r| r.name.as_str());
        let message = format!(
            "`{}` (slot `{}`, {samples} sample(s), {}) cannot be resolved into `{}` (slot `{}`, {resolve_samples} sample(s), {}): a resolve needs a multisampled colour target (samples 4) and a single-sampled target of the same format",
            name(b),
            b.slot,
            format.name(),
            name(r),
            r.slot,
            resolve_format.name(),
        );
        self.error(&r.location, message);
    }
}
