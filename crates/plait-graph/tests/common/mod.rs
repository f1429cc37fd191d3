//! A small in-test pass registry and helpers shared by the graph tests.
#![allow(dead_code)]

use plait_graph::*;
use std::path::Path;

fn slot(name: &str, kind: ResourceKind, access: Access, formats: Formats) -> SlotSpec {
    SlotSpec {
        name: name.into(),
        kind,
        access,
        formats,
        loads: false,
        optional: false,
        doc: String::new(),
        binding: None,
    }
}

fn param(name: &str, ty: ParamType, default: Option<Value>) -> ParamSpec {
    ParamSpec {
        name: name.into(),
        ty,
        default,
        doc: String::new(),
    }
}

fn pass_type(
    name: &str,
    shape: PassShape,
    inputs: Vec<SlotSpec>,
    outputs: Vec<SlotSpec>,
    params: Vec<ParamSpec>,
) -> PassTypeSpec {
    PassTypeSpec {
        inputs,
        outputs,
        params,
        ..PassTypeSpec::new(name, shape, "", "")
    }
}

/// depth_range (raster → rg32float|rg16float), shade (fullscreen), blur
/// (any → any), accumulate (loads into rgba16float), fullscreen (data-only).
pub fn registry() -> Registry {
    use ResourceKind::Texture;
    let depth_formats = Formats::OneOf(vec![Format::Rg32Float, Format::Rg16Float]);
    let mut r = Registry::new();
    r.register(pass_type(
        "depth_range",
        PassShape::Raster,
        vec![],
        vec![slot(
            "range",
            Texture,
            Access::ColorTarget,
            depth_formats.clone(),
        )],
        vec![],
    ));
    r.register(pass_type(
        "shade",
        PassShape::Fullscreen,
        vec![slot("shadow", Texture, Access::Sampled, depth_formats)],
        vec![slot(
            "color",
            Texture,
            Access::ColorTarget,
            Formats::OneOf(vec![Format::Rgba16Float, Format::Rgba8Unorm]),
        )],
        vec![
            param(
                "color",
                ParamType::Vec3,
                Some(Value::List(vec![Value::Float(1.0); 3])),
            ),
            param(
                "mode",
                ParamType::Enum(vec!["kajiya".into(), "marschner".into()]),
                Some(Value::Str("kajiya".into())),
            ),
            param(
                "strength",
                ParamType::Float {
                    min: 0.0,
                    max: 10.0,
                },
                Some(Value::Float(1.0)),
            ),
            param(
                "slices",
                ParamType::Int { min: 1, max: 1024 },
                Some(Value::Int(16)),
            ),
        ],
    ));
    r.register(pass_type(
        "blur",
        PassShape::Fullscreen,
        vec![slot("src", Texture, Access::Sampled, Formats::Any)],
        vec![slot("dst", Texture, Access::ColorTarget, Formats::Any)],
        vec![param("radius", ParamType::Int { min: 1, max: 64 }, None)],
    ));
    let mut acc = slot(
        "acc",
        Texture,
        Access::ColorTarget,
        Formats::OneOf(vec![Format::Rgba16Float]),
    );
    acc.loads = true;
    r.register(pass_type(
        "accumulate",
        PassShape::Fullscreen,
        vec![slot("src", Texture, Access::Sampled, Formats::Any)],
        vec![acc],
        vec![],
    ));
    let mut data_only = pass_type("fullscreen", PassShape::Fullscreen, vec![], vec![], vec![]);
    data_only.dynamic_slots = true;
    data_only.needs_shader = true;
    // Like the real `fullscreen`: blend, loads and depth come from the file.
    data_only.state_from_data = true;
    r.register(data_only);
    r
}

/// The reference pipeline most tests edit. Line numbers matter: tests point
/// at them.
pub const GOOD: &str = r#"[pipeline]
name = "good"
outputs = ["final"]

[params]
size = 256

[resources.depth]
kind = "texture"
format = "rg32float"
size = ["${size}", "${size}"]

[resources.final]
kind = "texture"
format = "rgba16float"
size = "screen"

[passes.light_range]
type = "depth_range"
view = "light"
draw = "hair"
writes = { range = "depth" }

[passes.shade]
type = "shade"
reads = { shadow = "depth" }
writes = { color = "final" }
"#;

pub const PATH: &str = "pipelines/test.toml";

pub fn load_text(text: &str, sets: &[&str]) -> Result<Pipeline, Errors> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    load_str(Path::new(PATH), text, &sets)
}

pub fn compile_text(text: &str, sets: &[&str]) -> Result<Schedule, Errors> {
    let pipeline = load_text(text, sets)?;
    compile(&pipeline, &registry(), &CompileOptions::default())
}

/// The errors of a load or compile that must fail.
pub fn errors_of(text: &str, sets: &[&str]) -> Vec<Error> {
    match compile_text(text, sets) {
        Ok(_) => panic!("expected errors, the pipeline compiled"),
        Err(e) => e.0,
    }
}

/// `path:line:column` of a file location.
pub fn at(line: u32, column: u32) -> Location {
    Location::File {
        path: PATH.into(),
        line,
        column,
    }
}

/// Replaces exactly one occurrence of `from`.
pub fn edit(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "`{from}` must occur once");
    text.replace(from, to)
}
