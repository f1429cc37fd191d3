//! Short constructors for pass type specs, so each pass module reads as a table.

use plait_graph::{Access, Format, Formats, ParamSpec, ParamType, ResourceKind, SlotSpec, Value};

pub fn texture(name: &str, access: Access, formats: &[Format], doc: &str) -> SlotSpec {
    SlotSpec {
        name: name.into(),
        kind: ResourceKind::Texture,
        access,
        formats: if formats.is_empty() {
            Formats::Any
        } else {
            Formats::OneOf(formats.to_vec())
        },
        loads: false,
        optional: false,
        doc: doc.into(),
        binding: None,
    }
}

pub fn buffer(name: &str, access: Access, doc: &str) -> SlotSpec {
    SlotSpec {
        name: name.into(),
        kind: ResourceKind::Buffer,
        access,
        formats: Formats::Any,
        loads: false,
        optional: false,
        doc: doc.into(),
        binding: None,
    }
}

pub trait SlotExt {
    /// Keeps and adds to the previous contents.
    fn loads(self) -> Self;
    fn optional(self) -> Self;
}

impl SlotExt for SlotSpec {
    fn loads(mut self) -> Self {
        self.loads = true;
        self
    }
    fn optional(mut self) -> Self {
        self.optional = true;
        self
    }
}

pub fn float(name: &str, default: f64, min: f64, max: f64, doc: &str) -> ParamSpec {
    ParamSpec {
        name: name.into(),
        ty: ParamType::Float { min, max },
        default: Some(Value::Float(default)),
        doc: doc.into(),
    }
}

pub fn int(name: &str, default: i64, min: i64, max: i64, doc: &str) -> ParamSpec {
    ParamSpec {
        name: name.into(),
        ty: ParamType::Int { min, max },
        default: Some(Value::Int(default)),
        doc: doc.into(),
    }
}

pub fn choice(name: &str, default: &str, options: &[&str], doc: &str) -> ParamSpec {
    ParamSpec {
        name: name.into(),
        ty: ParamType::Enum(options.iter().map(|s| s.to_string()).collect()),
        default: Some(Value::Str(default.into())),
        doc: doc.into(),
    }
}

pub const DEPTH: &[Format] = &[Format::Depth32Float];
pub const HDR: &[Format] = &[Format::Rgba16Float, Format::Rgba32Float];

/// The binding of `pass`'s declared slot `slot` (a constant handle of its
/// Rust pass type, whose spec is `spec`), or an error naming the slot.
pub fn bound<'p>(
    pass: &'p plait_graph::ScheduledPass,
    spec: &plait_graph::PassTypeSpec,
    slot: plait_graph::SlotId,
) -> Result<&'p plait_graph::Binding, plait_gpu::GpuError> {
    pass.bound(slot).ok_or_else(|| plait_gpu::GpuError::Pass {
        pass: pass.name.clone(),
        message: format!(
            "slot `{}` is not bound",
            spec.slot(slot).map_or("?", |s| s.name.as_str())
        ),
    })
}

/// Fails unless each constant handle names the slot it is written beside:
/// the one place a Rust pass type's handles meet its slots' names.
#[cfg(test)]
pub fn assert_handles(spec: &plait_graph::PassTypeSpec, handles: &[(plait_graph::SlotId, &str)]) {
    for &(id, name) in handles {
        assert_eq!(
            spec.slot(id).map(|s| s.name.as_str()),
            Some(name),
            "pass type `{}`: handle {id:?} is not the slot `{name}`",
            spec.name
        );
    }
}
