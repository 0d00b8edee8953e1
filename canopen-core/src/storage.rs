//! Store/restore of parameters (1010h/1011h; STORE-01..STORE-11, NMT-06).
//!
//! # The contract: two slots, never torn
//!
//! The application provides non-volatile memory through the small [`Storage`] trait: **two independent
//! slots** (0 and 1) of [`capacity`](Storage::capacity) bytes each, with `erase`, `write` at an offset and
//! `read` at an offset. A flash-based MCU gives each slot its own erase page; the Linux adapter uses one
//! file per slot (or two regions of one file). The only thing the trait demands is that **writing one slot
//! never changes the other one**; a write may be torn at any byte by a power loss.
//!
//! The core makes saving atomic on top of that (the A/B scheme, as many bootloaders do):
//! - a record is `header | payload`, the header holding a magic, the format version, a sequence number,
//!   the payload length and a CRC-32 over version, sequence, length and payload;
//! - a save goes to the slot that does **not** hold the newest valid record: erase, payload first, header
//!   last, with sequence + 1;
//! - a load reads both headers, checks both CRCs and takes the valid record with the higher sequence
//!   (serial-number arithmetic, so the counter may wrap).
//!
//! A power loss during a save therefore leaves the slot being written without a valid header or with a
//! failing CRC, and the other slot, untouched, still holds the previous record: after a restart the
//! parameters are either all old or all new, never a mix. `tests/pdo_sync_emcy.rs` checks it with a storage
//! that fails after every possible number of written bytes.
//!
//! # What a record holds
//!
//! Items `index u16 LE | sub u8 | len u8 | value[len]`, in two groups: communication (1000h–1FFFh, the
//! writable entries of the [`CommProfile`](crate::profile::CommProfile)) and application (every writable
//! and readable entry of the application dictionary found through [`OdDescribe`], DOMAIN excluded, at most
//! 255 bytes each). A header flag says which groups are present, so that 1010h sub 02h/03h save one group
//! and keep the other, and 1011h ("load") removes a group so that its defaults come back at the next reset
//! (STORE-10). Values are written back through the dictionary's normal write path, so a value that a newer
//! firmware no longer accepts is skipped rather than stored blindly.

use crate::od::{is_comm, AbortCode, NoApplication, ObjectDictionary, OdDescribe};

/// 1010h signature "save" (UNSIGNED32 6576 6173h): `73 61 76 65` on the bus.
pub const SAVE_SIGNATURE: u32 = 0x6576_6173;
/// 1011h signature "load" (UNSIGNED32 6461 6F6Ch): `6C 6F 61 64` on the bus.
pub const LOAD_SIGNATURE: u32 = 0x6461_6F6C;

/// Why a storage operation failed (every failure becomes SDO abort 0606 0000h, STORE-04/STORE-09).
///
/// ```
/// use canopen_core::storage::StorageError;
/// assert_ne!(StorageError::Io, StorageError::TooLarge);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StorageError {
    /// The memory reported a failure (flash program/erase error, file I/O error).
    Io,
    /// The record does not fit into a slot.
    TooLarge,
    /// No storage is present.
    Unsupported,
}

/// ```
/// use canopen_core::storage::StorageError;
/// assert_eq!(StorageError::TooLarge.to_string(), "the parameters do not fit into a storage slot");
/// ```
impl core::fmt::Display for StorageError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            StorageError::Io => "the non-volatile memory failed",
            StorageError::TooLarge => "the parameters do not fit into a storage slot",
            StorageError::Unsupported => "no non-volatile storage",
        })
    }
}

impl core::error::Error for StorageError {}

