//! glTF 2.0 meshes (`.glb` binary or `.gltf` JSON with `.bin` buffers),
//! read with the `gltf` crate's document model (it validates every index
//! between objects); the accessors are read here, so that each one's count,
//! type and byte range is checked against the limits and the buffer before
//! anything is allocated for it.
//!
//! What is drawn: every triangle primitive of every mesh the default scene's
//! nodes place (all meshes, unplaced, when the file has no scene), each by
//! its node's world matrix, merged into one mesh. Normals are the file's or,
//! when it has none, the area-weighted average of the faces'. The albedo is
//! the primitives' materials' `baseColorFactor` (their mean by triangle
//! count when they differ; 0.8 grey when no primitive has a material).

use std::path::Path;

use glam::{Mat3, Mat4, Vec3};
use gltf::Gltf;
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

use super::{Limits, MeshFileError};
use crate::mesh::{Mesh, MeshVertex};

/// Deeper node hierarchies are refused (a real head file is a few levels);
/// this also bounds a walk the document's validation leaves to us.
const MAX_DEPTH: usize = 64;

/// Reads a `.glb` or `.gltf` file's bytes; `path` names it in messages and
/// locates external buffers.
pub fn read_bytes(bytes: &[u8], path: &Path, limits: &Limits) -> Result<Mesh, MeshFileError> {
    let error = |message: String| MeshFileError {
        path: path.to_path_buf(),
        message,
    };
    check_glb_header(bytes).map_err(error)?;
    let invalid = |e: gltf::Error| error(format!("not a valid glTF 2.0 file: {e}"));
    // Parsed first, validated once the attribute indices are known to be in
    // range: gltf-json 1.4.1's validation indexes the accessors with the
    // POSITION attribute's index unchecked (a panic, found by tests/fuzz/).
    let parsed = Gltf::from_slice_without_validation(bytes).map_err(invalid)?;
    check_attribute_indices(parsed.document.as_json()).map_err(error)?;
    let file = Gltf {
        document: gltf::Document::from_json(parsed.document.into_json()).map_err(invalid)?,
        blob: parsed.blob,
    };
    let buffers = load_buffers(&file, path, limits).map_err(error)?;
    let mut out = Mesh {
        name: path
            .file_stem()
            .map_or_else(|| "mesh".into(), |s| s.to_string_lossy().into_owned()),
        vertices: Vec::new(),
        indices: Vec::new(),
        albedo: [0.8, 0.8, 0.8],
        head: false,
    };
    let (mut colour, mut weight) = ([0.0f64; 3], 0.0f64);
    for (mesh, model) in instances(&file.document).map_err(error)? {
        for primitive in mesh.primitives() {
            let at = format!(
                "mesh {}{} primitive {}",
                mesh.index(),
                mesh.name().map_or(String::new(), |n| format!(" (`{n}`)")),
                primitive.index()
            );
            let before = out.indices.len();
            append_primitive(&mut out, &primitive, model, &buffers, limits)
                .map_err(|m| error(format!("{at}: {m}")))?;
            if primitive.material().index().is_some() {
                let triangles = ((out.indices.len() - before) / 3) as f64;
                let [r, g, b, _] = primitive
                    .material()
                    .pbr_metallic_roughness()
                    .base_color_factor();
                for (s, c) in colour.iter_mut().zip([r, g, b]) {
                    *s += triangles * f64::from(c);
                }
                weight += triangles;
            }
        }
    }
    if out.indices.is_empty() {
        return Err(error("the file places no triangle mesh".into()));
    }
    // One mesh has one albedo: its materials' base colour factors, weighted
    // by the triangles each covers (textures are not read).
    if weight > 0.0 {
        out.albedo = colour.map(|c| (c / weight) as f32);
    }
    Ok(out)
}

