//! Program download (CiA 302-3): 1F50h program data, 1F51h program control, 1F56h program software
//! identification and 1F57h flash status identification, for one program area (sub-index 1).
//!
//! [`ProgramDownload`] is a ready-made dictionary part: it serves those four objects and passes every
//! other index to the application dictionary it wraps, so an application composes it with its own
//! (`Node::new(id, config, ProgramDownload::new(sink, app))`). The node routes 1F50h–1F57h to the
//! application half when the application says it serves them (`ObjectDictionary::SERVES_PROGRAM`, a
//! constant, so a node whose application is not wrapped compiles no extra test); without the feature
//! (`program-download`) none of this is compiled.
//!
//! The image is never buffered: each SDO segment or block of 1F50h:01 goes straight to the application's
//! [`ProgramSink`] (`write_chunk`, in increasing contiguous offsets), as for any streamed DOMAIN
//! ([`od::Domain`](crate::od::Domain)); a transfer that is aborted (by the client, by an SDO time-out, by a
//! new transfer) reaches the sink as [`ProgramSink::abort`].
//!
//! # What this relies on
//!
//! CiA 302-3 itself was not at hand. The object layout and values come from public restatements of it:
//! the TR-Electronic CM-36 user manual §7.19.4 (1F57h: ARRAY of UNSIGNED32, ro; bit 0 "in progress",
//! bits 1..7 an error code, 0 = program valid, 1 = program not valid; bits 8..15 reserved), CANopenNode
//! based bootloaders (CU/`CO_Prog` sequences: read 1F56h, 1F51h = 0 stop, 1F51h = 3 clear, download
//! 1F50h, read 1F57h, 1F51h = 1 start), and the commonly quoted program control commands 00h stop,
//! 01h start, 02h reset, 03h clear (80h–FFh manufacturer-specific, not offered here). Where the
//! restatements are silent we chose, and say so:
//!
//! - 1F51h reads back the program state: 00h stopped, 01h started (CiA 302-3 wording "program stopped /
//!   started"); a cleared area reads 00h with 1F57h saying "program not valid".
//! - A command that is not 00h..03h is answered 0609 0030h (invalid value); a command the present state
//!   refuses (start or reset without a valid program, clear or download while the program runs) is
//!   answered 0800 0022h (device state), as CiA 301 gives that code for "present device state".
//! - The error codes of 1F57h bits 1..7 used here: 1 no valid program, 3 data format error (the sink
//!   refused the image at its end), 5 flash write error (the sink refused a chunk), 63 unspecified
//!   (the sink refused the start of a download).

use crate::od::is_program;
use crate::od::{
    check_len, count_entry, AbortCode, Access, DataType, EntryDesc, ObjectCode, ObjectDesc, ObjectDictionary,
    OdDescribe, PdoMapping, SubInfo,
};

/// The application's side of a program area: where the image goes and what program control does.
///
/// ```
/// use canopen_core::od::AbortCode;
/// use canopen_core::program::{ProgramCommand, ProgramSink};
/// /// Sums the image (a stand-in for writing flash).
/// #[derive(Default)]
/// struct Sum { bytes: usize, sum: u32 }
/// impl ProgramSink for Sum {
///     fn begin(&mut self, _size: Option<usize>) -> Result<(), AbortCode> { *self = Sum::default(); Ok(()) }
///     fn write_chunk(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
///         self.bytes = offset + data.len();
///         self.sum = data.iter().fold(self.sum, |s, &b| s.wrapping_add(u32::from(b)));
///         Ok(())
///     }
///     fn end(&mut self, _total: usize) -> Result<(), AbortCode> { Ok(()) }
///     fn abort(&mut self) {}
/// }
/// let mut s = Sum::default();
/// s.write_chunk(0, &[1, 2, 3]).unwrap();
/// assert_eq!((s.bytes, s.sum), (3, 6));
/// assert_eq!(s.control(ProgramCommand::Start), Ok(()));
/// ```
pub trait ProgramSink {
    /// A download of 1F50h:01 starts; `size` is the announced total if the client gave one. Erase here,
    /// or refuse a size that cannot fit (0607 0012h).
    fn begin(&mut self, size: Option<usize>) -> Result<(), AbortCode>;