/// Non-volatile memory with two independent slots; see the [module docs](self) for the guarantees the core
/// builds on it.
///
/// ```
/// use canopen_core::storage::{Storage, StorageError};
///
/// /// Two RAM slots (a test double; an MCU uses two flash pages, Linux two files).
/// struct Ram([[u8; 256]; 2]);
/// impl Storage for Ram {
///     fn capacity(&self) -> usize { 256 }
///     fn erase(&mut self, slot: u8) -> Result<(), StorageError> {
///         self.0.get_mut(usize::from(slot)).ok_or(StorageError::Io)?.fill(0xFF);
///         Ok(())
///     }
///     fn write(&mut self, slot: u8, offset: usize, data: &[u8]) -> Result<(), StorageError> {
///         let s = self.0.get_mut(usize::from(slot)).ok_or(StorageError::Io)?;
///         s.get_mut(offset..offset + data.len()).ok_or(StorageError::TooLarge)?.copy_from_slice(data);
///         Ok(())
///     }
///     fn read(&mut self, slot: u8, offset: usize, buf: &mut [u8]) -> Result<(), StorageError> {
///         let s = self.0.get(usize::from(slot)).ok_or(StorageError::Io)?;
///         buf.copy_from_slice(s.get(offset..offset + buf.len()).ok_or(StorageError::TooLarge)?);
///         Ok(())
///     }
/// }
/// let mut ram = Ram([[0xFF; 256]; 2]);
/// ram.write(1, 10, &[1, 2]).unwrap();
/// let mut b = [0u8; 2];
/// ram.read(1, 10, &mut b).unwrap();
/// assert_eq!(b, [1, 2]);
/// ```
pub trait Storage {
    /// Bytes per slot (0: no storage; 1010h/1011h then answer 0606 0000h).
    fn capacity(&self) -> usize;
    /// Prepares `slot` (0 or 1) for a new record (erases a flash page, truncates a file). Must not touch
    /// the other slot.
    fn erase(&mut self, slot: u8) -> Result<(), StorageError>;
    /// Writes `data` at `offset` of `slot`. May be torn by a power loss; must not touch the other slot.
    fn write(&mut self, slot: u8, offset: usize, data: &[u8]) -> Result<(), StorageError>;
    /// Reads `buf.len()` bytes at `offset` of `slot`. Reading an erased or never-written area must succeed
    /// (with any content); only a failure of the memory itself is an error.
    fn read(&mut self, slot: u8, offset: usize, buf: &mut [u8]) -> Result<(), StorageError>;
}

/// No non-volatile memory: the default of [`Node`](crate::Node).
///
/// ```
/// use canopen_core::storage::{NoStorage, Storage};
/// assert_eq!(NoStorage.capacity(), 0);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NoStorage;

impl Storage for NoStorage {
    fn capacity(&self) -> usize {
        0
    }
    fn erase(&mut self, _: u8) -> Result<(), StorageError> {
        Err(StorageError::Unsupported)
    }
    fn write(&mut self, _: u8, _: usize, _: &[u8]) -> Result<(), StorageError> {
        Err(StorageError::Unsupported)
    }
    fn read(&mut self, _: u8, _: usize, _: &mut [u8]) -> Result<(), StorageError> {
        Err(StorageError::Unsupported)
    }
}

impl<T: Storage + ?Sized> Storage for &mut T {
    fn capacity(&self) -> usize {
        (**self).capacity()
    }
    fn erase(&mut self, slot: u8) -> Result<(), StorageError> {
        (**self).erase(slot)
    }
    fn write(&mut self, slot: u8, offset: usize, data: &[u8]) -> Result<(), StorageError> {
        (**self).write(slot, offset, data)
    }
    fn read(&mut self, slot: u8, offset: usize, buf: &mut [u8]) -> Result<(), StorageError> {
        (**self).read(slot, offset, buf)
    }
}

/// Two slots of `N` bytes in RAM: the storage of a device whose parameters live in battery-backed or
/// retained RAM, and a test double for any other (what a test writes can be read back with
/// [`slot`](Self::slot)). A slot other than 0 or 1 is an [`Io`](StorageError::Io) error, an access past
/// `N` bytes [`TooLarge`](StorageError::TooLarge); nothing panics.
///
/// ```
/// use canopen_core::storage::{RamStorage, Storage, StorageError};
///
/// let mut ram = RamStorage::<64>::new();
/// ram.write(1, 10, &[1, 2]).unwrap();
/// let mut b = [0u8; 2];
/// ram.read(1, 10, &mut b).unwrap();
/// assert_eq!(b, [1, 2]);
/// assert_eq!(&ram.slot(1)[9..13], &[0xFF, 1, 2, 0xFF]); // erased bytes read 0xFF
/// assert_eq!(ram.write(1, 63, &[1, 2]), Err(StorageError::TooLarge));
/// assert_eq!(ram.erase(2), Err(StorageError::Io));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RamStorage<const N: usize> {
    slots: [[u8; N]; 2],
}

