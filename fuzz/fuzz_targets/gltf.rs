//! glTF meshes (`.glb`): any bytes give a mesh or an error; a mesh writes
//! back as `.glb` and reads again to the same triangles, and its signed
//! distance field bakes without NaN.
#![no_main]
use libfuzzer_sys::fuzz_target;
use plait_hair::mesh_file::{Limits, gltf, write};
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    let limits = Limits::DEFAULT;
    if let Ok(mesh) = gltf::read_bytes(bytes, Path::new("x.glb"), &limits) {
        let again = gltf::read_bytes(&write::to_glb(&mesh), Path::new("y.glb"), &limits)
            .expect("a mesh read writes back and reads again");
        assert_eq!(again.indices, mesh.indices);
        let sdf = plait_hair::sdf::SignedDistanceField::bake(&mesh, 6);
        assert!(sdf.values.iter().all(|d| !d.is_nan()));
    }
});
