//! Strands as a USD layer: one linear `BasisCurves` prim, `/Groom/Strands`,
//! under an `Xform` `/Groom` (the default prim), in metres and Y up, with
//! vertex `widths`, `primvars:displayColor` and `primvars:displayOpacity`.
//! Built as layer data and written by `openusd`'s writers.

use std::io::Cursor;
use std::path::Path;

use openusd::gf;
use openusd::sdf::{self, ChildrenKey, FieldKey, SpecType, Specifier, Value, Variability};

use super::UsdError;
use crate::strands::Strands;

/// The USD container to write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WriteFormat {
    /// Text.
    Usda,
    /// Binary crate.
    Usdc,
    /// A zip package holding one crate layer.
    Usdz,
}

impl WriteFormat {
    /// From a path's extension (`.usd` is written as text, which every USD
    /// reader takes under that name).
    pub fn from_extension(path: &Path) -> Option<WriteFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "usda" | "usd" => Some(WriteFormat::Usda),
            "usdc" => Some(WriteFormat::Usdc),
            "usdz" => Some(WriteFormat::Usdz),
            _ => None,
        }
    }

    fn id(self) -> &'static str {
        match self {
            WriteFormat::Usda => "usda",
            WriteFormat::Usdc => "usdc",
            WriteFormat::Usdz => "usdz",
        }
    }
}

fn err(message: String) -> UsdError {
    UsdError::Field {
        prim: "/Groom/Strands".into(),
        field: "points",
        message,
    }
}

/// The strands as a USD file's bytes.
pub fn write(strands: &Strands, format: WriteFormat) -> Result<Vec<u8>, UsdError> {
    if strands.strand_count() == 0 {
        return Err(err("there are no strands to write".into()));
    }
    let mut counts = Vec::with_capacity(strands.strand_count());
    for (i, r) in strands.ranges().enumerate() {
        if r.len() < 2 {
            return Err(err(format!(
                "strand {i} has {} point(s): a USD linear curve needs at least 2",
                r.len()
            )));
        }
        counts.push(i32::try_from(r.len()).map_err(|_| {
            err(format!(
                "strand {i} has {} points, more than USD's int",
                r.len()
            ))
        })?);
    }
    let data = layer(strands, counts).map_err(err)?;
    let format_impl = sdf::LayerRegistry::find_by_id(format.id())
        .ok_or_else(|| err(format!("openusd has no {} writer", format.id())))?;
    let mut out = Cursor::new(Vec::new());
    format_impl
        .write(&data, &mut out)
        .map_err(|e| err(format!("writing {}: {e:#}", format.id())))?;
    Ok(out.into_inner())
}

fn tokens(names: &[&str]) -> Value {
    Value::TokenVec(names.iter().map(|n| (*n).into()).collect())
}

fn layer(strands: &Strands, counts: Vec<i32>) -> Result<sdf::Data, String> {
    let path = |p: &str| sdf::path(p).map_err(|e| format!("{e:#}"));
    let mut data = sdf::Data::new();
    let root = data.create_spec(sdf::Path::abs_root(), SpecType::PseudoRoot);
    root.add(ChildrenKey::PrimChildren, tokens(&["Groom"]));
    root.add(FieldKey::DefaultPrim, Value::Token("Groom".into()));
    root.add("metersPerUnit", Value::Double(1.0));
    root.add("upAxis", Value::Token("Y".into()));
    root.add(
        FieldKey::Documentation,
        Value::String("strands written by plait".into()),
    );

    let groom = path("/Groom")?;
    let spec = data.create_spec(groom, SpecType::Prim);
    spec.add(FieldKey::Specifier, Value::Specifier(Specifier::Def));
    spec.add(FieldKey::TypeName, Value::Token("Xform".into()));
    spec.add(ChildrenKey::PrimChildren, tokens(&["Strands"]));

    let curves = path("/Groom/Strands")?;
    let spec = data.create_spec(curves.clone(), SpecType::Prim);
    spec.add(FieldKey::Specifier, Value::Specifier(Specifier::Def));
    spec.add(FieldKey::TypeName, Value::Token("BasisCurves".into()));
    let names = [
        "type",
        "wrap",
        "curveVertexCounts",
        "points",
        "widths",
        "primvars:displayColor",
        "primvars:displayOpacity",
    ];
    spec.add(ChildrenKey::PropertyChildren, tokens(&names));

    let v3 = |v: &[glam::Vec3]| {
        v.iter()
            .map(|p| gf::Vec3f::from(p.to_array()))
            .collect::<Vec<_>>()
    };
    let attrs: [(&str, &str, Value, Option<&str>, bool); 7] = [
        ("type", "token", Value::Token("linear".into()), None, true),
        (
            "wrap",
            "token",
            Value::Token("nonperiodic".into()),
            None,
            true,
        ),
        (
            "curveVertexCounts",
            "int[]",
            Value::IntVec(counts),
            None,
            false,
        ),
        (
            "points",
            "point3f[]",
            Value::Vec3fVec(v3(&strands.points)),
            None,
            false,
        ),
        (
            "widths",
            "float[]",
            Value::FloatVec(strands.thickness.clone()),
            Some("vertex"),
            false,
        ),
        (
            "primvars:displayColor",
            "color3f[]",
            Value::Vec3fVec(v3(&strands.color)),
            Some("vertex"),
            false,
        ),
        (
            "primvars:displayOpacity",
            "float[]",
            Value::FloatVec(strands.alpha.clone()),
            Some("vertex"),
            false,
        ),
    ];
    for (name, ty, value, interpolation, uniform) in attrs {
        let spec = data.create_spec(
            curves.append_property(name).map_err(|e| format!("{e:#}"))?,
            SpecType::Attribute,
        );
        spec.add(FieldKey::TypeName, Value::Token(ty.into()));
        spec.add(FieldKey::Default, value);
        if uniform {
            spec.add(
                FieldKey::Variability,
                Value::Variability(Variability::Uniform),
            );
        }
        if let Some(i) = interpolation {
            spec.add("interpolation", Value::Token(i.into()));
        }
    }
    Ok(data)
}

/// The example groom (`examples/scenes/groom.usda`): 300 strands of
/// the procedural groom grown over the example head's ellipsoid (the shape
/// of `examples/scenes/head.glb`), written as `.usda` with widths and
/// colours. `cargo run --example make_assets` writes it; a test checks the
/// committed file is these bytes.
pub fn example_groom_usda() -> Vec<u8> {
    let spec = crate::groom::GroomSpec {
        style: crate::groom::Style::Straight,
        strands: 300,
        segments: 12,
        seed: 7,
        length: 2.0,
        thickness: 0.012,
        alpha: 0.85,
        color: [0.25, 0.15, 0.07],
        ..Default::default()
    };
    let strands = crate::groom::generate(&spec);
    write(&strands, WriteFormat::Usda).expect("the procedural groom has strands")
}
