//! `.tfx` files built byte by byte from the published layout (TressFX's
//! `TressFXFileFormat.h`), independently of plait's writer: read, written,
//! round-tripped, and every malformed header refused with the field named.

use plait_hair::tfx::{TfxError, TfxFile, TfxWarning, V3_HEADER_SIZE, V4_HEADER_SIZE};
use plait_hair::{Asset, Format, HairFile, Strands};
use std::path::Path;

fn f32le(out: &mut Vec<u8>, v: f32) {
    out.extend_from_slice(&v.to_le_bytes());
}
fn u32le(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}

/// Vertex `k` of strand `s`: distinct, exactly representable values.
fn vertex(s: usize, k: usize) -> [f32; 3] {
    [
        s as f32 * 0.5,
        -(k as f32) * 0.25,
        1.0 + s as f32 + k as f32 * 0.125,
    ]
}

/// A TressFX 4 file: 160-byte header (version, strands, vertices per strand,
/// five offsets, 32 reserved u32), then positions (float4, w = inverse mass),
/// strand UVs (float2), strand thickness (f32, padded to 8) and vertex
/// colours (float4); no vertex UVs (offset 0).
fn v4_file(strands: u32, per: u32) -> Vec<u8> {
    let n = (strands * per) as usize;
    let pos = V4_HEADER_SIZE as u32;
    let uv = pos + 16 * n as u32;
    let thick = uv + 8 * strands;
    let color = (thick + 4 * strands).next_multiple_of(8);
    let mut b = Vec::new();
    f32le(&mut b, 4.0);
    u32le(&mut b, strands);
    u32le(&mut b, per);
    for offset in [pos, uv, 0, thick, color] {
        u32le(&mut b, offset);
    }
    b.resize(V4_HEADER_SIZE, 0);
    for s in 0..strands as usize {
        for k in 0..per as usize {
            let p = vertex(s, k);
            for c in p {
                f32le(&mut b, c);
            }
            f32le(&mut b, if k < 2 { 0.0 } else { 1.0 });
        }
    }
    for s in 0..strands {
        f32le(&mut b, s as f32 / 8.0);
        f32le(&mut b, 0.5);
    }
    for s in 0..strands {
        f32le(&mut b, 0.01 * (s + 1) as f32);
    }
    b.resize(color as usize, 0);
    for i in 0..n {
        for c in [0.5, 0.25, i as f32 / 64.0, 0.75] {
            f32le(&mut b, c);
        }
    }
    b
}

/// A TressFX 3 file: 296-byte header (version, guide strands, vertices per
/// strand, follow strands per guide, both-ends-immovable, 31 reserved u32,
/// six offsets, 32 reserved u32), then positions as float3.
fn v3_file(strands: u32, per: u32, follow: u32) -> Vec<u8> {
    let mut b = Vec::new();
    f32le(&mut b, 3.0);
    u32le(&mut b, strands);
    u32le(&mut b, per);
    u32le(&mut b, follow);
    u32le(&mut b, 1);
    b.resize(144, 0);
    u32le(&mut b, V3_HEADER_SIZE as u32);
    b.resize(V3_HEADER_SIZE, 0);
    for s in 0..strands as usize {
        for k in 0..per as usize {
            for c in vertex(s, k) {
                f32le(&mut b, c);
            }
        }
    }
    b
}

fn err(bytes: &[u8]) -> TfxError {
    TfxFile::from_bytes(bytes).expect_err("must be refused")
}

fn set_u32(b: &mut [u8], at: usize, v: u32) {
    b[at..at + 4].copy_from_slice(&v.to_le_bytes());
}

