//! Binding one pass's `reads` or `writes` to resources: each slot looked up
//! among its type's slots (and the shared slots of hair draws), the resource
//! among the declared and scene resources, and the pair checked — kind,
//! texture format, writes to read-only scene resources or histories, and
//! required slots left unbound.

use indexmap::IndexMap;

use crate::error::{Error, ErrorKind, Spanned};
use crate::load::{PassDecl, Pipeline};
use crate::scene_resources::{SCENE_RESOURCES, scene_resource};
use crate::schedule::*;
use crate::spec::{Access, PassTypeSpec, ResourceKind, SlotSpec};

#[derive(Clone, Copy, PartialEq)]
pub(super) enum Direction {
    Read,
    Write,
}

impl Direction {
    fn word(self) -> &'static str {
        match self {
            Direction::Read => "input",
            Direction::Write => "output",
        }
    }
}

/// What binding one direction of one pass's slots shares.
struct Binder<'a> {
    decl: &'a PassDecl,
    spec: Option<&'a PassTypeSpec>,
    /// Slots the pass takes beyond its type's ([`Registry::shared_slots`]).
    shared: &'a [SlotSpec],
    pipeline: &'a Pipeline,
    descs: &'a [Option<ResourceDesc>],
    direction: Direction,
    /// The type's slots for `direction` (none for an unknown type).
    slots: &'a [SlotSpec],
    errors: &'a mut Vec<Error>,
}

/// Binds `reads` or `writes`; `Binding::resource` is an index into
/// `pipeline.resources` until [`build_schedule`](super::schedule::build_schedule) renumbers it.
pub(super) fn bind_slots(
    decl: &PassDecl,
    spec: Option<&PassTypeSpec>,
    shared: &[SlotSpec],
    pipeline: &Pipeline,
    descs: &[Option<ResourceDesc>],
    direction: Direction,
    errors: &mut Vec<Error>,
) -> Vec<Binding> {
    let (written, slots): (_, &[SlotSpec]) = match direction {
        Direction::Read => (&decl.reads, spec.map_or(&[][..], |s| &s.inputs)),
        Direction::Write => (&decl.writes, spec.map_or(&[][..], |s| &s.outputs)),
    };
    let mut binder = Binder {
        decl,
        spec,
        shared,
        pipeline,
        descs,
        direction,
        slots,
        errors,
    };
    let mut bindings = Vec::new();
    for (slot_name, resource) in written {
        // `slot = ""` unbinds a slot the base file bound: how a variant
        // (`extends`) drops an input it does not need.
        if resource.value.is_empty() {
            continue;
        }
        if let Some(binding) = binder.bind(slot_name, resource) {
            bindings.push(binding);
        }
    }
    if spec.is_some() {
        binder.check_missing(written);
    }
    bindings
}

