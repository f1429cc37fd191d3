//! Hand-crafted crate files, one per kind of count or size openusd would
//! trust: each is refused with an error naming the file and the section or
//! the prim and field, before openusd allocates what it claims.

use std::path::Path;

use glam::Vec3;

use super::blocks::Cursor;
use super::{Crate, MAX_DEPTH, MAX_NESTING, version};
use crate::strands::Strands;
use crate::usd::{UsdGroom, UsdOptions, WriteFormat, write};

fn strands() -> Strands {
    let mut s = Strands::new();
    let points = [
        Vec3::ZERO,
        Vec3::new(0.0, -0.1, 0.01),
        Vec3::new(0.0, -0.2, 0.03),
    ];
    s.push_strand(&points, |_| 0.002, |_| 1.0, Vec3::new(0.3, 0.2, 0.1));
    s.push_strand(&points[..2], |_| 0.001, |_| 0.75, Vec3::ONE);
    s
}

fn read(bytes: Vec<u8>) -> Result<(), String> {
    UsdGroom::from_bytes(Path::new("c.usdc"), bytes, &UsdOptions::default(), false)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

fn u64_at(b: &[u8], at: usize) -> u64 {
    u64::from_le_bytes(b[at..at + 8].try_into().unwrap())
}

fn set(b: &[u8], at: usize, value: u64) -> Vec<u8> {
    let mut b = b.to_vec();
    b[at..at + 8].copy_from_slice(&value.to_le_bytes());
    b
}

/// Each count and size of the tables and of an array value, made a lie.
#[test]
fn a_crate_file_claiming_more_than_it_holds_is_an_error() {
    let good = write(&strands(), WriteFormat::Usdc).unwrap();
    assert_eq!(read(good.clone()), Ok(()));
    let toc = u64_at(&good, 16) as usize;
    let sections = u64_at(&good, toc) as usize;
    let entry = |name: &str| {
        (0..sections)
            .map(|i| toc + 8 + 32 * i)
            .find(|&at| good[at..at + 16].starts_with(format!("{name}\0").as_bytes()))
            .unwrap()
    };
    let start = |name: &str| u64_at(&good, entry(name) + 16) as usize;
    // The points: `count` (u64) then the float triples.
    let first: Vec<u8> = [0.0f32, 0.0, 0.0, 0.0, -0.1, 0.01]
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let points = good.windows(24).position(|w| w == first).unwrap() - 8;
    assert_eq!(u64_at(&good, points), 5);
    let tokens = start("TOKENS");
    let text = u64_at(&good, tokens + 8);
    let huge = 1u64 << 40;
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (
            set(&good, tokens, u64::MAX),
            "section TOKENS: claims 18446744073709551615 tokens, its text holds",
        ),
        (
            set(&good, tokens + 8, huge),
            "section TOKENS: the token text: reading it needs 1099511627776 bytes of memory",
        ),
        (
            set(&good, tokens + 8, text + 4096),
            "bytes of token text, its block holds",
        ),
        (
            set(&good, tokens + 16, 1 << 60),
            "section TOKENS: the token text: compressed block: 1152921504606846976 bytes at offset",
        ),
        (
            {
                let mut b = good.clone();
                b[tokens + 24] = 1;
                b
            },
            "chunked LZ4",
        ),
        (
            set(&good, start("STRINGS"), huge),
            "section STRINGS: the strings: 1099511627776 elements of 4 bytes",
        ),
        (
            set(&good, start("FIELDS"), 1 << 20),
            "section FIELDS: the fields' names: 1048576 integers need 262144 code bytes",
        ),
        (
            set(&good, start("FIELDS"), huge),
            "section FIELDS: the fields' names: reading it needs",
        ),
        (
            set(&good, start("FIELDSETS"), 1 << 20),
            "section FIELDSETS: the fieldsets: 1048576 integers need",
        ),
        (
            set(&good, start("PATHS"), huge),
            "section PATHS: claims 1099511627776 paths but encodes",
        ),
        (
            set(&good, start("PATHS") + 8, 1 << 20),
            "section PATHS: the paths' indexes: 1048576 integers need",
        ),
        (
            set(&good, start("SPECS"), 1 << 20),
            "section SPECS: the specs' paths: 1048576 integers need",
        ),
        (
            set(&good, entry("PATHS") + 24, huge),
            "section PATHS (1099511627776 bytes at",
        ),
        (
            set(&good, points, huge),
            "attribute `/Groom/Strands.points`, field `default`: the array: 1099511627776 elements of 12 bytes",
        ),
        (
            {
                let mut b = good.clone();
                b[9] = 3;
                b
            },
            "crate version 0.3",
        ),
        (good[..40].to_vec(), "past the end"),
    ];
    for (bytes, want) in cases {
        let e = read(bytes).unwrap_err();
        assert!(
            e.starts_with("c.usdc: not a readable USD file") && e.contains(want),
            "{want}: {e}"
        );
    }
}