/// A GLB header's total length must cover the header itself: gltf 1.4.1's
/// `Glb::from_slice` subtracts the header's 12 bytes from it unchecked (an
/// overflow panic in debug builds, found by `tests/fuzz/`).
fn check_glb_header(bytes: &[u8]) -> Result<(), String> {
    if !bytes.starts_with(b"glTF") {
        return Ok(());
    }
    let length = bytes
        .get(8..12)
        .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]))
        .ok_or("not a valid glTF 2.0 file: the GLB header is cut short")?;
    if length < 12 {
        return Err(format!(
            "not a valid glTF 2.0 file: the GLB header's length is {length}, less than the header's 12 bytes"
        ));
    }
    Ok(())
}

/// Every primitive's attributes name an accessor the file has.
fn check_attribute_indices(root: &gltf::json::Root) -> Result<(), String> {
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for (semantic, index) in &primitive.attributes {
                if index.value() >= root.accessors.len() {
                    return Err(format!(
                        "not a valid glTF 2.0 file: meshes[{m}].primitives[{p}].attributes[{:?}] is accessor {}, but the file has {}",
                        match semantic {
                            gltf::json::validation::Checked::Valid(s) => s.to_string(),
                            gltf::json::validation::Checked::Invalid => "?".into(),
                        },
                        index.value(),
                        root.accessors.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Every buffer's bytes: the GLB's BIN chunk or an external file next to
/// `path`. Each is checked to hold the length the document declares.
fn load_buffers(file: &Gltf, path: &Path, limits: &Limits) -> Result<Vec<Vec<u8>>, String> {
    let mut out = Vec::new();
    let mut total = 0usize;
    for buffer in file.document.buffers() {
        let i = buffer.index();
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => file.blob.clone().ok_or_else(|| {
                format!("buffer {i} is the GLB's BIN chunk, which the file does not have")
            })?,
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
                return Err(format!(
                    "buffer {i} is embedded as a data: URI, which plait does not read; write a .glb or a .bin file"
                ));
            }
            gltf::buffer::Source::Uri(uri) => {
                let external = path.parent().unwrap_or(Path::new("")).join(uri);
                super::read_file(&external, limits).map_err(|e| format!("buffer {i}: {e}"))?
            }
        };
        if data.len() < buffer.length() {
            return Err(format!(
                "buffer {i} declares {} bytes but holds {}",
                buffer.length(),
                data.len()
            ));
        }
        total += data.len();
        if total > limits.buffer_bytes {
            return Err(format!(
                "the buffers hold over the limit of {} bytes",
                limits.buffer_bytes
            ));
        }
        out.push(data);
    }
    Ok(out)
}

/// Every placed mesh with its world matrix: the default (or first) scene's
/// node trees, or every mesh at the identity when the file has no scene.
fn instances(document: &gltf::Document) -> Result<Vec<(gltf::Mesh<'_>, Mat4)>, String> {
    let Some(scene) = document
        .default_scene()
        .or_else(|| document.scenes().next())
    else {
        return Ok(document.meshes().map(|m| (m, Mat4::IDENTITY)).collect());
    };
    let mut out = Vec::new();
    let mut stack: Vec<(gltf::Node<'_>, Mat4, usize)> =
        scene.nodes().map(|n| (n, Mat4::IDENTITY, 0)).collect();
    let mut visited = 0usize;
    while let Some((node, parent, depth)) = stack.pop() {
        visited += 1;
        if depth > MAX_DEPTH || visited > 1 << 16 {
            return Err(format!(
                "node {} is more than {MAX_DEPTH} levels deep or one of over 65536 placed nodes (a cycle?)",
                node.index()
            ));
        }
        let model = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if !model.is_finite() {
            return Err(format!(
                "node {}: its transform is not finite",
                node.index()
            ));
        }
        if let Some(mesh) = node.mesh() {
            out.push((mesh, model));
        }
        stack.extend(node.children().map(|c| (c, model, depth + 1)));
    }
    // The stack visits in reverse; the file's order is easier to follow.
    out.reverse();
    Ok(out)
}

/// Reads one primitive into `out`, placed by `model`; every count is checked
/// against `limits` (with what `out` already holds) before it is read.
fn append_primitive(
    out: &mut Mesh,
    primitive: &gltf::Primitive<'_>,
    model: Mat4,
    buffers: &[Vec<u8>],
    limits: &Limits,
) -> Result<(), String> {
    if primitive.mode() != Mode::Triangles {
        return Err(format!(
            "mode is {:?}; plait reads triangle lists only",
            primitive.mode()
        ));
    }
    let positions = primitive
        .get(&gltf::Semantic::Positions)
        .ok_or("has no POSITION attribute")?;
    let count = positions.count();
    if count == 0 {
        return Err("POSITION has no vertices".into());
    }
    if out.vertices.len() + count > limits.vertices {
        return Err(format!(
            "POSITION claims {count} vertices; with the file's other primitives that is over the limit of {}",
            limits.vertices
        ));
    }
    let indices = match primitive.indices() {
        Some(accessor) => {
            if accessor.count() % 3 != 0 {
                return Err(format!(
                    "indices: {} is not a multiple of 3",
                    accessor.count()
                ));
            }
            check_triangles(out, accessor.count() / 3, limits)?;
            read_indices(&accessor, buffers).map_err(|m| format!("indices: {m}"))?
        }
        None => {
            if count % 3 != 0 {
                return Err(format!(
                    "has no indices and POSITION's {count} vertices are not a multiple of 3"
                ));
            }
            check_triangles(out, count / 3, limits)?;
            (0..count as u32).collect()
        }
    };
    if let Some((k, &i)) = indices
        .iter()
        .enumerate()
        .find(|(_, i)| **i as usize >= count)
    {
        return Err(format!(
            "indices: index {k} is {i}, but POSITION has {count} vertices"
        ));
    }
    let points = read_vec3(&positions, buffers).map_err(|m| format!("POSITION: {m}"))?;
    if let Some((i, p)) = points.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(format!("POSITION: vertex {i} is not finite ({p})"));
    }
    let normals = match primitive.get(&gltf::Semantic::Normals) {
        Some(a) if a.count() == count => {
            Some(read_vec3(&a, buffers).map_err(|m| format!("NORMAL: {m}"))?)
        }
        Some(a) => {
            return Err(format!(
                "NORMAL has {} vertices, POSITION {count}",
                a.count()
            ));
        }
        None => None,
    };
    let normal_model = Mat3::from_mat4(model).inverse().transpose();
    let placed: Vec<Vec3> = points.iter().map(|p| model.transform_point3(*p)).collect();
    if let Some((i, p)) = placed.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(format!(
            "POSITION: vertex {i} leaves the f32 range when its node places it ({p})"
        ));
    }
    // A mirroring node turns the winding around; front faces stay CCW.
    let mirrored = model.determinant() < 0.0;
    let mut triangles: Vec<u32> = indices;
    if mirrored {
        for t in triangles.chunks_exact_mut(3) {
            t.swap(1, 2);
        }
    }
    let normals: Vec<Vec3> = match normals {
        Some(n) if n.iter().all(|v| v.is_finite() && v.length_squared() > 0.0) => n
            .iter()
            .map(|v| (normal_model * *v).normalize_or(Vec3::Y))
            .collect(),
        _ => face_normals(&placed, &triangles),
    };
    let base = out.vertices.len() as u32;
    out.vertices
        .extend(placed.iter().zip(&normals).map(|(p, n)| MeshVertex {
            position: p.to_array(),
            normal: n.to_array(),
        }));
    out.indices.extend(triangles.iter().map(|i| i + base));
    Ok(())
}

fn check_triangles(out: &Mesh, triangles: usize, limits: &Limits) -> Result<(), String> {
    if out.indices.len() / 3 + triangles > limits.triangles {
        return Err(format!(
            "claims {triangles} triangles; with the file's other primitives that is over the limit of {}",
            limits.triangles
        ));
    }
    Ok(())
}

/// Area-weighted vertex normals of a triangle list (CCW front faces).
pub(crate) fn face_normals(points: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
    let mut normals = vec![Vec3::ZERO; points.len()];
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| points[i as usize]);
        let face = (b - a).cross(c - a);
        for &i in t {
            normals[i as usize] += face;
        }
    }
    normals.iter().map(|n| n.normalize_or(Vec3::Y)).collect()
}