impl<const N: usize> RamStorage<N> {
    /// Both slots erased (every byte 0xFF, as erased flash reads).
    ///
    /// ```
    /// use canopen_core::storage::RamStorage;
    /// assert!(RamStorage::<8>::new().slot(0).iter().all(|&b| b == 0xFF));
    /// ```
    pub const fn new() -> Self {
        RamStorage { slots: [[0xFF; N]; 2] }
    }

    /// The bytes of `slot` (0 or 1; any other reads as slot 1).
    ///
    /// ```
    /// use canopen_core::storage::RamStorage;
    /// assert_eq!(RamStorage::<4>::new().slot(0).len(), 4);
    /// ```
    pub fn slot(&self, slot: u8) -> &[u8; N] {
        &self.slots[usize::from(slot.min(1))]
    }

    fn slot_mut(&mut self, slot: u8) -> Result<&mut [u8; N], StorageError> {
        self.slots.get_mut(usize::from(slot)).ok_or(StorageError::Io)
    }
}

impl<const N: usize> Default for RamStorage<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> Storage for RamStorage<N> {
    fn capacity(&self) -> usize {
        N
    }
    fn erase(&mut self, slot: u8) -> Result<(), StorageError> {
        self.slot_mut(slot)?.fill(0xFF);
        Ok(())
    }
    fn write(&mut self, slot: u8, offset: usize, data: &[u8]) -> Result<(), StorageError> {
        let end = offset.checked_add(data.len()).ok_or(StorageError::TooLarge)?;
        let s = self.slot_mut(slot)?;
        s.get_mut(offset..end).ok_or(StorageError::TooLarge)?.copy_from_slice(data);
        Ok(())
    }
    fn read(&mut self, slot: u8, offset: usize, buf: &mut [u8]) -> Result<(), StorageError> {
        let end = offset.checked_add(buf.len()).ok_or(StorageError::TooLarge)?;
        let s = self.slots.get(usize::from(slot)).ok_or(StorageError::Io)?;
        buf.copy_from_slice(s.get(offset..end).ok_or(StorageError::TooLarge)?);
        Ok(())
    }
}

/// Parameter groups of 1010h/1011h (STORE-02, STORE-07).
///
/// ```
/// use canopen_core::storage::Groups;
/// assert_eq!(Groups::from_sub(1), Some(Groups::ALL));
/// assert_eq!(Groups::from_sub(4), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Groups(u8);

impl Groups {
    /// Communication parameters (1000h–1FFFh), sub 02h.
    pub const COMM: Groups = Groups(1);
    /// Application parameters (2000h–9FFFh), sub 03h.
    pub const APP: Groups = Groups(2);
    /// Everything, sub 01h.
    pub const ALL: Groups = Groups(3);
    /// Nothing.
    pub const NONE: Groups = Groups(0);

    /// The group of a 1010h/1011h sub-index.
    pub const fn from_sub(sub: u8) -> Option<Groups> {
        match sub {
            1 => Some(Self::ALL),
            2 => Some(Self::COMM),
            3 => Some(Self::APP),
            _ => None,
        }
    }

    /// Whether every group of `other` is in `self`.
    pub const fn contains(self, other: Groups) -> bool {
        self.0 & other.0 == other.0
    }

    const fn has_comm(self) -> bool {
        self.0 & 1 != 0
    }

    const fn has_app(self) -> bool {
        self.0 & 2 != 0
    }
}

const MAGIC: u32 = 0x5253_4F43; // "COSR"
/// Version of the record format.
pub const FORMAT_VERSION: u8 = 1;
/// Header: magic u32, version u8, groups u8, reserved u16, sequence u32, payload length u32, CRC-32 u32.
pub const HEADER_LEN: usize = 20;

/// CRC-32/ISO-HDLC (the CRC of zip and Ethernet: reflected polynomial EDB8 8320h, initial value and final
/// XOR FFFF FFFFh), the parameter record's check, a nibble at a time from a 16-entry table: a record is a
/// few hundred bytes, hashed once per save or power-on, so no 1 KB byte table. About 90 bytes of Thumb code
/// and the 64-byte table, where the `crc` crate's generic bitwise digest linked 330 bytes of code
/// (footprint.sh: node+store). `canopen-embassy` checks its LSS record with it too.
///
/// ```
/// use canopen_core::storage::Crc32;
/// let mut c = Crc32::new();
/// c.update(b"1234");
/// c.update(b"56789");
/// assert_eq!(c.finish(), 0xCBF4_3926); // the check value of CRC-32/ISO-HDLC
/// assert_eq!(Crc32::checksum(b"123456789"), 0xCBF4_3926);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Crc32(u32);

