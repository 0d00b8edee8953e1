//! Store/restore on NOR flash: the core's two-slot [`Storage`] (1010h/1011h, STORE-01..STORE-11, NMT-06)
//! and the LSS configuration store ([`LssStore`], CiA 305 "store configuration") on any
//! `embedded-storage` [`NorFlash`], for example embassy-stm32's blocking `Flash`.
//!
//! # Layout
//!
//! Each of the core's two slots is a range of whole erase sectors of its own, so erasing one never
//! touches the other (the contract of [`Storage`]). The core's A/B scheme on top makes a save atomic: the
//! record goes to the older slot, header last, so a power cut at any program or erase step leaves the
//! other slot's record intact and the node starts on the old parameters or the new ones, never a mix and
//! never nothing (`tests/power_cut.rs` cuts at every step).
//!
//! Flash is programmed in words of [`NorFlash::WRITE_SIZE`] bytes, once per erase. The core writes a
//! record's payload front to back in small pieces and the header last, so [`FlashStorage`] collects the
//! bytes of one word in RAM and programs the word when it is full or when the writes move on; the header
//! gets a word-aligned area of its own in front of the payload, so header and payload never share a word,
//! and the header is programmed before `write` returns (it is the commit point). Reads see the bytes still
//! being collected.
//!
//! The LSS configuration (node-ID and bit-rate table index) is one small record with a CRC-32 in a third
//! sector range ([`FlashStorage::with_lss`]); [`FlashStorage::lss_config`] reads it at power-on, where it
//! wins over the factory node-ID (CiA 305). A power cut while it is being stored loses it (the node
//! starts on the factory node-ID), as on other stacks that keep it in a single block.

use core::ops::Range;

#[cfg(feature = "lss")]
use canopen_core::lss::{LssStore, StoreError as LssStoreError};
#[cfg(feature = "lss")]
use canopen_core::storage::Crc32;
use canopen_core::storage::{Storage, StorageError, HEADER_LEN};
#[cfg(feature = "lss")]
use canopen_core::wire::lss::BitRate;
use embedded_storage::nor_flash::NorFlash;

/// The largest [`NorFlash::WRITE_SIZE`] and [`ReadNorFlash::READ_SIZE`](embedded_storage::nor_flash::ReadNorFlash::READ_SIZE)
/// supported (STM32H7 programs 32-byte words; most parts 1 to 8).
pub const MAX_WORD: usize = 32;

/// Why a flash layout was refused by [`FlashStorage::new`] or [`FlashStorage::with_lss`].
///
/// ```
/// use canopen_embassy::flash::LayoutError;
/// assert_ne!(LayoutError::Overlap, LayoutError::Unaligned);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LayoutError {
    /// A range does not start and end on an erase-sector boundary, or lies outside the flash.
    Unaligned,
    /// Two ranges share a sector.
    Overlap,
    /// The flash's write or read word is larger than [`MAX_WORD`], or a range is too small for a record.
    Unsupported,
}

impl core::fmt::Display for LayoutError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            LayoutError::Unaligned => "flash range not aligned to erase sectors or outside the flash",
            LayoutError::Overlap => "flash ranges overlap",
            LayoutError::Unsupported => "flash word too large or range too small",
        })
    }
}

impl core::error::Error for LayoutError {}

/// The word being collected before it is programmed.
struct Word {
    /// The slot it belongs to (`None`: nothing collected).
    slot: Option<u8>,
    /// Flash address of the word.
    at: u32,
    /// Address of the next byte expected.
    next: u32,
    /// Bit `i`: `bytes[i]` was pushed. The others are programmed as erased bytes (FFh) by `flush`, so the
    /// buffer is never filled with FFh: a fill is a `memset` call, and `memset` is 404 B of flash that
    /// nothing else of a firmware links (footprint.sh: node+store).
    written: u32,
    bytes: [u8; MAX_WORD],
}

const _: () = assert!(MAX_WORD <= 32, "one bit of `Word::written` per byte");

/// The value of an erased NOR flash byte.
const ERASED: u8 = 0xFF;