#[test]
fn reads_a_tressfx4_file_built_byte_by_byte() {
    let bytes = v4_file(3, 4);
    let (f, warnings) = TfxFile::from_bytes(&bytes).expect("reads");
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!((f.version, f.vertices_per_strand), (4.0, 4));
    assert_eq!((f.strand_count(), f.vertex_count()), (3, 12));
    assert_eq!(f.positions[6], vertex(1, 2));
    assert_eq!(
        f.inverse_mass.as_ref().expect("v4 has w")[..4],
        [0.0, 0.0, 1.0, 1.0]
    );
    assert_eq!(f.strand_uv.as_ref().expect("uv")[2], [0.25, 0.5]);
    assert!(f.vertex_uv.is_none());
    assert_eq!(f.strand_thickness, Some(vec![0.01, 0.02, 0.03]));
    assert_eq!(
        f.vertex_color.as_ref().expect("colours")[5],
        [0.5, 0.25, 5.0 / 64.0, 0.75]
    );
    assert_eq!(f.major_version(), 4);
}

#[test]
fn writing_reproduces_the_bytes_and_round_trips() {
    // plait's writer lays arrays out in the order and alignment above, so a
    // file read and written again is byte-identical.
    let bytes = v4_file(5, 8);
    let (f, _) = TfxFile::from_bytes(&bytes).expect("reads");
    assert_eq!(f.to_bytes().expect("writes"), bytes);
    // An odd strand count exercises the 8-byte padding after the thickness.
    let bytes = v4_file(3, 16);
    let (f, _) = TfxFile::from_bytes(&bytes).expect("reads");
    assert_eq!(f.to_bytes().expect("writes"), bytes);
}

#[test]
fn reads_a_tressfx3_file_and_writes_it_as_tressfx4() {
    let bytes = v3_file(2, 4, 3);
    let (f, _) = TfxFile::from_bytes(&bytes).expect("reads v3");
    assert_eq!(f.major_version(), 3);
    assert_eq!(f.follow_strands_per_guide, 3);
    assert!(f.both_ends_immovable);
    assert_eq!(f.positions[7], vertex(1, 3));
    assert!(f.inverse_mass.is_none());
    let v4 = f.to_bytes().expect("writes");
    assert_eq!(v4.len(), V4_HEADER_SIZE + 8 * 16);
    let (g, _) = TfxFile::from_bytes(&v4).expect("reads back");
    assert_eq!(g.version, 4.0);
    assert_eq!(g.positions, f.positions);
    // TressFX 3 pins the first two vertices of each strand (inverse mass 0).
    assert_eq!(g.inverse_mass.expect("w")[4..8], [0.0, 0.0, 1.0, 1.0]);
}

#[test]
fn strands_hair_and_tfx_round_trip() {
    let (f, _) = TfxFile::from_bytes(&v4_file(4, 8)).expect("reads");
    let strands = Strands::from(&f);
    assert_eq!(strands.strand_count(), 4);
    assert_eq!(strands.strand(2)[3].to_array(), vertex(2, 3));
    assert_eq!(strands.thickness[8], 0.02);
    assert_eq!(strands.alpha[0], 0.75);
    // .tfx → strands → .tfx keeps positions, thickness and colours.
    let back = TfxFile::from_strands(&strands, None).expect("converts");
    assert_eq!(back.positions, f.positions);
    assert_eq!(back.strand_thickness, f.strand_thickness);
    assert_eq!(back.vertex_color, f.vertex_color);
    // .tfx → .hair → .tfx keeps them too (through the .hair byte layout).
    let hair = strands.to_hair_file().expect("hair");
    let (hair, _) = HairFile::from_bytes(&hair.to_bytes()).expect("parse hair");
    let again = TfxFile::from_strands(&Strands::from_hair_file(&hair), None).expect("tfx");
    assert_eq!(again.positions, f.positions);
    assert_eq!(again.strand_thickness, f.strand_thickness);
    assert_eq!(again.vertex_color, f.vertex_color);
}

