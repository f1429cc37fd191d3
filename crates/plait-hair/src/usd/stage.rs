//! Opening a USD stage with `openusd` and reading its `BasisCurves` prims.
//!
//! The root layer is served from bytes already read (so a device or a FIFO
//! is refused before the crate sees it, and the fuzz targets need no files);
//! other layers a file names (sublayers, references, payloads) resolve on
//! disk relative to it, as `openusd`'s default resolver does, and an
//! unresolvable one is a warning.

use std::io::{self, Cursor, Read};
use std::path::Path;
use std::sync::Arc;

use glam::{DMat4, Vec3};
use openusd::ar::{self, DefaultResolver, ResolvedPath, Resolver};
use openusd::schemas::geom::Xformable;
use openusd::sdf::{self, Value};
use openusd::usd::{Prim, PrimPredicate, SchemaBase, SchemaKind, Stage, TimeCode};

use super::UsdError;
use super::curves::{Basis, CurveKind, CurvesData, Interpolation, Primvar, Wrap};

/// Serves the root layer from memory; anything else from disk (or nothing,
/// for bytes with no file behind them).
struct GroomResolver {
    name: String,
    bytes: Arc<Vec<u8>>,
    disk: Option<DefaultResolver>,
}

impl GroomResolver {
    fn is_root(&self, path: &str) -> bool {
        path == self.name
    }

    /// `name[inner]` inside a root `.usdz` held in memory.
    fn packaged(&self, path: &str) -> Option<String> {
        let (package, inner) = ar::split_package_relative_path_outer(path)?;
        self.is_root(&package).then_some(inner)
    }

    fn read_packaged(&self, inner: &str) -> io::Result<Vec<u8>> {
        let mut zip =
            zip::ZipArchive::new(Cursor::new(self.bytes.as_slice())).map_err(io::Error::other)?;
        let entry = zip.by_name(inner).map_err(io::Error::other)?;
        // USDZ stores its entries uncompressed, so an entry larger than the
        // archive is a lie (or a compression bomb) and is refused unread.
        if entry.size() > self.bytes.len() as u64 {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!(
                    "usdz entry {inner} claims {} bytes, more than the {}-byte archive (USDZ entries are stored uncompressed)",
                    entry.size(),
                    self.bytes.len()
                ),
            ));
        }
        let mut out = Vec::with_capacity(entry.size() as usize);
        entry.take(self.bytes.len() as u64).read_to_end(&mut out)?;
        Ok(out)
    }
}

impl Resolver for GroomResolver {
    fn create_identifier(&self, asset_path: &str, anchor: Option<&ResolvedPath>) -> String {
        if self.is_root(asset_path) || self.packaged(asset_path).is_some() {
            return asset_path.to_string();
        }
        // Inside the in-memory package: stay inside it.
        if let Some(anchor) = anchor
            && let Some(inner) = self.packaged(&anchor.to_string_lossy())
        {
            let dir = inner.rsplit_once('/').map_or("", |(d, _)| d);
            let joined = if dir.is_empty() {
                asset_path.trim_start_matches("./").to_string()
            } else {
                format!("{dir}/{}", asset_path.trim_start_matches("./"))
            };
            return ar::join_package_relative_path(&self.name, &joined);
        }
        if self.is_root(
            &anchor
                .map(|a| a.to_string_lossy().into_owned())
                .unwrap_or_default(),
        ) && self.name.to_ascii_lowercase().ends_with(".usdz")
        {
            return ar::join_package_relative_path(&self.name, asset_path.trim_start_matches("./"));
        }
        match &self.disk {
            Some(disk) => disk.create_identifier(asset_path, anchor),
            None => asset_path.to_string(),
        }
    }

    fn resolve(&self, asset_path: &str) -> Option<ResolvedPath> {
        if self.is_root(asset_path) || self.packaged(asset_path).is_some() {
            return Some(ResolvedPath::new(asset_path));
        }
        self.disk.as_ref()?.resolve(asset_path)
    }

