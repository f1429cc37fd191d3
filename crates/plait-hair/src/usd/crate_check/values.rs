//! Every value a crate file's fields hold, walked as openusd's
//! `CrateFile::value` reads it, with what reading it costs in memory.

use std::collections::HashMap;

use super::blocks::{
    Cursor, MAX_ALLOCATION, allocation, block, decode_ints, encoded_ints, encoded_size,
};
use super::{Crate, MAX_NESTING, STRING, version};

/// A value representation's parts (`usdc/layout.rs`).
#[derive(Clone, Copy)]
pub(super) struct Rep(pub(super) u64);

impl Rep {
    fn ty(self) -> u8 {
        (self.0 >> 48) as u8
    }
    fn payload(self) -> u64 {
        self.0 & ((1 << 48) - 1)
    }
    fn array(self) -> bool {
        self.0 & (1 << 63) != 0
    }
    fn inlined(self) -> bool {
        self.0 & (1 << 62) != 0
    }
    fn compressed(self) -> bool {
        self.0 & (1 << 61) != 0
    }
}

/// How an array's elements are stored (openusd's `ArrayKind`).
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Ints,
    Floats,
    Other,
}

/// For an array type: how it is stored and its element's size in bytes.
fn array_type(ty: u8) -> Option<(Kind, u64)> {
    Some(match ty {
        1 | 2 => (Kind::Other, 1),              // bool, uchar
        3 | 4 => (Kind::Ints, 4),               // int, uint
        5 | 6 => (Kind::Ints, 8),               // int64, uint64
        7 => (Kind::Floats, 2),                 // half
        8 => (Kind::Floats, 4),                 // float
        9 | 56 => (Kind::Floats, 8),            // double, timecode
        13 => (Kind::Other, 32),                // matrix2d
        14 => (Kind::Other, 72),                // matrix3d
        15 => (Kind::Other, 128),               // matrix4d
        16 | 27 => (Kind::Other, 32),           // quatd, vec4d
        17 | 28 | 30 | 19 => (Kind::Other, 16), // quatf, vec4f, vec4i, vec2d
        18 | 29 | 20 | 22 => (Kind::Other, 8),  // quath, vec4h, vec2f, vec2i
        21 => (Kind::Other, 4),                 // vec2h
        23 => (Kind::Other, 24),                // vec3d
        24 | 26 => (Kind::Other, 12),           // vec3f, vec3i
        25 => (Kind::Other, 6),                 // vec3h
        _ => return None,
    })
}

/// The value walk: memory per value, nesting, and the values already
/// costed (a value shared by many fields is walked once).
pub(super) struct Walk {
    nesting: u32,
    costs: HashMap<u64, u64>,
}

impl Walk {
    pub(super) fn new() -> Walk {
        Walk {
            nesting: 0,
            costs: HashMap::new(),
        }
    }
}