/// The reflected CRC-32 of each 4-bit value: [`Crc32::update`] takes a byte in two lookups (64 bytes of
/// table; a byte-wise table would be 1 KB).
const CRC32_NIBBLE: [u32; 16] = {
    let mut t = [0u32; 16];
    let mut i = 0;
    while i < 16 {
        let mut c = i as u32;
        let mut k = 0;
        while k < 4 {
            c = (c >> 1) ^ (0xEDB8_8320 & (c & 1).wrapping_neg());
            k += 1;
        }
        t[i] = c;
        i += 1;
    }
    t
};

impl Crc32 {
    /// Nothing hashed yet.
    ///
    /// ```
    /// use canopen_core::storage::Crc32;
    /// assert_eq!(Crc32::new().finish(), 0);
    /// ```
    pub const fn new() -> Self {
        Crc32(u32::MAX)
    }

    /// Hashes `bytes` after what was hashed before.
    ///
    /// ```
    /// use canopen_core::storage::Crc32;
    /// let mut c = Crc32::new();
    /// c.update(&[]);
    /// assert_eq!(c, Crc32::new());
    /// ```
    #[inline(never)] // one copy: the record is hashed from four places
    pub fn update(&mut self, bytes: &[u8]) {
        let mut c = self.0;
        for &b in bytes {
            c = (c >> 4) ^ CRC32_NIBBLE[((c ^ u32::from(b)) & 0xF) as usize];
            c = (c >> 4) ^ CRC32_NIBBLE[((c ^ u32::from(b >> 4)) & 0xF) as usize];
        }
        self.0 = c;
    }

    /// The CRC of everything hashed.
    ///
    /// ```
    /// use canopen_core::storage::Crc32;
    /// assert_eq!(Crc32::checksum(b"a"), 0xE8B7_BE43);
    /// ```
    pub const fn finish(self) -> u32 {
        !self.0
    }

    /// The CRC of `bytes`.
    ///
    /// ```
    /// use canopen_core::storage::Crc32;
    /// assert_eq!(Crc32::checksum(&[]), 0);
    /// ```
    pub fn checksum(bytes: &[u8]) -> u32 {
        let mut c = Crc32::new();
        c.update(bytes);
        c.finish()
    }
}

