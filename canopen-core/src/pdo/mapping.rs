//! Resolved PDO mappings: each mapping entry is checked and resolved once (when it is written, or when
//! the PDO is configured) into a [`PdoHandle`], so packing and unpacking a PDO never searches the dictionary.
//!
//! Requirements (`docs/CONFORMANCE.md`): PDO-31 (entry layout), PDO-32 (packed in entry order from bit 0, LE, ≤ 64 bits), PDO-33
//! (mappability per direction, through [`ObjectDictionary::pdo_resolve`]), PDO-34 (dummy entries in RPDOs),
//! PDO-36/PDO-37 (abort codes of a bad entry / a bad count).
//!
//! Granularity. The EDS announces byte granularity (`[DeviceInfo] Granularity=8`), and every build maps
//! whole objects of whole bytes (and RPDO dummy entries of whole bytes): values are copied straight between
//! the dictionary and the frame. With the Cargo feature `pdo-bit-mapping` (on by default) an entry may also
//! map fewer bits than its object holds (e.g. a BOOLEAN as 1 bit, a UNSIGNED8 as 4 bits); the low bits are
//! transferred and, on reception, the remaining high bits of the object are written as 0 (no sign
//! extension). Such a mapping's frame is assembled in a `u64`, so bit granularity costs a shift and a mask
//! per entry, never a loop over bits. Without the feature that path is not in the build (about 550 B of
//! Cortex-M flash) and an entry that is not a whole object of whole bytes is refused like any unmappable
//! one, 0604 0041h (PDO-36): CANopenNode makes the same cut.

use crate::od::{AbortCode, ObjectDictionary, PdoDir, PdoHandle};
use crate::wire::pdo_mapping::MappingEntry;

/// Whether this build maps parts of objects and entries of any bit length (the feature `pdo-bit-mapping`);
/// without it every entry is a whole object of whole bytes (see the module docs).
const BIT_MAPPING: bool = cfg!(feature = "pdo-bit-mapping");

/// Mapping entries per PDO that this stack stores: 8 (sub 01h–08h; CANopenNode's default limit), or 64
/// (sub 01h–40h, all that CiA 301 allows, PDO-30) with the Cargo feature `pdo-mapping-64`. 8 entries
/// already fill 64 bits with byte-sized objects; only bit-sized entries need more. Writing a sub-index
/// above it → 0609 0011h, a count above it → 0604 0042h (PDO-37).
///
/// The feature is off by default: every PDO keeps this many raw entries (1600h+k / 1A00h+k, 4 bytes each)
/// and this many resolved ones (8 bytes each), 8 → 64 costs about 670 B of RAM per PDO.
pub const MAX_ENTRIES: usize = if cfg!(feature = "pdo-mapping-64") { 64 } else { 8 };

/// One resolved entry (8 bytes): the object's handle and the mapped length in bits. A dummy entry (RPDO only,
/// PDO-34) has a handle of size 0: its bits are skipped, nothing is read or written.
///
/// ```
/// use canopen_core::{od::PdoHandle, pdo::mapping::Mapped};
/// let m = Mapped { handle: PdoHandle { index: 5, sub: 0, size: 0, slot: PdoHandle::NO_SLOT }, bits: 8 };
/// assert!(m.is_dummy());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mapped {
    /// The object; size 0 for a dummy entry.
    pub handle: PdoHandle,
    /// Mapped length in bits (1..=64).
    pub bits: u8,
}

impl Mapped {
    /// An unused entry (past the count): all zero, so that an empty map is zeroed memory, not a copy.
    const NONE: Mapped = Mapped { handle: PdoHandle { index: 0, sub: 0, size: 0, slot: 0 }, bits: 0 };

    /// Whether this is a dummy entry (no object behind it).
    pub const fn is_dummy(&self) -> bool {
        self.handle.size == 0
    }
}

