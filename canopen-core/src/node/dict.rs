//! The dictionary SDO sees on a node: the one router of the communication profile and the application
//! ([`Merged`]), plus the three things that need both halves or the storage:
//! - (feature `pdo-dynamic-mapping`) a mapping entry (1600h–17FFh / 1A00h–1BFFh sub 01h–08h) must name an
//!   existing, mappable object of the merged dictionary (PDO-36: 0602 0000h / 0609 0011h / 0604 0041h), and
//!   enabling a mapping (sub 00h) resolves every entry again (PDO-37: 0602 0000h, 0604 0042h above 64 bits);
//!   a refused write is rolled back, so nothing changes;
//! - (feature `mpdo`) a TPDO mapping count FEh while another TPDO is the SAM producer already: 0604 0043h
//!   (MPDO-03, one SAM producer per device);
//! - (feature `store-restore`) 1010h "save" stores the groups of its sub-index before the SDO response goes
//!   out (STORE-04); 1011h "load" removes the groups from the stored record (STORE-08..10).
//!
//! Everything else goes to [`Merged`] unchanged.

use crate::od::{AbortCode, Merged, ObjectDictionary, PdoDir, PdoHandle, SubInfo};
#[cfg(feature = "pdo-dynamic-mapping")]
use crate::pdo::mapping::ResolvedMap;
use crate::profile::{CommProfile, ProfileSizes, SIZE_NOT_INDICATED};
use crate::storage::{Groups, Storage, StorageError};
#[cfg(feature = "store-restore")]
use crate::{profile::STORE_GO_AHEAD, storage::abort_of};

/// Writes a new record (`storage::update`): the groups to save (1010h), the groups to drop (1011h), with the
/// application's description where the node has it. One function for both, so one copy of the record code.
pub(crate) type SaveFn<S, C, A> = fn(&mut S, Groups, Groups, &C, &A) -> Result<(), StorageError>;

pub(crate) struct NodeDict<'a, Z: ProfileSizes, A, S> {
    od: Merged<&'a mut CommProfile<Z>, &'a mut A>,
    /// For 1010h/1011h only (feature `store-restore`).
    #[cfg_attr(not(feature = "store-restore"), allow(dead_code))]
    storage: &'a mut S,
    #[cfg_attr(not(feature = "store-restore"), allow(dead_code))]
    save: SaveFn<S, CommProfile<Z>, A>,
}

impl<'a, Z: ProfileSizes, A: ObjectDictionary, S: Storage> NodeDict<'a, Z, A, S> {
    /// The node's dictionary over its profile, application and storage.
    pub(crate) fn new(
        comm: &'a mut CommProfile<Z>,
        app: &'a mut A,
        storage: &'a mut S,
        save: SaveFn<S, CommProfile<Z>, A>,
    ) -> Self {
        NodeDict { od: Merged { comm, app }, storage, save }
    }

    /// Every SDO write to the communication profile (`write`, `write_expedited`): one call of the
    /// profile's write path, then what needs both halves or the storage. The entry's bytes are `data`'s
    /// first `len`, or as many as the entry has when `len` is [`SIZE_NOT_INDICATED`] (an expedited download
    /// without the size indicated, SDO-13). Out of line, so that `write_expedited` stays small enough to be inlined
    /// into the SDO server for the application's downloads (bench-node.sh expedited_download).
    /// - A mapping record (PDO-36/37): undone when its entries do not resolve; the record as it was is
    ///   kept aside (one copy of the struct) and put back, so nothing changes.
    /// - 1010h "save" / 1011h "load" (STORE-04, STORE-08..10): the profile checks the entry, access, length
    ///   and signature as for any write (0602 0000h, 0609 0011h, 0601 0002h, 0607 0012h/0013h,
    ///   0800 0020h) and answers a right signature with [`STORE_GO_AHEAD`]; then the record is written.
    #[inline(never)]
    fn comm_write(&mut self, index: u16, sub: u8, data: &[u8], len: usize) -> Result<(), AbortCode> {
        #[cfg(feature = "pdo-dynamic-mapping")]
        let (dir, k) = (if index < 0x1A00 { PdoDir::Rpdo } else { PdoDir::Tpdo }, usize::from(index & 0x1FF));
        #[cfg(feature = "pdo-dynamic-mapping")]
        let saved = if is_mapping(index) { self.map_mut(dir, k).map(|m| *m) } else { None };
        // A PDO this node has not: 0602 0000h, as any write.
        let written = self.od.comm.write_sdo(index, sub, data, len);
        #[cfg(feature = "store-restore")]
        if matches!(index, 0x1010 | 0x1011) && written == Err(STORE_GO_AHEAD) {
            let groups = Groups::from_sub(sub).unwrap_or(Groups::NONE);
            let (save, drop) = if index == 0x1010 { (groups, Groups::NONE) } else { (Groups::NONE, groups) };
            return (self.save)(self.storage, save, drop, self.od.comm, self.od.app).map_err(abort_of);
        }
        #[cfg(feature = "pdo-dynamic-mapping")]
        if is_mapping(index) && written.is_ok() {
            let checked = self.check_mapping(sub, k, dir);
            if let (Err(_), Some(saved), Some(map)) = (checked, saved, self.map_mut(dir, k)) {
                *map = saved;
            }
            return checked;
        }
        written
    }

    #[cfg(feature = "pdo-dynamic-mapping")]
    fn map_mut(&mut self, dir: PdoDir, k: usize) -> Option<&mut crate::pdo::PdoMapParams> {
        let p = &mut self.od.comm.params;
        if dir == PdoDir::Rpdo { p.rpdo_map.as_mut() } else { p.tpdo_map.as_mut() }.get_mut(k)
    }

