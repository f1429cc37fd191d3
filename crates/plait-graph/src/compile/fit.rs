//! The two compile inputs that are not the pipeline: a checker of each pass
//! against its shader, and the adapter's capabilities. Both act before the
//! memory plan, so the schedule compile returns is final — its accesses
//! settled, its formats the ones the adapter will allocate, its memory sums
//! those formats' — and nothing rewrites it afterwards.
//!
//! The graph crate knows no shader language: the checker is a trait the GPU
//! crate implements with naga ([`PassChecker`]). Without one
//! ([`NoShaders`]) compile checks everything the pipeline files say and
//! nothing its shaders do.

use crate::error::Error;
use crate::format::Format;
use crate::schedule::{Binding, ResolvedResource, ResourceDesc, ResourceId, ScheduledPass};
use crate::spec::Access;

/// What the adapter can do that changes a schedule (not merely refuses it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capabilities {
    /// 32-bit float colour targets can be blended (`FLOAT32_BLENDABLE`).
    /// Without it every blended r/rg/rgba32float target, and every resource
    /// sharing its memory, becomes the 16-bit float format with the same
    /// channels, and the schedule's notes say so.
    pub float32_blendable: bool,
}

impl Default for Capabilities {
    /// Checking without a GPU keeps the formats as written: the device a
    /// pipeline runs on compiles it again with its own capabilities.
    fn default() -> Self {
        Capabilities {
            float32_blendable: true,
        }
    }
}

/// Which slot of a pass a settled access is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlotRef {
    Read(usize),
    Write(usize),
}

impl SlotRef {
    /// Every slot of `pass`, reads first, with its binding.
    pub fn all(pass: &ScheduledPass) -> impl Iterator<Item = (SlotRef, &Binding)> {
        let reads = pass.reads.iter().enumerate();
        let writes = pass.writes.iter().enumerate();
        reads
            .map(|(i, b)| (SlotRef::Read(i), b))
            .chain(writes.map(|(i, b)| (SlotRef::Write(i), b)))
    }

    pub fn is_write(self) -> bool {
        matches!(self, SlotRef::Write(_))
    }

    /// The binding this refers to in `pass`, if it has that many slots.
    pub fn get(self, pass: &ScheduledPass) -> Option<&Binding> {
        match self {
            SlotRef::Read(i) => pass.reads.get(i),
            SlotRef::Write(i) => pass.writes.get(i),
        }
    }

    pub fn get_mut(self, pass: &mut ScheduledPass) -> Option<&mut Binding> {
        match self {
            SlotRef::Read(i) => pass.reads.get_mut(i),
            SlotRef::Write(i) => pass.writes.get_mut(i),
        }
    }
}

/// Give `pass`'s slots the accesses a checker settled.
pub fn apply_settled(pass: &mut ScheduledPass, settled: &[(SlotRef, Access)]) {
    for &(slot, access) in settled {
        if let Some(b) = slot.get_mut(pass) {
            b.access = access;
        }
    }
}

/// What checking one pass against its shader found.
#[derive(Clone, Debug, Default)]
pub struct PassCheck {
    pub errors: Vec<Error>,
    /// How the slots of a data-only pass are accessed, read from its shader.
    pub settled: Vec<(SlotRef, Access)>,
    /// The colour targets the pass blends into.
    pub blended: Vec<ResourceId>,
}

/// Checks passes against their shaders; the GPU crate's naga checker.
pub trait PassChecker {
    /// Errors that concern the whole shader library (a provider breaking its
    /// contract): reported once, not once per pass importing it.
    fn check_library(&self) -> Vec<Error> {
        Vec::new()
    }
    fn check_pass(&self, pass: &ScheduledPass, resources: &[ResolvedResource]) -> PassCheck;
}

/// No shader checks: the pipeline files' own rules only.
pub struct NoShaders;

impl PassChecker for NoShaders {
    fn check_pass(&self, _: &ScheduledPass, _: &[ResolvedResource]) -> PassCheck {
        PassCheck::default()
    }
}

/// Check every pass (live and culled), settle the accesses, and return the
/// errors and the resources blended into.
pub(super) fn check_passes<'p>(
    checker: &dyn PassChecker,
    passes: impl Iterator<Item = &'p mut ScheduledPass>,
    resources: &[ResolvedResource],
) -> (Vec<Error>, Vec<ResourceId>) {
    let library = checker.check_library();
    if !library.is_empty() {
        return (library, Vec::new());
    }
    let mut errors = Vec::new();
    let mut blended = Vec::new();
    for pass in passes {
        let found = checker.check_pass(pass, resources);
        errors.extend(found.errors);
        apply_settled(pass, &found.settled);
        blended.extend(found.blended);
    }
    (errors, blended)
}

fn half(f: Format) -> Option<Format> {
    match f {
        Format::R32Float => Some(Format::R16Float),
        Format::Rg32Float => Some(Format::Rg16Float),
        Format::Rgba32Float => Some(Format::Rgba16Float),
        _ => None,
    }
}

/// Fit the formats of `blended` resources to `caps`, before the memory plan
/// (so resources share memory by their final descriptors). A history's
/// versions follow the resource they age, or the copy would change format.
/// Returns a note per resource changed.
pub(super) fn fit_formats(
    resources: &mut [ResolvedResource],
    blended: &[ResourceId],
    history: &[crate::schedule::HistoryCopy],
    caps: &Capabilities,
) -> Vec<String> {
    let mut notes = Vec::new();
    if caps.float32_blendable {
        return notes;
    }
    for &id in blended {
        let Some(r) = resources.get_mut(id.index()) else {
            continue;
        };
        if let ResourceDesc::Texture { format, .. } = &mut r.desc
            && let Some(to) = half(*format)
        {
            notes.push(format!(
                "`{}`: blended into, but the adapter lacks FLOAT32_BLENDABLE; using {to} instead of {format}",
                r.name
            ));
            *format = to;
        }
    }
    for copy in history.iter().rev() {
        let from = resources[copy.from].desc.clone();
        resources[copy.to].desc = from;
    }
    notes
}
