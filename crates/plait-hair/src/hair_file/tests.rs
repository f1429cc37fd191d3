use super::*;

/// An independent writer: builds a file byte by byte from the published
/// layout, without using `to_bytes`.
fn independent_file() -> Vec<u8> {
    let mut b: Vec<u8> = Vec::new();
    b.extend_from_slice(b"HAIR");
    b.extend_from_slice(&2u32.to_le_bytes()); // 2 strands
    b.extend_from_slice(&5u32.to_le_bytes()); // 5 points
    b.extend_from_slice(&(1u32 | 2 | 8).to_le_bytes()); // segments, points, transparency
    b.extend_from_slice(&7u32.to_le_bytes()); // default segments (unused: array present)
    b.extend_from_slice(&0.25f32.to_le_bytes()); // default thickness
    b.extend_from_slice(&0.5f32.to_le_bytes()); // default transparency
    for c in [0.1f32, 0.2, 0.3] {
        b.extend_from_slice(&c.to_le_bytes());
    }
    let mut info = [0u8; 88];
    info[..11].copy_from_slice(b"independent");
    b.extend_from_slice(&info);
    assert_eq!(b.len(), 128);
    b.extend_from_slice(&1u16.to_le_bytes()); // strand 0: 1 segment, 2 points
    b.extend_from_slice(&2u16.to_le_bytes()); // strand 1: 2 segments, 3 points
    for i in 0..5 {
        for c in [i as f32, 2.0 * i as f32, -(i as f32)] {
            b.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in 0..5 {
        b.extend_from_slice(&(i as f32 * 0.1).to_le_bytes());
    }
    b
}

#[test]
fn reads_independent_writer() {
    let bytes = independent_file();
    let (f, w) = HairFile::from_bytes(&bytes).expect("valid file");
    assert!(w.is_empty());
    assert_eq!(f.hair_count, 2);
    assert_eq!(f.points.len(), 5);
    assert_eq!(f.segments.as_deref(), Some(&[1u16, 2][..]));
    assert_eq!(f.points[3], [3.0, 6.0, -3.0]);
    assert_eq!(f.default_segments, 7);
    assert_eq!(f.default_thickness, 0.25);
    assert_eq!(f.default_transparency, 0.5);
    assert_eq!(f.default_color, [0.1, 0.2, 0.3]);
    assert!(f.thickness.is_none() && f.colors.is_none());
    assert_eq!(f.transparency.as_ref().map(|t| t[2]), Some(0.2));
    assert_eq!(f.info_string(), "independent");
    assert_eq!(f.arrays(), vec!["segments", "points", "transparency"]);
    assert_eq!(f.segment_count(), 3);
    // and writing it back is bit-identical
    assert_eq!(f.to_bytes(), bytes);
}

fn full_file() -> HairFile {
    let mut f = HairFile {
        hair_count: 3,
        segments: Some(vec![0, 2, 1]),
        points: (0..6)
            .map(|i| [i as f32, -0.5 * i as f32, 1e-7 * i as f32])
            .collect(),
        thickness: Some((0..6).map(|i| 0.01 * i as f32).collect()),
        transparency: Some((0..6).map(|i| 0.1 * i as f32).collect()),
        colors: Some(
            (0..6)
                .map(|i| [0.1 * i as f32, 0.2, f32::MIN_POSITIVE])
                .collect(),
        ),
        default_segments: 3,
        default_thickness: 0.5,
        default_transparency: 0.25,
        default_color: [0.4, 0.5, 0.6],
        info: [0; INFO_SIZE],
    };
    f.set_info("plait test");
    f
}

#[test]
fn round_trip_all_arrays_bit_identical() {
    let f = full_file();
    let bytes = f.to_bytes();
    assert_eq!(bytes.len(), 128 + 3 * 2 + 6 * (12 + 4 + 4 + 12));
    let (g, w) = HairFile::from_bytes(&bytes).expect("round trip");
    assert!(w.is_empty());
    assert_eq!(g, f);
    assert_eq!(g.to_bytes(), bytes);
}

#[test]
fn round_trip_defaults_only_and_files() {
    let f = HairFile {
        hair_count: 2,
        default_segments: 2,
        points: (0..6).map(|i| [i as f32; 3]).collect(),
        ..HairFile::default()
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("a.hair");
    f.write(&path).expect("write");
    let bytes = std::fs::read(&path).expect("read back");
    let (g, _) = HairFile::read(&path).expect("read");
    assert_eq!(g, f);
    assert_eq!(g.to_bytes(), bytes);
    // no temp file left behind
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .expect("dir")
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(names.len(), 1);
}

fn root(e: &HairError) -> &HairError {
    e.root()
}

#[test]
fn bad_signature() {
    let mut b = independent_file();
    b[0] = b'X';
    let e = HairFile::from_bytes(&b).unwrap_err();
    assert!(matches!(e, HairError::BadSignature { .. }), "{e}");
    assert!(e.to_string().contains("HAIR"));
}

#[test]
fn short_header() {
    let b = &independent_file()[..100];
    assert!(matches!(
        HairFile::from_bytes(b).unwrap_err(),
        HairError::ShortHeader { len: 100 }
    ));
}

#[test]
fn truncated_array_names_array_and_sizes() {
    let b = independent_file();
    let cut = &b[..b.len() - 3];
    let e = HairFile::from_bytes(cut).unwrap_err();
    match &e {
        HairError::Truncated {
            array,
            expected,
            present,
            ..
        } => {
            assert_eq!(*array, "transparency");
            assert_eq!(*expected, 20);
            assert_eq!(*present, 17);
        }
        other => panic!("wrong error {other}"),
    }
    let msg = e.to_string();
    assert!(
        msg.contains("transparency") && msg.contains("20") && msg.contains("17"),
        "{msg}"
    );
}

#[test]
fn huge_claim_fails_fast_without_allocating() {
    let mut b = vec![0u8; 1024];
    b[..4].copy_from_slice(b"HAIR");
    b[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
    b[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
    b[12..16].copy_from_slice(&(FLAG_SEGMENTS | FLAG_POINTS | FLAG_COLORS).to_le_bytes());
    let start = std::time::Instant::now();
    let e = HairFile::from_bytes(&b).unwrap_err();
    assert!(start.elapsed().as_secs_f32() < 0.5);
    match e {
        HairError::Truncated {
            array,
            expected,
            present,
            ..
        } => {
            assert_eq!(array, "segments");
            assert_eq!(expected, u64::from(u32::MAX) * 2);
            assert_eq!(present, 1024 - 128);
        }
        other => panic!("wrong error {other}"),
    }
    // without a segments array the points array is the one reported
    b[12..16].copy_from_slice(&FLAG_POINTS.to_le_bytes());
    match HairFile::from_bytes(&b).unwrap_err() {
        HairError::Truncated {
            array, expected, ..
        } => {
            assert_eq!(array, "points");
            assert_eq!(expected, u64::from(u32::MAX) * 12);
        }
        other => panic!("wrong error {other}"),
    }
}

#[test]
fn segment_mismatch() {
    let mut b = independent_file();
    b[128..130].copy_from_slice(&3u16.to_le_bytes()); // 4 + 3 = 7 != 5
    let e = HairFile::from_bytes(&b).unwrap_err();
    assert!(
        matches!(
            e,
            HairError::SegmentMismatch {
                implied: 7,
                points: 5,
                strands: 2
            }
        ),
        "{e}"
    );
    // default segments path
    let f = HairFile {
        hair_count: 2,
        default_segments: 2,
        points: vec![[0.0; 3]; 5],
        ..HairFile::default()
    };
    let e = HairFile::from_bytes(&f.to_bytes()).unwrap_err();
    assert!(
        matches!(
            e,
            HairError::SegmentMismatch {
                implied: 6,
                points: 5,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn non_finite_names_strand() {
    let mut f = full_file();
    f.points[4] = [0.0, f32::NAN, 0.0]; // strand 2 (points 4..6)
    let e = HairFile::from_bytes(&f.to_bytes()).unwrap_err();
    assert!(
        matches!(
            e,
            HairError::NonFinite {
                strand: 2,
                point: 4,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("strand 2"));
    f.points[4] = [0.0, 0.0, 0.0];
    f.points[1] = [f32::INFINITY, 0.0, 0.0];
    let e = HairFile::from_bytes(&f.to_bytes()).unwrap_err();
    assert!(matches!(e, HairError::NonFinite { strand: 1, .. }), "{e}");
}

#[test]
fn no_points_array() {
    let mut b = independent_file();
    b[12..16].copy_from_slice(&1u32.to_le_bytes());
    assert!(matches!(
        HairFile::from_bytes(&b).unwrap_err(),
        HairError::NoPoints
    ));
}

#[test]
fn trailing_garbage_is_a_warning() {
    let mut b = independent_file();
    b.extend_from_slice(b"garbage");
    let (f, w) = HairFile::from_bytes(&b).expect("still readable");
    assert_eq!(f.points.len(), 5);
    assert_eq!(w, vec![HairWarning::TrailingBytes { count: 7 }]);
    assert!(w[0].to_string().contains('7'));
}

#[test]
fn unknown_flags_are_a_warning() {
    let mut b = independent_file();
    b[12..16].copy_from_slice(&(1u32 | 2 | 8 | 64).to_le_bytes());
    let (_, w) = HairFile::from_bytes(&b).expect("readable");
    assert_eq!(w, vec![HairWarning::UnknownFlags { bits: 64 }]);
}

#[test]
fn read_errors_name_the_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("bad.hair");
    std::fs::write(&path, b"NOPE and some more bytes").expect("write");
    let e = HairFile::read(&path).unwrap_err();
    assert!(e.to_string().contains("bad.hair"), "{e}");
    assert!(matches!(root(&e), HairError::BadSignature { .. }));
    let missing = dir.path().join("missing.hair");
    let e = HairFile::read(&missing).unwrap_err();
    assert!(e.to_string().contains("missing.hair"), "{e}");
}
