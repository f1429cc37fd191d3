//! A stage's `BasisCurves` into strands: which prims, their data checked,
//! then the strands built once everything is known to fit.

use std::path::Path;

use glam::DMat4;
use openusd::sdf;
use openusd::usd::Stage;

use super::curves::{self, CurvesData};
use super::{CurvesPrim, UsdError, UsdGroom, UsdOptions, container, stage};
use crate::strands::Strands;

pub(super) fn read(
    path: &Path,
    bytes: Vec<u8>,
    options: &UsdOptions,
    on_disk: bool,
) -> Result<(UsdGroom, Vec<String>), UsdError> {
    options
        .validate("prim", "segments_per_span")
        .map_err(UsdError::Option)?;
    let container = container(&bytes);
    let stage = stage::open(path, bytes, on_disk)?;
    let units = stage::units(&stage).map_err(|(field, message)| UsdError::Field {
        prim: "/".into(),
        field,
        message,
    })?;
    let mut warnings = Vec::new();
    let found = select(&stage, options, &mut warnings)?;
    let (data, prims, total) = gather(&stage, &found, options, units.to_plait())?;
    let strands = build(&data, &prims, total, options, &mut warnings)?;
    // Prims compose lazily: their errors are known once they were read.
    let composition = stage.composition_errors();
    warnings.splice(
        0..0,
        composition.iter().map(|e| format!("composition: {e}")),
    );
    Ok((
        UsdGroom {
            strands,
            prims,
            units,
            container,
            options: options.clone(),
        },
        warnings,
    ))
}

/// The `BasisCurves` prims under the option's prim (all of them without
/// one); an error if the prim is not there or holds none.
fn select(
    stage: &Stage,
    options: &UsdOptions,
    warnings: &mut Vec<String>,
) -> Result<Vec<sdf::Path>, UsdError> {
    let all = stage::prim_paths(stage).map_err(UsdError::NotUsd)?;
    let root_name = options.prim.clone().unwrap_or_else(|| "/".into());
    let root = sdf::path(&root_name).map_err(|e| UsdError::Field {
        prim: root_name.clone(),
        field: "prim",
        message: format!("is not a prim path: {e:#}"),
    })?;
    if root != sdf::Path::abs_root() && !all.contains(&root) {
        let names: Vec<&str> = all.iter().map(|p| p.as_str()).collect();
        return Err(UsdError::NoPrim {
            prim: root_name,
            nearest: plait_graph::suggest::nearest(root.as_str(), names).map(str::to_string),
        });
    }
    let mut found = Vec::new();
    let mut others = Vec::new();
    for p in all.iter().filter(|p| p.has_prefix(&root)) {
        match stage::type_name(stage, p).as_deref() {
            Some("BasisCurves") => found.push(p.clone()),
            Some(t @ ("NurbsCurves" | "HermiteCurves")) => {
                others.push(format!("{t} {}", p.as_str()))
            }
            _ => {}
        }
    }
    if found.is_empty() {
        return Err(UsdError::NoCurves {
            prim: root_name,
            others,
        });
    }
    for o in &others {
        warnings.push(format!("{o} is not read: plait reads BasisCurves only"));
    }
    Ok(found)
}

/// Each prim's data, checked, with its placement (into metres, Y up), and
/// the number of points they evaluate to.
#[allow(clippy::type_complexity)]
fn gather(
    stage: &Stage,
    found: &[sdf::Path],
    options: &UsdOptions,
    to_plait: DMat4,
) -> Result<(Vec<(CurvesData, DMat4)>, Vec<CurvesPrim>, u64), UsdError> {
    let mut prims = Vec::new();
    let mut total = 0u64;
    let mut data = Vec::new();
    for p in found {
        let field = |(field, message): (&'static str, String)| UsdError::Field {
            prim: p.as_str().to_string(),
            field,
            message,
        };
        let d = stage::curves_data(&stage.prim(p.clone())).map_err(field)?;
        total += d.check(options.segments_per_span).map_err(field)?;
        if total > curves::MAX_POINTS {
            return Err(field((
                "points",
                format!(
                    "the stage's curves evaluate to more than {} points",
                    curves::MAX_POINTS
                ),
            )));
        }
        let world = to_plait * stage::to_world(stage, p).map_err(field)?;
        prims.push(CurvesPrim {
            path: p.as_str().to_string(),
            kind: d.kind,
            wrap: d.wrap,
            curves: d.counts.len(),
            points: d.points.len(),
            widths: d.widths.as_ref().map(|w| w.interpolation),
            colors: d.colors.as_ref().map(|w| w.interpolation),
            opacity: d.opacity.as_ref().map(|w| w.interpolation),
        });
        data.push((d, world));
    }
    Ok((data, prims, total))
}

/// The strands, allocated once (`total` points, checked), prim after prim.
fn build(
    data: &[(CurvesData, DMat4)],
    prims: &[CurvesPrim],
    total: u64,
    options: &UsdOptions,
    warnings: &mut Vec<String>,
) -> Result<Strands, UsdError> {
    let mut strands = Strands::new();
    strands
        .offsets
        .reserve(prims.iter().map(|p| p.curves).sum());
    for v in [&mut strands.thickness, &mut strands.alpha] {
        v.reserve(total as usize);
    }
    strands.points.reserve(total as usize);
    strands.color.reserve(total as usize);
    let lacking: Vec<&str> = prims
        .iter()
        .filter(|p| p.widths.is_none())
        .map(|p| p.path.as_str())
        .collect();
    if !lacking.is_empty() && lacking.len() < prims.len() {
        warnings.push(format!(
            "{} have no widths: their strands are 1 unit wide",
            lacking.join(", ")
        ));
    }
    for ((d, world), prim) in data.iter().zip(prims) {
        let from = strands.points.len();
        let negative = d.append_to(&mut strands, *world, options.segments_per_span, 1.0);
        if negative > 0 {
            warnings.push(format!(
                "{}: {negative} evaluated widths overshoot below 0 (the basis overshoots between its vertices) and are 0",
                prim.path
            ));
        }
        // Finite control points can still overflow once placed (a huge
        // scale): checked on what was built.
        if let Some(i) = (from..strands.points.len())
            .find(|&i| !(strands.points[i].is_finite() && strands.thickness[i].is_finite()))
        {
            return Err(UsdError::Field {
                prim: prim.path.clone(),
                field: "xformOpOrder",
                message: format!(
                    "the prim's transform takes point {} to {} (width {}): not finite",
                    i - from,
                    strands.points[i],
                    strands.thickness[i]
                ),
            });
        }
    }
    Ok(strands)
}
