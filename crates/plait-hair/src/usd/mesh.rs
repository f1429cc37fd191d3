//! A stage's `Mesh` prims as one opaque triangle mesh for a scene's
//! `[[meshes]]` (docs/formats.md, "Meshes in a scene"): the same stage code
//! as the groom reader, so the same composition, `xformOp`s and
//! `metersPerUnit`/`upAxis` conversion (metres, Y up).

use std::path::Path;

use glam::{DMat4, Mat3, Mat4, Vec3};
use openusd::sdf::{self, Value};
use openusd::usd::Stage;

use super::stage;
use crate::mesh::{Mesh, MeshVertex};
use crate::mesh_file::{Limits, MeshFileError};

/// The start of the message when openusd panicked on a file (the fuzz
/// target fails on it).
pub const READER_PANIC: &str = "the USD reader failed on this file (a bug in openusd)";

/// Reads every `Mesh` prim of the stage at `path` (under `prim` if given).
pub fn read(path: &Path, prim: Option<&str>, limits: &Limits) -> Result<Mesh, MeshFileError> {
    let bytes = crate::mesh_file::read_file(path, limits)?;
    read_bytes(path, bytes, prim, limits, true)
}

/// Reads `bytes` as the USD file `path` (named in errors; its extension
/// picks the format). `on_disk`: layers it names resolve beside it.
pub fn read_bytes(
    path: &Path,
    bytes: Vec<u8>,
    prim: Option<&str>,
    limits: &Limits,
    on_disk: bool,
) -> Result<Mesh, MeshFileError> {
    let error = |message: String| MeshFileError {
        path: path.to_path_buf(),
        message,
    };
    // openusd may panic on malformed input: reported, never a crash.
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        read_stage(path, bytes, prim, limits, on_disk)
    }));
    match result {
        Ok(r) => r.map_err(error),
        Err(_) => Err(error(format!("{READER_PANIC}; please report it"))),
    }
}

fn read_stage(
    path: &Path,
    bytes: Vec<u8>,
    prim: Option<&str>,
    limits: &Limits,
    on_disk: bool,
) -> Result<Mesh, String> {
    let stage = stage::open(path, bytes, on_disk).map_err(|e| e.to_string())?;
    let units = stage::units(&stage)
        .map_err(|(field, message)| format!("prim `/`, field `{field}`: {message}"))?;
    let found = select(&stage, prim)?;
    let mut mesh = Mesh {
        name: path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "mesh".into()),
        vertices: Vec::new(),
        indices: Vec::new(),
        albedo: [0.8, 0.8, 0.8],
        head: false,
    };
    let mut albedo = None;
    for p in &found {
        let at = |(field, message): (&'static str, String)| {
            format!("prim `{}`, field `{field}`: {message}", p.as_str())
        };
        let world = units.to_plait() * stage::to_world(&stage, p).map_err(at)?;
        let color = append_prim(&stage, p, world, limits, &mut mesh).map_err(at)?;
        albedo = albedo.or(color);
    }
    if let Some(a) = albedo {
        mesh.albedo = a;
    }
    Ok(mesh)
}

/// The `Mesh` prims under `prim` (the whole stage without one).
fn select(stage: &Stage, prim: Option<&str>) -> Result<Vec<sdf::Path>, String> {
    let all = stage::prim_paths(stage).map_err(|e| format!("not a readable USD file: {e}"))?;
    let root_name = prim.unwrap_or("/");
    let root = sdf::path(root_name)
        .map_err(|e| format!("prim `{root_name}`, field `prim`: is not a prim path: {e:#}"))?;
    if root != sdf::Path::abs_root() && !all.contains(&root) {
        let names: Vec<&str> = all.iter().map(|p| p.as_str()).collect();
        let hint = plait_graph::suggest::nearest(root.as_str(), names)
            .map(|n| format!(" (did you mean `{n}`?)"))
            .unwrap_or_default();
        return Err(format!("prim `{root_name}` is not on the stage{hint}"));
    }
    let found: Vec<sdf::Path> = all
        .iter()
        .filter(|p| p.has_prefix(&root) && stage::type_name(stage, p).as_deref() == Some("Mesh"))
        .cloned()
        .collect();
    if found.is_empty() {
        return Err(format!("no Mesh prim under `{root_name}`"));
    }
    Ok(found)
}

fn ints(field: &'static str, v: Option<Value>) -> Result<Vec<i32>, (&'static str, String)> {
    match v {
        None => Err((field, "is missing".into())),
        Some(Value::IntVec(v)) => Ok(v),
        Some(other) => Err((field, format!("must be int[], not {}", stage::kind(&other)))),
    }
}