/// A crate over `bytes` with the tokens `a`, `b`, … and one string per
/// token, as its tables would be once read.
fn crate_over(bytes: &[u8], tokens: usize) -> Crate<'_> {
    Crate {
        bytes,
        version: version(0, 8, 0),
        tokens: (0..tokens).map(|i| format!("t{i}")).collect(),
        strings: (0..tokens as u32).collect(),
        fields: Vec::new(),
        fieldsets: Vec::new(),
        paths: Vec::new(),
        specs: Vec::new(),
    }
}

/// `values` in USD's integer coding (every delta 32 bits), LZ4-compressed
/// as a crate block: u64 size, chunk count 0, the block.
fn int_block(values: &[i32]) -> Vec<u8> {
    let mut coded = 0i32.to_le_bytes().to_vec();
    // Code 3 (a 32-bit delta) per value; 0 (the common delta) for the
    // padding of the last code byte.
    coded.extend((0..values.len().div_ceil(4)).map(|byte| {
        (0..4)
            .filter(|i| byte * 4 + i < values.len())
            .fold(0u8, |b, i| b | (3 << (2 * i)))
    }));
    let mut prev = 0i32;
    for &v in values {
        coded.extend(v.wrapping_sub(prev).to_le_bytes());
        prev = v;
    }
    let lz4 = lz4_flex::block::compress(&coded);
    let mut out = ((lz4.len() + 1) as u64).to_le_bytes().to_vec();
    out.push(0);
    out.extend(lz4);
    out
}

/// A PATHS section: path count, entry count, the three integer blocks.
fn paths_section(index: &[i32], token: &[i32], jump: &[i32]) -> Vec<u8> {
    let mut b = (index.len() as u64).to_le_bytes().to_vec();
    b.extend((index.len() as u64).to_le_bytes());
    b.extend(int_block(index));
    b.extend(int_block(token));
    b.extend(int_block(jump));
    b
}

fn read_paths(section: &[u8], tokens: usize) -> Result<(), String> {
    let mut file = crate_over(section, tokens);
    file.paths(&mut Cursor::new(section, 0))
}

/// A path tree that is one (root, two children, a grandchild) reads; one
/// whose jumps reach an entry twice (openusd would walk it again, each
/// revisit doubling the work) or that goes deeper than `MAX_DEPTH` does not.
#[test]
fn the_path_tree_must_be_a_tree() {
    // / with children /t1 (which has /t1/t3) and /t2.
    let good = paths_section(&[0, 1, 3, 2], &[0, 1, 3, 2], &[-1, 2, -2, -2]);
    assert_eq!(read_paths(&good, 4), Ok(()));
    // Entry 1's sibling is its own child, entry 2.
    let twice = paths_section(&[0, 1, 2], &[0, 1, 2], &[-1, 1, -2]);
    let e = read_paths(&twice, 3).unwrap_err();
    assert!(e.contains("is not a tree"), "{e}");
    let revisit = paths_section(&[0, 1, 2, 3], &[0, 1, 1, 1], &[1, 1, 1, -2]);
    let e = read_paths(&revisit, 2).unwrap_err();
    assert!(e.contains("is not a tree"), "{e}");
    // A chain of children deeper than plait reads.
    let n = MAX_DEPTH as i32 + 2;
    let index: Vec<i32> = (0..n).collect();
    let mut jump = vec![-1; n as usize];
    jump[n as usize - 1] = -2;
    let deep = paths_section(&index, &vec![1; n as usize], &jump);
    let e = read_paths(&deep, 2).unwrap_err();
    assert!(e.contains("levels deep"), "{e}");
    // A path naming a token that is not there.
    let e = read_paths(&good, 2).unwrap_err();
    assert!(e.contains("names token 3 of 2"), "{e}");
}

