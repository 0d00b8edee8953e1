//! The object dictionary contract between the services (SDO, PDO, store/restore, EDS) and whatever holds
//! the values: the `#[derive]`-generated application dictionary and the core's communication profile.
//!
//! Covers the shape of OD-01 (16-bit index, 8-bit sub-index), OD-03/OD-04 (VAR at sub 0,
//! ARRAY/RECORD count at sub 0), OD-06 ([`ObjectCode`]), OD-08/OD-09 ([`Access`], with `rwr`/`rww` as rw plus
//! a PDO direction hint), OD-16 (access errors map to fixed [`AbortCode`]s) and DT-17 ([`DataType`] indices).
//!
//! The trait is byte-oriented and offset-based so that SDO can stream a large value (a string, a DOMAIN
//! holding a firmware image) segment by segment without a buffer of the value's size.
//!
//! Submodules: value types and their encodings (`value`: DT-01..DT-08, DT-13, DT-14; `string`: DT-10..DT-12),
//! [`Domain`] streaming (DT-15),
//! the `const` entry tables and their binary-search [`lookup`] (`table`), the [`Merged`] dictionary (two
//! dictionaries dispatched by index range: the profile's and the application's) and the per-object
//! sections of the CiA 306 EDS ([`eds`]; the file around them is `profile::eds`). PDO access goes through [`PdoHandle`]s: resolved once when a mapping is
//! written, then used without any table search.

pub mod data;
mod domain;
pub mod eds;
mod merged;
mod string;
mod table;
mod value;

pub use crate::abort::AbortCode;
pub use domain::{Domain, DomainBuf};
#[cfg(feature = "program-download")]
pub(crate) use merged::is_program;
pub(crate) use merged::{is_comm, is_comm_for};
pub use merged::{merge_nth, merged_position, Merged};
pub use string::{OctetString, UnicodeString, VisibleString};
pub use table::{count_entry, is_sorted, lookup, lookup_key, scan_key, EntryDesc, ObjectDesc, OdDescribe, Value};
pub use value::{
    check_len, check_limits, check_range, copy_at, OdValue, TimeDifference, TimeOfDay, I24, I40, I48, I56, U24, U40,
    U48, U56,
};

/// CiA 301 basic data types with their static type index (DT-17, 000 §7.4.7.1 Table 44).
///
/// ```
/// use canopen_core::od::DataType;
/// assert_eq!(DataType::Unsigned32 as u16, 0x0007);
/// assert_eq!(DataType::Unsigned32.size(), Some(4));
/// assert_eq!(DataType::TimeOfDay.size(), Some(6));
/// assert_eq!(DataType::VisibleString.size(), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum DataType {
    /// 0001h BOOLEAN (one byte on SDO: 0 or 1).
    Boolean = 0x0001,
    /// 0002h INTEGER8.
    Integer8 = 0x0002,
    /// 0003h INTEGER16.
    Integer16 = 0x0003,
    /// 0004h INTEGER32.
    Integer32 = 0x0004,
    /// 0005h UNSIGNED8.
    Unsigned8 = 0x0005,
    /// 0006h UNSIGNED16.
    Unsigned16 = 0x0006,
    /// 0007h UNSIGNED32.
    Unsigned32 = 0x0007,
    /// 0008h REAL32.
    Real32 = 0x0008,
    /// 0009h VISIBLE_STRING.
    VisibleString = 0x0009,
    /// 000Ah OCTET_STRING.
    OctetString = 0x000A,
    /// 000Bh UNICODE_STRING.
    UnicodeString = 0x000B,
    /// 000Ch TIME_OF_DAY.
    TimeOfDay = 0x000C,
    /// 000Dh TIME_DIFFERENCE.
    TimeDifference = 0x000D,
    /// 000Fh DOMAIN.
    Domain = 0x000F,
    /// 0010h INTEGER24.
    Integer24 = 0x0010,
    /// 0011h REAL64.
    Real64 = 0x0011,
    /// 0012h INTEGER40.
    Integer40 = 0x0012,
    /// 0013h INTEGER48.
    Integer48 = 0x0013,
    /// 0014h INTEGER56.
    Integer56 = 0x0014,
    /// 0015h INTEGER64.
    Integer64 = 0x0015,
    /// 0016h UNSIGNED24.
    Unsigned24 = 0x0016,
    /// 0018h UNSIGNED40.
    Unsigned40 = 0x0018,
    /// 0019h UNSIGNED48.
    Unsigned48 = 0x0019,
    /// 001Ah UNSIGNED56.
    Unsigned56 = 0x001A,
    /// 001Bh UNSIGNED64.
    Unsigned64 = 0x001B,
}

