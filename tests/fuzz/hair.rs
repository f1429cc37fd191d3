//! Fuzz target: `.hair` files.

use super::*;

/// `.hair`: read, write, read again: the same file.
#[test]
fn fuzz_hair_reader() {
    let mut seeds = vec![Vec::new(), b"HAIR".to_vec()];
    for spec in [(1, 1), (3, 8)] {
        let mut s = Strands::new();
        for i in 0..spec.0 {
            let pts: Vec<glam::Vec3> = (0..=spec.1)
                .map(|k| glam::Vec3::new(i as f32, k as f32, 0.5))
                .collect();
            s.push_strand(&pts, |t| 1.0 - t * 0.5, |_| 0.7, glam::Vec3::X);
        }
        seeds.push(s.to_hair_file().expect("hair").to_bytes());
    }
    let mut varied = Strands::new();
    varied.push_strand(
        &[glam::Vec3::ZERO, glam::Vec3::Y],
        |_| 1.0,
        |_| 1.0,
        glam::Vec3::ONE,
    );
    varied.push_strand(&[glam::Vec3::ZERO; 3], |_| 2.0, |t| t, glam::Vec3::Z);
    seeds.push(varied.to_hair_file().expect("hair").to_bytes());
    // Measured at the default seed (`cargo test -p plait-tests --test fuzz --
    // --nocapture`): 24,333 of 73,794 mutated inputs accepted (32.97%); 8,920
    // of 26,206 unmutated seeds. The floor is half the mutated fraction.
    fuzz(
        "hair",
        100_000,
        0.16,
        &seeds,
        mutated(&seeds, &[]),
        |bytes| {
            if let Ok((file, _)) = HairFile::from_bytes(bytes) {
                let written = file.to_bytes();
                let again = HairFile::from_bytes(&written).map_err(|e| {
                    TestCaseError::fail(format!("written file does not read back: {e}"))
                })?;
                // Bytes, not values: NaN thickness is kept, and NaN != NaN.
                prop_assert_eq!(again.0.to_bytes(), written);
                let strands = Strands::from_hair_file(&file);
                let _ = strands.to_hair_file();
                let _ = TfxFile::from_strands(&strands, None);
                return Ok(true);
            }
            Ok(false)
        },
    );
}