/// Appends one prim's faces (fans) placed by `world`; returns its constant
/// `displayColor`, if any.
fn append_prim(
    stage: &Stage,
    p: &sdf::Path,
    world: DMat4,
    limits: &Limits,
    mesh: &mut Mesh,
) -> Result<Option<[f32; 3]>, (&'static str, String)> {
    let prim = stage.prim(p.clone());
    let points = match stage::value(&prim, "points")? {
        None => return Err(("points", "is missing".into())),
        Some(v) => stage::vec3s("points", v)?,
    };
    let counts = ints("faceVertexCounts", stage::value(&prim, "faceVertexCounts")?)?;
    let indices = ints(
        "faceVertexIndices",
        stage::value(&prim, "faceVertexIndices")?,
    )?;
    if mesh.vertices.len() + points.len() > limits.vertices {
        return Err((
            "points",
            format!(
                "the stage's meshes have more than {} vertices",
                limits.vertices
            ),
        ));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(("points", format!("point {i} is {}: not finite", points[i])));
    }
    // Counts checked against the indices and the limits before allocating.
    let mut needed = 0usize;
    let mut triangles = 0usize;
    for (f, &c) in counts.iter().enumerate() {
        if c < 3 {
            return Err((
                "faceVertexCounts",
                format!("face {f} has {c} vertices: a face needs at least 3"),
            ));
        }
        needed += c as usize;
        triangles += c as usize - 2;
    }
    if needed != indices.len() {
        return Err((
            "faceVertexIndices",
            format!(
                "has {} entries but faceVertexCounts sums to {needed}",
                indices.len()
            ),
        ));
    }
    if mesh.indices.len() / 3 + triangles > limits.triangles {
        return Err((
            "faceVertexCounts",
            format!(
                "the stage's meshes have more than {} triangles",
                limits.triangles
            ),
        ));
    }
    if let Some(i) = indices
        .iter()
        .position(|&v| v < 0 || v as usize >= points.len())
    {
        return Err((
            "faceVertexIndices",
            format!(
                "entry {i} is {}, outside the {} points",
                indices[i],
                points.len()
            ),
        ));
    }
    let model = world.as_mat4();
    let placed: Vec<Vec3> = points.iter().map(|p| model.transform_point3(*p)).collect();
    if let Some(i) = placed.iter().position(|p| !p.is_finite()) {
        return Err((
            "xformOpOrder",
            format!(
                "the prim's transform takes point {i} to {}: not finite",
                placed[i]
            ),
        ));
    }
    // USD's default orientation is rightHanded (counter-clockwise front
    // faces), as plait's; a leftHanded prim is flipped.
    let left = matches!(
        stage::value(&prim, "orientation")?,
        Some(Value::Token(t)) if t.as_str() == "leftHanded"
    );
    let flip = left != (Mat4::determinant(&model) < 0.0);
    let mut local = Vec::with_capacity(triangles * 3);
    let mut at = 0usize;
    for &c in &counts {
        let face = &indices[at..at + c as usize];
        for k in 1..face.len() - 1 {
            let (b, c) = if flip {
                (face[k + 1], face[k])
            } else {
                (face[k], face[k + 1])
            };
            local.extend([face[0] as u32, b as u32, c as u32]);
        }
        at += c as usize;
    }
    let normals = match stage::value(&prim, "normals")? {
        Some(v) => {
            let n = stage::vec3s("normals", v)?;
            if n.len() == points.len() {
                let normal_model = Mat3::from_mat4(model).inverse().transpose();
                Some(
                    n.iter()
                        .map(|v| (normal_model * *v).normalize_or(Vec3::Y))
                        .collect(),
                )
            } else {
                None // faceVarying normals: computed instead.
            }
        }
        None => None,
    }
    .unwrap_or_else(|| crate::mesh_file::gltf::face_normals(&placed, &local));
    let base = mesh.vertices.len() as u32;
    mesh.vertices
        .extend(placed.iter().zip(&normals).map(|(p, n)| MeshVertex {
            position: p.to_array(),
            normal: n.to_array(),
        }));
    mesh.indices.extend(local.iter().map(|i| i + base));
    let color = match stage::value(&prim, "primvars:displayColor")? {
        Some(v) => stage::vec3s("primvars:displayColor", v)?
            .first()
            .filter(|c| c.is_finite())
            .map(|c| c.to_array()),
        None => None,
    };
    Ok(color)
}