const DICTIONARY: u64 = 31 << 48;

/// A dictionary at offset 8 with one entry whose value is `rep`; the rep
/// sits at offset 28 (`offset` after the entry's offset field at 20).
fn dictionary(rep: u64, offset: i64) -> Vec<u8> {
    let mut b = vec![0u8; 8];
    b.extend(1u64.to_le_bytes()); // one entry
    b.extend(0u32.to_le_bytes()); // key: string 0
    b.extend(offset.to_le_bytes());
    b.extend(rep.to_le_bytes());
    b
}

fn walk(bytes: &[u8], rep: u64) -> Result<u64, String> {
    let file = crate_over(bytes, 2);
    let mut walk = super::values::Walk::new();
    file.value(&mut walk, super::values::Rep(rep))
}

/// Dictionaries: one holding a double reads; one holding itself (openusd
/// would recurse until the stack overflows), one nested deeper than
/// `MAX_NESTING` and one whose entry points backwards (a loop) do not.
#[test]
fn dictionaries_are_bounded() {
    let double = (9u64 << 48) | (1 << 62); // an inlined double
    assert!(walk(&dictionary(double, 8), DICTIONARY | 8).is_ok());
    let cycle = dictionary(DICTIONARY | 8, 8);
    let e = walk(&cycle, DICTIONARY | 8).unwrap_err();
    assert!(
        e.contains(&format!("nest more than {MAX_NESTING} deep")),
        "{e}"
    );
    let back = dictionary(double, -12);
    let e = walk(&back, DICTIONARY | 8).unwrap_err();
    assert!(e.contains("points backwards"), "{e}");
    // A chain of dictionaries, each holding the next.
    let mut chain = vec![0u8; 8];
    for i in 0..(MAX_NESTING as u64 + 2) {
        let next = 8 + (i + 1) * 28;
        chain.extend(1u64.to_le_bytes());
        chain.extend(0u32.to_le_bytes());
        chain.extend(8i64.to_le_bytes());
        chain.extend((DICTIONARY | next).to_le_bytes());
    }
    chain.extend(0u64.to_le_bytes());
    let e = walk(&chain, DICTIONARY | 8).unwrap_err();
    assert!(e.contains("nest more than"), "{e}");
}

/// Arrays: a compressed int array whose count its block cannot hold, an
/// array far longer than the file, a token array naming a missing token.
#[test]
fn arrays_are_bounded() {
    let int_array = (3u64 << 48) | (1 << 63);
    // Uncompressed: count then 4 bytes each.
    let mut b = vec![0u8; 8];
    b.extend(3u64.to_le_bytes());
    b.extend([0u8; 12]);
    assert_eq!(walk(&b, int_array | 8), Ok(12));
    let e = walk(&set(&b, 8, 1 << 50), int_array | 8).unwrap_err();
    assert!(e.contains("1125899906842624 elements of 4 bytes"), "{e}");
    // Compressed: the block holds 4 integers, the count claims a million.
    let mut c = vec![0u8; 8];
    c.extend((1u64 << 20).to_le_bytes());
    c.extend(int_block(&[1, 2, 3, 4]));
    let e = walk(&c, int_array | (1 << 61) | 8).unwrap_err();
    assert!(e.contains("1048576 integers need 262144 code bytes"), "{e}");
    let tokens = (11u64 << 48) | (1 << 63);
    let mut t = vec![0u8; 8];
    t.extend(2u64.to_le_bytes());
    t.extend(1u32.to_le_bytes());
    t.extend(7u32.to_le_bytes());
    let e = walk(&t, tokens | 8).unwrap_err();
    assert!(e.contains("token 7 of 2"), "{e}");
}