impl Crate<'_> {
    /// Every field's value, each within `MAX_ALLOCATION` once read.
    pub(super) fn values(&self) -> Result<(), String> {
        let mut walk = Walk::new();
        for (i, &(name, rep)) in self.fields.iter().enumerate() {
            let cost = self
                .value(&mut walk, Rep(rep))
                .and_then(|cost| allocation(cost, "the value").map(|_| cost));
            if let Err(message) = cost {
                let field = self.tokens.get(name as usize).map_or("?", |t| t.as_str());
                return Err(match self.prim_of(i) {
                    Some(path) if path.contains('.') => {
                        format!("attribute `{path}`, field `{field}`: {message}")
                    }
                    Some(path) => format!("prim `{path}`, field `{field}`: {message}"),
                    None => format!("field `{field}` (unused by any spec): {message}"),
                });
            }
        }
        Ok(())
    }

    /// The first spec's path whose fields include field `field`.
    fn prim_of(&self, field: usize) -> Option<String> {
        self.specs.iter().find_map(|&(path, set)| {
            let mut at = set as usize;
            while let Some(&f) = self.fieldsets.get(at) {
                if f == u32::MAX {
                    break;
                }
                if f as usize == field {
                    return Some(self.path_text(path));
                }
                at += 1;
            }
            None
        })
    }

    fn token(&self, index: u64) -> Result<u64, String> {
        match self.tokens.get(index as usize) {
            Some(t) => Ok(STRING + t.len() as u64),
            None => Err(format!("token {index} of {}", self.tokens.len())),
        }
    }

    fn string(&self, index: u64) -> Result<u64, String> {
        match self.strings.get(index as usize) {
            Some(&t) => self.token(u64::from(t)),
            None => Err(format!("string {index} of {}", self.strings.len())),
        }
    }

    fn path(&self, index: u64) -> Result<u64, String> {
        if index as usize >= self.paths.len() {
            return Err(format!("path {index} of {}", self.paths.len()));
        }
        Ok(STRING)
    }

    /// What reading `rep` costs in memory (bytes), once checked.
    pub(super) fn value(&self, walk: &mut Walk, rep: Rep) -> Result<u64, String> {
        if let Some(&cost) = walk.costs.get(&rep.0) {
            return Ok(cost);
        }
        if walk.nesting >= MAX_NESTING {
            return Err(format!(
                "values nest more than {MAX_NESTING} deep (or in a cycle), more than plait reads"
            ));
        }
        walk.nesting += 1;
        let cost = self.value_uncached(walk, rep);
        walk.nesting -= 1;
        let cost = cost?;
        allocation(cost, "the value")?;
        walk.costs.insert(rep.0, cost);
        Ok(cost)
    }

    fn value_uncached(&self, walk: &mut Walk, rep: Rep) -> Result<u64, String> {
        let ty = rep.ty();
        let at = |p: u64| Cursor::new(self.bytes, p);
        // Scalars read at most 128 bytes in place: nothing to bound but
        // the indexes they hold.
        let scalar_index = || -> Result<u64, String> {
            if rep.inlined() {
                Ok(rep.payload() & 0xffff_ffff)
            } else {
                let mut c = at(rep.payload());
                match ty {
                    11 | 53 => c.u64("a token"),
                    _ => c.u32("an index").map(u64::from),
                }
            }
        };
        // openusd reads no array in place (and asserts so in debug builds).
        if rep.array() && rep.inlined() {
            return Err("an array cannot be stored in place (inlined)".into());
        }
        match ty {
            _ if rep.array() && array_type(ty).is_some() => self.array(rep),
            48 => self.array(rep), // double vector: read as a double array
            11 if rep.array() => {
                let mut c = at(rep.payload());
                let (count, _) = self.array_len(&mut c, rep, Kind::Other)?;
                self.indexes(&mut c, count, |f, i| f.token(i))
            }
            10 | 12 | 57 if rep.array() => self.indexed(rep.payload(), |f, i| f.string(i)),
            50 => self.indexed(rep.payload(), |f, i| f.string(i)),
            41 => self.indexed(rep.payload(), |f, i| f.token(i)),
            40 => self.indexed(rep.payload(), |f, i| f.path(i)),
            11 | 53 if !rep.array() => scalar_index().and_then(|i| self.token(i)),
            10 if !rep.array() => scalar_index().and_then(|i| self.string(i)),
            12 | 57 if !rep.array() => {
                let i = scalar_index()?;
                if rep.inlined() {
                    self.token(i)
                } else {
                    self.string(i)
                }
            }
            32 | 33 | 34 | 35 | 36 | 37 | 38 | 39 | 54 | 55 => self.list_op(walk, rep),
            45 => {
                let mut c = at(rep.payload());
                let count = c.u64("the variant selection count")?;
                c.elements(count, 8, "the variant selections")?;
                let mut c = at(rep.payload() + 8);
                let mut cost = count.saturating_mul(2 * STRING);
                for _ in 0..count {
                    cost += self.string(u64::from(c.u32("a variant")?))?;
                    cost += self.string(u64::from(c.u32("a selection")?))?;
                }
                Ok(cost)
            }
            49 => {
                let mut c = at(rep.payload());
                let count = c.u64("the layer offset count")?;
                c.elements(count, 16, "the layer offsets")?;
                Ok(count * 16)
            }
            47 => self.payload_item(&mut at(rep.payload())),
            46 => self.time_samples(walk, rep),
            31 if !rep.inlined() => self.dictionary(walk, &mut at(rep.payload())),
            58 => {
                let mut c = at(rep.payload());
                let count = c.u64("the relocation count")?;
                c.elements(count, 8, "the relocations")?;
                let mut c = at(rep.payload() + 8);
                for _ in 0..count {
                    self.path(u64::from(c.u32("a relocation")?))?;
                    self.path(u64::from(c.u32("a relocation")?))?;
                }
                Ok(count.saturating_mul(2 * STRING))
            }
            _ => Ok(0),
        }
    }

    /// An array's length as openusd's `unpack_array_len` reads it, and
    /// whether it is compressed.
    fn array_len(&self, c: &mut Cursor, rep: Rep, kind: Kind) -> Result<(u64, bool), String> {
        if rep.payload() == 0 {
            return Ok((0, false));
        }
        if self.version < version(0, 5, 0) {
            c.u32("an array's shape")?;
        }
        let compressed = match kind {
            Kind::Ints => self.version >= version(0, 5, 0) && rep.compressed(),
            Kind::Floats => self.version >= version(0, 6, 0) && rep.compressed(),
            // No writer compresses these (openusd asserts so in debug builds).
            Kind::Other if rep.compressed() => {
                return Err("an array of this type cannot be compressed".into());
            }
            Kind::Other => false,
        };
        let count = if self.version < version(0, 7, 0) {
            u64::from(c.u32("an array's length")?)
        } else {
            c.u64("an array's length")?
        };
        Ok((count, compressed && count >= 4))
    }

    /// A numeric, vector, matrix or quaternion array.
    fn array(&self, rep: Rep) -> Result<u64, String> {
        // A double vector is a double array whatever its flags.
        let (kind, size) = array_type(rep.ty()).unwrap_or((Kind::Floats, 8));
        let mut c = Cursor::new(self.bytes, rep.payload());
        let (count, compressed) = self.array_len(&mut c, rep, kind)?;
        // Matrices and quaternions are read, then copied once reordered.
        let copies = if matches!(rep.ty(), 13..=18) { 2 } else { 1 };
        let out = count.saturating_mul(size).saturating_mul(copies);
        if !compressed {
            if count > 0 {
                c.elements(count, size, "the array")?;
            }
            return Ok(out);
        }
        allocation(out, "the array")?;
        match kind {
            Kind::Ints => {
                encoded_ints(&mut c, count, size, "the array", |_| {})?;
                Ok(out)
            }
            _ => match c.u8("the array's coding")? {
                b'i' => {
                    encoded_ints(&mut c, count, 4, "the array", |_| {})?;
                    Ok(out.saturating_add(count * 4))
                }
                b't' => {
                    let lut = u64::from(c.u32("the array's table size")?);
                    c.elements(lut, size, "the array's table")?;
                    allocation(encoded_size(count) + count * 4, "the array")?;
                    let data = block(&mut c, encoded_size(count), "the array")?;
                    let mut bad = None;
                    decode_ints(&data, count, false, "the array", |i| {
                        if (i as u32) as u64 >= lut && bad.is_none() {
                            bad = Some(i as u32);
                        }
                    })?;
                    if let Some(i) = bad {
                        return Err(format!(
                            "the array indexes entry {i} of a {lut}-entry table"
                        ));
                    }
                    Ok(out.saturating_add(count * 4 + lut * size))
                }
                code => Err(format!(
                    "the array's coding {code} is not one openusd reads"
                )),
            },
        }
    }

    /// `count` u32 indexes at the cursor, each checked by `index` (which
    /// gives what the element costs).
    fn indexes(
        &self,
        c: &mut Cursor,
        count: u64,
        index: impl Fn(&Self, u64) -> Result<u64, String>,
    ) -> Result<u64, String> {
        let start = c.at;
        c.elements(count, 4, "the array")?;
        let mut read = Cursor::new(self.bytes, start);
        let mut cost = count.saturating_mul(4);
        for _ in 0..count {
            cost = cost.saturating_add(index(self, u64::from(read.u32("an index")?))?);
            if cost > MAX_ALLOCATION {
                break;
            }
        }
        Ok(cost)
    }

    /// A u64 count then that many u32 indexes, at `payload`.
    fn indexed(
        &self,
        payload: u64,
        index: impl Fn(&Self, u64) -> Result<u64, String>,
    ) -> Result<u64, String> {
        let mut c = Cursor::new(self.bytes, payload);
        let count = c.u64("a count")?;
        self.indexes(&mut c, count, index)
    }
}