impl Binder<'_> {
    /// Binds one slot to the resource it names, or reports why it cannot be.
    fn bind(&mut self, slot_name: &String, resource: &Spanned<String>) -> Option<Binding> {
        let scene = scene_resource(&resource.value);
        let index = self.resource_index(resource)?;
        self.check_not_history(index, resource)?;
        let declared_kind = self
            .pipeline
            .resources
            .get_index(index)
            .map_or(ResourceKind::Buffer, |(_, r)| r.kind.value);
        let slot = self
            .slots
            .iter()
            .chain(self.shared)
            .find(|s| &s.name == slot_name);
        let (access, loads) = self.access(slot, slot_name, resource, declared_kind)?;
        if let Some(slot) = slot {
            self.check_fit(slot, slot_name, resource, index, declared_kind);
        }
        Some(Binding {
            slot: slot_name.clone(),
            slot_id: self.slot_id(slot_name),
            resolves: None,
            resource: Some(ResourceId::new(index)),
            resource_name: resource.value.clone(),
            access,
            // The scene's contents are there before any pass: never cleared.
            // `loads = [...]`: the pass draws over what the attachment holds.
            loads: loads
                || (self.direction == Direction::Write
                    && (scene.is_some() || self.decl.raster.keeps(slot_name))),
            location: resource.location.clone(),
            shared: !self.slots.iter().any(|s| &s.name == slot_name)
                && self.shared.iter().any(|s| &s.name == slot_name),
        })
    }

    /// The handle of `slot_name` ([`crate::SlotId`]): one of the type's
    /// slots for this direction, else one of the shared slots.
    fn slot_id(&self, slot_name: &str) -> Option<crate::SlotId> {
        let named = |s: &SlotSpec| s.name == slot_name;
        let own = self.slots.iter().position(named).map(match self.direction {
            Direction::Read => crate::SlotId::Input,
            Direction::Write => crate::SlotId::Output,
        });
        own.or_else(|| {
            self.shared
                .iter()
                .position(named)
                .map(crate::SlotId::Shared)
        })
    }

    /// The index of the resource named, declared or scene (after the
    /// declared ones), or `None` once reported unknown or not writable.
    fn resource_index(&mut self, resource: &Spanned<String>) -> Option<usize> {
        let pipeline = self.pipeline;
        let scene = scene_resource(&resource.value);
        match (pipeline.resources.get_index_of(&resource.value), scene) {
            (Some(index), _) => Some(index),
            (None, Some((i, scene))) => {
                if self.direction == Direction::Write && !scene.writable {
                    let writable: Vec<_> = SCENE_RESOURCES
                        .iter()
                        .filter(|r| r.writable)
                        .map(|r| r.name)
                        .collect();
                    self.errors.push(Error::new(
                        resource.location.clone(),
                        ErrorKind::Pass {
                            pass: self.decl.name.clone(),
                            message: format!(
                                "scene resource `{}` is read-only ({}); passes may write only {}",
                                scene.name,
                                scene.doc,
                                writable.join(", ")
                            ),
                        },
                    ));
                    return None;
                }
                Some(pipeline.resources.len() + i)
            }
            (None, None) => {
                self.errors
                    .push(crate::history::undeclared(pipeline, resource));
                None
            }
        }
    }

    /// Reports a write to a history (`R.previous`), returning `None` then.
    fn check_not_history(&mut self, index: usize, resource: &Spanned<String>) -> Option<()> {
        if self.direction == Direction::Write
            && let Some((_, declared)) = self.pipeline.resources.get_index(index)
            && let Some(of) = &declared.previous_of
        {
            self.errors.push(Error::new(
                resource.location.clone(),
                ErrorKind::WritesHistory {
                    pass: self.decl.name.clone(),
                    previous: resource.value.clone(),
                    resource: of.resource.clone(),
                },
            ));
            return None;
        }
        Some(())
    }

    /// The slot's access and whether it loads, or `None` once the slot is
    /// reported unknown to the type.
    fn access(
        &mut self,
        slot: Option<&SlotSpec>,
        slot_name: &str,
        resource: &Spanned<String>,
        declared_kind: ResourceKind,
    ) -> Option<(Access, bool)> {
        match (slot, self.spec) {
            (Some(slot), _) => Some((slot.access, slot.loads)),
            // Data-only passes: the shader's bindings decide (checked later by
            // naga reflection); assume the common access for the direction.
            (None, Some(spec)) if spec.dynamic_slots => {
                Some((dynamic_access(self.direction, declared_kind), false))
            }
            (None, Some(spec)) => {
                let known: Vec<_> = self.slots.iter().map(|s| s.name.as_str()).collect();
                self.errors.push(Error::new(
                    resource.location.clone(),
                    ErrorKind::UnknownSlot {
                        pass: self.decl.name.clone(),
                        pass_type: spec.name.clone(),
                        direction: self.direction.word(),
                        slot: slot_name.to_owned(),
                        known: if known.is_empty() {
                            "none".into()
                        } else {
                            known.join(", ")
                        },
                    },
                ));
                None
            }
            // Unknown pass type (already reported): keep the edge so graph
            // errors can still be found.
            (None, None) => Some((dynamic_access(self.direction, declared_kind), false)),
        }
    }

    /// Checks the resource's kind, then its texture format, against the slot's.
    fn check_fit(
        &mut self,
        slot: &SlotSpec,
        slot_name: &str,
        resource: &Spanned<String>,
        index: usize,
        declared_kind: ResourceKind,
    ) {
        if slot.kind != declared_kind {
            self.errors.push(Error::new(
                resource.location.clone(),
                ErrorKind::KindMismatch {
                    resource: resource.value.clone(),
                    declared: declared_kind.to_string(),
                    pass: self.decl.name.clone(),
                    slot: slot_name.to_owned(),
                    expected: slot.kind.to_string(),
                },
            ));
        } else if let Some(Some(ResourceDesc::Texture { format, .. })) = self.descs.get(index)
            && !slot.formats.accepts(*format)
        {
            self.errors.push(Error::new(
                resource.location.clone(),
                ErrorKind::FormatMismatch {
                    resource: resource.value.clone(),
                    declared: format.to_string(),
                    pass: self.decl.name.clone(),
                    slot: slot_name.to_owned(),
                    accepted: slot.formats.to_string(),
                },
            ));
        }
    }

    /// Reports each required slot of the type the pass leaves unbound.
    fn check_missing(&mut self, written: &IndexMap<String, Spanned<String>>) {
        for slot in self.slots.iter().filter(|s| !s.optional) {
            if !written.contains_key(&slot.name) {
                self.errors.push(Error::new(
                    self.decl.location.clone(),
                    ErrorKind::MissingSlot {
                        pass: self.decl.name.clone(),
                        direction: self.direction.word(),
                        slot: slot.name.clone(),
                    },
                ));
            }
        }
    }
}

fn dynamic_access(direction: Direction, kind: ResourceKind) -> Access {
    match (direction, kind) {
        (Direction::Read, ResourceKind::Texture) => Access::Sampled,
        (Direction::Read, ResourceKind::Buffer | ResourceKind::AccelerationStructure) => {
            Access::StorageRead
        }
        (Direction::Write, _) => Access::StorageWrite,
    }
}
