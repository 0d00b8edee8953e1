//! Static description of a dictionary: the `const` entry tables the derive macro generates, and the
//! [`OdDescribe`] view that the EDS writer (and tools) walk.
//!
//! Covers OD-04 (sub 00h of ARRAY/RECORD is the UNSIGNED8 count, [`count_entry`]), OD-06 (object
//! codes per object), OD-11 (each entry: name, data type, access, PDO mapping, value range, default) and
//! OD-16 (unknown index → 0602 0000h, unknown sub-index → 0609 0011h, in [`lookup`]).
//!
//! Lookup is a binary search over the `(index, sub)` keys (a compact `u32` array, [`lookup_key`]) of a table sorted at compile time
//! (`O(log n)`, about 7 probes for 100 entries, no hashing, no RAM); the position it returns is then used by
//! a `match` (a jump table) to reach the field, and PDO handles keep that position so process data never
//! searches again. On bare metal, the derive's default layout scans a dictionary of 2 to 12 entries instead
//! ([`scan_key`]: less flash for a firmware's few objects).

use super::{AbortCode, Access, DataType, ObjectCode, PdoMapping};

/// A constant value in an entry table: a default or a limit (OD-11).
///
/// ```
/// use canopen_core::od::Value;
/// assert_eq!(Value::Int(-5), Value::Int(-5));
/// assert_ne!(Value::Uint(5), Value::Int(5));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// BOOLEAN.
    Bool(bool),
    /// A signed integer (any INTEGERn).
    Int(i64),
    /// An unsigned integer (any UNSIGNEDn, TIME_OF_DAY/TIME_DIFFERENCE as their 48-bit raw value).
    Uint(u64),
    /// REAL32.
    Real32(f32),
    /// REAL64.
    Real64(f64),
    /// VISIBLE_STRING or UNICODE_STRING text.
    Str(&'static str),
    /// OCTET_STRING or DOMAIN bytes.
    Bytes(&'static [u8]),
    /// An UNSIGNED32 that depends on the node-ID: `$NODEID + n` in the EDS (e.g. a default COB-ID).
    NodeIdPlus(u32),
}

/// Description of one sub-entry (OD-11).
///
/// ```
/// use canopen_core::od::{Access, DataType, EntryDesc, PdoMapping, Value};
/// const E: EntryDesc = EntryDesc::var(0x2000, 0, "Setpoint", DataType::Integer16, Access::Rw)
///     .with_limits(Some(Value::Int(-100)), Some(Value::Int(100)));
/// assert_eq!(E.key(), 0x2000_00);
/// assert_eq!(E.pdo, PdoMapping::No);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EntryDesc {
    /// Object index.
    pub index: u16,
    /// Sub-index.
    pub sub: u8,
    /// ParameterName of the sub-entry.
    pub name: &'static str,
    /// When true the name is followed by the sub-index number (`"Consumer heartbeat time 3"`), for arrays
    /// whose length is a const generic.
    pub numbered: bool,
    /// Data type.
    pub data_type: DataType,
    /// Access type.
    pub access: Access,
    /// PDO mapping.
    pub pdo: PdoMapping,
    /// Largest encoded size in bytes (capacity of a string; `usize::MAX` for DOMAIN).
    pub max_size: usize,
    /// Default value (EDS DefaultValue), if any.
    pub default: Option<Value>,
    /// Low limit (EDS LowLimit), if any.
    pub low: Option<Value>,
    /// High limit (EDS HighLimit), if any.
    pub high: Option<Value>,
}

impl EntryDesc {
    /// A plain entry without default, limits or mapping.
    pub const fn var(index: u16, sub: u8, name: &'static str, data_type: DataType, access: Access) -> Self {
        EntryDesc {
            index,
            sub,
            name,
            numbered: false,
            data_type,
            access,
            pdo: PdoMapping::No,
            max_size: match data_type.size() {
                Some(s) => s,
                None => usize::MAX,
            },
            default: None,
            low: None,
            high: None,
        }
    }

    /// The same entry with a default value.
    pub const fn with_default(mut self, default: Value) -> Self {
        self.default = Some(default);
        self
    }

    /// The same entry with limits.
    pub const fn with_limits(mut self, low: Option<Value>, high: Option<Value>) -> Self {
        self.low = low;
        self.high = high;
        self
    }

    /// The same entry with a PDO mapping.
    pub const fn with_pdo(mut self, pdo: PdoMapping) -> Self {
        self.pdo = pdo;
        self
    }

    /// The sort key `index << 8 | sub`.
    pub const fn key(&self) -> u32 {
        ((self.index as u32) << 8) | self.sub as u32
    }
}

