//! The strands' acceleration structure against the adapter's BLAS primitive
//! limit, checked when the scene is known and before any GPU work (issue 48,
//! bad input). A `strand_structure` pass puts each pair of consecutive hair
//! vertices in one bottom-level structure as its `primitive`: one
//! procedural box (`swept_sphere`) or four DOTS triangles (`dots`)
//! (`plait_gpu::strand_structure`): past the adapter's
//! `max_blas_primitive_count` the build would fail. Until this check the
//! build found it, after the device, the geometry and every other pass had
//! been made; now `plait render`, `view`, `ab` and `check --adapter` refuse
//! it with the numbers and the fix (exit 2). The scene's meshes are in the
//! structure too, one triangle bottom-level structure and one top-level
//! instance each: a mesh past `max_blas_primitive_count` triangles, or more
//! instances than `max_tlas_instance_count`, is refused the same way (a
//! pass with `meshes = false` holds none). Every structure pass is checked.

use plait_gpu::Capabilities;
use plait_gpu::strand_structure::{StrandPrimitive, StructureError, check_meshes, segment_count};
use plait_graph::Schedule;

use crate::session::SessionError;

/// The pass type whose boxes fill one bottom-level structure.
pub const STRUCTURE_PASS: &str = "strand_structure";

/// The hair a structure would hold: its strands and points.
#[derive(Clone, Copy, Debug)]
pub struct HairSize {
    pub strands: u64,
    pub points: u64,
}

impl HairSize {
    pub fn of(strands: &plait_hair::Strands) -> Self {
        HairSize {
            strands: strands.strand_count() as u64,
            points: strands.point_count() as u64,
        }
    }
}

/// Each opaque mesh as the structure holds it: its name and triangles.
pub fn mesh_sizes(meshes: &[plait_hair::mesh::Mesh]) -> Vec<(String, u64)> {
    meshes
        .iter()
        .filter(|m| !m.indices.is_empty())
        .map(|m| (m.name.clone(), (m.indices.len() / 3) as u64))
        .collect()
}

/// `Err` naming the first `strand_structure` pass of `schedule` whose
/// primitives for `hair` (a box or four DOTS triangles per segment, its
/// `primitive`) outnumber what one bottom-level structure of the adapter
/// (`caps`, named `adapter`) holds, or one of whose `meshes` (name,
/// triangles: [`mesh_sizes`]; none with `meshes = false`) does, or whose
/// instances (the strands and each mesh) outnumber what one top-level
/// structure holds; `Ok` when there is none or all fit. Without ray queries
/// the technique is refused before this, by its `adapter = ["ray_query"]`
/// ([`crate::adapter`]).
pub fn check(
    schedule: &Schedule,
    hair: HairSize,
    meshes: &[(String, u64)],
    caps: &Capabilities,
    adapter: &str,
) -> Result<(), SessionError> {
    if !caps.ray_query {
        return Ok(());
    }
    for pass in schedule
        .passes
        .iter()
        .filter(|p| p.type_name == STRUCTURE_PASS)
    {
        check_pass(pass, hair, meshes, caps, adapter)?;
    }
    Ok(())
}

fn check_pass(
    pass: &plait_graph::ScheduledPass,
    hair: HairSize,
    meshes: &[(String, u64)],
    caps: &Capabilities,
    adapter: &str,
) -> Result<(), SessionError> {
    let primitive = match pass.params.get("primitive") {
        Some(plait_graph::Value::Str(name)) => StrandPrimitive::from_name(name).unwrap_or_default(),
        _ => StrandPrimitive::default(),
    };
    let with_meshes = !matches!(
        pass.params.get("meshes"),
        Some(plait_graph::Value::Bool(false))
    );
    // Saturating as the u32 the builder takes: a point count past 2^32 is
    // past every adapter's limit too.
    let segments = segment_count(u32::try_from(hair.points).unwrap_or(u32::MAX)).max(1);
    let per_segment = primitive.per_segment();
    let primitives = segments * per_segment;
    let limit = u64::from(caps.max_blas_primitives);
    let technique = pass
        .technique
        .as_deref()
        .map_or(String::new(), |t| format!(" (technique {t})"));
    if primitives <= limit {
        let sizes = meshes
            .iter()
            .filter(|_| with_meshes)
            .map(|(name, n)| (name.as_str(), *n));
        let sizes: Vec<_> = sizes.collect();
        return check_meshes(sizes.into_iter(), caps, adapter).map_err(|e| {
            let fix = match e {
                StructureError::TooManyTriangles { .. } => {
                    "simplify the mesh (fewer triangles), or leave it out of the scene"
                }
                _ => "merge the scene's [[meshes]] into fewer files",
            };
            SessionError::StructureLimit(format!(
                "{}: pass `{}`{technique} puts the scene's meshes in its acceleration structure: {e}; {fix}",
                pass.location, pass.name,
            ))
        });
    }
    // Strands at the scene's mean points per strand that fit the limit.
    let per_strand = hair.points as f64 / hair.strands.max(1) as f64;
    let strands_fitting = ((limit / per_segment + 1) as f64 / per_strand).floor() as u64;
    let what = match primitive {
        StrandPrimitive::SweptSphere => {
            format!("{primitives} boxes (one per pair of consecutive points)")
        }
        StrandPrimitive::Dots => format!(
            "{segments} segments as DOTS, {primitives} triangles (four per pair of consecutive points)"
        ),
    };
    let other = match primitive {
        StrandPrimitive::SweptSphere => String::new(),
        StrandPrimitive::Dots => format!(
            ", or primitive = \"swept_sphere\" (one box per segment: {segments} primitives{})",
            if segments <= limit { ", which fit" } else { "" }
        ),
    };
    Err(SessionError::StructureLimit(format!(
        "{}: pass `{}`{technique} puts the scene's hair in one acceleration structure: {} strands, {} points, {what}, more than the {limit} primitives one bottom-level structure holds on adapter {adapter} (max_blas_primitive_count); the structure holds every hair vertex (geometry = \"lod\" leaves none out of it), so draw fewer strands (at most {strands_fitting} of this groom's {per_strand:.1} points each) or fewer points per strand: the scene's [hair.procedural] strands or segments, or resample a hair file to N points per strand with `plait hair convert IN OUT.tfx --vertices-per-strand N`{other}",
        pass.location, pass.name, hair.strands, hair.points,
    )))
}
