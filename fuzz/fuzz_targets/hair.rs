//! `.hair`: any bytes give a file or an error; a file writes back and
//! reads again to the same bytes.
#![no_main]
use libfuzzer_sys::fuzz_target;
use plait_hair::{HairFile, Strands, TfxFile};

fuzz_target!(|bytes: &[u8]| {
    if let Ok((file, _)) = HairFile::from_bytes(bytes) {
        let written = file.to_bytes();
        let (again, _) = HairFile::from_bytes(&written).expect("written file reads back");
        assert_eq!(again.to_bytes(), written);
        let strands = Strands::from_hair_file(&file);
        let _ = strands.to_hair_file();
        let _ = TfxFile::from_strands(&strands, None);
    }
});
