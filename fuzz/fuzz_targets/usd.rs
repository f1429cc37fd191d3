//! USD text (`.usda`): any bytes give a groom or an error; a groom writes
//! back as `.usda` and reads again to the same strands. Text only, as in
//! `tests/fuzz.rs`: openusd 0.6's `.usdc` reader allocates sizes a file
//! claims deep in it before checking them (docs/formats.md, "USD grooms").
#![no_main]
use libfuzzer_sys::fuzz_target;
use plait_hair::usd::{self, UsdGroom, UsdOptions, WriteFormat};
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    for prim in [None, Some("/G".to_string())] {
        let options = UsdOptions {
            prim,
            segments_per_span: 3,
        };
        if let Ok((groom, _)) =
            UsdGroom::from_bytes(Path::new("g.usda"), bytes.to_vec(), &options, false)
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
    }
});