/// Resolves one mapping entry (PDO-33, PDO-34, PDO-36): the object must exist (0602 0000h / 0609 0011h),
/// be mappable in `dir` (0604 0041h) and hold at least `bits` bits (0604 0041h otherwise); length 0 is
/// refused with 0604 0041h. Dummy entries are accepted in RPDOs only. Without the feature
/// `pdo-bit-mapping`, `bits` must be the whole object (a dummy: whole bytes), else 0604 0041h.
///
/// ```
/// # use canopen_core::Sizes;
/// use canopen_core::{profile::NodeConfig, od::{PdoDir, AbortCode}, profile::CommProfile, pdo::mapping::resolve};
/// let od: CommProfile<Sizes<0, 16, 16, 0, 0>> = CommProfile::new(NodeConfig::DEFAULT);
/// assert!(resolve(&od, 0x1001_0008, PdoDir::Tpdo).is_ok()); // 1001h is TPDO-mappable
/// assert_eq!(resolve(&od, 0x1001_0008, PdoDir::Rpdo), Err(AbortCode::NotMappable));
/// assert_eq!(resolve(&od, 0x5000_0008, PdoDir::Tpdo), Err(AbortCode::ObjectDoesNotExist));
/// assert!(resolve(&od, 0x0005_0008, PdoDir::Rpdo).unwrap().is_dummy());
/// ```
#[inline]
pub fn resolve<D: ObjectDictionary + ?Sized>(od: &D, raw: u32, dir: PdoDir) -> Result<Mapped, AbortCode> {
    let mut m = Mapped::NONE;
    resolve_into(od, raw, dir, &mut m)?;
    Ok(m)
}

/// [`resolve`] into `slot` (left as it is, or partly written, on a refusal): no `Result` carrying the entry,
/// which the map's resolution copied field by field into its place.
fn resolve_into<D: ObjectDictionary + ?Sized>(
    od: &D,
    raw: u32,
    dir: PdoDir,
    slot: &mut Mapped,
) -> Result<(), AbortCode> {
    let e = MappingEntry::from_raw(raw);
    if e.bits == 0 || e.bits > 64 {
        return Err(AbortCode::NotMappable);
    }
    slot.bits = e.bits;
    slot.handle = match e.dummy_bits() {
        None => od.pdo_resolve(e.index, e.sub, dir)?,
        Some(bits) if dir == PdoDir::Rpdo && e.bits <= bits && (BIT_MAPPING || e.bits % 8 == 0) => {
            slot.handle = PdoHandle { index: e.index, sub: e.sub, size: 0, slot: PdoHandle::NO_SLOT };
            return Ok(());
        }
        Some(_) => return Err(AbortCode::NotMappable),
    };
    // The object must hold at least `bits` bits (PDO-36); without `pdo-bit-mapping`, exactly `bits`.
    let (size, bits) = (u16::from(slot.handle.size), u16::from(e.bits));
    if size == 0 || bits > size * 8 || (!BIT_MAPPING && bits != size * 8) {
        return Err(AbortCode::NotMappable);
    }
    Ok(())
}

/// A PDO's resolved mapping.
///
/// ```
/// use canopen_core::pdo::mapping::ResolvedMap;
/// let m = ResolvedMap::EMPTY;
/// assert_eq!((m.len(), m.bytes()), (0, 0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
// Aligned to 4, so that clearing one (`resolve_in`) is the firmware's `__aeabi_memclr4`: at its natural
// alignment of 2 it linked the 208-byte unaligned `__aeabi_memclr` (footprint.sh, +188 B).
#[repr(align(4))]
pub struct ResolvedMap {
    entries: [Mapped; MAX_ENTRIES],
    count: u8,
    bits: u8,
    /// Not [`direct`](Self::direct) (the negation, so that [`Self::EMPTY`] is all zero: building the node's
    /// PDOs clears memory instead of copying a 68-byte constant into each).
    indirect: bool,
}

impl ResolvedMap {
    /// No entries (mapping disabled).
    pub const EMPTY: ResolvedMap =
        ResolvedMap { entries: [Mapped::NONE; MAX_ENTRIES], count: 0, bits: 0, indirect: false };

    /// Resolves entries `raw` in `dir` (PDO-37: more than 64 bits or more than [`MAX_ENTRIES`] → 0604 0042h;
    /// a bad entry → its [`resolve`] error).
    ///
    /// ```
    /// # use canopen_core::Sizes;
    /// use canopen_core::{profile::NodeConfig, od::{PdoDir, AbortCode}, profile::CommProfile, pdo::mapping::ResolvedMap};
    /// let od: CommProfile<Sizes<0, 16, 16, 0, 0>> = CommProfile::new(NodeConfig::DEFAULT);
    /// let m = ResolvedMap::resolve(&od, &[0x1001_0008, 0x1001_0008], PdoDir::Tpdo).unwrap();
    /// assert_eq!((m.len(), m.bits(), m.bytes()), (2, 16, 2));
    /// assert_eq!(ResolvedMap::resolve(&od, &[0x1001_0008; 9], PdoDir::Tpdo), Err(AbortCode::PdoLengthExceeded));
    /// ```
    #[inline]
    pub fn resolve<D: ObjectDictionary + ?Sized>(od: &D, raw: &[u32], dir: PdoDir) -> Result<Self, AbortCode> {
        let mut m = Self::EMPTY;
        m.resolve_in(od, raw, dir)?;
        Ok(m)
    }