    fn resolve_for_new_asset(&self, _asset_path: &str) -> Option<ResolvedPath> {
        None
    }

    fn open_asset(&self, resolved: &ResolvedPath) -> io::Result<Box<dyn ar::Asset>> {
        let path = resolved.to_string_lossy();
        if self.is_root(&path) {
            return checked(self.bytes.as_ref().clone());
        }
        if let Some(inner) = self.packaged(&path) {
            return checked(self.read_packaged(&inner)?);
        }
        match &self.disk {
            // A device or FIFO a file names would be read forever.
            Some(_)
                if !ar::is_package_relative_path(&path)
                    && !std::fs::metadata(&**resolved).is_ok_and(|m| m.is_file()) =>
            {
                Err(io::Error::new(
                    io::ErrorKind::InvalidInput,
                    format!("{path}: not a regular file"),
                ))
            }
            Some(disk) => checked(disk.open_asset(resolved)?.read_all()?),
            None => Err(io::Error::new(
                io::ErrorKind::NotFound,
                format!("{path}: not found (only the file itself is read here)"),
            )),
        }
    }

    fn identity(&self) -> String {
        format!("plait:{}", self.name)
    }
}

/// An asset's bytes for the crate, a `.usdc` one checked first
/// (`super::crate_check`).
fn checked(bytes: Vec<u8>) -> io::Result<Box<dyn ar::Asset>> {
    if bytes.starts_with(b"PXR-USDC") {
        super::crate_check::check(&bytes)
            .map_err(|m| io::Error::new(io::ErrorKind::InvalidData, m))?;
    }
    Ok(Box::new(Cursor::new(bytes)))
}

/// Opens `bytes` as the stage named `path` (its extension picks the format;
/// `.usd` is told apart by content). `on_disk`: resolve other layers beside
/// it.
pub(crate) fn open(path: &Path, bytes: Vec<u8>, on_disk: bool) -> Result<Stage, UsdError> {
    let name = path.to_string_lossy().into_owned();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default()
        .to_ascii_lowercase();
    if !matches!(ext.as_str(), "usd" | "usda" | "usdc" | "usdz") {
        return Err(UsdError::NotUsd(format!(
            "the name must end in .usd, .usda, .usdc or .usdz to be read as USD, not `.{ext}`"
        )));
    }
    let disk = on_disk.then(|| {
        let dir = path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        DefaultResolver::with_search_paths([dir])
    });
    let resolver = GroomResolver {
        name: name.clone(),
        bytes: Arc::new(bytes),
        disk,
    };
    Stage::builder()
        .resolver(resolver)
        .open(&name)
        .map_err(|e| UsdError::NotUsd(format!("{e:#}")))
}

/// A prim viewed as `Xformable`, whatever its type (an `Xform`, a `Scope`,
/// the curves themselves): its `xformOpOrder` is what counts.
struct AnyXformable(Prim);

impl SchemaBase for AnyXformable {
    const KIND: SchemaKind = SchemaKind::ConcreteTyped;
    fn prim(&self) -> &Prim {
        &self.0
    }
}
impl openusd::schemas::geom::Imageable for AnyXformable {}
impl Xformable for AnyXformable {}

/// The stage's units and up axis (USD's fallbacks when not authored:
/// centimetres, Y up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StageUnits {
    /// `metersPerUnit`.
    pub meters_per_unit: f64,
    /// Whether `metersPerUnit` was authored.
    pub meters_authored: bool,
    /// `upAxis` is `Z` (else `Y`).
    pub z_up: bool,
}

impl StageUnits {
    /// Into plait's frame: metres, Y up (a Z-up stage turned −90° about X).
    pub fn to_plait(&self) -> DMat4 {
        let up = if self.z_up {
            DMat4::from_rotation_x(-std::f64::consts::FRAC_PI_2)
        } else {
            DMat4::IDENTITY
        };
        DMat4::from_scale(glam::DVec3::splat(self.meters_per_unit)) * up
    }
}