    /// One chunk of the image at `offset` (increasing, contiguous offsets).
    fn write_chunk(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode>;

    /// The download completed with `total` bytes: verify (CRC, signature) and commit.
    fn end(&mut self, total: usize) -> Result<(), AbortCode>;

    /// The download was abandoned: what was written is not a valid program.
    fn abort(&mut self);

    /// A program control command (1F51h:01) the state allowed; an error refuses it with that abort code.
    /// The provided method accepts every command (the application acts on the node's `ObjectWritten`
    /// event for 1F51h).
    fn control(&mut self, command: ProgramCommand) -> Result<(), AbortCode> {
        let _ = command;
        Ok(())
    }

    /// 1F56h:01 program software identification (e.g. the image's CRC or version); 0 if none.
    fn software_id(&self) -> u32 {
        0
    }
}

/// A program control command (1F51h:01 written).
///
/// ```
/// use canopen_core::program::ProgramCommand;
/// assert_eq!(ProgramCommand::from_u8(3), Some(ProgramCommand::Clear));
/// assert_eq!(ProgramCommand::from_u8(4), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ProgramCommand {
    /// 00h stop the program.
    Stop = 0,
    /// 01h start the program.
    Start = 1,
    /// 02h reset the program (stop, then start).
    Reset = 2,
    /// 03h clear the program area.
    Clear = 3,
}

impl ProgramCommand {
    /// The command of a written value, `None` for values this device does not offer.
    pub const fn from_u8(v: u8) -> Option<Self> {
        Some(match v {
            0 => ProgramCommand::Stop,
            1 => ProgramCommand::Start,
            2 => ProgramCommand::Reset,
            3 => ProgramCommand::Clear,
            _ => return None,
        })
    }
}

/// 1F57h bit 0: a download is in progress (the other bits are not valid).
pub const FLASH_IN_PROGRESS: u32 = 1;
/// 1F57h error code 1 (bits 1..7): no valid program.
pub const FLASH_NO_VALID_PROGRAM: u32 = 1 << 1;
/// 1F57h error code 3: data format error (the image was refused at its end).
pub const FLASH_DATA_FORMAT_ERROR: u32 = 3 << 1;
/// 1F57h error code 5: flash write error (a chunk was refused).
pub const FLASH_WRITE_ERROR: u32 = 5 << 1;
/// 1F57h error code 63: unspecified error (the start of a download was refused).
pub const FLASH_UNSPECIFIED_ERROR: u32 = 63 << 1;

/// The four program download objects over a [`ProgramSink`] `P`, in front of the application dictionary
/// `A` (every other index goes to `A`).
///
/// ```
/// use canopen_core::od::{AbortCode, NoApplication, ObjectDictionary};
/// use canopen_core::program::{ProgramCommand, ProgramDownload, ProgramSink};
/// # struct Null;
/// # impl ProgramSink for Null {
/// #     fn begin(&mut self, _: Option<usize>) -> Result<(), AbortCode> { Ok(()) }
/// #     fn write_chunk(&mut self, _: usize, _: &[u8]) -> Result<(), AbortCode> { Ok(()) }
/// #     fn end(&mut self, _: usize) -> Result<(), AbortCode> { Ok(()) }
/// #     fn abort(&mut self) {}
/// # }
/// let mut od = ProgramDownload::new(Null, NoApplication);
/// // No program yet: start is refused, an unknown command is an invalid value.
/// assert_eq!(od.write(0x1F51, 1, &[1]), Err(AbortCode::CannotStoreDeviceState));
/// assert_eq!(od.write(0x1F51, 1, &[9]), Err(AbortCode::InvalidValue));
/// canopen_core::od::write_whole_stream(&mut od, 0x1F50, 1, &[1, 2, 3]).unwrap();
/// assert_eq!(od.flash_status(), 0);
/// od.write(0x1F51, 1, &[1]).unwrap();
/// assert!(od.running());
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ProgramDownload<P, A> {
    /// The program area's sink.
    pub sink: P,
    /// The application dictionary behind (every index but 1F50h, 1F51h, 1F56h, 1F57h).
    pub app: A,
    running: bool,
    flash: u32,
}

/// The objects served, with their sub-entries (sub 0 the count, sub 1 the one program area).
const OBJECTS: [(u16, &str, DataType, Access, &str); 4] = [
    (0x1F50, "Program data", DataType::Domain, Access::Wo, "Program data 1"),
    (0x1F51, "Program control", DataType::Unsigned8, Access::Rw, "Program control 1"),
    (0x1F56, "Program software identification", DataType::Unsigned32, Access::Ro, "Program software identification 1"),
    (0x1F57, "Flash status identification", DataType::Unsigned32, Access::Ro, "Flash status identification 1"),
];

impl<P: ProgramSink, A> ProgramDownload<P, A> {
    /// A program area with no valid program yet (1F57h = "no valid program", 1F51h = stopped).
    pub const fn new(sink: P, app: A) -> Self {
        ProgramDownload { sink, app, running: false, flash: FLASH_NO_VALID_PROGRAM }
    }

    /// Whether the program is started (1F51h reads 01h).
    pub const fn running(&self) -> bool {
        self.running
    }

    /// 1F57h:01 flash status identification: 0 when a valid program is stored.
    pub const fn flash_status(&self) -> u32 {
        self.flash
    }