impl Default for Crc32 {
    fn default() -> Self {
        Crc32::new()
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Header {
    groups: Groups,
    seq: u32,
    len: u32,
    crc: u32,
}

impl Header {
    fn emit(&self) -> [u8; HEADER_LEN] {
        let mut h = [0u8; HEADER_LEN];
        h[0..4].copy_from_slice(&MAGIC.to_le_bytes());
        h[4] = FORMAT_VERSION;
        h[5] = self.groups.0;
        h[8..12].copy_from_slice(&self.seq.to_le_bytes());
        h[12..16].copy_from_slice(&self.len.to_le_bytes());
        h[16..20].copy_from_slice(&self.crc.to_le_bytes());
        h
    }

    fn parse(h: &[u8; HEADER_LEN]) -> Option<Header> {
        let u32_at = |i: usize| u32::from_le_bytes([h[i], h[i + 1], h[i + 2], h[i + 3]]);
        if u32_at(0) != MAGIC || h[4] != FORMAT_VERSION || h[5] > 3 {
            return None;
        }
        Some(Header { groups: Groups(h[5]), seq: u32_at(8), len: u32_at(12), crc: u32_at(16) })
    }

    /// The CRC covers what the header says about the payload and the payload.
    fn digest_start(&self) -> Crc32 {
        let mut d = Crc32::new();
        d.update(&[FORMAT_VERSION, self.groups.0]);
        d.update(&self.seq.to_le_bytes());
        d.update(&self.len.to_le_bytes());
        d
    }
}

/// Reads a slot's header and verifies its CRC over the payload; `None` when the slot holds no valid record.
fn valid_header<S: Storage + ?Sized>(st: &mut S, slot: u8) -> Result<Option<Header>, StorageError> {
    let mut raw = [0u8; HEADER_LEN];
    if st.capacity() < HEADER_LEN {
        return Ok(None);
    }
    st.read(slot, 0, &mut raw)?;
    let Some(h) = Header::parse(&raw) else {
        return Ok(None);
    };
    let len = h.len as usize;
    if len > st.capacity() - HEADER_LEN {
        return Ok(None);
    }
    let mut d = h.digest_start();
    let mut chunk = [0u8; 64];
    let mut off = 0;
    while off < len {
        let n = (len - off).min(chunk.len());
        st.read(slot, HEADER_LEN + off, &mut chunk[..n])?;
        d.update(&chunk[..n]);
        off += n;
    }
    Ok((d.finish() == h.crc).then_some(h))
}

/// What a slot holds, as [`slot_status`] finds it.
///
/// ```
/// use canopen_core::storage::SlotStatus;
/// assert_ne!(SlotStatus::Valid, SlotStatus::BadCrc);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlotStatus {
    /// Never written or erased: the header bytes are all FFh.
    Erased,
    /// A record whose header and CRC-32 check out.
    Valid,
    /// The header is not a record header of this format (magic, version, group flags or length wrong).
    BadFormat,
    /// A record header whose CRC-32 does not match the payload.
    BadCrc,
}

/// Checks one slot (0 or 1) without loading anything: an application calls it at start-up to report a
/// damaged store rather than silently starting on defaults (a record torn by a power loss during a save
/// also shows as [`SlotStatus::BadCrc`] or [`SlotStatus::BadFormat`]; [`load`] then uses the other slot).
///
/// ```
/// use canopen_core::storage::{slot_status, SlotStatus, Storage, StorageError};
/// struct Ram([u8; 64]);
/// impl Storage for Ram {
///     fn capacity(&self) -> usize { 64 }
///     fn erase(&mut self, _: u8) -> Result<(), StorageError> { self.0.fill(0xFF); Ok(()) }
///     fn write(&mut self, _: u8, o: usize, d: &[u8]) -> Result<(), StorageError> {
///         self.0[o..o + d.len()].copy_from_slice(d);
///         Ok(())
///     }
///     fn read(&mut self, _: u8, o: usize, b: &mut [u8]) -> Result<(), StorageError> {
///         b.copy_from_slice(&self.0[o..o + b.len()]);
///         Ok(())
///     }
/// }
/// let mut ram = Ram([0xFF; 64]);
/// assert_eq!(slot_status(&mut ram, 0), Ok(SlotStatus::Erased));
/// ram.write(0, 0, b"garbage").unwrap();
/// assert_eq!(slot_status(&mut ram, 0), Ok(SlotStatus::BadFormat));
/// ```
pub fn slot_status<S: Storage + ?Sized>(st: &mut S, slot: u8) -> Result<SlotStatus, StorageError> {
    if st.capacity() < HEADER_LEN {
        return Ok(SlotStatus::Erased);
    }
    let mut raw = [0u8; HEADER_LEN];
    st.read(slot, 0, &mut raw)?;
    if raw.iter().all(|&b| b == 0xFF) {
        return Ok(SlotStatus::Erased);
    }
    match Header::parse(&raw) {
        Some(h) if h.len as usize <= st.capacity() - HEADER_LEN => {}
        _ => return Ok(SlotStatus::BadFormat),
    }
    Ok(if valid_header(st, slot)?.is_some() { SlotStatus::Valid } else { SlotStatus::BadCrc })
}

/// The slot holding the newest valid record and its header (serial-number comparison of the sequences).
fn newest<S: Storage + ?Sized>(st: &mut S) -> Result<Option<(u8, Header)>, StorageError> {
    let a = valid_header(st, 0)?;
    let b = valid_header(st, 1)?;
    Ok(match (a, b) {
        (Some(a), Some(b)) => {
            if (b.seq.wrapping_sub(a.seq) as i32) > 0 {
                Some((1, b))
            } else {
                Some((0, a))
            }
        }
        (Some(a), None) => Some((0, a)),
        (None, Some(b)) => Some((1, b)),
        (None, None) => None,
    })
}

/// Items of one stored record, read one by one from the storage (which each call is given, so that a
/// record can be read while another is written).
struct Items {
    slot: u8,
    off: usize,
    end: usize,
}

impl Items {
    /// The items of the record `h` in `slot`.
    fn of(slot: u8, h: &Header) -> Items {
        Items { slot, off: 0, end: h.len as usize }
    }

