//! Fuzz target: glTF meshes.

use super::*;

const GLTF_TOKENS: &[&str] = &[
    "\"count\":",
    "4294967295",
    "18446744073709551615",
    "-1",
    "1e39",
    "\"VEC3\"",
    "\"VEC2\"",
    "\"SCALAR\"",
    "5121",
    "5123",
    "5125",
    "5126",
    "\"byteStride\":",
    "\"byteOffset\":",
    "\"normalized\":true,",
    "\"mode\":0,",
    "\"children\":[0],",
    "\"matrix\":[-1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],",
    "\"uri\":\"data:,\",",
    "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":2,\"componentType\":5125},\"values\":{\"bufferView\":0}},",
];

/// glTF meshes (`.glb`): read (every count bounded before it is read), write
/// back as `.glb`, read again to the same triangles; bake a small signed
/// distance field of what was read (degenerate meshes included).
#[test]
fn fuzz_gltf_reader() {
    use plait_hair::mesh::Mesh;
    use plait_hair::mesh_file::{Limits, gltf, write};
    let mut seeds = vec![Vec::new(), b"glTF".to_vec()];
    for (stacks, slices) in [(2, 3), (3, 4)] {
        let m = Mesh::ellipsoid(glam::Vec3::ZERO, glam::Vec3::ONE, stacks, slices);
        seeds.push(write::to_glb(&m));
    }
    let limits = Limits::DEFAULT;
    // Measured at the default seed (`cargo test -p plait-tests --test fuzz --
    // --nocapture`): 907 of 78,667 mutated inputs accepted (1.15%); 6,204 of
    // 21,333 unmutated seeds. The floor is half the mutated fraction.
    fuzz(
        "gltf",
        100_000,
        0.0055,
        &seeds,
        mutated(&seeds, GLTF_TOKENS),
        |bytes| {
            let Ok(mesh) = gltf::read_bytes(bytes, Path::new("x.glb"), &limits) else {
                return Ok(false);
            };
            let again = gltf::read_bytes(&write::to_glb(&mesh), Path::new("y.glb"), &limits)
                .map_err(|e| {
                    TestCaseError::fail(format!("written mesh does not read back: {e}"))
                })?;
            let positions = |m: &Mesh| m.vertices.iter().map(|v| v.position).collect::<Vec<_>>();
            prop_assert_eq!(positions(&again), positions(&mesh));
            prop_assert_eq!(&again.indices, &mesh.indices);
            let sdf = plait_hair::sdf::SignedDistanceField::bake(&mesh, 6);
            prop_assert!(sdf.values.iter().all(|d| !d.is_nan()));
            Ok(true)
        },
    );
}