pub(crate) fn units(stage: &Stage) -> Result<StageUnits, (&'static str, String)> {
    let mpu = stage
        .stage_metadata("metersPerUnit")
        .map_err(|e| ("metersPerUnit", format!("{e:#}")))?;
    let (meters_per_unit, meters_authored) = match mpu {
        None => (0.01, false),
        Some(v) => match number(&v) {
            Some(m) if m.is_finite() && m > 0.0 => (m, true),
            _ => {
                return Err((
                    "metersPerUnit",
                    format!("is {v:?}: it must be a positive number"),
                ));
            }
        },
    };
    let up = stage
        .stage_metadata("upAxis")
        .map_err(|e| ("upAxis", format!("{e:#}")))?;
    let z_up = match up.as_ref().and_then(token) {
        None if up.is_none() => false,
        Some(t) if t == "Y" => false,
        Some(t) if t == "Z" => true,
        _ => return Err(("upAxis", format!("is {up:?}: USD allows \"Y\" or \"Z\""))),
    };
    Ok(StageUnits {
        meters_per_unit,
        meters_authored,
        z_up,
    })
}

fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Double(d) => Some(*d),
        Value::Float(f) => Some(f64::from(*f)),
        Value::Int(i) => Some(f64::from(*i)),
        _ => None,
    }
}

fn token(v: &Value) -> Option<String> {
    match v {
        Value::Token(t) => Some(t.as_str().to_string()),
        Value::String(s) => Some(s.clone()),
        _ => None,
    }
}

/// A prim name USD allows: an identifier.
fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Every prim spec in every layer of the stage has an identifier for a
/// name: the text reader takes any quoted string, and the crate's
/// traversal recurses without end on some (found by fuzzing).
fn check_prim_names(stage: &Stage) -> Result<(), String> {
    for id in stage.layer_identifiers() {
        let Some(layer) = stage.layer(&id) else {
            continue;
        };
        let data = layer.data();
        for path in data.spec_paths() {
            if data.spec_type(&path) != Some(sdf::SpecType::Prim) {
                continue;
            }
            let text = path.as_str();
            let tail = text.rsplit('/').next().unwrap_or(text);
            // A prim inside a variant: `/A{set=sel}B`.
            let name = match tail.contains('{') {
                true => tail.rsplit('}').next().unwrap_or(tail),
                false => tail,
            };
            if !is_identifier(name) {
                return Err(format!(
                    "prim name {name:?} is not an identifier (letters, digits and _, not starting with a digit)"
                ));
            }
        }
    }
    Ok(())
}

/// Every prim path on the stage, depth first.
pub(crate) fn prim_paths(stage: &Stage) -> Result<Vec<sdf::Path>, String> {
    check_prim_names(stage)?;
    let mut paths = Vec::new();
    stage
        .traverse(PrimPredicate::DEFAULT, |p| paths.push(p.clone()))
        .map_err(|e| format!("{e:#}"))?;
    Ok(paths)
}

/// The prim's type name, if any.
pub(crate) fn type_name(stage: &Stage, path: &sdf::Path) -> Option<String> {
    stage
        .prim(path.clone())
        .type_name()
        .ok()
        .flatten()
        .map(|t| t.as_str().to_string())
}

/// The local-to-world matrix of the prim at `path` (glam's column-vector
/// form of USD's row-vector matrices: the transpose, which is how the
/// row-major array reads as columns).
pub(crate) fn to_world(stage: &Stage, path: &sdf::Path) -> Result<DMat4, (&'static str, String)> {
    let mut world = DMat4::IDENTITY;
    let mut at = Some(path.clone());
    while let Some(p) = at {
        if p == sdf::Path::abs_root() {
            break;
        }
        let x = AnyXformable(stage.prim(p.clone()));
        check_op_order(&x).map_err(|m| ("xformOpOrder", format!("on {}: {m}", p.as_str())))?;
        let local = x
            .local_to_parent_transform(TimeCode::EARLIEST)
            .map_err(|e| ("xformOpOrder", format!("on {}: {e:#}", p.as_str())))?;
        world = DMat4::from_cols_array(&local.0) * world;
        if x.resets_xform_stack().unwrap_or(false) {
            break;
        }
        at = p.parent();
    }
    if !world.is_finite() {
        return Err(("xformOpOrder", "the prim's transform is not finite".into()));
    }
    Ok(world)
}