#[test]
fn strands_of_other_lengths_are_resampled_by_arc_length() {
    use glam::Vec3;
    let mut s = Strands::new();
    // 3 points over a length of 4 (uneven segments), and 5 points
    let bent = [
        Vec3::ZERO,
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 3.0, 0.0),
    ];
    s.push_strand(&bent, |_| 1.0, |_| 1.0, Vec3::ONE);
    let line: Vec<Vec3> = (0..5).map(|i| Vec3::new(0.0, -(i as f32), 0.0)).collect();
    s.push_strand(&line, |_| 1.0, |_| 1.0, Vec3::ONE);
    let f = TfxFile::from_strands(&s, None).expect("converts");
    assert_eq!(f.vertices_per_strand, 5, "the longest strand's count");
    assert!(f.strand_thickness.is_none() && f.vertex_color.is_none());
    // the bent strand: 5 points 1 apart along the path
    let expect = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0, 2.0], [1.0, 3.0]];
    for (p, e) in f.positions[..5].iter().zip(expect) {
        assert!(
            (p[0] - e[0]).abs() < 1e-6 && (p[1] - e[1]).abs() < 1e-6,
            "{p:?}"
        );
    }
    // the straight one is kept as it is
    let line: Vec<[f32; 3]> = line.iter().map(|p| p.to_array()).collect();
    assert_eq!(f.positions[5..], line[..]);
    let four = TfxFile::from_strands(&s, Some(4)).expect("converts");
    assert_eq!(four.positions.len(), 8);
    assert_eq!(four.positions[7], [0.0, -4.0, 0.0]);
    assert!(TfxFile::from_strands(&s, Some(1)).is_err());
    assert!(TfxFile::from_strands(&Strands::new(), None).is_err());
}

#[test]
fn truncated_files_name_the_array_and_field() {
    let bytes = v4_file(3, 4);
    // every truncation is an error, never a panic
    for cut in 0..bytes.len() {
        let e = err(&bytes[..cut]);
        let msg = e.to_string();
        if cut >= V4_HEADER_SIZE {
            assert!(matches!(e, TfxError::Truncated { .. }), "{cut}: {msg}");
            assert!(msg.contains("offset"), "{msg}");
        }
    }
    let e = err(&bytes[..V4_HEADER_SIZE + 100]);
    let msg = e.to_string();
    assert!(
        msg.contains("positions") && msg.contains("offsetVertexPosition"),
        "{msg}"
    );
    let e = err(&bytes[..50]);
    assert!(e.to_string().contains("160-byte TressFX 4 header"), "{e}");
    let v3 = v3_file(2, 4, 0);
    assert!(
        err(&v3[..200])
            .to_string()
            .contains("296-byte TressFX 3 header")
    );
}

#[test]
fn counts_that_disagree_with_the_file_size_fail_before_allocating() {
    let mut bytes = v4_file(3, 4);
    // a billion strands in a 1 kB file: refused at once, naming the array
    set_u32(&mut bytes, 4, 1_000_000_000);
    let msg = err(&bytes).to_string();
    assert!(msg.contains("64000000000 bytes"), "{msg}");
    let mut bytes = v4_file(3, 4);
    set_u32(&mut bytes, 8, u32::MAX);
    assert!(matches!(err(&bytes), TfxError::Truncated { .. }));
    // 0 strands, 0 or 1 vertices
    for (at, value, field) in [
        (4, 0, "numHairStrands"),
        (8, 0, "numVerticesPerStrand"),
        (8, 1, "numVerticesPerStrand"),
    ] {
        let mut bytes = v4_file(3, 4);
        set_u32(&mut bytes, at, value);
        let msg = err(&bytes).to_string();
        assert!(msg.contains(field), "{msg}");
    }
    // Regression (fuzzing): u32::MAX strands × u32::MAX vertices × 16 bytes
    // overflowed the size check.
    let mut bytes = v4_file(3, 4);
    set_u32(&mut bytes, 4, u32::MAX);
    set_u32(&mut bytes, 8, u32::MAX);
    assert!(matches!(err(&bytes), TfxError::Truncated { .. }));
    let mut v3 = v3_file(2, 4, 0);
    set_u32(&mut v3, 4, 0);
    assert!(err(&v3).to_string().contains("numGuideHairStrands"));
}