/// Sub 00h of an ARRAY or RECORD: "Highest sub-index supported", UNSIGNED8, const (OD-04).
///
/// ```
/// use canopen_core::od::{count_entry, Access, Value};
/// let e = count_entry(0x1018, 4);
/// assert_eq!((e.sub, e.access, e.default), (0, Access::Const, Some(Value::Uint(4))));
/// ```
pub const fn count_entry(index: u16, highest: u8) -> EntryDesc {
    EntryDesc::var(index, 0, "Highest sub-index supported", DataType::Unsigned8, Access::Const)
        .with_default(Value::Uint(highest as u64))
}

/// Description of one object (index).
///
/// ```
/// use canopen_core::od::{ObjectCode, ObjectDesc};
/// let o = ObjectDesc { index: 0x1018, name: "Identity object", code: ObjectCode::Record, first: 0, subs: 5 };
/// assert_eq!(o.subs, 5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjectDesc {
    /// Index.
    pub index: u16,
    /// ParameterName of the object.
    pub name: &'static str,
    /// VAR, ARRAY, RECORD (or DOMAIN).
    pub code: ObjectCode,
    /// Position of its first sub-entry in the owning entry table (derive-generated tables; 0 otherwise).
    pub first: u16,
    /// Number of sub-entries, sub 00h included (1 for a VAR).
    pub subs: u16,
}

/// A walkable description of a dictionary, in increasing index order: what the EDS writer needs.
///
/// ```
/// use canopen_core::od::{Access, DataType, EntryDesc, ObjectCode, ObjectDesc, OdDescribe};
/// struct Two;
/// impl OdDescribe for Two {
///     fn object_count(&self) -> usize { 1 }
///     fn object(&self, n: usize) -> Option<ObjectDesc> {
///         (n == 0).then_some(ObjectDesc { index: 0x2000, name: "X", code: ObjectCode::Var, first: 0, subs: 1 })
///     }
///     fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
///         ((index, sub) == (0x2000, 0)).then_some(EntryDesc::var(0x2000, 0, "X", DataType::Unsigned8, Access::Rw))
///     }
/// }
/// assert_eq!(Two.object(0).unwrap().index, 0x2000);
/// ```
pub trait OdDescribe {
    /// Number of objects.
    fn object_count(&self) -> usize;
    /// The `n`-th object in increasing index order.
    fn object(&self, n: usize) -> Option<ObjectDesc>;
    /// The description of one sub-entry.
    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc>;
    /// The index of the `n`-th object, without the rest of its description: what store/restore walks
    /// (with [`ObjectDictionary::info`](crate::od::ObjectDictionary::info) for the sub-entries), so that a
    /// firmware which stores its parameters does not link the names and defaults the EDS writer reads.
    /// The default takes it from [`object`](Self::object); a dictionary with a table of its indices
    /// answers from that.
    ///
    /// ```
    /// use canopen_core::od::{NoApplication, OdDescribe};
    /// assert_eq!(NoApplication.object_index(0), None);
    /// ```
    fn object_index(&self, n: usize) -> Option<u16> {
        self.object(n).map(|o| o.index)
    }
}

/// Binary search of `(index, sub)` in a table sorted by [`EntryDesc::key`]: the position, or 0602 0000h
/// when no entry has `index`, or 0609 0011h when the index exists without `sub` (OD-16).
///
/// ```
/// use canopen_core::od::{count_entry, lookup, AbortCode};
/// const T: &[canopen_core::od::EntryDesc] = &[count_entry(0x2000, 0), count_entry(0x2002, 0)];
/// assert_eq!(lookup(T, 0x2002, 0), Ok(1));
/// assert_eq!(lookup(T, 0x2002, 1), Err(AbortCode::SubIndexDoesNotExist));
/// assert_eq!(lookup(T, 0x2001, 0), Err(AbortCode::ObjectDoesNotExist));
/// ```
#[inline]
pub fn lookup(table: &[EntryDesc], index: u16, sub: u8) -> Result<usize, AbortCode> {
    let key = (u32::from(index) << 8) | u32::from(sub);
    match table.binary_search_by_key(&key, EntryDesc::key) {
        Ok(pos) => Ok(pos),
        Err(ins) => {
            let same = |p: usize| table.get(p).is_some_and(|e| e.index == index);
            if same(ins) || ins.checked_sub(1).is_some_and(same) {
                Err(AbortCode::SubIndexDoesNotExist)
            } else {
                Err(AbortCode::ObjectDoesNotExist)
            }
        }
    }
}