    /// [`resolve`](Self::resolve) into this map, which becomes the resolved entries `raw`, or
    /// [`EMPTY`](Self::EMPTY) when they do not resolve (the error says why): no `Result` carrying a 68-byte
    /// map, which the node's `configure_pdo` copied twice on its way into the PDO.
    // Out of line: a configuration path (the node's `configure_pdo` and the mapping checks of an SDO write).
    #[inline(never)]
    pub(crate) fn resolve_in<D: ObjectDictionary + ?Sized>(
        &mut self,
        od: &D,
        raw: &[u32],
        dir: PdoDir,
    ) -> Result<(), AbortCode> {
        *self = Self::EMPTY;
        let r = self.fill(od, raw, dir);
        if r.is_err() {
            *self = Self::EMPTY; // one exit for every refusal
        }
        r
    }

    /// The body of [`resolve_in`](Self::resolve_in), into an [`EMPTY`](Self::EMPTY) map.
    #[inline(always)]
    fn fill<D: ObjectDictionary + ?Sized>(&mut self, od: &D, raw: &[u32], dir: PdoDir) -> Result<(), AbortCode> {
        if raw.len() > MAX_ENTRIES {
            return Err(AbortCode::PdoLengthExceeded);
        }
        let mut total = 0u16;
        for (slot, &r) in self.entries.iter_mut().zip(raw) {
            resolve_into(od, r, dir, slot)?;
            let e = *slot;
            total += u16::from(e.bits);
            if total > 64 {
                return Err(AbortCode::PdoLengthExceeded);
            }
            // Not direct: an entry of part of a byte or part of an object, or a communication-profile object
            // (no mapping is direct without the bit-granular path, see `direct`).
            if BIT_MAPPING {
                self.indirect |= e.bits % 8 != 0
                    || (!e.is_dummy()
                        && (u16::from(e.handle.size) * 8 != u16::from(e.bits)
                            || (0x1000..=0x1FFF).contains(&e.handle.index)));
            }
        }
        self.count = raw.len() as u8;
        self.bits = total as u8;
        Ok(())
    }

    /// Number of entries.
    pub const fn len(&self) -> usize {
        self.count as usize
    }

    /// Whether the mapping is empty.
    pub const fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Whether the node moves this mapping's data with the application dictionary alone and the byte-aligned
    /// path only (`pack_bytes`, `unpack_bytes`), without the merged view's routing: every entry is a whole
    /// object of whole bytes and none maps a communication-profile object (1000h–1FFFh).
    ///
    /// Only in a build with the feature `pdo-bit-mapping`, where the merged view's path is the bit-granular one
    /// (a `u64` assembled with shifts) and the direct path keeps whole-byte mappings off it. Without the
    /// feature the merged view's path is byte-aligned too: a direct path would save one index compare per
    /// entry (the routing) for a second copy of the node's sampling and unpacking loops, about 150 B of
    /// Cortex-M flash (the minimal firmware, footprint.sh), so no mapping is direct there.
    ///
    /// ```
    /// # use canopen_core::Sizes;
    /// use canopen_core::{profile::{CommProfile, NodeConfig}, od::PdoDir, pdo::mapping::ResolvedMap};
    /// let od: CommProfile<Sizes<0, 16, 16, 0, 0>> = CommProfile::new(NodeConfig::DEFAULT);
    /// assert_eq!(ResolvedMap::EMPTY.direct(), cfg!(feature = "pdo-bit-mapping"));
    /// assert!(!ResolvedMap::resolve(&od, &[0x1001_0008], PdoDir::Tpdo).unwrap().direct()); // 1001h: profile
    /// ```
    pub const fn direct(&self) -> bool {
        BIT_MAPPING && !self.indirect
    }