impl DataType {
    /// The encoded size in bytes for fixed-size types, `None` for strings and DOMAIN.
    ///
    /// ```
    /// # use canopen_core::od::DataType;
    /// assert_eq!(DataType::Integer24.size(), Some(3));
    /// assert_eq!(DataType::Domain.size(), None);
    /// ```
    ///
    /// A load from a 32-byte table indexed by the type code (0 for no fixed size): smaller than the match's
    /// jump table.
    #[inline(never)]
    pub const fn size(self) -> Option<usize> {
        match SIZES[self as usize & 0x1F] {
            0 => None,
            n => Some(n as usize),
        }
    }

    /// [`size`](Self::size) as a number, 0 for strings and DOMAIN, inline: what the data dictionary's
    /// paths ([`data`]) test per access.
    ///
    /// ```
    /// # use canopen_core::od::DataType;
    /// assert_eq!(DataType::Unsigned16.fixed_size(), 2);
    /// assert_eq!(DataType::OctetString.fixed_size(), 0);
    /// ```
    #[inline]
    pub const fn fixed_size(self) -> usize {
        SIZES[self as usize & 0x1F] as usize
    }
}

/// [`DataType::size`] by type code (DT-17): 0 for the strings, DOMAIN and the codes that name no type.
const SIZES: [u8; 32] = {
    use DataType::*;
    let mut t = [0u8; 32];
    let fixed: [(DataType, u8); 21] = [
        (Boolean, 1),
        (Integer8, 1),
        (Unsigned8, 1),
        (Integer16, 2),
        (Unsigned16, 2),
        (Integer24, 3),
        (Unsigned24, 3),
        (Integer32, 4),
        (Unsigned32, 4),
        (Real32, 4),
        (Integer40, 5),
        (Unsigned40, 5),
        (Integer48, 6),
        (Unsigned48, 6),
        (TimeOfDay, 6),
        (TimeDifference, 6),
        (Integer56, 7),
        (Unsigned56, 7),
        (Integer64, 8),
        (Unsigned64, 8),
        (Real64, 8),
    ];
    let mut i = 0;
    while i < fixed.len() {
        t[fixed[i].0 as usize] = fixed[i].1;
        i += 1;
    }
    t
};

/// Access type of a sub-entry (OD-08, OD-09).
///
/// `Rwr` and `Rww` are CiA 306 refinements: read-write on SDO, plus the hint that the entry is an input
/// (mapped to TPDOs) or an output (mapped to RPDOs).
///
/// ```
/// use canopen_core::od::Access;
/// assert!(Access::Ro.readable() && !Access::Ro.writable());
/// assert!(Access::Rww.readable() && Access::Rww.writable());
/// assert!(!Access::Wo.readable());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Access {
    /// Read only; the value may change at run time.
    Ro,
    /// Write only.
    Wo,
    /// Read and write.
    Rw,
    /// Read and write; an input (TPDO direction).
    Rwr,
    /// Read and write; an output (RPDO direction).
    Rww,
    /// Read only; the value changes only in NMT Initialization.
    Const,
}

impl Access {
    /// Whether SDO may read it.
    pub const fn readable(self) -> bool {
        !matches!(self, Access::Wo)
    }

    /// Whether SDO may write it.
    pub const fn writable(self) -> bool {
        matches!(self, Access::Wo | Access::Rw | Access::Rwr | Access::Rww)
    }
}

/// Where a sub-entry may be mapped (OD-11: optional / TPDO only / RPDO only / no).
///
/// ```
/// use canopen_core::od::PdoMapping;
/// assert!(PdoMapping::Both.tpdo() && PdoMapping::Both.rpdo());
/// assert!(!PdoMapping::No.tpdo());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PdoMapping {
    /// Not mappable.
    No,
    /// Mappable into TPDOs only.
    Tpdo,
    /// Mappable into RPDOs only.
    Rpdo,
    /// Mappable both ways.
    Both,
}