    fn control(&mut self, data: &[u8]) -> Result<(), AbortCode> {
        check_len(data, 1)?;
        let command = ProgramCommand::from_u8(data[0]).ok_or(AbortCode::InvalidValue)?;
        let allowed = match command {
            ProgramCommand::Stop => true,
            ProgramCommand::Start | ProgramCommand::Reset => self.flash == 0,
            ProgramCommand::Clear => !self.running && self.flash & FLASH_IN_PROGRESS == 0,
        };
        if !allowed {
            return Err(AbortCode::CannotStoreDeviceState);
        }
        self.sink.control(command)?;
        match command {
            ProgramCommand::Stop => self.running = false,
            ProgramCommand::Start | ProgramCommand::Reset => self.running = true,
            ProgramCommand::Clear => self.flash = FLASH_NO_VALID_PROGRAM,
        }
        Ok(())
    }

    /// The value of a fixed-size entry, little-endian, with its length.
    fn fixed(&self, index: u16, sub: u8) -> Result<([u8; 4], usize), AbortCode> {
        Ok(match (index, sub) {
            (_, 0) => ([1, 0, 0, 0], 1),
            (0x1F51, 1) => ([u8::from(self.running), 0, 0, 0], 1),
            (0x1F56, 1) => (self.sink.software_id().to_le_bytes(), 4),
            (0x1F57, 1) => (self.flash.to_le_bytes(), 4),
            (0x1F50, 1) => return Err(AbortCode::ReadOfWriteOnly),
            _ => return Err(sub_missing(index)),
        })
    }

    /// Sub 1 of 1F50h, else the error for (index, sub).
    fn data_entry(&self, index: u16, sub: u8) -> Result<(), AbortCode> {
        match (index, sub) {
            (0x1F50, 1) => Ok(()),
            (0x1F50, 0) => Err(AbortCode::WriteOfReadOnly),
            (0x1F50, _) => Err(AbortCode::SubIndexDoesNotExist),
            _ => Err(AbortCode::UnsupportedAccess),
        }
    }

    /// A failed step of a download: the sink is told, 1F57h says why.
    fn failed(&mut self, code: AbortCode, status: u32) -> AbortCode {
        self.sink.abort();
        self.flash = status;
        code
    }
}

/// The application dictionary's fields and methods are reached through the wrapper
/// (`node.app_mut().setpoint = 5` keeps working when the application is wrapped).
///
/// ```
/// use canopen_core::od::{AbortCode, NoApplication};
/// use canopen_core::program::{ProgramDownload, ProgramSink};
/// # struct Null;
/// # impl ProgramSink for Null {
/// #     fn begin(&mut self, _: Option<usize>) -> Result<(), AbortCode> { Ok(()) }
/// #     fn write_chunk(&mut self, _: usize, _: &[u8]) -> Result<(), AbortCode> { Ok(()) }
/// #     fn end(&mut self, _: usize) -> Result<(), AbortCode> { Ok(()) }
/// #     fn abort(&mut self) {}
/// # }
/// struct App { setpoint: i16 }
/// let mut od = ProgramDownload::new(Null, App { setpoint: 0 });
/// od.setpoint = 5;
/// assert_eq!(od.app.setpoint, 5);
/// ```
impl<P, A> core::ops::Deref for ProgramDownload<P, A> {
    type Target = A;
    fn deref(&self) -> &A {
        &self.app
    }
}

impl<P, A> core::ops::DerefMut for ProgramDownload<P, A> {
    fn deref_mut(&mut self) -> &mut A {
        &mut self.app
    }
}

fn sub_missing(index: u16) -> AbortCode {
    match index {
        0x1F50 | 0x1F51 | 0x1F56 | 0x1F57 => AbortCode::SubIndexDoesNotExist,
        _ => AbortCode::ObjectDoesNotExist,
    }
}