/// The bytes of `accessor`'s elements of `size` bytes: its view's range in
/// its buffer, checked (with overflow-safe arithmetic) to hold them all,
/// and the stride between elements.
fn element_bytes<'b>(
    accessor: &gltf::Accessor<'_>,
    buffers: &'b [Vec<u8>],
    size: usize,
) -> Result<(&'b [u8], usize), String> {
    if accessor.sparse().is_some() {
        return Err("sparse accessors are not supported".into());
    }
    let view = accessor
        .view()
        .ok_or("has no bufferView (an all-zero accessor), which plait does not read")?;
    let buffer = &buffers[view.buffer().index()];
    let view_bytes = view
        .offset()
        .checked_add(view.length())
        .and_then(|end| buffer.get(view.offset()..end))
        .ok_or_else(|| {
            format!(
                "bufferView {} (bytes {}..+{}) lies outside buffer {} ({} bytes)",
                view.index(),
                view.offset(),
                view.length(),
                view.buffer().index(),
                buffer.len()
            )
        })?;
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(format!(
            "bufferView {} has byteStride {stride}, less than the element's {size} bytes",
            view.index()
        ));
    }
    let end = (accessor.count().max(1) - 1)
        .checked_mul(stride)
        .and_then(|n| n.checked_add(size))
        .and_then(|n| n.checked_add(accessor.offset()));
    let bytes = end
        .and_then(|end| view_bytes.get(accessor.offset()..end))
        .ok_or_else(|| {
            format!(
                "{} elements of {size} bytes from byte {} do not fit in bufferView {} ({} bytes)",
                accessor.count(),
                accessor.offset(),
                view.index(),
                view.length()
            )
        })?;
    Ok((bytes, stride))
}