impl PdoMapping {
    /// Mappable into a TPDO.
    pub const fn tpdo(self) -> bool {
        matches!(self, PdoMapping::Tpdo | PdoMapping::Both)
    }

    /// Mappable into an RPDO.
    pub const fn rpdo(self) -> bool {
        matches!(self, PdoMapping::Rpdo | PdoMapping::Both)
    }
}

/// Object codes (OD-06, 000 §7.4.3 Table 42).
///
/// ```
/// use canopen_core::od::ObjectCode;
/// assert_eq!(ObjectCode::Record as u8, 9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum ObjectCode {
    /// 00h NULL.
    Null = 0x00,
    /// 02h DOMAIN.
    Domain = 0x02,
    /// 05h DEFTYPE.
    DefType = 0x05,
    /// 06h DEFSTRUCT.
    DefStruct = 0x06,
    /// 07h VAR.
    Var = 0x07,
    /// 08h ARRAY.
    Array = 0x08,
    /// 09h RECORD.
    Record = 0x09,
}

/// What SDO and PDO need to know about one sub-entry before touching its value.
///
/// ```
/// use canopen_core::od::{Access, DataType, PdoMapping, SubInfo};
/// let info = SubInfo { data_type: DataType::Unsigned16, access: Access::Rw, pdo: PdoMapping::No, size: 2 };
/// assert_eq!(info.size, 2);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SubInfo {
    /// The data type.
    pub data_type: DataType,
    /// The access type.
    pub access: Access,
    /// Where it may be mapped.
    pub pdo: PdoMapping,
    /// The current size of the value in bytes (the fixed size, or the current length of a string/DOMAIN).
    pub size: usize,
}