    /// Total mapped bits.
    pub const fn bits(&self) -> u8 {
        self.bits
    }

    /// The PDO length in bytes (bits rounded up).
    pub const fn bytes(&self) -> usize {
        (self.bits as usize).div_ceil(8)
    }

    /// The entries in use. The count is at most [`MAX_ENTRIES`] (`fill`); above it this would be all of them
    /// (the same start, only the length differs: one select, no second exit, an empty slice, compiled into
    /// each loop over them).
    fn entries(&self) -> &[Mapped] {
        self.entries.get(..self.len()).unwrap_or(&self.entries)
    }

    /// Samples the mapped objects into a frame payload; returns its length (PDO-32). An object that cannot be
    /// read leaves zeros. For a TPDO mapping: those have no dummy entries (PDO-34, [`resolve`] refuses them),
    /// so the byte-aligned path does not test for one.
    ///
    /// With the feature `pdo-bit-mapping` every mapping takes the bit-granular path here, which moves whole
    /// bytes as well (a whole object's `bits` are all its bytes): one path for the merged view, where the
    /// node routes every mapping that is not [`direct`](Self::direct), instead of two.
    pub fn pack<D: ObjectDictionary + ?Sized>(&self, od: &mut D, out: &mut [u8; 8]) -> usize {
        *out = [0; 8];
        if BIT_MAPPING {
            self.move_bits(od, out, false);
            return self.bytes();
        }
        self.pack_bytes(od, out)
    }

    /// [`pack`](Self::pack) for a mapping whose entries are whole objects of whole bytes (see
    /// [`direct`](Self::direct)) and no dummy entry (a TPDO mapping), into a zeroed `out`: each is read
    /// straight into its place.
    pub(crate) fn pack_bytes<D: ObjectDictionary + ?Sized>(&self, od: &D, out: &mut [u8; 8]) -> usize {
        let mut rest: &mut [u8] = out;
        for e in self.entries() {
            let Some((dst, tail)) = rest.split_at_mut_checked(usize::from(e.bits >> 3)) else { break };
            let _ = od.pdo_read(&e.handle, dst);
            rest = tail;
        }
        self.bytes()
    }

    /// Writes a received payload (at least [`bytes`](Self::bytes) long) into the mapped objects; returns
    /// how many writes the dictionary refused (limits, hooks). With the feature `pdo-bit-mapping`, every
    /// mapping through the bit-granular path, as [`pack`](Self::pack).
    pub fn unpack<D: ObjectDictionary + ?Sized>(&self, od: &mut D, data: &[u8]) -> usize {
        if !BIT_MAPPING {
            return self.unpack_bytes(od, data);
        }
        self.unpack_padded(od, padded(data))
    }

    /// [`unpack`](Self::unpack) of a payload already padded to 8 bytes (a received frame's
    /// [`padded`](crate::CanFrame::padded) data, at least [`bytes`](Self::bytes) of them received): the node's
    /// one path for a frame and for a synchronous RPDO's data at the SYNC, with no copy of a slice of the
    /// frame's length.
    pub(crate) fn unpack_padded<D: ObjectDictionary + ?Sized>(&self, od: &mut D, mut data: [u8; 8]) -> usize {
        if !BIT_MAPPING {
            return self.unpack_bytes(od, &data);
        }
        self.move_bits(od, &mut data, true)
    }

    /// The bit-granular path of both directions, one function for [`pack`](Self::pack) (`write` false: the
    /// objects sampled into `payload`, which is zero) and [`unpack`](Self::unpack) (`write`: `payload`'s
    /// entries written into the objects; returns how many writes were refused): each entry is read into or
    /// taken out of a little-endian `u64` with one shift pair ([`Bits`]). One loop instead of a sampling
    /// and an unpacking loop of their own; the direction is one test per entry, on a path that no whole-byte
    /// mapping of the application takes (those are [`direct`](Self::direct)).
    #[inline(never)]
    fn move_bits<D: ObjectDictionary + ?Sized>(&self, od: &mut D, payload: &mut [u8; 8], write: bool) -> usize {
        let mut refused = 0;
        let mut frame = Bits { value: u64::from_le_bytes(*payload), off: 0 };
        for e in self.entries() {
            let mut v = if write { frame.pop(e.bits) } else { 0 }.to_le_bytes();
            if let Some(buf) = v.get_mut(..usize::from(e.handle.size)).filter(|b| !b.is_empty()) {
                if write {
                    refused += usize::from(od.pdo_write(&e.handle, buf).is_err());
                } else {
                    let _ = od.pdo_read(&e.handle, buf);
                }
            }
            if !write {
                frame.push(u64::from_le_bytes(v), e.bits);
            }
        }
        *payload = frame.value.to_le_bytes();
        refused
    }

