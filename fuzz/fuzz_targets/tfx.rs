//! `.tfx` (TressFX 3 and 4): any bytes give a file or an error; a file
//! writes back as TressFX 4 and reads again to the same positions.
#![no_main]
use libfuzzer_sys::fuzz_target;
use plait_hair::{Asset, Strands, TfxFile};
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    if let Ok((file, _)) = TfxFile::from_bytes(bytes) {
        let written = file.to_bytes().expect("a file read is writable");
        let (again, _) = TfxFile::from_bytes(&written).expect("written file reads back");
        assert_eq!(again.positions, file.positions);
        let _ = Strands::from(&file).to_hair_file();
    }
    for name in ["x.tfx", "x.hair", "x.bin"] {
        if let Ok((asset, _)) = Asset::from_bytes(Path::new(name), bytes) {
            let _ = asset.strands();
        }
    }
});