/// Read and write access to an object dictionary by (index, sub-index).
///
/// Contract (the SDO server, PDO mapping and store/restore rely on it):
/// - [`info`](Self::info) fails with [`AbortCode::ObjectDoesNotExist`] for an unknown index and
///   [`AbortCode::SubIndexDoesNotExist`] for an unknown sub-index of an existing index (OD-16).
/// - [`read`](Self::read) copies bytes `offset..` of the current little-endian encoding into `buf` and
///   returns how many it copied (fewer than `buf.len()` only at the end of the value). It refuses a
///   write-only entry with [`AbortCode::ReadOfWriteOnly`].
/// - [`write`](Self::write) replaces a whole value at once: access (`WriteOfReadOnly`), length
///   (`LengthTooHigh`/`LengthTooLow`/`LengthMismatch`), limits (`ValueTooHigh`/`ValueTooLow`/`InvalidValue`) and
///   application hooks are checked before anything changes, so a refused write changes nothing.
/// - Values that are streamed (strings, OCTET_STRING, DOMAIN, anything longer than 8 bytes) are written with
///   [`begin_write`](Self::begin_write), [`write_chunk`](Self::write_chunk) in increasing offsets, and
///   [`end_write`](Self::end_write); a transfer that is abandoned calls [`abort_write`](Self::abort_write).
///   Fixed-size values (at most 8 bytes) are always written whole with `write`; the derive-generated
///   dictionaries answer `begin_write` on them with 0601 0000h. The derived dictionaries stage a streamed
///   string apart from its value ([`OdValue::end_stream`]) and store it at `end_write` after the same checks
///   as `write`, so an aborted or refused string download changes nothing. A DOMAIN streams into the
///   application's [`Domain`] as the bytes arrive: its content is the application's (DT-15), which decides
///   in [`Domain::abort_write`] what an abandoned transfer leaves.
/// - Every `Ok` from `write`/`end_write`/[`pdo_write`](Self::pdo_write) is an accepted change: the caller
///   (the node) reports it to the application as an event.
/// - PDO mapping resolves each mapped entry once with [`pdo_resolve`](Self::pdo_resolve) and then moves
///   process data with [`pdo_read`](Self::pdo_read)/[`pdo_write`](Self::pdo_write), which the
///   derive-generated dictionaries serve without any search. The defaults fall back to `read`/`write`.
///   A handle belongs to the dictionary whose `pdo_resolve` made it ([`Merged`] routes each handle to its
///   half by index): a derived dictionary trusts the slot of a handle it is given and does not look the
///   entry up again (a handle of another dictionary moves the bytes of whatever entry has that slot here,
///   or falls back to `read`/`write` when the slot is out of range; never a panic).
///
/// ```
/// use canopen_core::od::{AbortCode, Access, DataType, ObjectDictionary, PdoMapping, SubInfo};
///
/// /// A one-entry dictionary: 2000h:00 UNSIGNED16 rw.
/// struct One(u16);
/// impl ObjectDictionary for One {
///     fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
///         match (index, sub) {
///             (0x2000, 0) => Ok(SubInfo { data_type: DataType::Unsigned16, access: Access::Rw, pdo: PdoMapping::No, size: 2 }),
///             (0x2000, _) => Err(AbortCode::SubIndexDoesNotExist),
///             _ => Err(AbortCode::ObjectDoesNotExist),
///         }
///     }
///     fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
///         self.info(index, sub)?;
///         let bytes = self.0.to_le_bytes();
///         let src = bytes.get(offset..).unwrap_or(&[]);
///         let n = src.len().min(buf.len());
///         buf[..n].copy_from_slice(&src[..n]);
///         Ok(n)
///     }
///     fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
///         self.info(index, sub)?;
///         let v: [u8; 2] = data.try_into().map_err(|_| if data.len() > 2 { AbortCode::LengthTooHigh } else { AbortCode::LengthTooLow })?;
///         self.0 = u16::from_le_bytes(v);
///         Ok(())
///     }
/// }
///
/// let mut od = One(0);
/// od.write(0x2000, 0, &[0x34, 0x12]).unwrap();
/// let mut buf = [0u8; 4];
/// assert_eq!(od.read(0x2000, 0, 0, &mut buf), Ok(2));
/// assert_eq!(&buf[..2], &[0x34, 0x12]);
/// assert_eq!(od.write(0x2000, 0, &[1]), Err(AbortCode::LengthTooLow));
/// assert_eq!(od.info(0x2001, 0).err(), Some(AbortCode::ObjectDoesNotExist));
/// ```
pub trait ObjectDictionary {
    /// Whether this dictionary serves the program download objects 1F50h–1F57h (CiA 302-3) although they lie
    /// in the communication profile's range: [`Merged`] then routes them to it. Only
    /// `program::ProgramDownload` says so; for every other dictionary the routing test compiles away (the
    /// firmware of a device without program download does not grow).
    const SERVES_PROGRAM: bool = false;

    /// Whether [`begin_write`](Self::begin_write) can succeed for some entry: a string or DOMAIN written by a
    /// segmented or block download as a stream. `false` promises that it always fails, and the SDO server
    /// then builds no streaming path for this dictionary (`sdo::server`: 196 B less flash in the firmware
    /// example, `scripts/footprint.sh`). The default is `true`; the derive answers `false` for a struct
    /// without a writable string or DOMAIN, as do [`NoApplication`] and the communication profile.
    ///
    /// ```
    /// use canopen_core::od::{ObjectDictionary, NoApplication, Merged};
    /// assert!(!NoApplication::STREAMS);
    /// struct Custom; // a hand-written dictionary keeps the default
    /// # impl ObjectDictionary for Custom {
    /// #     fn info(&self, _: u16, _: u8) -> Result<canopen_core::od::SubInfo, canopen_core::od::AbortCode> { unimplemented!() }
    /// #     fn read(&self, _: u16, _: u8, _: usize, _: &mut [u8]) -> Result<usize, canopen_core::od::AbortCode> { unimplemented!() }
    /// #     fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), canopen_core::od::AbortCode> { unimplemented!() }
    /// # }
    /// assert!(Custom::STREAMS && <Merged<NoApplication, Custom>>::STREAMS);
    /// ```
    const STREAMS: bool = true;

    /// Whether an SDO upload of some readable entry is segmented: its value can be longer than 4 bytes or
    /// empty (a string, an OCTET_STRING, a DOMAIN, a 64-bit value). `false` promises that every readable
    /// entry has 1..=4 bytes, so that every upload is expedited (or a block upload), and the SDO server then
    /// builds no segmented-upload path for this dictionary (556 B of the minimal firmware example,
    /// `scripts/footprint.sh`). The default is `true`; the derive answers from its entries' types, the
    /// communication profile from its strings (feature `manufacturer-strings`), [`NoApplication`] `false`.
    ///
    /// ```
    /// use canopen_core::od::{ObjectDictionary, NoApplication};
    /// assert!(!NoApplication::SEGMENTED_UPLOADS);
    /// ```
    const SEGMENTED_UPLOADS: bool = true;

