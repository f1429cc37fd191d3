//! The data-only pass types: a WGSL file and a few lines of TOML, no Rust.
//!
//! `fullscreen` draws one triangle over its colour targets (the pass's
//! `writes` that the shader does not bind, in file order); `compute`
//! dispatches one thread per texel of its first written texture (or per 4
//! bytes of its first written buffer). Every other slot is matched by name to
//! a shader binding in group 1, checked with naga's reflection when the
//! pipeline is loaded; a `params` uniform is filled from the pass params by
//! member name.

use plait_gpu::pass::{BuiltinShader, PassType};
use plait_graph::{PassShape, PassTypeSpec};

fn data_only(name: &str, shape: PassShape, description: &str) -> PassTypeSpec {
    PassTypeSpec {
        name: name.into(),
        description: description.into(),
        source: "plait".into(),
        shape,
        inputs: vec![],
        outputs: vec![],
        params: vec![],
        dynamic_slots: true,
        needs_shader: true,
        required_features: vec![],
    }
}

pub struct Fullscreen;

impl PassType for Fullscreen {
    fn spec(&self) -> PassTypeSpec {
        data_only(
            "fullscreen",
            PassShape::Fullscreen,
            "A WGSL fragment shader over the whole target; slots are the shader's bindings.",
        )
    }
    fn shader(&self) -> Option<BuiltinShader> {
        None
    }
}

pub struct Compute;

impl PassType for Compute {
    fn spec(&self) -> PassTypeSpec {
        data_only(
            "compute",
            PassShape::Compute,
            "A WGSL compute shader; slots are the shader's bindings.",
        )
    }
    fn shader(&self) -> Option<BuiltinShader> {
        None
    }
}
