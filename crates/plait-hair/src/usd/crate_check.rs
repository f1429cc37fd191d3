//! A structural check of a `.usdc` crate file before `openusd` 0.6 reads
//! it. That reader allocates the counts and sizes its table of contents and
//! section headers claim before checking them against the file (a corrupt
//! file can then stop the process on a failed allocation) and panics on
//! versions and compressions it does not implement. This checks, in u64,
//! what it reads first: the bootstrap header and version, the table of
//! contents, that every section lies inside the file, that each structural
//! section's element count could fit in its bytes (at most 1024 elements per
//! byte: integer coding then LZ4, at most 255 : 1, cannot pack more) and
//! that the first compressed block of a section is in the file and not
//! chunked. Array values deeper in the file are read lazily by the crate
//! and are not checked here (`docs/formats.md`, "USD grooms").

const MAGIC: &[u8] = b"PXR-USDC";
const BOOTSTRAP: u64 = 32;
const SECTION: u64 = 32;
/// Elements a byte of a compressed section can hold, at most.
const PER_BYTE: u64 = 1024;

fn u64_at(bytes: &[u8], at: u64) -> Result<u64, String> {
    let at = usize::try_from(at).map_err(|_| format!("offset {at} is past the end"))?;
    let b = bytes
        .get(at..at.saturating_add(8))
        .filter(|b| b.len() == 8)
        .ok_or_else(|| {
            format!(
                "offset {at} is past the end of the {}-byte file",
                bytes.len()
            )
        })?;
    Ok(u64::from_le_bytes([
        b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7],
    ]))
}

/// Checks a crate file's structure; the message says what is wrong.
pub(crate) fn check(bytes: &[u8]) -> Result<(), String> {
    let len = bytes.len() as u64;
    if len < BOOTSTRAP || !bytes.starts_with(MAGIC) {
        return Err("not a USD crate file (no PXR-USDC header)".into());
    }
    let (major, minor, patch) = (bytes[8], bytes[9], bytes[10]);
    if (major, minor) < (0, 4) || (major, minor) > (0, 12) {
        return Err(format!(
            "crate version {major}.{minor}.{patch}: openusd 0.6 reads 0.4.0 to 0.12.x"
        ));
    }
    let toc = u64_at(bytes, 16)?;
    let count = u64_at(bytes, toc)?;
    if count == 0 || count >= 64 {
        return Err(format!(
            "the table of contents at {toc} claims {count} sections"
        ));
    }
    let table_end = toc
        .checked_add(8 + count * SECTION)
        .filter(|&e| e <= len)
        .ok_or_else(|| format!("the table of contents at {toc} ({count} sections) runs past the end of the {len}-byte file"))?;
    let _ = table_end;
    for i in 0..count {
        let at = toc + 8 + i * SECTION;
        let raw = &bytes[at as usize..at as usize + 16];
        let name =
            String::from_utf8_lossy(raw.split(|&b| b == 0).next().unwrap_or(raw)).into_owned();
        let start = u64_at(bytes, at + 16)?;
        let size = u64_at(bytes, at + 24)?;
        let end = start
            .checked_add(size)
            .filter(|&e| e <= len)
            .ok_or_else(|| format!("section {name} ({size} bytes at {start}) runs past the end of the {len}-byte file"))?;
        section(bytes, &name, start, end)?;
    }
    Ok(())
}

/// The counts a structural section starts with, against its size.
fn section(bytes: &[u8], name: &str, start: u64, end: u64) -> Result<(), String> {
    let size = end - start;
    let claim = |what: &str, n: u64, limit: u64| {
        if n > limit {
            Err(format!("section {name} claims {n} {what} in {size} bytes"))
        } else {
            Ok(())
        }
    };
    // A compressed block: u64 size, then a chunk count byte (0: one block).
    let block = |at: u64| -> Result<(), String> {
        let compressed = u64_at(bytes, at)?;
        claim("compressed bytes", compressed, end.saturating_sub(at + 8))?;
        if compressed > 0 && bytes[(at + 8) as usize] != 0 {
            return Err(format!(
                "section {name} uses chunked LZ4, which openusd 0.6 does not read"
            ));
        }
        Ok(())
    };
    match name {
        "TOKENS" => {
            claim(
                "tokens",
                u64_at(bytes, start)?,
                size.saturating_mul(PER_BYTE),
            )?;
            let uncompressed = u64_at(bytes, start + 8)?;
            claim(
                "bytes of token text",
                uncompressed,
                size.saturating_mul(256),
            )?;
            block(start + 16)
        }
        "STRINGS" => claim("strings", u64_at(bytes, start)?, size.saturating_sub(8) / 4),
        "FIELDS" | "FIELDSETS" | "SPECS" => {
            claim(
                "entries",
                u64_at(bytes, start)?,
                size.saturating_mul(PER_BYTE),
            )?;
            block(start + 8)
        }
        "PATHS" => claim(
            "paths",
            u64_at(bytes, start)?,
            size.saturating_mul(PER_BYTE),
        ),
        _ => Ok(()),
    }
}