    /// Describes a sub-entry.
    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode>;

    /// Copies bytes `offset..offset + buf.len()` of the current value; returns the number copied.
    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode>;

    /// Replaces a whole value atomically (all checks first).
    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode>;

    /// Starts a streamed write; `size` is the announced total when the client gave one. Checks access and,
    /// where known, the length, so that a wrong size is refused before any data moves.
    fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        let _ = (index, sub, size);
        Err(AbortCode::UnsupportedAccess)
    }

    /// Writes one chunk of a streamed value at `offset`.
    fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        let _ = (index, sub, offset, data);
        Err(AbortCode::UnsupportedAccess)
    }

    /// Completes a streamed write of `total` bytes (final length and value checks, hooks).
    fn end_write(&mut self, index: u16, sub: u8, total: usize) -> Result<(), AbortCode> {
        let _ = (index, sub, total);
        Err(AbortCode::UnsupportedAccess)
    }

    /// A streamed write was abandoned (abort, timeout, new transfer).
    fn abort_write(&mut self, index: u16, sub: u8) {
        let _ = (index, sub);
    }

    /// Sets every value back to its default (power-on) value: NMT Reset Application (NMT-04) calls it for
    /// the application dictionary. The default does nothing, for dictionaries without defaults.
    fn restore_defaults(&mut self) {}

    /// Whether the node reports an SDO download of one of this dictionary's entries to the application
    /// ([`Event::ObjectWritten`](crate::event::Event::ObjectWritten)); the default is yes. A dictionary whose
    /// application reads its values when it needs them, or reacts in a write hook (the derive's
    /// `on_write`), answers no (the derive's struct-level `#[od(write_events = false)]`): then an expedited
    /// download is no event queued and polled, about 40 instructions less per download
    /// (`scripts/bench-node.sh`, x86-64). The communication profile's entries (1000h–1FFFh) are always
    /// reported.
    ///
    /// ```
    /// use canopen_core::od::{ObjectDictionary, NoApplication};
    /// assert!(NoApplication.write_events());
    /// ```
    fn write_events(&self) -> bool {
        true
    }

    /// The first step of an SDO upload with one lookup: the current size of a readable entry and, when that
    /// size is 1..=4 (an expedited upload), its bytes in `buf`; returns (size, bytes copied). Errors are
    /// those of [`info`](Self::info), then 0601 0001h for a write-only entry, then those of
    /// [`read`](Self::read). The provided method is `info` then `read`; the derived dictionaries and the
    /// communication profile override it so the entry is looked up once.
    fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> Result<(usize, usize), AbortCode> {
        let info = self.info(index, sub)?;
        if !info.access.readable() {
            return Err(AbortCode::ReadOfWriteOnly);
        }
        match buf.get_mut(..info.size) {
            Some(dst) if info.size > 0 => Ok((info.size, self.read(index, sub, 0, dst)?)),
            _ => Ok((info.size, 0)),
        }
    }

    /// An expedited SDO download with one lookup: `data` holds the frame's 4 data bytes, `len` the indicated
    /// size (`None`: not indicated, then the entry's fixed size up to 4 bytes, else 4; SDO-13). Errors are
    /// those of [`info`](Self::info), then 0601 0002h for a read-only entry, then those of
    /// [`write`](Self::write) (fixed-size entries) or of the streamed write. The provided method is
    /// [`expedited_download`]; the derived dictionaries override it so the entry is looked up once.
    fn write_expedited(&mut self, index: u16, sub: u8, data: &[u8; 4], len: Option<usize>) -> Result<(), AbortCode> {
        expedited_download(self, index, sub, data, len)
    }

    /// The dictionary's own position of an entry (the `slot` of [`PdoHandle`]), looked up once when an SDO
    /// transfer of several frames starts, so that each segment reads it with [`read_slot`](Self::read_slot)
    /// without a search. [`PdoHandle::NO_SLOT`] (the provided method) when the dictionary keeps no
    /// positions or has no such entry.
    fn slot(&self, index: u16, sub: u8) -> u16 {
        let _ = (index, sub);
        PdoHandle::NO_SLOT
    }

    /// [`read`](Self::read) of the entry at `slot`, which [`slot`](Self::slot) gave for `index`/`sub`, that
    /// fills `buf` exactly (an SDO upload segment): fewer bytes from `offset` are 0607 0010h. The derived
    /// dictionaries go straight to the entry (its access is checked again, not its key); the provided
    /// method, and any dictionary for [`PdoHandle::NO_SLOT`], is `read`. No count to return: the result fits
    /// a register, where a `Result<usize, _>` is returned through memory.
    fn read_slot(&self, index: u16, sub: u8, slot: u16, offset: usize, buf: &mut [u8]) -> Result<(), AbortCode> {
        let _ = slot;
        filled(self.read(index, sub, offset, buf)?, buf.len())
    }

    /// Resolves a mapping target once: checks it exists (0602 0000h / 0609 0011h), is mappable in `dir`
    /// (0604 0041h: PDO mapping attribute, readable for a TPDO, writable for an RPDO) and has a fixed size
    /// of at most 8 bytes. A derived dictionary also maps a string marked mappable with its capacity, and a
    /// DOMAIN with its size at the time, when 1 to 8 bytes (PDO-33).
    fn pdo_resolve(&self, index: u16, sub: u8, dir: PdoDir) -> Result<PdoHandle, AbortCode> {
        let info = self.info(index, sub)?;
        PdoHandle::check(index, sub, &info, dir, PdoHandle::NO_SLOT)
    }

    /// Copies the current value of a resolved entry into `buf` (its [`PdoHandle::size`] bytes). `handle`
    /// comes from this dictionary's [`pdo_resolve`](Self::pdo_resolve) (see the trait docs).
    fn pdo_read(&self, handle: &PdoHandle, buf: &mut [u8]) -> Result<usize, AbortCode> {
        self.read(handle.index, handle.sub, 0, buf)
    }

    /// Writes a resolved entry from received process data (limits and hooks apply as for `write`). `handle`
    /// comes from this dictionary's [`pdo_resolve`](Self::pdo_resolve) (see the trait docs).
    fn pdo_write(&mut self, handle: &PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
        self.write(handle.index, handle.sub, data)
    }
}

