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