/// What openusd holds per element of a reference, payload, sample or entry.
const REFERENCE: u64 = std::mem::size_of::<openusd::sdf::Reference>() as u64;
const PAYLOAD: u64 = std::mem::size_of::<openusd::sdf::Payload>() as u64;
const VALUE: u64 = std::mem::size_of::<openusd::sdf::Value>() as u64;

impl Crate<'_> {
    /// A list op: a header byte, then up to six lists of the op's items.
    fn list_op(&self, walk: &mut Walk, rep: Rep) -> Result<u64, String> {
        let mut c = Cursor::new(self.bytes, rep.payload());
        let header = c.u8("the list op's header")?;
        let mut cost = 0u64;
        // explicit, added, prepended, appended, deleted, ordered
        for bit in [1, 2, 5, 6, 3, 4] {
            if header & (1 << bit) == 0 {
                continue;
            }
            let count_at = c.at;
            let items = match rep.ty() {
                32 => self.indexes_at(&mut c, |f, i| f.token(i))?,
                33 | 54 => self.indexes_at(&mut c, |f, i| f.string(i))?,
                34 => self.indexes_at(&mut c, |f, i| f.path(i))?,
                36..=39 => {
                    let size = if matches!(rep.ty(), 36 | 38) { 4 } else { 8 };
                    let count = c.u64("the list's length")?;
                    c.elements(count, size, "the list")?;
                    count * size
                }
                35 => {
                    let count = c.u64("the reference count")?;
                    // A reference is at least 32 bytes in the file: a
                    // string, a path, a layer offset, a dictionary's count.
                    self.items(&c, count, 32, REFERENCE, "references")?;
                    let mut items = count * REFERENCE;
                    for _ in 0..count {
                        items += self.string(u64::from(c.u32("a reference's asset")?))?;
                        self.path(u64::from(c.u32("a reference's prim")?))?;
                        c.take(16, "a reference's layer offset")?;
                        items = items.saturating_add(self.dictionary(walk, &mut c)?);
                        allocation(items, "the references")?;
                    }
                    items
                }
                _ => {
                    let count = c.u64("the payload count")?;
                    let size = if self.version >= super::version(0, 8, 0) {
                        24
                    } else {
                        8
                    };
                    self.items(&c, count, size, PAYLOAD, "payloads")?;
                    let mut items = count * PAYLOAD;
                    for _ in 0..count {
                        items += self.payload_item(&mut c)?;
                    }
                    items
                }
            };
            let _ = count_at;
            cost = cost.saturating_add(items);
            allocation(cost, "the list op")?;
        }
        Ok(cost)
    }

    /// `count` items of at least `size` bytes each must be in the file,
    /// and `count × held` bytes (allocated first) within the limit.
    fn items(
        &self,
        c: &Cursor,
        count: u64,
        size: u64,
        held: u64,
        what: &str,
    ) -> Result<(), String> {
        Cursor::new(self.bytes, c.at).elements(count, size, what)?;
        allocation(count.saturating_mul(held), what)
    }

    /// A u64 count and that many u32 indexes at the cursor, which moves past.
    fn indexes_at(
        &self,
        c: &mut Cursor,
        index: impl Fn(&Self, u64) -> Result<u64, String>,
    ) -> Result<u64, String> {
        let count = c.u64("a count")?;
        self.indexes(c, count, index)
    }

    /// A payload: an asset, a prim and (from 0.8.0) a layer offset.
    fn payload_item(&self, c: &mut Cursor) -> Result<u64, String> {
        let cost = self.string(u64::from(c.u32("a payload's asset")?))?;
        self.path(u64::from(c.u32("a payload's prim")?))?;
        if self.version >= super::version(0, 8, 0) {
            c.take(16, "a payload's layer offset")?;
        }
        Ok(cost + STRING)
    }

    /// A relative offset in the stream (openusd's `apply_recursive_offset`):
    /// where it lands, which must be in the file.
    fn jump(&self, c: &mut Cursor, what: &str) -> Result<u64, String> {
        let from = c.at;
        let offset = c.u64(what)? as i64;
        let to = (from as i64)
            .checked_add(offset)
            .filter(|&t| t >= 0 && (t as u64) < self.bytes.len() as u64);
        to.map(|t| t as u64).ok_or_else(|| {
            format!(
                "{what} at {from} ({offset}) leads outside the {}-byte file",
                self.bytes.len()
            )
        })
    }

    /// A dictionary at the cursor (openusd's `read_custom_data`): a count,
    /// then per entry a key, a forward offset and the value's rep there.
    fn dictionary(&self, walk: &mut Walk, c: &mut Cursor) -> Result<u64, String> {
        let count = c.u64("the dictionary's size")?;
        let mut cost = 0u64;
        for _ in 0..count {
            cost += self.string(u64::from(c.u32("a dictionary key")?))?;
            let from = c.at;
            let to = self.jump(c, "a dictionary entry's offset")?;
            // Forward, as every writer writes it: each entry then takes 20
            // bytes or more, and the loop ends with the file.
            if to < from + 8 {
                return Err(format!(
                    "a dictionary entry's offset at {from} points backwards"
                ));
            }
            c.at = to;
            let rep = Rep(c.u64("a dictionary value")?);
            cost = cost.saturating_add(VALUE + 2 * STRING + self.value(walk, rep)?);
            allocation(cost, "the dictionary")?;
        }
        Ok(cost)
    }

    /// Time samples: the times (a double array), then as many value reps.
    fn time_samples(&self, walk: &mut Walk, rep: Rep) -> Result<u64, String> {
        let mut c = Cursor::new(self.bytes, rep.payload());
        c.at = self.jump(&mut c, "the time samples' offset")?;
        let times = Rep(c.u64("the times")?);
        if !(times.ty() == 48 || (times.ty() == 9 && times.array())) {
            return Err("the times are not a double array".into());
        }
        let mut cost = self.value(walk, times)?;
        let n = self
            .array_len(
                &mut Cursor::new(self.bytes, times.payload()),
                times,
                Kind::Floats,
            )?
            .0;
        c.at = self.jump(&mut c, "the time samples' second offset")?;
        let count = c.u64("the sample count")?;
        if count != n {
            return Err(format!("{count} samples for {n} times"));
        }
        let at = c.at;
        c.elements(count, 8, "the samples")?;
        allocation(count.saturating_mul(VALUE + 8), "the samples")?;
        let mut c = Cursor::new(self.bytes, at);
        for _ in 0..count {
            let rep = Rep(c.u64("a sample")?);
            cost = cost.saturating_add(VALUE + 8 + self.value(walk, rep)?);
            allocation(cost, "the samples")?;
        }
        Ok(cost)
    }
}