/// Every `xformOpOrder` entry is `!resetXformStack!` or an (optionally
/// `!invert!`ed) `xformOp:` attribute name of identifier characters: the
/// crate evaluating the ops loops forever on some malformed names (found by
/// fuzzing), so they are refused first.
fn check_op_order(x: &AnyXformable) -> Result<(), String> {
    let Some(order) = x.xform_op_order().map_err(|e| format!("{e:#}"))? else {
        return Ok(());
    };
    for op in &order {
        if op == "!resetXformStack!" {
            continue;
        }
        let name = op.strip_prefix("!invert!").unwrap_or(op);
        let valid = name.strip_prefix("xformOp:").is_some_and(|rest| {
            !rest.is_empty()
                && rest.split(':').all(|part| {
                    !part.is_empty() && part.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
                })
        });
        if !valid {
            return Err(format!(
                "{op:?} is not an xformOp: attribute name (xformOp:translate, !invert!xformOp:scale:pivot, …)"
            ));
        }
    }
    Ok(())
}

/// An attribute's value: its first time sample, else its default.
pub(crate) fn value(prim: &Prim, name: &str) -> Result<Option<Value>, (&'static str, String)> {
    let attr = prim.attribute(name);
    attr.get_at::<Value>(TimeCode::EARLIEST)
        .map_err(|e| (static_name(name), format!("{e:#}")))
}

fn static_name(name: &str) -> &'static str {
    match name {
        "points" => "points",
        "curveVertexCounts" => "curveVertexCounts",
        "widths" => "widths",
        "primvars:displayColor" => "primvars:displayColor",
        "primvars:displayOpacity" => "primvars:displayOpacity",
        "type" => "type",
        "basis" => "basis",
        "wrap" => "wrap",
        "faceVertexCounts" => "faceVertexCounts",
        "faceVertexIndices" => "faceVertexIndices",
        "normals" => "normals",
        _ => "attribute",
    }
}

pub(crate) fn vec3s(field: &'static str, v: Value) -> Result<Vec<Vec3>, (&'static str, String)> {
    Ok(match v {
        Value::Vec3fVec(v) => v.into_iter().map(|p| Vec3::new(p.x, p.y, p.z)).collect(),
        Value::Vec3dVec(v) => v
            .into_iter()
            .map(|p| Vec3::new(p.x as f32, p.y as f32, p.z as f32))
            .collect(),
        Value::Vec3hVec(v) => v
            .into_iter()
            .map(|p| Vec3::new(p.x.to_f32(), p.y.to_f32(), p.z.to_f32()))
            .collect(),
        other => {
            return Err((
                field,
                format!("must be an array of 3-vectors, not {}", kind(&other)),
            ));
        }
    })
}

fn floats(field: &'static str, v: Value) -> Result<Vec<f32>, (&'static str, String)> {
    Ok(match v {
        Value::FloatVec(v) => v,
        Value::DoubleVec(v) => v.into_iter().map(|d| d as f32).collect(),
        Value::HalfVec(v) => v.into_iter().map(|h| h.to_f32()).collect(),
        Value::Float(f) => vec![f],
        Value::Double(d) => vec![d as f32],
        other => {
            return Err((
                field,
                format!("must be an array of numbers, not {}", kind(&other)),
            ));
        }
    })
}

pub(crate) fn kind(v: &Value) -> String {
    let s = format!("{v:?}");
    s.split(['(', ' ', '{']).next().unwrap_or("").to_string()
}

fn tokens(prim: &Prim, name: &'static str) -> Result<Option<String>, (&'static str, String)> {
    match value(prim, name)? {
        None => Ok(None),
        Some(v) => token(&v)
            .map(Some)
            .ok_or_else(|| (name, format!("must be a token, not {}", kind(&v)))),
    }
}

