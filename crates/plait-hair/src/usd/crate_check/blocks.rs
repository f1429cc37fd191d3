//! Reading a crate file's bytes as openusd 0.6 does — little-endian scalars
//! at a position, LZ4 blocks, integer-coded arrays — but checking every
//! size against the file before anything is allocated.

/// The most bytes plait lets openusd allocate at once for one table or one
/// value (an array, a dictionary with all it holds): 1 GiB, about 89
/// million `point3f`. A file needing more is refused, named, rather than
/// risking an allocation failure, which aborts the process.
pub(crate) const MAX_ALLOCATION: u64 = 1 << 30;

/// LZ4 turns one input byte into at most 255 output bytes: a match's length
/// grows by 255 per extension byte, and a sequence's 3 fixed bytes (token,
/// offset) yield at most 19 more. So a block of `n` bytes holds at most
/// `255 n` once decompressed; no claim beyond that can be true.
pub(crate) const LZ4_MAX_RATIO: u64 = 255;

/// A position in the file.
pub(crate) struct Cursor<'a> {
    pub bytes: &'a [u8],
    pub at: u64,
}

impl<'a> Cursor<'a> {
    pub fn new(bytes: &'a [u8], at: u64) -> Cursor<'a> {
        Cursor { bytes, at }
    }

    /// Bytes from the position to the end of the file.
    pub fn left(&self) -> u64 {
        (self.bytes.len() as u64).saturating_sub(self.at)
    }

    /// The next `n` bytes (`what` names them in the error).
    pub fn take(&mut self, n: u64, what: &str) -> Result<&'a [u8], String> {
        if n > self.left() {
            return Err(format!(
                "{what}: {n} bytes at offset {} run past the end of the {}-byte file",
                self.at,
                self.bytes.len()
            ));
        }
        let start = self.at as usize;
        self.at += n;
        Ok(&self.bytes[start..start + n as usize])
    }

    pub fn u8(&mut self, what: &str) -> Result<u8, String> {
        Ok(self.take(1, what)?[0])
    }

    pub fn u32(&mut self, what: &str) -> Result<u32, String> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    pub fn u64(&mut self, what: &str) -> Result<u64, String> {
        let b = self.take(8, what)?;
        Ok(u64::from_le_bytes([
            b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7],
        ]))
    }

    /// `n` elements of `size` bytes each must be in the file from here (an
    /// uncompressed array openusd allocates whole, then reads); skips them.
    pub fn elements(&mut self, n: u64, size: u64, what: &str) -> Result<(), String> {
        let bytes = n.checked_mul(size).filter(|&b| b <= self.left());
        match bytes {
            Some(b) => {
                self.at += b;
                Ok(())
            }
            None => Err(format!(
                "{what}: {n} elements of {size} bytes at offset {} need more than the {} bytes left in the {}-byte file",
                self.at,
                self.left(),
                self.bytes.len()
            )),
        }
    }
}

/// Checks that openusd may allocate `bytes` at once for `what`.
pub(crate) fn allocation(bytes: u64, what: &str) -> Result<(), String> {
    if bytes > MAX_ALLOCATION {
        return Err(format!(
            "{what}: reading it needs {bytes} bytes of memory, more than plait's limit of {MAX_ALLOCATION} for one table or value"
        ));
    }
    Ok(())
}

/// A compressed block as openusd's `read_compressed` reads one: a u64 size,
/// then a chunk count (0: one LZ4 block; openusd reads no other) and the
/// block. `out` is what openusd allocates for the output before
/// decompressing. Decompressed here into at most what the block can hold
/// (`LZ4_MAX_RATIO`), so a lie about sizes costs plait nothing either.
pub(crate) fn block(cur: &mut Cursor, out: u64, what: &str) -> Result<Vec<u8>, String> {
    let at = cur.at;
    let size = cur.u64(what)?;
    let data = cur.take(size, &format!("{what}: compressed block"))?;
    let Some((&chunks, lz4)) = data.split_first() else {
        return Err(format!(
            "{what}: the compressed block at offset {at} is empty"
        ));
    };
    if chunks != 0 {
        return Err(format!(
            "{what}: the block at offset {at} is chunked LZ4 ({chunks} chunks), which openusd 0.6 does not read"
        ));
    }
    allocation(out, what)?;
    let room = out.min(LZ4_MAX_RATIO * lz4.len() as u64);
    let mut buf = vec![0u8; room as usize];
    let n = lz4_flex::block::decompress_into(lz4, &mut buf).map_err(|e| {
        format!("{what}: the LZ4 block at offset {at} does not decompress into {out} bytes: {e}")
    })?;
    buf.truncate(n);
    Ok(buf)
}

/// What openusd allocates to decompress `count` integer-coded values
/// (`coding::encoded_buffer_size::<u32>`, whatever their width).
pub(crate) fn encoded_size(count: u64) -> u64 {
    if count == 0 {
        0
    } else {
        4u64.saturating_add(count.saturating_mul(2).div_ceil(8))
            .saturating_add(count.saturating_mul(4))
    }
}

/// Decodes `count` integers (32- or 64-bit: `wide`) of USD's integer coding
/// (a common delta, 2-bit codes, then the other deltas), as openusd's
/// `coding::decode_ints` does, to `sink`. Every byte read is checked: a
/// count the data cannot hold is an error, never a long loop.
pub(crate) fn decode_ints(
    data: &[u8],
    count: u64,
    wide: bool,
    what: &str,
    mut sink: impl FnMut(i64),
) -> Result<(), String> {
    if count == 0 {
        return Ok(());
    }
    let width: usize = if wide { 8 } else { 4 };
    let codes = count.saturating_mul(2).div_ceil(8);
    if (data.len() as u64) < width as u64 + codes {
        return Err(format!(
            "{what}: {count} integers need {codes} code bytes, the {}-byte block holds {}",
            data.len(),
            data.len().saturating_sub(width)
        ));
    }
    let codes = codes as usize;
    let word = |b: &[u8]| -> i64 {
        match b.len() {
            1 => i64::from(b[0] as i8),
            2 => i64::from(i16::from_le_bytes([b[0], b[1]])),
            4 => i64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            _ => i64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]),
        }
    };
    let common = word(&data[..width]);
    let mut at = width + codes;
    let mut prev = 0i64;
    let mut n = 0u64;
    // openusd decodes all four codes of the last byte, padding included.
    for &code_byte in &data[width..width + codes] {
        for i in 0..4 {
            let size = match ((code_byte >> (2 * i)) & 3, wide) {
                (0, _) => 0,
                (1, true) | (2, false) => 2,
                (1, false) => 1,
                (2, true) | (3, false) => 4,
                _ => 8,
            };
            let delta = if size == 0 {
                common
            } else {
                let b = data.get(at..at + size).ok_or_else(|| {
                    format!(
                        "{what}: the integer coding runs past the end of its {}-byte block",
                        data.len()
                    )
                })?;
                at += size;
                word(b)
            };
            prev = prev.wrapping_add(delta);
            if n < count {
                sink(prev);
            }
            n += 1;
        }
    }
    Ok(())
}

/// `count` integer-coded values read as openusd's `read_encoded_ints` does
/// (a block, then decoding), `size` bytes each once decoded.
pub(crate) fn encoded_ints(
    cur: &mut Cursor,
    count: u64,
    size: u64,
    what: &str,
    sink: impl FnMut(i64),
) -> Result<(), String> {
    allocation(
        encoded_size(count).saturating_add(count.saturating_mul(size)),
        what,
    )?;
    let data = block(cur, encoded_size(count), what)?;
    decode_ints(&data, count, size == 8, what, sink)
}