/// PDO direction of a mapping.
///
/// ```
/// use canopen_core::od::PdoDir;
/// assert_ne!(PdoDir::Tpdo, PdoDir::Rpdo);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PdoDir {
    /// Transmitted by this node (the entry is read).
    Tpdo,
    /// Received by this node (the entry is written).
    Rpdo,
}

/// `Ok` when a read of `n` bytes filled a buffer of `len` (see [`ObjectDictionary::read_slot`]), else
/// 0607 0010h.
///
/// ```
/// use canopen_core::od::{filled, AbortCode};
/// assert_eq!(filled(7, 7), Ok(()));
/// assert_eq!(filled(3, 7), Err(AbortCode::LengthMismatch));
/// ```
#[inline]
pub fn filled(n: usize, len: usize) -> Result<(), AbortCode> {
    if n == len {
        Ok(())
    } else {
        Err(AbortCode::LengthMismatch)
    }
}

/// The provided [`ObjectDictionary::write_expedited`]: `info`, the access check, then `write` for a
/// fixed-size entry or [`write_whole_stream`] for the others.
pub fn expedited_download<O: ObjectDictionary + ?Sized>(
    od: &mut O,
    index: u16,
    sub: u8,
    data: &[u8; 4],
    len: Option<usize>,
) -> Result<(), AbortCode> {
    let info = od.info(index, sub)?;
    if !info.access.writable() {
        return Err(AbortCode::WriteOfReadOnly);
    }
    let fixed = info.data_type.size();
    let n = len.unwrap_or(fixed.filter(|&n| n <= 4).unwrap_or(4));
    let bytes = data.get(..n).unwrap_or(data);
    match fixed {
        Some(_) => od.write(index, sub, bytes),
        None => write_whole_stream(od, index, sub, bytes),
    }
}

