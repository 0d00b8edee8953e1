//! A blocking CANopen master on a [`BlockingBus`]: the core's sans-IO [`SdoClient`] driven frame by frame,
//! NMT node control, and heartbeat observation. Used by the `master` example, the vcan load test and the
//! throughput bench.
//!
//! The socket only receives the server's SDO responses (580h + node) and error-control frames (700h +
//! node), filtered in the kernel, so a busy bus costs the master nothing.

use std::fmt;
use std::io;
use std::time::Duration as StdDuration;

use canopen_core::od::{copy_at, AbortCode};
use canopen_core::sdo::client::{ClientData, ClientError, ClientEvent, Mode, SdoClient};
use canopen_core::sdo::SdoClientParams;
use canopen_core::wire::nmt::NmtCommand;
use canopen_core::wire::sdo::Multiplexer;
use canopen_core::{CanFrame, Duration, Instant, NodeId};

use crate::{AdapterEvent, BlockingBus, Rx};

/// Why a master operation failed.
#[derive(Debug)]
pub enum MasterError {
    /// The socket failed.
    Io(io::Error),
    /// The transfer was aborted (by the server or by the client, e.g. on a time-out).
    Sdo(ClientError),
}

impl fmt::Display for MasterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MasterError::Io(e) => write!(f, "{e}"),
            MasterError::Sdo(ClientError::Server(code)) => write!(f, "aborted by the server: {code:08X}h"),
            MasterError::Sdo(ClientError::Local(code)) => {
                write!(f, "aborted by the client: {:08X}h ({code:?})", code.code())
            }
        }
    }
}

impl std::error::Error for MasterError {}

impl From<io::Error> for MasterError {
    fn from(e: io::Error) -> Self {
        MasterError::Io(e)
    }
}

impl MasterError {
    /// The SDO abort code, if the transfer was aborted.
    pub fn abort_code(&self) -> Option<u32> {
        match self {
            MasterError::Sdo(e) => Some(e.code()),
            MasterError::Io(_) => None,
        }
    }
}

/// How long the line must be quiet after a failed transfer before the next one starts.
pub const QUIET: StdDuration = StdDuration::from_millis(50);

/// The bytes of one SDO transfer for the core's client ([`ClientData`]) over a `Vec`: a download reads
/// `src`; an upload writes into `buf`, which grows up to `cap` bytes (a longer value aborts the transfer
/// with 0504 0005h, out of memory, instead of growing without bound). Used by this blocking [`Master`] and
/// by `canopen-master`.
///
/// ```
/// use canopen_core::sdo::client::ClientData;
/// use canopen_socketcan::master::VecData;
/// let mut up = VecData::upload(4);
/// up.write(0, &[1, 2, 3]).unwrap();
/// assert_eq!(up.buf, [1, 2, 3]);
/// assert_eq!(up.write(3, &[4, 5]).unwrap_err().code(), 0x0504_0005);
/// let mut down = VecData::download(&[9, 8, 7]);
/// let mut seg = [0; 2];
/// assert_eq!((down.download_len(), down.read(1, &mut seg)), (3, 2));
/// assert_eq!(seg, [8, 7]);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VecData<'a> {
    /// The bytes uploaded so far.
    pub buf: Vec<u8>,
    /// At most this many bytes are uploaded.
    pub cap: usize,
    /// The bytes to download.
    pub src: &'a [u8],
}

impl<'a> VecData<'a> {
    /// An upload of at most `cap` bytes.
    ///
    /// ```
    /// assert!(canopen_socketcan::master::VecData::upload(64).buf.is_empty());
    /// ```
    pub fn upload(cap: usize) -> Self {
        VecData { buf: Vec::new(), cap, src: &[] }
    }

    /// A download of `src`.
    ///
    /// ```
    /// assert_eq!(canopen_socketcan::master::VecData::download(&[1, 2]).src, [1, 2]);
    /// ```
    pub fn download(src: &'a [u8]) -> Self {
        VecData { buf: Vec::new(), cap: 0, src }
    }
}

