//! The strands' acceleration structure against the adapter's BLAS primitive
//! limit, checked when the scene is known and before any GPU work (issue 48,
//! bad input). A `strand_structure` pass puts one procedural box in one
//! bottom-level structure per pair of consecutive hair vertices
//! (`plait_gpu::strand_structure`): past the adapter's
//! `max_blas_primitive_count` the build would fail. Until this check the
//! build found it, after the device, the geometry and every other pass had
//! been made; now `plait render`, `view`, `ab` and `check --adapter` refuse
//! it with the numbers and the fix (exit 2). The scene's meshes are in the
//! structure too, one triangle bottom-level structure and one top-level
//! instance each: a mesh past `max_blas_primitive_count` triangles, or more
//! instances than `max_tlas_instance_count`, is refused the same way.

use plait_gpu::Capabilities;
use plait_gpu::strand_structure::{StructureError, check_meshes, segment_count};
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

/// `Err` naming the first `strand_structure` pass of `schedule` whose boxes
/// for `hair` outnumber what one bottom-level structure of the adapter
/// (`caps`, named `adapter`) holds, or one of whose `meshes` (name,
/// triangles: [`mesh_sizes`]) does, or whose instances (the strands and
/// each mesh) outnumber what one top-level structure holds; `Ok` when there
/// is none or it fits. Without ray queries the technique is refused before
/// this, by its `adapter = ["ray_query"]` ([`crate::adapter`]).
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
    let Some(pass) = schedule
        .passes
        .iter()
        .find(|p| p.type_name == STRUCTURE_PASS)
    else {
        return Ok(());
    };
    // Saturating as the u32 the builder takes: a point count past 2^32 is
    // past every adapter's limit too.
    let boxes = segment_count(u32::try_from(hair.points).unwrap_or(u32::MAX)).max(1);
    let limit = u64::from(caps.max_blas_primitives);
    let technique = pass
        .technique
        .as_deref()
        .map_or(String::new(), |t| format!(" (technique {t})"));
    if boxes <= limit {
        let sizes = meshes.iter().map(|(name, n)| (name.as_str(), *n));
        return check_meshes(sizes, caps, adapter).map_err(|e| {
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
    let strands_fitting = ((limit + 1) as f64 / per_strand).floor() as u64;
    Err(SessionError::StructureLimit(format!(
        "{}: pass `{}`{technique} puts the scene's hair in one acceleration structure: {} strands, {} points, {boxes} boxes (one per pair of consecutive points), more than the {limit} primitives one bottom-level structure holds on adapter {adapter} (max_blas_primitive_count); the structure holds every hair vertex (geometry = \"lod\" leaves none out of it), so draw fewer strands (at most {strands_fitting} of this groom's {per_strand:.1} points each) or fewer points per strand: the scene's [hair.procedural] strands or segments, or resample a hair file to N points per strand with `plait hair convert IN OUT.tfx --vertices-per-strand N`",
        pass.location, pass.name, hair.strands, hair.points,
    )))
}