    /// The next item: (index, sub, value length); the value is in `buf[..len]`.
    fn next<S: Storage + ?Sized>(
        &mut self,
        st: &mut S,
        buf: &mut [u8; 255],
    ) -> Result<Option<(u16, u8, usize)>, StorageError> {
        if self.off + 4 > self.end {
            return Ok(None);
        }
        let mut h = [0u8; 4];
        st.read(self.slot, HEADER_LEN + self.off, &mut h)?;
        let len = usize::from(h[3]);
        if self.off + 4 + len > self.end {
            return Ok(None);
        }
        st.read(self.slot, HEADER_LEN + self.off + 4, &mut buf[..len])?;
        self.off += 4 + len;
        Ok(Some((u16::from_le_bytes([h[0], h[1]]), h[2], len)))
    }
}

/// Writes a record's payload item by item, computing the CRC on the way.
struct Writer<'s, S: Storage + ?Sized> {
    st: &'s mut S,
    slot: u8,
    len: usize,
    crc_data: CrcBuf,
}

/// The payload CRC cannot be computed before the length is known, so the payload is hashed twice: the
/// first pass counts, the second writes. `CrcBuf` hashes in the second pass only.
struct CrcBuf(Option<Crc32>);

impl<S: Storage + ?Sized> Writer<'_, S> {
    fn item(&mut self, index: u16, sub: u8, value: &[u8]) -> Result<(), StorageError> {
        let Ok(n) = u8::try_from(value.len()) else {
            return Ok(());
        };
        let i = index.to_le_bytes();
        let head = [i[0], i[1], sub, n];
        for part in [&head[..], value] {
            if HEADER_LEN + self.len + part.len() > self.st.capacity() {
                return Err(StorageError::TooLarge);
            }
            if let Some(d) = &mut self.crc_data.0 {
                d.update(part);
                self.st.write(self.slot, HEADER_LEN + self.len, part)?;
            }
            self.len += part.len();
        }
        Ok(())
    }
}

/// Every storable entry of `od` with index in `range`: readable and writable, not DOMAIN, at most 255 bytes.
/// 1010h/1011h (commands), 1003h (history) and 1013h (a clock) are never stored; 1028h entries that hold
/// their default are left out (the 127 of them would take 1,016 bytes of every record, and a load sets
/// every entry to its default before it writes the stored ones back).
fn for_each_storable<D: ObjectDictionary + OdDescribe + ?Sized>(
    od: &D,
    range: core::ops::RangeInclusive<u16>,
    mut f: impl FnMut(u16, u8, &[u8]) -> Result<(), StorageError>,
) -> Result<(), StorageError> {
    let mut buf = [0u8; 255];
    for n in 0..od.object_count() {
        // The index alone and the SDO path's `info`: the names and defaults of `entry` stay out of a
        // firmware that stores (footprint.sh: node+store).
        let Some(index) = od.object_index(n) else { continue };
        let clock = cfg!(feature = "high-res-time") && index == 0x1013;
        if !range.contains(&index) || matches!(index, 0x1003 | 0x1010 | 0x1011) || clock {
            continue;
        }
        for sub in 0..=255u8 {
            let Ok(e) = od.info(index, sub) else { continue };
            if !(e.access.writable() && e.access.readable()) || e.data_type == crate::od::DataType::Domain {
                continue;
            }
            if let Ok(len) = od.read(index, sub, 0, &mut buf) {
                #[cfg(feature = "emcy-consumer")]
                if index == 0x1028 && od.entry(index, sub).is_some_and(|e| holds_default(&e, &buf[..len])) {
                    continue; // a load leaves it at its default anyway
                }
                f(index, sub, &buf[..len])?;
            }
            if sub == 255 {
                break;
            }
        }
    }
    Ok(())
}

/// Whether `value` (little-endian, at most 8 bytes) is the entry's numeric default.
#[cfg(feature = "emcy-consumer")]
fn holds_default(e: &crate::od::EntryDesc, value: &[u8]) -> bool {
    let v = value.iter().rev().fold(0u64, |v, &b| v << 8 | u64::from(b));
    value.len() <= 8 && e.default == Some(crate::od::Value::Uint(v))
}

/// Writes one stored value back through the dictionary (whole for fixed sizes, streamed otherwise).
/// Refusals are ignored: the entry keeps its default.
pub fn write_back<D: ObjectDictionary + ?Sized>(od: &mut D, index: u16, sub: u8, value: &[u8]) {
    let Ok(info) = od.info(index, sub) else { return };
    if info.data_type.size().is_some() {
        let _ = od.write(index, sub, value);
    } else if od.begin_write(index, sub, Some(value.len())).is_ok()
        && od.write_chunk(index, sub, 0, value).and_then(|()| od.end_write(index, sub, value.len())).is_err()
    {
        od.abort_write(index, sub);
    }
}