/// The core's [`Storage`] (and the LSS [`LssStore`]) on a [`NorFlash`]; see the [module docs](self).
///
/// ```
/// # use canopen_embassy::flash::FlashStorage;
/// # use embedded_storage::nor_flash::{ErrorType, NorFlash, ReadNorFlash, NorFlashErrorKind};
/// # struct Ram([u8; 4096]);
/// # impl ErrorType for Ram { type Error = NorFlashErrorKind; }
/// # impl ReadNorFlash for Ram {
/// #     const READ_SIZE: usize = 1;
/// #     fn read(&mut self, o: u32, b: &mut [u8]) -> Result<(), Self::Error> { b.copy_from_slice(&self.0[o as usize..o as usize + b.len()]); Ok(()) }
/// #     fn capacity(&self) -> usize { self.0.len() }
/// # }
/// # impl NorFlash for Ram {
/// #     const WRITE_SIZE: usize = 8;
/// #     const ERASE_SIZE: usize = 1024;
/// #     fn erase(&mut self, f: u32, t: u32) -> Result<(), Self::Error> { self.0[f as usize..t as usize].fill(0xFF); Ok(()) }
/// #     fn write(&mut self, o: u32, b: &[u8]) -> Result<(), Self::Error> { self.0[o as usize..o as usize + b.len()].copy_from_slice(b); Ok(()) }
/// # }
/// use canopen_core::{lss::LssStore, storage::Storage, wire::lss::BitRate};
///
/// // Two sectors for the parameters' A/B slots, a third for the LSS configuration.
/// let mut st = FlashStorage::new(Ram([0xFF; 4096]), 1024..2048, 2048..3072)
///     .and_then(|s| s.with_lss(3072..4096))
///     .unwrap();
/// assert_eq!(st.capacity(), 1024 - 4); // the header's area is rounded up to whole words
/// assert_eq!(st.lss_config(), None);
/// st.store(0x22, BitRate::K250).unwrap();
/// assert_eq!(st.lss_config(), Some((0x22, BitRate::K250)));
/// ```
pub struct FlashStorage<F> {
    flash: F,
    slots: [Range<u32>; 2],
    lss: Option<Range<u32>>,
    word: Word,
}

/// "LSS" and the record version.
#[cfg(feature = "lss")]
const LSS_MAGIC: [u8; 4] = *b"LSS\x01";
/// magic, node-ID, bit-rate index, two reserved bytes (FFh), CRC-32 over the first 8 bytes.
const LSS_RECORD: usize = 12;
/// The word collector's slot number for the LSS record (the parameter record's slots are 0 and 1).
#[cfg(feature = "lss")]
const LSS_SLOT: u8 = 2;

const fn align_up(n: usize, word: usize) -> usize {
    n.div_ceil(word) * word
}

impl<F: NorFlash> FlashStorage<F> {
    /// Bytes between the start of a slot and its payload: the header's area, in whole words.
    const HEADER_AREA: usize = align_up(HEADER_LEN, F::WRITE_SIZE);

    /// Storage on two ranges of whole erase sectors of `flash` (addresses as `flash` counts them), one per
    /// slot.
    ///
    /// ```
    /// # use canopen_embassy::flash::{FlashStorage, LayoutError};
    /// # use embedded_storage::nor_flash::{ErrorType, NorFlash, ReadNorFlash, NorFlashErrorKind};
    /// # struct Ram([u8; 4096]);
    /// # impl ErrorType for Ram { type Error = NorFlashErrorKind; }
    /// # impl ReadNorFlash for Ram {
    /// #     const READ_SIZE: usize = 1;
    /// #     fn read(&mut self, o: u32, b: &mut [u8]) -> Result<(), Self::Error> { b.copy_from_slice(&self.0[o as usize..o as usize + b.len()]); Ok(()) }
    /// #     fn capacity(&self) -> usize { self.0.len() }
    /// # }
    /// # impl NorFlash for Ram {
    /// #     const WRITE_SIZE: usize = 4;
    /// #     const ERASE_SIZE: usize = 1024;
    /// #     fn erase(&mut self, f: u32, t: u32) -> Result<(), Self::Error> { Ok(()) }
    /// #     fn write(&mut self, o: u32, b: &[u8]) -> Result<(), Self::Error> { Ok(()) }
    /// # }
    /// assert!(FlashStorage::new(Ram([0xFF; 4096]), 0..1024, 1024..2048).is_ok());
    /// assert_eq!(FlashStorage::new(Ram([0xFF; 4096]), 0..1000, 1024..2048).err(), Some(LayoutError::Unaligned));
    /// assert_eq!(FlashStorage::new(Ram([0xFF; 4096]), 0..2048, 1024..3072).err(), Some(LayoutError::Overlap));
    /// ```
    pub fn new(flash: F, slot_a: Range<u32>, slot_b: Range<u32>) -> Result<Self, LayoutError> {
        if F::WRITE_SIZE > MAX_WORD || F::READ_SIZE > MAX_WORD || F::WRITE_SIZE == 0 || F::READ_SIZE == 0 {
            return Err(LayoutError::Unsupported);
        }
        for r in [&slot_a, &slot_b] {
            Self::check_range(&flash, r)?;
            if (r.len()) < Self::HEADER_AREA + LSS_RECORD {
                return Err(LayoutError::Unsupported);
            }
        }
        if overlap(&slot_a, &slot_b) {
            return Err(LayoutError::Overlap);
        }
        let word = Word { slot: None, at: 0, next: 0, written: 0, bytes: [0; MAX_WORD] };
        Ok(FlashStorage { flash, slots: [slot_a, slot_b], lss: None, word })
    }