    #[cfg(feature = "pdo-dynamic-mapping")]
    fn check_mapping(&self, sub: u8, k: usize, dir: PdoDir) -> Result<(), AbortCode> {
        let p = &self.od.comm.params;
        let map = if dir == PdoDir::Rpdo { p.rpdo_map.as_ref().get(k) } else { p.tpdo_map.as_ref().get(k) };
        let Some(map) = map else { return Ok(()) };
        #[cfg(feature = "mpdo")]
        if sub == 0 && dir == PdoDir::Tpdo && map.count == 0xFE {
            // MPDO-03: one SAM producer per device; a second SAM TPDO conflicts with the first (0604 0043h).
            if p.tpdo_map.as_ref().iter().enumerate().any(|(i, m)| i != k && m.count == 0xFE) {
                return Err(AbortCode::ParameterIncompatibility);
            }
        }
        // Sub 00h: every entry of the new count; an entry: that one alone, through the same resolution (one
        // entry resolves to the answer `mapping::resolve` gives: it refuses more than 64 bits itself, so the
        // sum's 0604 0042h cannot come up), one call instead of two.
        let raw = match usize::from(sub).checked_sub(1) {
            None => map.active(),
            Some(i) => map.entries.get(i..=i).unwrap_or(&[0]),
        };
        ResolvedMap::resolve(&self.od, raw, dir).map(|_| ())
    }
}

/// Whether `index` is a PDO mapping record, whose writes this view checks against the merged dictionary
/// (feature `pdo-dynamic-mapping`).
#[cfg(feature = "pdo-dynamic-mapping")]
const fn is_mapping(index: u16) -> bool {
    matches!(index, 0x1600..=0x17FF | 0x1A00..=0x1BFF)
}

impl<Z: ProfileSizes, A: ObjectDictionary, S: Storage> ObjectDictionary for NodeDict<'_, Z, A, S> {
    /// 1010h/1011h and the mappings it intercepts are numeric: streams are the merged dictionary's.
    const STREAMS: bool = <Merged<&mut CommProfile<Z>, &mut A>>::STREAMS;
    const SEGMENTED_UPLOADS: bool = <Merged<&mut CommProfile<Z>, &mut A>>::SEGMENTED_UPLOADS;

    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        self.od.info(index, sub)
    }
    /// Inline, straight to the half that owns the index: each segment of an upload comes here, and the
    /// routing as a function of its own cost 17 instructions per segment (bench-node.sh segmented_upload).
    #[inline]
    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        if crate::od::is_comm_for::<A>(index) {
            self.od.comm.read(index, sub, offset, buf)
        } else {
            self.od.app.read(index, sub, offset, buf)
        }
    }
    fn slot(&self, index: u16, sub: u8) -> u16 {
        self.od.slot(index, sub)
    }
    /// Inline, as `read`: each segment of an upload comes here.
    #[inline]
    fn read_slot(&self, index: u16, sub: u8, slot: u16, offset: usize, buf: &mut [u8]) -> Result<(), AbortCode> {
        if crate::od::is_comm_for::<A>(index) {
            self.od.comm.read_slot(index, sub, slot, offset, buf)
        } else {
            self.od.app.read_slot(index, sub, slot, offset, buf)
        }
    }
    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        if crate::od::is_comm_for::<A>(index) {
            self.comm_write(index, sub, data, data.len())
        } else {
            self.od.app.write(index, sub, data)
        }
    }
    fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        self.od.begin_write(index, sub, size)
    }
    fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        self.od.write_chunk(index, sub, offset, data)
    }
    fn end_write(&mut self, index: u16, sub: u8, total: usize) -> Result<(), AbortCode> {
        self.od.end_write(index, sub, total)
    }
    fn abort_write(&mut self, index: u16, sub: u8) {
        self.od.abort_write(index, sub)
    }
    /// Inline, as `read`: a call of its own cost 13 instructions per expedited upload (bench-node.sh).
    #[inline]
    fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> Result<(usize, usize), AbortCode> {
        // Straight to the half that owns the index, as write_expedited below: through `Merged` and the
        // `&mut` forwarding it cost 3 instructions per upload (bench-node.sh segmented_upload).
        if crate::od::is_comm_for::<A>(index) {
            self.od.comm.read_expedited(index, sub, buf)
        } else {
            self.od.app.read_expedited(index, sub, buf)
        }
    }
    #[inline]
    fn write_expedited(&mut self, index: u16, sub: u8, data: &[u8; 4], len: Option<usize>) -> Result<(), AbortCode> {
        // The communication profile through the one write path above (store/restore and mappings
        // intercepted), the application with its single lookup.
        if crate::od::is_comm_for::<A>(index) {
            self.comm_write(index, sub, data, len.unwrap_or(SIZE_NOT_INDICATED))
        } else {
            self.od.app.write_expedited(index, sub, data, len)
        }
    }
    fn pdo_resolve(&self, index: u16, sub: u8, dir: PdoDir) -> Result<PdoHandle, AbortCode> {
        self.od.pdo_resolve(index, sub, dir)
    }
    fn pdo_read(&self, handle: &PdoHandle, buf: &mut [u8]) -> Result<usize, AbortCode> {
        self.od.pdo_read(handle, buf)
    }
    fn pdo_write(&mut self, handle: &PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
        self.od.pdo_write(handle, data)
    }
}