    /// [`unpack`](Self::unpack) for a mapping whose entries are whole objects of whole bytes (see
    /// [`direct`](Self::direct)).
    pub(crate) fn unpack_bytes<D: ObjectDictionary + ?Sized>(&self, od: &mut D, data: &[u8]) -> usize {
        let mut refused = 0;
        let mut rest = data;
        for e in self.entries() {
            let Some((src, tail)) = rest.split_at_checked(usize::from(e.bits >> 3)) else { break };
            if !e.is_dummy() {
                refused += usize::from(od.pdo_write(&e.handle, src).is_err());
            }
            rest = tail;
        }
        refused
    }
}

/// A PDO payload as a little-endian `u64` with a bit position (PDO-32: entries packed from bit 0 in order),
/// for mappings that are not whole bytes: a shift and a mask per entry, never a loop over bits. Kept out
/// of the generic `pack`/`unpack` so that each dictionary type does not get its own copy.
#[derive(Default)]
struct Bits {
    value: u64,
    off: u32,
}

impl Bits {
    #[cfg(test)]
    fn from_payload(data: &[u8]) -> Self {
        Bits { value: u64::from_le_bytes(padded(data)), off: 0 }
    }

    // An entry has 1..=64 bits and the entries total at most 64 (ResolvedMap::resolve): an entry of `bits`
    // at `off` has off + bits <= 64, so every shift count below is 0..=63 (the `& 63` in `shl_shr` only
    // spares a panic path).

    /// Appends the low `bits` bits of `v`: shifted up to the top (dropping the bits above the entry), then
    /// down to `off`.
    fn push(&mut self, v: u64, bits: u8) {
        let free = 64 - u32::from(bits);
        self.value |= shl_shr(v, free, free.wrapping_sub(self.off));
        self.off += u32::from(bits);
    }

    /// Takes the next `bits` bits (the object's remaining high bits are 0, no sign extension): the entry
    /// shifted up to the top (dropping the entries after it), then down to bit 0.
    fn pop(&mut self, bits: u8) -> u64 {
        let free = 64 - u32::from(bits);
        let v = shl_shr(self.value, free.wrapping_sub(self.off), free);
        self.off += u32::from(bits);
        v
    }
}

/// The first 8 bytes of a received payload, zeros after a shorter one (no entry reads past the payload's
/// length: ResolvedMap::unpack is given at least `bytes()`).
fn padded(data: &[u8]) -> [u8; 8] {
    let mut buf = [0u8; 8];
    let n = data.len().min(8);
    buf[..n].copy_from_slice(&data[..n]);
    buf
}