#[test]
fn offsets_inside_the_header_and_missing_positions_are_refused() {
    let mut bytes = v4_file(1, 4);
    set_u32(&mut bytes, 16, 8); // strand UVs inside the header
    let msg = err(&bytes).to_string();
    assert!(
        msg.contains("offsetStrandUV") && msg.contains("inside"),
        "{msg}"
    );
    let mut bytes = v4_file(1, 4);
    set_u32(&mut bytes, 12, 0);
    assert!(err(&bytes).to_string().contains("offsetVertexPosition"));
}

#[test]
fn non_finite_values_name_strand_and_vertex() {
    for (bad, array) in [(f32::NAN, "position"), (f32::INFINITY, "position")] {
        let mut bytes = v4_file(3, 4);
        // strand 2, vertex 1, y
        let at = V4_HEADER_SIZE + (2 * 4 + 1) * 16 + 4;
        bytes[at..at + 4].copy_from_slice(&bad.to_le_bytes());
        let msg = err(&bytes).to_string();
        assert!(
            msg.contains(&format!("{array} of strand 2, vertex 1")),
            "{msg}"
        );
    }
    let mut bytes = v4_file(3, 4);
    let thick = u32::from_le_bytes(bytes[24..28].try_into().unwrap()) as usize;
    bytes[thick + 4..thick + 8].copy_from_slice(&f32::NEG_INFINITY.to_le_bytes());
    assert!(err(&bytes).to_string().contains("thickness of strand 1"));
}

#[test]
fn versions_other_than_3_and_4_are_refused_and_odd_vertex_counts_warned() {
    for version in [0.0f32, 2.0, 5.0, f32::NAN, -4.0] {
        let mut bytes = v4_file(1, 4);
        bytes[..4].copy_from_slice(&version.to_le_bytes());
        assert!(matches!(err(&bytes), TfxError::UnsupportedVersion { .. }));
    }
    let mut bytes = v4_file(2, 4);
    bytes[..4].copy_from_slice(&4.1f32.to_le_bytes());
    assert!(
        TfxFile::from_bytes(&bytes).is_ok(),
        "4.1 reads as TressFX 4"
    );
    let (_, warnings) = TfxFile::from_bytes(&v4_file(2, 5)).expect("5 vertices read");
    assert_eq!(
        warnings,
        vec![TfxWarning::VertexCountNotTressFx { count: 5 }]
    );
}

#[test]
fn formats_are_told_apart_by_content_then_name() {
    let tfx = v4_file(1, 4);
    assert_eq!(Format::detect(Path::new("x.bin"), &tfx), Some(Format::Tfx));
    assert_eq!(
        Format::detect(Path::new("x.tfx"), b"junk"),
        Some(Format::Tfx)
    );
    assert_eq!(
        Format::detect(Path::new("x.tfx"), b"HAIRjunk"),
        Some(Format::Hair)
    );
    assert_eq!(Format::detect(Path::new("x.bin"), b"junk"), None);
    let e = Asset::from_bytes(Path::new("dir/x.bin"), b"junk").unwrap_err();
    assert!(
        e.to_string().starts_with("dir/x.bin: not a hair asset"),
        "{e}"
    );
    let e = Asset::from_bytes(Path::new("dir/m.tfx"), &tfx[..100]).unwrap_err();
    assert!(
        e.to_string().starts_with("dir/m.tfx: file is 100 bytes"),
        "{e}"
    );
    let (asset, _) = Asset::from_bytes(Path::new("m.tfx"), &tfx).expect("reads");
    assert_eq!(asset.strands().point_count(), 4);
}

#[test]
fn read_names_the_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("short.tfx");
    std::fs::write(&path, &v4_file(2, 4)[..170]).expect("write");
    let e = TfxFile::read(&path).unwrap_err();
    assert!(
        e.to_string().starts_with(&path.display().to_string()),
        "{e}"
    );
    assert!(matches!(e.root(), TfxError::Truncated { .. }));
}