fn read_vec3(accessor: &gltf::Accessor<'_>, buffers: &[Vec<u8>]) -> Result<Vec<Vec3>, String> {
    if accessor.dimensions() != Dimensions::Vec3
        || accessor.data_type() != DataType::F32
        || accessor.normalized()
    {
        return Err(format!(
            "is {:?} of {:?}{}; plait reads VEC3 of 32-bit floats",
            accessor.dimensions(),
            accessor.data_type(),
            if accessor.normalized() {
                " (normalized)"
            } else {
                ""
            }
        ));
    }
    let (bytes, stride) = element_bytes(accessor, buffers, 12)?;
    let f = |b: &[u8], k: usize| f32::from_le_bytes([b[k], b[k + 1], b[k + 2], b[k + 3]]);
    Ok((0..accessor.count())
        .map(|i| {
            let e = &bytes[i * stride..i * stride + 12];
            Vec3::new(f(e, 0), f(e, 4), f(e, 8))
        })
        .collect())
}

fn read_indices(accessor: &gltf::Accessor<'_>, buffers: &[Vec<u8>]) -> Result<Vec<u32>, String> {
    let size = match (accessor.dimensions(), accessor.data_type()) {
        (Dimensions::Scalar, DataType::U8) => 1,
        (Dimensions::Scalar, DataType::U16) => 2,
        (Dimensions::Scalar, DataType::U32) => 4,
        (d, t) => {
            return Err(format!(
                "is {d:?} of {t:?}; indices are unsigned 8-, 16- or 32-bit scalars"
            ));
        }
    };
    let (bytes, stride) = element_bytes(accessor, buffers, size)?;
    Ok((0..accessor.count())
        .map(|i| {
            let e = &bytes[i * stride..i * stride + size];
            match size {
                1 => u32::from(e[0]),
                2 => u32::from(u16::from_le_bytes([e[0], e[1]])),
                _ => u32::from_le_bytes([e[0], e[1], e[2], e[3]]),
            }
        })
        .collect())
}