/// `x` shifted left by `l`, then right by `r` (each 0..=63): the one pair of 64-bit shifts (a dozen
/// instructions each on a 32-bit core) that both puts an entry into a payload and takes one out; masks and
/// two shift directions per entry were twice the code.
#[inline(never)]
fn shl_shr(x: u64, l: u32, r: u32) -> u64 {
    (x << (l & 63)) >> (r & 63)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::od::{Access, DataType, PdoMapping, SubInfo};

    /// 2000h:01..04 u8/u16/u32/bool, all mappable both ways.
    #[derive(Default)]
    struct Od {
        a: u8,
        b: u16,
        c: u32,
        d: bool,
    }

    impl ObjectDictionary for Od {
        fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
            let dt = match (index, sub) {
                (0x2000, 1) => DataType::Unsigned8,
                (0x2000, 2) => DataType::Unsigned16,
                (0x2000, 3) => DataType::Unsigned32,
                (0x2000, 4) => DataType::Boolean,
                (0x2000, _) => return Err(AbortCode::SubIndexDoesNotExist),
                _ => return Err(AbortCode::ObjectDoesNotExist),
            };
            Ok(SubInfo { data_type: dt, access: Access::Rw, pdo: PdoMapping::Both, size: dt.size().unwrap_or(0) })
        }
        fn read(&self, index: u16, sub: u8, _: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
            self.info(index, sub)?;
            let v = match sub {
                1 => u32::from(self.a),
                2 => u32::from(self.b),
                3 => self.c,
                _ => u32::from(self.d),
            }
            .to_le_bytes();
            let n = buf.len().min(4);
            buf[..n].copy_from_slice(&v[..n]);
            Ok(n)
        }
        fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
            self.info(index, sub)?;
            let mut v = [0u8; 4];
            v[..data.len().min(4)].copy_from_slice(&data[..data.len().min(4)]);
            let v = u32::from_le_bytes(v);
            match sub {
                1 => self.a = v as u8,
                2 => self.b = v as u16,
                3 => self.c = v,
                _ if v > 1 => return Err(AbortCode::InvalidValue),
                _ => self.d = v == 1,
            }
            Ok(())
        }
    }

    /// Resolves `entries` as a TPDO mapping of `od` and packs it: the map, the 8 data bytes and the length.
    fn pack(od: &mut Od, entries: &[u32]) -> (ResolvedMap, [u8; 8], usize) {
        let m = ResolvedMap::resolve(od, entries, PdoDir::Tpdo).unwrap();
        let mut out = [0u8; 8];
        let n = m.pack(od, &mut out);
        (m, out, n)
    }

    #[test]
    fn aligned_round_trip() {
        let mut od = Od { a: 0x11, b: 0x2233, c: 0x4455_6677, d: true };
        let (m, out, n) = pack(&mut od, &[0x2000_0108, 0x2000_0210, 0x2000_0320]);
        assert_eq!(n, 7);
        assert_eq!(out[..7], [0x11, 0x33, 0x22, 0x77, 0x66, 0x55, 0x44]);
        let mut rx = Od::default();
        assert_eq!(m.unpack(&mut rx, &out[..7]), 0);
        assert_eq!((rx.a, rx.b, rx.c), (0x11, 0x2233, 0x4455_6677));
    }

    /// PDO-32, PDO-34: whole-byte entries, a whole-byte dummy and a refused write give through
    /// `pack`/`unpack` (the merged view's path, bit-granular with `pdo-bit-mapping`) the bytes, the values and
    /// the refusal count of the byte-aligned path the node takes for a direct mapping.
    #[test]
    fn general_path_matches_bytes_path() {
        let mut od = Od { a: 0x11, b: 0x2233, c: 0x4455_6677, d: true };
        let m = ResolvedMap::resolve(&od, &[0x2000_0108, 0x2000_0210, 0x2000_0320], PdoDir::Tpdo).unwrap();
        let (mut general, mut bytes) = ([0xAAu8; 8], [0u8; 8]);
        assert_eq!((m.pack(&mut od, &mut general), m.pack_bytes(&od, &mut bytes)), (7, 7));
        assert_eq!(general, bytes);
        let rxm =
            ResolvedMap::resolve(&od, &[0x2000_0108, 0x0005_0008, 0x2000_0210, 0x2000_0408], PdoDir::Rpdo).unwrap();
        let data = [0x01, 0xEE, 0x03, 0x04, 0x02]; // 2 is not a BOOLEAN: that write is refused
        let (mut x, mut y) = (Od::default(), Od::default());
        assert_eq!((rxm.unpack(&mut x, &data), rxm.unpack_bytes(&mut y, &data)), (1, 1));
        assert_eq!((x.a, x.b, x.d), (0x01, 0x0403, false));
        assert_eq!((y.a, y.b, y.d), (0x01, 0x0403, false));
    }

    /// Bit granularity: a BOOLEAN as 1 bit, a UNSIGNED8 as 4 bits, a dummy of 3 bits, a UNSIGNED16.
    #[test]
    #[cfg(feature = "pdo-bit-mapping")]
    fn bit_granularity() {
        let mut od = Od { a: 0xFA, b: 0xBEEF, c: 0, d: true };
        let (_, out, n) = pack(&mut od, &[0x2000_0401, 0x2000_0104, 0x2000_0210]);
        assert_eq!(n, 3);
        // bit 0 = 1, bits 1..5 = 0xA, bits 5..21 = 0xBEEF
        let expect = 1u64 | (0xA << 1) | (0xBEEF << 5);
        assert_eq!(u64::from_le_bytes(out), expect);
        let rxm = ResolvedMap::resolve(&od, &[0x2000_0401, 0x0005_0004, 0x2000_0210], PdoDir::Rpdo).unwrap();
        let mut rx = Od::default();
        assert_eq!(rx.a, 0);
        assert_eq!(rxm.unpack(&mut rx, &out[..3]), 0);
        assert_eq!((rx.d, rx.a, rx.b), (true, 0, 0xBEEF));
    }

    /// PDO-36 without `pdo-bit-mapping`: only whole objects of whole bytes are mappable (the EDS says
    /// Granularity=8); a BOOLEAN as 1 bit, 4 bits of a UNSIGNED8, 8 bits of a UNSIGNED16 and a 4-bit dummy
    /// are refused with 0604 0041h, the whole objects and a whole-byte dummy resolve and round-trip.
    #[test]
    #[cfg(not(feature = "pdo-bit-mapping"))]
    fn whole_objects_only() {
        let mut od = Od { a: 0x11, b: 0x2233, c: 0, d: true };
        for raw in [0x2000_0401, 0x2000_0104, 0x2000_0208, 0x2000_0220] {
            assert_eq!(resolve(&od, raw, PdoDir::Tpdo), Err(AbortCode::NotMappable), "{raw:08X}h");
        }
        assert_eq!(resolve(&od, 0x0005_0004, PdoDir::Rpdo), Err(AbortCode::NotMappable));
        let (_, out, n) = pack(&mut od, &[0x2000_0108, 0x2000_0408, 0x2000_0210]);
        assert_eq!(out[..n], [0x11, 0x01, 0x33, 0x22]);
        let rxm = ResolvedMap::resolve(&od, &[0x2000_0108, 0x0005_0008, 0x2000_0210], PdoDir::Rpdo).unwrap();
        let mut rx = Od::default();
        assert_eq!(rxm.unpack(&mut rx, &out[..n]), 0);
        assert_eq!((rx.a, rx.b), (0x11, 0x2233));
    }

    /// PDO-32: entries packed from bit 0 in order, at the edges of the 64 bits: one 64-bit entry, entries that
    /// end at bit 64, a 1-bit one first; high bits of a value beyond its entry are dropped and nothing is
    /// sign-extended on the way out.
    #[test]
    fn bits_edges() {
        let mut b = Bits::default();
        b.push(0x8123_4567_89AB_CDEF, 64);
        assert_eq!(b.value, 0x8123_4567_89AB_CDEF);
        let mut b = Bits::default();
        b.push(0xFF, 1); // only bit 0 kept
        b.push(0xFFFF_FFFF_FFFF_FFF0, 3); // bits 1..4 = 000
        b.push(0x0123_4567_89AB_CDEF, 60); // bits 4..64
        assert_eq!(b.value, 0x1234_5678_9ABC_DEF1);
        let mut f = Bits::from_payload(&b.value.to_le_bytes());
        assert_eq!((f.pop(1), f.pop(3), f.pop(60)), (1, 0, 0x0123_4567_89AB_CDEF));
        let mut f = Bits::from_payload(&[0xFF; 8]);
        assert_eq!((f.pop(63), f.pop(1)), (u64::MAX >> 1, 1));
        let mut f = Bits::from_payload(&[0xA5]); // a short payload reads as zeros above it
        assert_eq!((f.pop(4), f.pop(4), f.pop(56)), (0x5, 0xA, 0));
    }

    /// PDO-36/PDO-37 error codes.
    #[test]
    fn resolve_errors() {
        let od = Od::default();
        assert_eq!(resolve(&od, 0x5000_0008, PdoDir::Rpdo), Err(AbortCode::ObjectDoesNotExist));
        assert_eq!(resolve(&od, 0x2000_0908, PdoDir::Rpdo), Err(AbortCode::SubIndexDoesNotExist));
        assert_eq!(resolve(&od, 0x2000_0110, PdoDir::Rpdo), Err(AbortCode::NotMappable)); // 16 bits of a u8
        assert_eq!(resolve(&od, 0x2000_0100, PdoDir::Rpdo), Err(AbortCode::NotMappable));
        assert_eq!(resolve(&od, 0x0005_0008, PdoDir::Tpdo), Err(AbortCode::NotMappable));
        assert_eq!(
            ResolvedMap::resolve(&od, &[0x2000_0320, 0x2000_0320, 0x2000_0320], PdoDir::Rpdo),
            Err(AbortCode::PdoLengthExceeded)
        );
    }
}