impl ClientData for VecData<'_> {
    fn download_len(&self) -> usize {
        self.src.len()
    }
    fn read(&mut self, offset: usize, buf: &mut [u8]) -> usize {
        copy_at(self.src, offset, buf)
    }
    fn write(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        let end = offset.checked_add(data.len()).filter(|&e| e <= self.cap).ok_or(AbortCode::OutOfMemory)?;
        if self.buf.len() < end {
            self.buf.resize(end, 0);
        }
        self.buf[offset..end].copy_from_slice(data);
        Ok(())
    }
}

/// Counts of what the master moved (for the bench).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MasterStats {
    /// Frames sent.
    pub sent: u64,
    /// SDO responses received.
    pub received: u64,
}

/// A blocking master talking to one node.
///
/// ```no_run
/// use canopen_core::{sdo::client::Mode, NodeId};
/// use canopen_socketcan::{BlockingBus, Master};
/// let mut m = Master::new(BlockingBus::open("vcan0")?, NodeId::new(5).unwrap())?;
/// let device_type = m.upload(0x1000, 0, Mode::Auto, 4)?;
/// m.download(0x2000, 0, &[7], Mode::Auto)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Master {
    bus: BlockingBus,
    node: NodeId,
    client: SdoClient,
    stats: MasterStats,
    events: Vec<AdapterEvent>,
}

impl Master {
    /// A master for `node` on `bus` (which it filters to 580h + node and 700h + node). SDO time-out 1 s.
    pub fn new(mut bus: BlockingBus, node: NodeId) -> io::Result<Self> {
        let n = u32::from(node.get());
        bus.set_filters(&[(0x580 + n, 0x7FF), (0x700 + n, 0x7FF)])?;
        let client = SdoClient::new(SdoClientParams::for_server(node)).with_timeout(Duration::from_millis(1000));
        Ok(Master { bus, node, client, stats: MasterStats::default(), events: Vec::new() })
    }

    /// Sets the SDO time-out.
    pub fn set_timeout(&mut self, timeout: StdDuration) {
        let params = *self.client.params();
        self.client = SdoClient::new(params).with_timeout(Duration::from_micros(timeout.as_micros() as u64));
    }

    /// The node this master talks to.
    pub fn node(&self) -> NodeId {
        self.node
    }

    /// Frames moved so far.
    pub fn stats(&self) -> MasterStats {
        self.stats
    }

    /// Adapter events seen so far (error frames, a full send buffer), drained.
    pub fn take_adapter_events(&mut self) -> Vec<AdapterEvent> {
        std::mem::take(&mut self.events)
    }

    /// Writes `data` to `index:sub`.
    pub fn download(&mut self, index: u16, sub: u8, data: &[u8], mode: Mode) -> Result<(), MasterError> {
        let mut d = VecData::download(data);
        let now = self.bus.now();
        let _ = self.client.abort(AbortCode::GeneralError);
        self.client
            .start_download(now, Multiplexer::new(index, sub), data.len(), mode)
            .map_err(|_| MasterError::Io(io::Error::new(io::ErrorKind::InvalidInput, "transfer too large for SDO")))?;
        self.drive(&mut d).map(|_| ())
    }

    /// Reads `index:sub` (at most `cap` bytes; more aborts with 0504 0005h).
    pub fn upload(&mut self, index: u16, sub: u8, mode: Mode, cap: usize) -> Result<Vec<u8>, MasterError> {
        let mut d = VecData::upload(cap);
        let now = self.bus.now();
        let _ = self.client.abort(AbortCode::GeneralError);
        self.client
            .start_upload(now, Multiplexer::new(index, sub), mode)
            .map_err(|_| MasterError::Io(io::Error::other("SDO client busy")))?;
        let len = self.drive(&mut d)?;
        d.buf.truncate(len);
        Ok(d.buf)
    }

    fn send(&mut self, frame: &CanFrame) -> io::Result<()> {
        let events = &mut self.events;
        self.bus.send(frame, &mut |e| events.push(e))?;
        self.stats.sent += 1;
        Ok(())
    }

    fn flush_client(&mut self, data: &mut VecData<'_>) -> io::Result<()> {
        let cob = self.client.params().tx_cob_id();
        while let Some(bytes) = self.client.poll_transmit(self.bus.now(), data) {
            self.send(&CanFrame::from_parts(cob, bytes, 8))?;
        }
        Ok(())
    }