/// Saves the groups `groups` of `comm` and `app` (1010h, STORE-03/04): the other group is copied from the
/// newest record, so that saving one group keeps the other's stored values.
///
/// ```
/// # use canopen_core::Sizes;
/// # use canopen_core::storage::*;
/// # use canopen_core::{profile::{CommProfile, NodeConfig}, node::NoApplication};
/// # struct Ram([[u8; 512]; 2]);
/// # impl Storage for Ram {
/// #     fn capacity(&self) -> usize { 512 }
/// #     fn erase(&mut self, s: u8) -> Result<(), StorageError> { self.0[usize::from(s)].fill(0xFF); Ok(()) }
/// #     fn write(&mut self, s: u8, o: usize, d: &[u8]) -> Result<(), StorageError> { self.0[usize::from(s)][o..o + d.len()].copy_from_slice(d); Ok(()) }
/// #     fn read(&mut self, s: u8, o: usize, b: &mut [u8]) -> Result<(), StorageError> { b.copy_from_slice(&self.0[usize::from(s)][o..o + b.len()]); Ok(()) }
/// # }
/// let mut ram = Ram([[0xFF; 512]; 2]);
/// let mut od: CommProfile<Sizes<0, 16, 16, 0, 0>> = CommProfile::new(NodeConfig::DEFAULT);
/// od.params.heartbeat_time_ms = 250;
/// save(&mut ram, Groups::ALL, &od, &NoApplication).unwrap();
/// od.reset_communication();
/// assert_eq!(od.params.heartbeat_time_ms, 0);
/// load(&mut ram, Groups::COMM, &mut od).unwrap();
/// assert_eq!(od.params.heartbeat_time_ms, 250);
/// ```
pub fn save<S, C, A>(st: &mut S, groups: Groups, comm: &C, app: &A) -> Result<(), StorageError>
where
    S: Storage + ?Sized,
    C: ObjectDictionary + OdDescribe + ?Sized,
    A: ObjectDictionary + OdDescribe + ?Sized,
{
    update(st, groups, Groups::NONE, 0, comm, app)
}

/// Writes a new record (the A/B rule of the module docs): the groups `fresh` from `comm` and `app`, the
/// newest record's other groups copied from it, except the groups `drop` and the items of index `skip`
/// (0: none). With nothing to write (nothing stored, nothing fresh) it writes nothing. [`save`] is
/// `fresh` alone, [`restore_defaults`] `drop` alone; the node does both through one instance (1010h and
/// 1011h: `node::dict`), so that a firmware links one copy of the record code.
pub(crate) fn update<S, C, A>(
    st: &mut S,
    fresh: Groups,
    drop: Groups,
    skip: u16,
    comm: &C,
    app: &A,
) -> Result<(), StorageError>
where
    S: Storage + ?Sized,
    C: ObjectDictionary + OdDescribe + ?Sized,
    A: ObjectDictionary + OdDescribe + ?Sized,
{
    if st.capacity() < HEADER_LEN {
        return Err(StorageError::Unsupported);
    }
    let old = newest(st)?;
    let target = match old {
        Some((slot, _)) => 1 - slot,
        None if fresh.0 == 0 => return Ok(()), // nothing stored: the defaults are what loads already
        None => 0,
    };
    let kept = Groups(old.map_or(0, |(_, h)| h.groups.0) & !drop.0);
    let stored = Groups(fresh.0 | kept.0);
    let seq = old.map_or(1, |(_, h)| h.seq.wrapping_add(1));
    // Pass 1 counts, pass 2 writes (the header, written last, needs length and CRC).
    let mut len = 0;
    for pass in 0..2 {
        if pass == 1 {
            st.erase(target)?;
        }
        let mut crc_data = CrcBuf(None);
        if pass == 1 {
            let h = Header { groups: stored, seq, len: len as u32, crc: 0 };
            crc_data = CrcBuf(Some(h.digest_start()));
        }
        let mut w = Writer { st: &mut *st, slot: target, len: 0, crc_data };
        write_group(&mut w, Groups::COMM, fresh, kept, old, comm, 0x1000..=0x1FFF, skip)?;
        write_group(&mut w, Groups::APP, fresh, kept, old, app, 0x2000..=0xFFFF, skip)?;
        len = w.len;
        if pass == 1 {
            let crc = w.crc_data.0.map_or(0, |d| d.finish());
            let h = Header { groups: stored, seq, len: len as u32, crc };
            st.write(target, 0, &h.emit())?;
        }
    }
    Ok(())
}