impl<P: ProgramSink, A: ObjectDictionary> ObjectDictionary for ProgramDownload<P, A> {
    /// `Merged` (and the node) route 1F50h–1F57h here rather than to the communication profile.
    const SERVES_PROGRAM: bool = true;

    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        if !is_program(index) {
            return self.app.info(index, sub);
        }
        let (_, _, data_type, access, _) =
            *OBJECTS.iter().find(|o| o.0 == index).ok_or(AbortCode::ObjectDoesNotExist)?;
        match sub {
            0 => Ok(SubInfo { data_type: DataType::Unsigned8, access: Access::Const, pdo: PdoMapping::No, size: 1 }),
            1 => Ok(SubInfo { data_type, access, pdo: PdoMapping::No, size: data_type.size().unwrap_or(0) }),
            _ => Err(AbortCode::SubIndexDoesNotExist),
        }
    }

    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        if !is_program(index) {
            return self.app.read(index, sub, offset, buf);
        }
        let (bytes, len) = self.fixed(index, sub)?;
        Ok(crate::od::copy_at(&bytes[..len], offset, buf))
    }

    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        if !is_program(index) {
            return self.app.write(index, sub, data);
        }
        match (index, sub) {
            (0x1F51, 1) => self.control(data),
            (0x1F50, 1) => crate::od::write_whole_stream(self, index, sub, data),
            _ => {
                self.fixed(index, sub)?;
                Err(AbortCode::WriteOfReadOnly)
            }
        }
    }

    fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        if !is_program(index) {
            return self.app.begin_write(index, sub, size);
        }
        self.data_entry(index, sub)?;
        if self.running || self.flash & FLASH_IN_PROGRESS != 0 {
            return Err(AbortCode::CannotStoreDeviceState);
        }
        self.flash = FLASH_IN_PROGRESS;
        self.sink.begin(size).map_err(|code| self.failed(code, FLASH_UNSPECIFIED_ERROR))
    }

    fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        if !is_program(index) {
            return self.app.write_chunk(index, sub, offset, data);
        }
        self.data_entry(index, sub)?;
        if self.flash & FLASH_IN_PROGRESS == 0 {
            return Err(AbortCode::GeneralError);
        }
        self.sink.write_chunk(offset, data).map_err(|code| self.failed(code, FLASH_WRITE_ERROR))
    }

    fn end_write(&mut self, index: u16, sub: u8, total: usize) -> Result<(), AbortCode> {
        if !is_program(index) {
            return self.app.end_write(index, sub, total);
        }
        self.data_entry(index, sub)?;
        if self.flash & FLASH_IN_PROGRESS == 0 {
            return Err(AbortCode::GeneralError);
        }
        self.sink.end(total).map_err(|code| self.failed(code, FLASH_DATA_FORMAT_ERROR))?;
        self.flash = 0;
        Ok(())
    }

    fn abort_write(&mut self, index: u16, sub: u8) {
        if !is_program(index) {
            return self.app.abort_write(index, sub);
        }
        // Only a download in progress is abandoned; a failed step has told the sink already.
        if (index, sub) == (0x1F50, 1) && self.flash & FLASH_IN_PROGRESS != 0 {
            self.sink.abort();
            self.flash = FLASH_NO_VALID_PROGRAM;
        }
    }

    fn restore_defaults(&mut self) {
        self.app.restore_defaults()
    }

    fn write_events(&self) -> bool {
        self.app.write_events()
    }

    fn slot(&self, index: u16, sub: u8) -> u16 {
        self.app.slot(index, sub)
    }

    fn read_slot(&self, index: u16, sub: u8, slot: u16, offset: usize, buf: &mut [u8]) -> Result<(), AbortCode> {
        if is_program(index) {
            return crate::od::filled(self.read(index, sub, offset, buf)?, buf.len());
        }
        self.app.read_slot(index, sub, slot, offset, buf)
    }

    fn pdo_resolve(&self, index: u16, sub: u8, dir: crate::od::PdoDir) -> Result<crate::od::PdoHandle, AbortCode> {
        if is_program(index) {
            self.info(index, sub)?;
            return Err(AbortCode::NotMappable);
        }
        self.app.pdo_resolve(index, sub, dir)
    }

    fn pdo_read(&self, handle: &crate::od::PdoHandle, buf: &mut [u8]) -> Result<usize, AbortCode> {
        self.app.pdo_read(handle, buf)
    }

    fn pdo_write(&mut self, handle: &crate::od::PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
        self.app.pdo_write(handle, data)
    }
}

impl<P, A: OdDescribe> OdDescribe for ProgramDownload<P, A> {
    /// The four objects first (the derive refuses indices below 2000h, so the order stays increasing).
    fn object_count(&self) -> usize {
        OBJECTS.len() + self.app.object_count()
    }
    fn object(&self, n: usize) -> Option<ObjectDesc> {
        match OBJECTS.get(n) {
            Some(&(index, name, ..)) => Some(ObjectDesc { index, name, code: ObjectCode::Array, first: 0, subs: 2 }),
            None => self.app.object(n - OBJECTS.len()),
        }
    }
    fn object_index(&self, n: usize) -> Option<u16> {
        match OBJECTS.get(n) {
            Some(&(index, ..)) => Some(index),
            None => self.app.object_index(n - OBJECTS.len()),
        }
    }
    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
        if !is_program(index) {
            return self.app.entry(index, sub);
        }
        let &(index, _, data_type, access, name) = OBJECTS.iter().find(|o| o.0 == index)?;
        match sub {
            0 => Some(count_entry(index, 1)),
            1 => Some(EntryDesc::var(index, 1, name, data_type, access)),
            _ => None,
        }
    }
}