/// Binary search of `(index, sub)` in a compact sorted key array (`index << 8 | sub`, as
/// [`EntryDesc::key`]): the same answer as [`lookup`] over the matching entry table, but the 4-byte keys keep
/// the search inside a few cache lines. The derive macro generates such an array (`OD_KEYS`) beside the
/// entry table.
///
/// ```
/// use canopen_core::od::{lookup_key, AbortCode};
/// const KEYS: &[u32] = &[0x2000_00, 0x2002_00, 0x2002_01];
/// assert_eq!(lookup_key(KEYS, 0x2002, 1), Ok(2));
/// assert_eq!(lookup_key(KEYS, 0x2002, 2), Err(AbortCode::SubIndexDoesNotExist));
/// assert_eq!(lookup_key(KEYS, 0x2001, 0), Err(AbortCode::ObjectDoesNotExist));
/// ```
#[inline]
pub fn lookup_key(keys: &[u32], index: u16, sub: u8) -> Result<usize, AbortCode> {
    let key = (u32::from(index) << 8) | u32::from(sub);
    match keys.binary_search(&key) {
        Ok(pos) => Ok(pos),
        Err(ins) => {
            let same = |p: usize| keys.get(p).is_some_and(|k| k >> 8 == u32::from(index));
            if same(ins) || ins.checked_sub(1).is_some_and(same) {
                Err(AbortCode::SubIndexDoesNotExist)
            } else {
                Err(AbortCode::ObjectDoesNotExist)
            }
        }
    }
}

/// The row of `(index, sub)` among rows of a key `index << 8 | sub` (as [`EntryDesc::key`]) each, and its
/// position, by a scan of every row: the same answers as [`lookup_key`] (0602 0000h when no row has
/// `index`, 0609 0011h when the index exists without `sub`, OD-16; a row of the same index makes a miss
/// the latter). The derive macro's default layout searches this way on bare metal (`target_os = "none"`)
/// when a dictionary has 2 to 12 entries, each key beside its entry's [`SubInfo`](super::SubInfo): a
/// short scan is less flash than a binary search and its two neighbour tests (64 B less in the reference
/// firmware), and the position found reaches its row without a second bounds test. A larger dictionary
/// keeps the binary search (its lookup does not grow with it, issue 41).
///
/// ```
/// use canopen_core::od::{scan_key, AbortCode};
/// const ROWS: &[(u32, char)] = &[(0x2000_00, 'a'), (0x2002_00, 'b'), (0x2002_01, 'c')];
/// assert_eq!(scan_key(ROWS, 0x2002, 1), Ok((2, &'c')));
/// assert_eq!(scan_key(ROWS, 0x2002, 2), Err(AbortCode::SubIndexDoesNotExist));
/// assert_eq!(scan_key(ROWS, 0x2001, 0), Err(AbortCode::ObjectDoesNotExist));
/// ```
#[inline]
pub fn scan_key<T>(rows: &[(u32, T)], index: u16, sub: u8) -> Result<(usize, &T), AbortCode> {
    let key = (u32::from(index) << 8) | u32::from(sub);
    let mut missing = AbortCode::ObjectDoesNotExist;
    for (pos, (k, row)) in rows.iter().enumerate() {
        if *k == key {
            return Ok((pos, row));
        }
        if k >> 8 == u32::from(index) {
            missing = AbortCode::SubIndexDoesNotExist;
        }
    }
    Err(missing)
}

/// Whether `table` is strictly sorted by key (no duplicate `(index, sub)`); the derive macro asserts it at
/// compile time.
///
/// ```
/// use canopen_core::od::{count_entry, is_sorted};
/// assert!(is_sorted(&[count_entry(0x2000, 0), count_entry(0x2001, 0)]));
/// assert!(!is_sorted(&[count_entry(0x2001, 0), count_entry(0x2000, 0)]));
/// ```
pub const fn is_sorted(table: &[EntryDesc]) -> bool {
    let mut i = 1;
    while i < table.len() {
        if table[i - 1].key() >= table[i].key() {
            return false;
        }
        i += 1;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `scan_key` gives `lookup_key`'s answer for every (index, sub) around tables of 0 to 30 rows: the
    /// position, 0602 0000h for an unknown index, 0609 0011h for an unknown sub-index of a known one (OD-16),
    /// at the ends and in between.
    #[test]
    fn the_scan_answers_as_the_key_search_od_16() {
        // Indices 2000h, 2002h, ... each with one to three sub-indices, every other one without sub 0.
        let mut all = [0u32; 40];
        let mut len = 0;
        for i in 0..20u32 {
            for s in 0..=(i % 3) {
                if len < all.len() {
                    all[len] = ((0x2000 + 2 * i) << 8) | (s + (i % 2));
                    len += 1;
                }
            }
        }
        let mut rows = [(0u32, 0u32); 40];
        for (row, &k) in rows.iter_mut().zip(&all) {
            *row = (k, !k);
        }
        for n in 0..=30 {
            let (keys, rows) = (&all[..n], &rows[..n]);
            for index in 0x1FFF..=0x2028u16 {
                for sub in 0..=4u8 {
                    let want = lookup_key(keys, index, sub);
                    let got = scan_key(rows, index, sub);
                    assert_eq!(got.map(|(p, _)| p), want, "{n} rows, {index:04X}h sub {sub}");
                    if let Ok((p, row)) = got {
                        assert_eq!(*row, !keys[p]);
                    }
                }
            }
        }
    }
}
