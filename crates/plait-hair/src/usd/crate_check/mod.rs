//! A complete check of a `.usdc` crate file before `openusd` 0.6 reads it.
//!
//! That reader trusts the sizes and counts a file claims: it allocates them
//! first and reads after (a lie then stops the process on a failed
//! allocation, which no `catch_unwind` can catch), builds the path tree
//! without checking it is a tree (exponential work on a crafted one),
//! recurses through dictionaries and time samples without a depth limit
//! (a stack overflow, also an abort), and panics on chunked LZ4 and on
//! indexes out of range. So before openusd sees a crate file, plait reads
//! every table as openusd will and every value any field holds, and refuses
//! the file — naming the section, or the prim and field — when:
//!
//! - a count or size needs more bytes than the file has from where it is
//!   read (uncompressed: `count × size`; an LZ4 block: at most 255 bytes
//!   out per byte in, and its data decompressed here, into at most that, to
//!   check what it truly holds);
//! - one table or one value would need more than [`blocks::MAX_ALLOCATION`]
//!   bytes of memory once read (a dictionary or time samples counted with
//!   everything they hold, shared parts once per use, as openusd copies
//!   them);
//! - the path tree visits an entry twice, goes deeper than [`MAX_DEPTH`] or
//!   spells paths longer than the limit in all;
//! - values nest deeper than [`MAX_NESTING`] (or in a cycle), a dictionary
//!   entry points backwards, or an index (token, string, path, lookup
//!   table) is out of range.
//!
//! What is checked is exactly what openusd reads (`usdc/reader.rs` of
//! 0.6.0), in its order; `docs/formats.md` ("USD grooms") lists it.

mod blocks;
mod values;

use blocks::{Cursor, allocation, block, encoded_ints};

const MAGIC: &[u8] = b"PXR-USDC";
const BOOTSTRAP: u64 = 32;
const SECTION: u64 = 32;
/// The deepest prim or property path plait reads (namespace levels).
pub(crate) const MAX_DEPTH: u32 = 1024;
/// The deepest nesting of dictionaries and time samples plait reads.
pub(crate) const MAX_NESTING: u32 = 32;
/// openusd's size for a path, a token or a string before its text.
const STRING: u64 = std::mem::size_of::<String>() as u64;

/// Reads one table (a section) into the crate.
type Table<'a> = fn(&mut Crate<'a>, &mut Cursor<'a>) -> Result<(), String>;

/// The crate's tables as openusd will hold them.
pub(crate) struct Crate<'a> {
    bytes: &'a [u8],
    /// `(major, minor, patch)` as one number, as openusd compares them.
    version: u32,
    tokens: Vec<String>,
    strings: Vec<u32>,
    /// `(token index, value rep)` per field.
    fields: Vec<(u32, u64)>,
    fieldsets: Vec<u32>,
    /// Per path index: its parent's path index (`u32::MAX`: the root) and
    /// its last element's token, to name a prim in an error.
    paths: Vec<(u32, i32)>,
    /// `(path index, fieldset index)` per spec.
    specs: Vec<(u32, u32)>,
}

const fn version(major: u8, minor: u8, patch: u8) -> u32 {
    (major as u32) << 16 | (minor as u32) << 8 | patch as u32
}