/// Writes `group`: from `od` when it is in `fresh`, else copied from the `old` record when `kept` has it,
/// without the items of index `skip` (0: none).
#[allow(clippy::too_many_arguments)]
fn write_group<S, D>(
    w: &mut Writer<'_, S>,
    group: Groups,
    fresh: Groups,
    kept: Groups,
    old: Option<(u8, Header)>,
    od: &D,
    range: core::ops::RangeInclusive<u16>,
    skip: u16,
) -> Result<(), StorageError>
where
    S: Storage + ?Sized,
    D: ObjectDictionary + OdDescribe + ?Sized,
{
    if fresh.contains(group) {
        return for_each_storable(od, range, |i, s, v| w.item(i, s, v));
    }
    let Some((slot, h)) = old.filter(|_| kept.contains(group)) else {
        return Ok(());
    };
    // Copy this group's items from the old record.
    copy_kept(w, Items::of(slot, &h), range, skip)
}

/// The items of `items` in `range` (without those of index `skip`) copied into the record `w` writes.
/// Not generic over the dictionary: one copy for both groups.
fn copy_kept<S: Storage + ?Sized>(
    w: &mut Writer<'_, S>,
    mut items: Items,
    range: core::ops::RangeInclusive<u16>,
    skip: u16,
) -> Result<(), StorageError> {
    let mut buf = [0u8; 255];
    while let Some((index, sub, n)) = items.next(&mut *w.st, &mut buf)? {
        // `skip` is only ever set with verify-config (`forget`): no compare in a build without it.
        if range.contains(&index) && (!cfg!(feature = "verify-config") || index != skip) {
            w.item(index, sub, &buf[..n])?;
        }
    }
    Ok(())
}

/// Loads the stored values of the groups in `groups` whose index lies in `od`'s range into `od`
/// (NMT-06: called by reset application / reset communication after the defaults were set). Returns
/// whether a valid record was found.
pub fn load<S, D>(st: &mut S, groups: Groups, od: &mut D) -> Result<bool, StorageError>
where
    S: Storage + ?Sized,
    D: ObjectDictionary + ?Sized,
{
    if st.capacity() < HEADER_LEN {
        return Ok(false);
    }
    let Some((slot, h)) = newest(st)? else {
        return Ok(false);
    };
    let mut items = Items::of(slot, &h);
    let mut buf = [0u8; 255];
    while let Some((index, sub, len)) = items.next(st, &mut buf)? {
        let comm = is_comm(index);
        let wanted =
            if comm { groups.has_comm() && h.groups.has_comm() } else { groups.has_app() && h.groups.has_app() };
        if wanted {
            write_back(od, index, sub, &buf[..len]);
        }
    }
    Ok(true)
}

/// Removes the groups `groups` from the stored record (1011h "load", STORE-08..10): their defaults come
/// back at the next reset. Writes a new record (same A/B rule as [`save`]), so it is power-safe too.
pub fn restore_defaults<S: Storage + ?Sized>(st: &mut S, groups: Groups) -> Result<(), StorageError> {
    update(st, Groups::NONE, groups, 0, &NoApplication, &NoApplication)
}

/// Removes the stored values of object `index` from the record (1020h verify configuration once another
/// command changed the boot-up configuration, STORE-12); same A/B rule as [`save`].
#[cfg(feature = "verify-config")]
pub(crate) fn forget<S: Storage + ?Sized>(st: &mut S, index: u16) -> Result<(), StorageError> {
    update(st, Groups::NONE, Groups::NONE, index, &NoApplication, &NoApplication)
}

/// Maps a storage failure onto the SDO abort of 1010h/1011h (STORE-04, STORE-09).
///
/// ```
/// use canopen_core::{storage::{abort_of, StorageError}, od::AbortCode};
/// assert_eq!(abort_of(StorageError::Io), AbortCode::HardwareError);
/// ```
pub const fn abort_of(_e: StorageError) -> AbortCode {
    AbortCode::HardwareError
}