    /// Adds a range of whole erase sectors for the LSS configuration ([`LssStore`]).
    ///
    /// See [`FlashStorage`] for an example.
    pub fn with_lss(mut self, range: Range<u32>) -> Result<Self, LayoutError> {
        Self::check_range(&self.flash, &range)?;
        if self.slots.iter().any(|s| overlap(s, &range)) {
            return Err(LayoutError::Overlap);
        }
        if range.len() < align_up(LSS_RECORD, F::WRITE_SIZE) {
            return Err(LayoutError::Unsupported);
        }
        self.lss = Some(range);
        Ok(self)
    }

    /// The flash, for the application's own use of the sectors it did not give to the storage.
    ///
    /// See [`FlashStorage`] for an example of building one.
    pub fn flash_mut(&mut self) -> &mut F {
        &mut self.flash
    }

    /// The stored LSS configuration (node-ID 1–127 or FFh, bit rate), or `None` when nothing valid is
    /// stored (never stored, or cut by a power loss while it was being stored). At power-on a stored
    /// node-ID wins over the factory one (CiA 305).
    ///
    /// See [`FlashStorage`] for an example.
    #[cfg(feature = "lss")]
    pub fn lss_config(&mut self) -> Option<(u8, BitRate)> {
        let at = self.lss.as_ref()?.start;
        let mut rec = [0u8; LSS_RECORD];
        self.read_at(at, &mut rec).ok()?;
        let crc = u32::from_le_bytes([rec[8], rec[9], rec[10], rec[11]]);
        if rec[..4] != LSS_MAGIC || Crc32::checksum(&rec[..8]) != crc {
            return None;
        }
        let id = rec[4];
        if !(matches!(id, 1..=127 | 0xFF)) {
            return None;
        }
        Some((id, BitRate::from_index(rec[5])?))
    }

    fn check_range(flash: &F, r: &Range<u32>) -> Result<(), LayoutError> {
        let erase = F::ERASE_SIZE as u32;
        let aligned = erase != 0 && r.start % erase == 0 && r.end % erase == 0 && r.start < r.end;
        if !aligned || r.end as usize > flash.capacity() {
            return Err(LayoutError::Unaligned);
        }
        Ok(())
    }

    fn slot(&self, slot: u8) -> Result<&Range<u32>, StorageError> {
        self.slots.get(usize::from(slot)).ok_or(StorageError::Io)
    }

    /// Flash address of byte `offset` of `slot` (the header's area is padded to whole words).
    fn address(&self, slot: u8, offset: usize) -> Result<u32, StorageError> {
        let physical = if offset < HEADER_LEN { offset } else { offset - HEADER_LEN + Self::HEADER_AREA };
        let r = self.slot(slot)?;
        let at = r.start as usize + physical;
        u32::try_from(at).ok().filter(|&a| a < r.end).ok_or(StorageError::TooLarge)
    }

    /// Programs the word being collected, padded with erased bytes.
    fn flush(&mut self) -> Result<(), StorageError> {
        if self.word.slot.take().is_some() {
            let written = self.word.written;
            for (i, b) in self.word.bytes[..F::WRITE_SIZE].iter_mut().enumerate() {
                if written & 1 << i == 0 {
                    *b = ERASED;
                }
            }
            self.flash.write(self.word.at, &self.word.bytes[..F::WRITE_SIZE]).map_err(|_| StorageError::Io)?;
        }
        Ok(())
    }

    /// Adds one byte at flash address `at` of `slot` to the word being collected.
    fn push(&mut self, slot: u8, at: u32, byte: u8) -> Result<(), StorageError> {
        let word = F::WRITE_SIZE as u32;
        let start = at - at % word;
        if self.word.slot.is_some() && (self.word.slot != Some(slot) || self.word.at != start) {
            self.flush()?;
        }
        if self.word.slot.is_none() {
            // A new word; its bytes stay as they are: only the `written` ones are programmed.
            self.word.slot = Some(slot);
            (self.word.at, self.word.next, self.word.written) = (start, start, 0);
        }
        if at < self.word.next {
            // A byte programmed twice between erases: NOR flash cannot do it (the core never asks for it).
            return Err(StorageError::Io);
        }
        let i = (at - start) as usize;
        self.word.bytes[i] = byte;
        self.word.written |= 1 << i;
        self.word.next = at + 1;
        if self.word.next == start + word {
            self.flush()?;
        }
        Ok(())
    }