/// Writes a variable-size entry (string, DOMAIN) in one streamed step: `begin_write`, `write_chunk`,
/// `end_write`, and `abort_write` if a step after the first fails.
pub fn write_whole_stream<O: ObjectDictionary + ?Sized>(
    od: &mut O,
    index: u16,
    sub: u8,
    bytes: &[u8],
) -> Result<(), AbortCode> {
    od.begin_write(index, sub, Some(bytes.len()))?;
    let r = od.write_chunk(index, sub, 0, bytes).and_then(|()| od.end_write(index, sub, bytes.len()));
    if let Err(code) = r {
        od.abort_write(index, sub);
        return Err(code);
    }
    Ok(())
}

/// A resolved PDO mapping target: enough to move its bytes without searching the dictionary again.
///
/// ```
/// use canopen_core::od::{Access, DataType, PdoDir, PdoHandle, PdoMapping, SubInfo};
/// let info = SubInfo { data_type: DataType::Unsigned16, access: Access::Ro, pdo: PdoMapping::Tpdo, size: 2 };
/// let h = PdoHandle::check(0x6000, 1, &info, PdoDir::Tpdo, 3).unwrap();
/// assert_eq!((h.size, h.slot), (2, 3));
/// assert!(PdoHandle::check(0x6000, 1, &info, PdoDir::Rpdo, 3).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PdoHandle {
    /// Index of the mapped entry.
    pub index: u16,
    /// Sub-index of the mapped entry.
    pub sub: u8,
    /// Encoded size in bytes (1..=8).
    pub size: u8,
    /// Implementation-defined position (the derive uses the entry-table position, which its `pdo_read` and
    /// `pdo_write` trust; [`Self::NO_SLOT`] if unused).
    pub slot: u16,
}

impl PdoHandle {
    /// The slot value of a handle that carries no position.
    pub const NO_SLOT: u16 = u16::MAX;

    /// Builds a handle after checking mappability of `info` in direction `dir` (0604 0041h otherwise).
    pub fn check(index: u16, sub: u8, info: &SubInfo, dir: PdoDir, slot: u16) -> Result<PdoHandle, AbortCode> {
        let ok = match dir {
            PdoDir::Tpdo => info.pdo.tpdo() && info.access.readable(),
            PdoDir::Rpdo => info.pdo.rpdo() && info.access.writable(),
        };
        // 1 to 8 bytes: the inline table load, one unsigned compare (0, no fixed size, wraps to the top).
        let size = info.data_type.fixed_size();
        if !ok || size.wrapping_sub(1) >= 8 {
            return Err(AbortCode::NotMappable);
        }
        Ok(PdoHandle { index, sub, size: size as u8, slot })
    }
}

/// An empty dictionary: the application of a node that only uses the communication profile (also
/// re-exported as `node::NoApplication`).
///
/// ```
/// use canopen_core::od::{AbortCode, NoApplication, ObjectDictionary};
/// assert_eq!(NoApplication.info(0x2000, 0).err(), Some(AbortCode::ObjectDoesNotExist));
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NoApplication;

impl ObjectDictionary for NoApplication {
    const STREAMS: bool = false;
    const SEGMENTED_UPLOADS: bool = false;

    fn info(&self, _: u16, _: u8) -> Result<SubInfo, AbortCode> {
        Err(AbortCode::ObjectDoesNotExist)
    }
    fn read(&self, _: u16, _: u8, _: usize, _: &mut [u8]) -> Result<usize, AbortCode> {
        Err(AbortCode::ObjectDoesNotExist)
    }
    fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> {
        Err(AbortCode::ObjectDoesNotExist)
    }
}

impl OdDescribe for NoApplication {
    fn object_count(&self) -> usize {
        0
    }
    fn object(&self, _: usize) -> Option<ObjectDesc> {
        None
    }
    fn entry(&self, _: u16, _: u8) -> Option<EntryDesc> {
        None
    }
}