    fn drive(&mut self, data: &mut VecData<'_>) -> Result<usize, MasterError> {
        let rx_cob = self.client.params().rx_cob_id();
        loop {
            self.flush_client(data)?;
            let event = match self.bus.recv_until(self.client.poll_timeout())? {
                Rx::Frame(f) if f.cob_id() == rx_cob && !f.is_rtr() => {
                    self.stats.received += 1;
                    let now = self.bus.now();
                    self.client.handle_response(now, f.data(), data)
                }
                Rx::Frame(_) => None,
                Rx::Adapter(e) => {
                    self.events.push(e);
                    None
                }
                Rx::Timeout => self.client.handle_timeout(self.bus.now()),
            };
            match event {
                None => {}
                Some(ClientEvent::Done { len }) => {
                    self.flush_client(data)?;
                    return Ok(len);
                }
                Some(ClientEvent::Failed(e)) => {
                    self.flush_client(data)?;
                    self.drain()?;
                    return Err(MasterError::Sdo(e));
                }
            }
        }
    }

    /// After a failed transfer: discards what the server still sends for it (late responses, the rest of a
    /// sub-block) until the line is quiet for [`QUIET`], so that the next transfer does not take a stale
    /// frame for its answer.
    fn drain(&mut self) -> io::Result<()> {
        loop {
            let until = Instant::from_micros(self.bus.now().as_micros() + QUIET.as_micros() as u64);
            match self.bus.recv_until(Some(until))? {
                Rx::Timeout => return Ok(()),
                Rx::Adapter(e) => self.events.push(e),
                Rx::Frame(_) => {}
            }
        }
    }

    /// Sends an NMT node-control command to this node (or to all nodes with `broadcast`).
    pub fn nmt(&mut self, command: NmtCommand, broadcast: bool) -> io::Result<()> {
        let target = if broadcast { 0 } else { self.node.get() };
        let frame = CanFrame::new(0x000, &[command as u8, target]).ok_or_else(|| io::Error::other("frame"))?;
        self.send(&frame)
    }

    /// Waits up to `timeout` for the node's next error-control frame (boot-up 00h or a heartbeat state) and
    /// returns its state byte.
    pub fn wait_heartbeat(&mut self, timeout: StdDuration) -> io::Result<Option<u8>> {
        let cob = 0x700 + u16::from(self.node.get());
        let deadline = Instant::from_micros(self.bus.now().as_micros() + timeout.as_micros() as u64);
        loop {
            match self.bus.recv_until(Some(deadline))? {
                Rx::Frame(f) if f.cob_id() == cob && !f.is_rtr() && f.dlc() == 1 => {
                    return Ok(Some(f.data()[0] & 0x7F))
                }
                Rx::Frame(_) => {}
                Rx::Adapter(e) => self.events.push(e),
                Rx::Timeout => return Ok(None),
            }
        }
    }

    /// Waits until a heartbeat of the node reports `state` (04h, 05h, 7Fh; 00h for a boot-up), skipping
    /// heartbeats with other states, which may have been sent before the node acted on a command.
    /// Returns `false` when `timeout` passes first.
    ///
    /// ```no_run
    /// use std::time::Duration;
    /// use canopen_core::{wire::nmt::NmtCommand, NodeId};
    /// use canopen_socketcan::{BlockingBus, Master};
    /// let mut m = Master::new(BlockingBus::open("vcan0")?, NodeId::new(5).unwrap())?;
    /// m.nmt(NmtCommand::Start, false)?;
    /// assert!(m.wait_state(0x05, Duration::from_secs(2))?);
    /// # Ok::<(), std::io::Error>(())
    /// ```
    pub fn wait_state(&mut self, state: u8, timeout: StdDuration) -> io::Result<bool> {
        let start = std::time::Instant::now();
        while let Some(left) = timeout.checked_sub(start.elapsed()) {
            match self.wait_heartbeat(left)? {
                Some(s) if s == state => return Ok(true),
                Some(_) => {}
                None => return Ok(false),
            }
        }
        Ok(false)
    }

    /// The underlying bus.
    pub fn bus(&self) -> &BlockingBus {
        &self.bus
    }
}