    /// Reads at a flash address, in whole read words, then overlays the bytes still being collected.
    fn read_at(&mut self, at: u32, buf: &mut [u8]) -> Result<(), StorageError> {
        let rs = F::READ_SIZE as u32;
        let mut chunk = [0u8; MAX_WORD];
        let mut done = 0usize;
        while done < buf.len() {
            let a = at + done as u32;
            let base = a - a % rs;
            self.flash.read(base, &mut chunk[..F::READ_SIZE]).map_err(|_| StorageError::Io)?;
            let from = (a - base) as usize;
            let n = (F::READ_SIZE - from).min(buf.len() - done);
            buf[done..done + n].copy_from_slice(&chunk[from..from + n]);
            done += n;
        }
        if self.word.slot.is_some() {
            // The bytes pushed into the word being collected; the others still read as flash has them.
            for (i, b) in buf.iter_mut().enumerate() {
                let k = (at + i as u32).wrapping_sub(self.word.at) as usize;
                if k < MAX_WORD && self.word.written & 1 << k != 0 {
                    *b = self.word.bytes[k];
                }
            }
        }
        Ok(())
    }
}

fn overlap(a: &Range<u32>, b: &Range<u32>) -> bool {
    a.start < b.end && b.start < a.end
}

impl<F: NorFlash> Storage for FlashStorage<F> {
    fn capacity(&self) -> usize {
        let len = self.slots[0].len().min(self.slots[1].len());
        len - (Self::HEADER_AREA - HEADER_LEN)
    }

    fn erase(&mut self, slot: u8) -> Result<(), StorageError> {
        if self.word.slot == Some(slot) {
            self.word.slot = None; // collected for a record that is being replaced
        }
        let r = self.slot(slot)?.clone();
        self.flash.erase(r.start, r.end).map_err(|_| StorageError::Io)
    }

    fn write(&mut self, slot: u8, offset: usize, data: &[u8]) -> Result<(), StorageError> {
        for (i, &b) in data.iter().enumerate() {
            let at = self.address(slot, offset + i)?;
            self.push(slot, at, b)?;
        }
        // The header is the commit point: it is in flash when `write` returns.
        if offset < HEADER_LEN && offset + data.len() >= HEADER_LEN {
            self.flush()?;
        }
        Ok(())
    }

    fn read(&mut self, slot: u8, offset: usize, buf: &mut [u8]) -> Result<(), StorageError> {
        // A read may cross from the header into the payload: read each side at its own address.
        let split = HEADER_LEN.saturating_sub(offset).min(buf.len());
        let (head, payload) = buf.split_at_mut(split);
        if !head.is_empty() {
            let at = self.address(slot, offset)?;
            self.read_at(at, head)?;
        }
        if !payload.is_empty() {
            let at = self.address(slot, offset + split)?;
            if at as usize + payload.len() > self.slot(slot)?.end as usize {
                return Err(StorageError::TooLarge);
            }
            self.read_at(at, payload)?;
        }
        Ok(())
    }
}

#[cfg(feature = "lss")]
impl<F: NorFlash> LssStore for FlashStorage<F> {
    /// Erases the LSS range and programs the record; [`LssStoreError::NotSupported`] without an LSS range,
    /// [`LssStoreError::MediaAccess`] when the flash fails.
    fn store(&mut self, node_id: u8, bit_rate: BitRate) -> Result<(), LssStoreError> {
        let r = self.lss.clone().ok_or(LssStoreError::NotSupported)?;
        let mut rec = [ERASED; LSS_RECORD];
        rec[..4].copy_from_slice(&LSS_MAGIC);
        rec[4] = node_id;
        rec[5] = bit_rate.index();
        let crc = Crc32::checksum(&rec[..8]);
        rec[8..].copy_from_slice(&crc.to_le_bytes());
        // Programmed through the word collector (slot number `LSS_SLOT`), which pads the last word with
        // erased bytes. A parameter record is never left half-collected between two calls (its header
        // write flushes), so nothing of one is programmed here.
        let media = |_| LssStoreError::MediaAccess;
        self.flush().map_err(media)?;
        self.flash.erase(r.start, r.end).map_err(|_| LssStoreError::MediaAccess)?;
        for (i, &b) in rec.iter().enumerate() {
            self.push(LSS_SLOT, r.start + i as u32, b).map_err(media)?;
        }
        self.flush().map_err(media)
    }
}