/// Checks a crate file; the message says what is wrong, and where.
pub(crate) fn check<'a>(bytes: &'a [u8]) -> Result<(), String> {
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
    let toc = Cursor::new(bytes, 16).u64("the table of contents' offset")?;
    let mut cur = Cursor::new(bytes, toc);
    let count = cur.u64("the table of contents")?;
    if count == 0 || count >= 64 {
        return Err(format!(
            "the table of contents at {toc} claims {count} sections"
        ));
    }
    if count * SECTION > cur.left() {
        return Err(format!(
            "the table of contents at {toc} ({count} sections) runs past the end of the {len}-byte file"
        ));
    }
    // openusd reads the first section of each name.
    let mut sections: Vec<(String, u64)> = Vec::new();
    for _ in 0..count {
        let raw = cur.take(16, "a section name")?;
        let name =
            String::from_utf8_lossy(raw.split(|&b| b == 0).next().unwrap_or(raw)).into_owned();
        let start = cur.u64("a section start")?;
        let size = cur.u64("a section size")?;
        if start.checked_add(size).is_none_or(|e| e > len) {
            return Err(format!(
                "section {name} ({size} bytes at {start}) runs past the end of the {len}-byte file"
            ));
        }
        if !sections.iter().any(|(n, _)| *n == name) {
            sections.push((name, start));
        }
    }
    let start = |name: &str| sections.iter().find(|(n, _)| n == name).map(|s| s.1);
    let mut file = Crate {
        bytes,
        version: version(major, minor, patch),
        tokens: Vec::new(),
        strings: Vec::new(),
        fields: Vec::new(),
        fieldsets: Vec::new(),
        paths: Vec::new(),
        specs: Vec::new(),
    };
    let sections: [(&str, Table<'a>); 6] = [
        ("TOKENS", Crate::tokens),
        ("STRINGS", Crate::strings),
        ("FIELDS", Crate::fields),
        ("FIELDSETS", Crate::fieldsets),
        ("PATHS", Crate::paths),
        ("SPECS", Crate::specs),
    ];
    for (name, read) in sections {
        if let Some(at) = start(name) {
            read(&mut file, &mut Cursor::new(bytes, at))
                .map_err(|m| format!("section {name}: {m}"))?;
        }
    }
    file.values()
}

impl Crate<'_> {
    fn tokens(&mut self, cur: &mut Cursor) -> Result<(), String> {
        let count = cur.u64("the token count")?;
        let size = cur.u64("the size of the token text")?;
        let text = block(cur, size, "the token text")?;
        if text.len() as u64 != size {
            return Err(format!(
                "claims {size} bytes of token text, its block holds {}",
                text.len()
            ));
        }
        let found = text.iter().filter(|&&b| b == 0).count() as u64;
        if count != found || text.last().is_some_and(|&b| b != 0) {
            return Err(format!(
                "claims {count} tokens, its text holds {found} (each ends in a 0 byte)"
            ));
        }
        allocation(
            count.saturating_mul(STRING).saturating_add(size),
            "the tokens",
        )?;
        if size > 0 {
            self.tokens = text[..text.len() - 1]
                .split(|&b| b == 0)
                .map(|t| String::from_utf8_lossy(t).into_owned())
                .collect();
        }
        Ok(())
    }

    fn strings(&mut self, cur: &mut Cursor) -> Result<(), String> {
        let count = cur.u64("the string count")?;
        let at = cur.at;
        cur.elements(count, 4, "the strings")?;
        let mut read = Cursor::new(cur.bytes, at);
        self.strings = (0..count)
            .map(|_| read.u32("a string"))
            .collect::<Result<_, _>>()?;
        Ok(())
    }

    fn fields(&mut self, cur: &mut Cursor) -> Result<(), String> {
        let count = cur.u64("the field count")?;
        let mut names = Vec::new();
        encoded_ints(cur, count, 4, "the fields' names", |i| names.push(i as u32))?;
        let reps = block(cur, count.saturating_mul(8), "the fields' values")?;
        if reps.len() as u64 != count * 8 {
            return Err(format!(
                "claims {count} fields, the block of their values holds {} bytes",
                reps.len()
            ));
        }
        self.fields = names
            .into_iter()
            .zip(reps.chunks_exact(8))
            .map(|(n, r)| (n, u64::from_le_bytes(r.try_into().expect("8 bytes"))))
            .collect();
        Ok(())
    }

    fn fieldsets(&mut self, cur: &mut Cursor) -> Result<(), String> {
        let count = cur.u64("the fieldset count")?;
        let mut sets = Vec::new();
        encoded_ints(cur, count, 4, "the fieldsets", |i| sets.push(i as u32))?;
        self.fieldsets = sets;
        Ok(())
    }

    fn specs(&mut self, cur: &mut Cursor) -> Result<(), String> {
        let count = cur.u64("the spec count")?;
        let (mut paths, mut sets) = (Vec::new(), Vec::new());
        encoded_ints(cur, count, 4, "the specs' paths", |i| paths.push(i as u32))?;
        encoded_ints(cur, count, 4, "the specs' fieldsets", |i| {
            sets.push(i as u32)
        })?;
        encoded_ints(cur, count, 4, "the specs' types", |_| {})?;
        allocation(count.saturating_mul(64), "the specs")?;
        self.specs = paths.into_iter().zip(sets).collect();
        Ok(())
    }

    /// The path tree, walked as openusd's `build_compressed_paths` walks it
    /// (an explicit stack of sibling subtrees, each entry once).
    fn paths(&mut self, cur: &mut Cursor) -> Result<(), String> {
        let slots = cur.u64("the path count")?;
        let count = cur.u64("the count of encoded paths")?;
        let (mut index, mut token, mut jump) = (Vec::new(), Vec::new(), Vec::new());
        encoded_ints(cur, count, 4, "the paths' indexes", |i| {
            index.push(i as u32)
        })?;
        encoded_ints(cur, count, 4, "the paths' names", |i| token.push(i as i32))?;
        encoded_ints(cur, count, 4, "the paths' jumps", |i| jump.push(i as i32))?;
        // openusd allocates `slots` empty paths before reading the entries;
        // a tree of `count` entries names at most `count` paths.
        if slots > count {
            return Err(format!("claims {slots} paths but encodes {count}"));
        }
        allocation(slots * STRING, "the paths")?;
        self.paths = vec![(u32::MAX, 0); slots as usize];
        if count == 0 {
            return Ok(());
        }
        // Per path index, once written: its depth and the length of its text.
        let mut shape: Vec<Option<(u32, u64)>> = vec![None; slots as usize];
        let mut visited = vec![false; count as usize];
        let mut text = 0u64;
        // (entry, parent path index; None: the empty path, as openusd
        // starts and as an unwritten path reads).
        let mut pending: Vec<(usize, Option<u32>)> = vec![(0, None)];
        let not_tree = |what: String| format!("the path tree is not a tree: {what}");
        while let Some((mut at, mut parent)) = pending.pop() {
            loop {
                let i = at;
                at += 1;
                if i >= count as usize || std::mem::replace(&mut visited[i], true) {
                    return Err(not_tree(format!(
                        "entry {i} of {count} is reached twice or is past the end"
                    )));
                }
                // openusd writes the root at the entry's own index.
                let (slot, depth, len) = match parent {
                    None => (i as u64, 0, 1),
                    Some(p) => {
                        let t = token[i].unsigned_abs() as usize;
                        let name = self.tokens.get(t).ok_or_else(|| {
                            format!("entry {i} names token {t} of {}", self.tokens.len())
                        })?;
                        let (d, l) = shape[p as usize].unwrap_or((0, 1));
                        (u64::from(index[i]), d + 1, l + 1 + name.len() as u64)
                    }
                };
                if slot >= slots {
                    return Err(format!("entry {i} names path {slot} of {slots}"));
                }
                if shape[slot as usize].replace((depth, len)).is_some() {
                    return Err(not_tree(format!("path {slot} is written twice")));
                }
                if let Some(p) = parent {
                    self.paths[slot as usize] = (p, token[i]);
                }
                if depth > MAX_DEPTH {
                    return Err(format!(
                        "a path is more than {MAX_DEPTH} levels deep, more than plait reads"
                    ));
                }
                text += STRING + len;
                allocation(text, "the paths' text")?;
                if parent.is_none() {
                    parent = Some(slot as u32);
                }
                let (has_child, has_sibling) = (jump[i] > 0 || jump[i] == -1, jump[i] >= 0);
                if has_child {
                    if has_sibling {
                        pending.push((i + jump[i] as usize, parent));
                    }
                    let child = index[i];
                    if u64::from(child) >= slots {
                        return Err(format!("entry {i} names path {child} of {slots}"));
                    }
                    parent = shape[child as usize].map(|_| child);
                }
                if !has_child && !has_sibling {
                    break;
                }
            }
        }
        Ok(())
    }

    /// The path at `index`, as text (for errors).
    fn path_text(&self, index: u32) -> String {
        let mut parts = Vec::new();
        let mut at = index;
        while let Some(&(parent, token)) = self.paths.get(at as usize) {
            if parent == u32::MAX || parts.len() > MAX_DEPTH as usize {
                break;
            }
            let name = self
                .tokens
                .get(token.unsigned_abs() as usize)
                .map_or("?", |t| t.as_str());
            parts.push(match token < 0 {
                true => format!(".{name}"),
                false => format!("/{name}"),
            });
            at = parent;
        }
        parts.reverse();
        let text = parts.concat();
        if text.is_empty() { "/".into() } else { text }
    }
}

#[cfg(test)]
mod tests;