/// A mutable reference is a dictionary too, so views such as `Merged<&mut CommProfile, &mut App>` work.
impl<T: ObjectDictionary + ?Sized> ObjectDictionary for &mut T {
    const SERVES_PROGRAM: bool = T::SERVES_PROGRAM;
    const STREAMS: bool = T::STREAMS;
    const SEGMENTED_UPLOADS: bool = T::SEGMENTED_UPLOADS;
    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        (**self).info(index, sub)
    }
    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        (**self).read(index, sub, offset, buf)
    }
    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        (**self).write(index, sub, data)
    }
    fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        (**self).begin_write(index, sub, size)
    }
    fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        (**self).write_chunk(index, sub, offset, data)
    }
    fn end_write(&mut self, index: u16, sub: u8, total: usize) -> Result<(), AbortCode> {
        (**self).end_write(index, sub, total)
    }
    fn abort_write(&mut self, index: u16, sub: u8) {
        (**self).abort_write(index, sub)
    }
    fn restore_defaults(&mut self) {
        (**self).restore_defaults()
    }
    fn write_events(&self) -> bool {
        (**self).write_events()
    }
    fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> Result<(usize, usize), AbortCode> {
        (**self).read_expedited(index, sub, buf)
    }
    fn write_expedited(&mut self, index: u16, sub: u8, data: &[u8; 4], len: Option<usize>) -> Result<(), AbortCode> {
        (**self).write_expedited(index, sub, data, len)
    }
    fn slot(&self, index: u16, sub: u8) -> u16 {
        (**self).slot(index, sub)
    }
    fn read_slot(&self, index: u16, sub: u8, slot: u16, offset: usize, buf: &mut [u8]) -> Result<(), AbortCode> {
        (**self).read_slot(index, sub, slot, offset, buf)
    }
    fn pdo_resolve(&self, index: u16, sub: u8, dir: PdoDir) -> Result<PdoHandle, AbortCode> {
        (**self).pdo_resolve(index, sub, dir)
    }
    fn pdo_read(&self, handle: &PdoHandle, buf: &mut [u8]) -> Result<usize, AbortCode> {
        (**self).pdo_read(handle, buf)
    }
    fn pdo_write(&mut self, handle: &PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
        (**self).pdo_write(handle, data)
    }
}

impl<T: OdDescribe + ?Sized> OdDescribe for &T {
    fn object_count(&self) -> usize {
        (**self).object_count()
    }
    fn object(&self, n: usize) -> Option<ObjectDesc> {
        (**self).object(n)
    }
    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
        (**self).entry(index, sub)
    }
    fn object_index(&self, n: usize) -> Option<u16> {
        (**self).object_index(n)
    }
}

impl<T: OdDescribe + ?Sized> OdDescribe for &mut T {
    fn object_count(&self) -> usize {
        (**self).object_count()
    }
    fn object(&self, n: usize) -> Option<ObjectDesc> {
        (**self).object(n)
    }
    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
        (**self).entry(index, sub)
    }
    fn object_index(&self, n: usize) -> Option<u16> {
        (**self).object_index(n)
    }
}

#[cfg(test)]
mod tests {
    use super::value::*;
    use super::DataType;

    /// DT-05..08, DT-13, DT-14, DT-17: the `SIZES` table agrees with the value type of every static data
    /// type (its `DATA_TYPE` and encoded `MAX_SIZE`), and has no size for the strings and DOMAIN.
    #[test]
    fn data_type_sizes_agree_with_the_value_types() {
        fn agrees<T: OdValue>() {
            assert_eq!(T::DATA_TYPE.size(), Some(T::MAX_SIZE), "{:?}", T::DATA_TYPE);
        }
        let checks: [fn(); 21] = [
            agrees::<bool>,
            agrees::<i8>,
            agrees::<i16>,
            agrees::<I24>,
            agrees::<i32>,
            agrees::<I40>,
            agrees::<I48>,
            agrees::<I56>,
            agrees::<i64>,
            agrees::<u8>,
            agrees::<u16>,
            agrees::<U24>,
            agrees::<u32>,
            agrees::<U40>,
            agrees::<U48>,
            agrees::<U56>,
            agrees::<u64>,
            agrees::<f32>,
            agrees::<f64>,
            agrees::<TimeOfDay>,
            agrees::<TimeDifference>,
        ];
        checks.iter().for_each(|check| check());
        for t in [DataType::VisibleString, DataType::OctetString, DataType::UnicodeString, DataType::Domain] {
            assert_eq!(t.size(), None, "{t:?}");
        }
    }
}
