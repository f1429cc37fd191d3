//! USD (text `.usda` and binary `.usdc`, told apart by content as a `.usd`
//! is): any bytes give a groom or an error, and a mesh or an error; a groom
//! writes back as `.usda` and reads again to the same strands, a mesh's
//! indices are in range and its vertices finite. Binary files are safe to
//! feed since plait checks every count a crate file claims before openusd
//! reads it (`crates/plait-hair/src/usd/crate_check/`).
#![no_main]
use libfuzzer_sys::fuzz_target;
use plait_hair::mesh_file::Limits;
use plait_hair::usd::{self, UsdGroom, UsdOptions, WriteFormat};
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    for prim in [None, Some("/G")] {
        let options = UsdOptions {
            prim: prim.map(str::to_string),
            segments_per_span: 3,
        };
        if let Ok((groom, _)) =
            UsdGroom::from_bytes(Path::new("g.usd"), bytes.to_vec(), &options, false)
        {
            let written = usd::write(&groom.strands, WriteFormat::Usda).expect("a groom read is writable");
            let (again, _) = UsdGroom::from_bytes(
                Path::new("w.usda"),
                written,
                &UsdOptions::default(),
                false,
            )
            .expect("written file reads back");
            assert_eq!(again.strands, groom.strands);
        }
        match usd::mesh::read_bytes(Path::new("m.usd"), bytes.to_vec(), prim, &Limits::DEFAULT, false) {
            Ok(mesh) => {
                let n = mesh.vertices.len() as u32;
                assert!(mesh.indices.len() % 3 == 0 && mesh.indices.iter().all(|&i| i < n));
                assert!(mesh.vertices.iter().all(|v| v.position.iter().chain(&v.normal).all(|c| c.is_finite())));
            }
            Err(e) => assert!(!e.message.starts_with(usd::mesh::READER_PANIC), "{e}"),
        }
    }
});