/// The `interpolation` of a primvar (or of `widths`), `default` if unset.
fn interpolation(
    prim: &Prim,
    name: &'static str,
    default: Interpolation,
) -> Result<Interpolation, (&'static str, String)> {
    let attr = prim.attribute(name);
    let raw = attr
        .get_metadata::<Value>("interpolation")
        .map_err(|e| (name, format!("{e:#}")))?;
    match raw {
        None => Ok(default),
        Some(v) => token(&v)
            .as_deref()
            .and_then(Interpolation::from_token)
            .ok_or_else(|| {
                (
                    name,
                    format!("interpolation {v:?} is none of constant, uniform, varying, vertex"),
                )
            }),
    }
}

/// A primvar with its interpolation; a single value with none authored is
/// constant (how it is usually meant, and how renderers take it).
fn primvar<T>(
    prim: &Prim,
    name: &'static str,
    default: Interpolation,
    convert: impl Fn(&'static str, Value) -> Result<Vec<T>, (&'static str, String)>,
) -> Result<Option<Primvar<T>>, (&'static str, String)> {
    let Some(v) = value(prim, name)? else {
        return Ok(None);
    };
    let values = convert(name, v)?;
    let authored = prim
        .attribute(name)
        .get_metadata::<Value>("interpolation")
        .ok()
        .flatten()
        .is_some();
    let interpolation = if !authored && values.len() == 1 {
        Interpolation::Constant
    } else {
        interpolation(prim, name, default)?
    };
    Ok(Some(Primvar {
        values,
        interpolation,
    }))
}

/// Reads a `BasisCurves` prim's attributes (not yet checked).
pub(crate) fn curves_data(prim: &Prim) -> Result<CurvesData, (&'static str, String)> {
    let ty = tokens(prim, "type")?.unwrap_or_else(|| "cubic".into());
    let basis = tokens(prim, "basis")?.unwrap_or_else(|| "bezier".into());
    let wrap = tokens(prim, "wrap")?.unwrap_or_else(|| "nonperiodic".into());
    let curve_kind = match ty.as_str() {
        "linear" => CurveKind::Linear,
        "cubic" => CurveKind::Cubic(match basis.as_str() {
            "bezier" => Basis::Bezier,
            "bspline" => Basis::Bspline,
            "catmullRom" => Basis::CatmullRom,
            other => {
                return Err((
                    "basis",
                    format!(
                        "`{other}` is not supported: plait reads bezier, bspline and catmullRom"
                    ),
                ));
            }
        }),
        other => return Err(("type", format!("`{other}` is neither linear nor cubic"))),
    };
    let wrap = match wrap.as_str() {
        "nonperiodic" => Wrap::Nonperiodic,
        "pinned" => Wrap::Pinned,
        other => {
            return Err((
                "wrap",
                format!(
                    "`{other}` is not supported: plait reads open curves (nonperiodic, pinned), not closed loops"
                ),
            ));
        }
    };
    let counts = match value(prim, "curveVertexCounts")? {
        None => return Err(("curveVertexCounts", "is missing".into())),
        Some(Value::IntVec(v)) => v,
        Some(other) => {
            return Err((
                "curveVertexCounts",
                format!("must be int[], not {}", kind(&other)),
            ));
        }
    };
    let points = match value(prim, "points")? {
        None => return Err(("points", "is missing".into())),
        Some(v) => vec3s("points", v)?,
    };
    Ok(CurvesData {
        kind: curve_kind,
        wrap,
        counts,
        points,
        widths: primvar(prim, "widths", Interpolation::Vertex, floats)?,
        colors: primvar(
            prim,
            "primvars:displayColor",
            Interpolation::Constant,
            vec3s,
        )?,
        opacity: primvar(
            prim,
            "primvars:displayOpacity",
            Interpolation::Constant,
            floats,
        )?,
    })
}
