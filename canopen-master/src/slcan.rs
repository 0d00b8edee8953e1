//! Serial CAN: the master on an slcan (LAWICEL) adapter ([`Slcan`]), a serial port (CANable, USBtin and the
//! like: `/dev/ttyACM0`, `COM3`) through the `serialport` crate or a TCP port (`tcp:HOST:PORT`, as QEMU's
//! serial port or a ser2net bridge) through tokio; and [`Interface`], which opens a SocketCAN name or an
//! `slcan:` one, so that a command line takes both. Off Linux (macOS, Windows) the master has slcan only:
//! `canopen-socketcan` is a Linux-only dependency.
//!
//! The lines are `canopen-slcan`'s: at open the master drops what a serial port had buffered, writes `C` (close, in case the adapter was left
//! open), `S`n when a bit rate was given (`slcan:/dev/ttyACM0@500000`), then `O`, and drops the frames of
//! the next [`SETTLE`] (an earlier session's, which a tty can deliver late). A reader (a tokio task for
//! TCP, a thread for a serial port, whose API blocks) decodes what the adapter sends; answers (`\r`, `z`,
//! BEL) are not frames and are dropped, bad lines and 29-bit frames are skipped and counted
//! ([`Slcan::counters`]), never a panic. The port closing ends the master's receive with an error.

use std::io::{self, Read, Write};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use canopen_core::CanFrame;
use canopen_slcan::{bitrate_code, encode_frame, Counters, Decoder, Message, MAX_LINE};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::sync::mpsc;

#[cfg(target_os = "linux")]
use crate::SocketCan;
use crate::{CanIo, IoFuture};

/// The serial line's baud rate (USB adapters ignore it; a UART adapter needs the one it was set to).
///
/// ```
/// assert_eq!(canopen_master::slcan::SERIAL_BAUD, 115_200);
/// ```
pub const SERIAL_BAUD: u32 = 115_200;

/// How long [`Slcan::open`] drops frames after it opened the channel.
///
/// ```
/// assert_eq!(canopen_master::slcan::SETTLE.as_millis(), 50);
/// ```
pub const SETTLE: Duration = Duration::from_millis(50);

/// What the reader hands to `recv`.
type Received = io::Result<CanFrame>;

/// How the master writes to the adapter.
enum Writer {
    Tcp(tokio::sync::Mutex<tokio::net::tcp::OwnedWriteHalf>),
    Serial(Arc<Mutex<Box<dyn serialport::SerialPort>>>),
}

/// Skipped input: the decoder's counters plus 29-bit frames (not CANopen, CAN-01).
///
/// ```
/// let c = canopen_master::slcan::SlcanCounters::default();
/// assert_eq!((c.lines.skipped(), c.extended), (0, 0));
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SlcanCounters {
    /// The line decoder's counters (frames, commands/answers, malformed, unknown, over-long lines).
    pub lines: Counters,
    /// 29-bit frames received and ignored.
    pub extended: u32,
}

/// The decoding side, shared by the reader and [`Slcan::counters`].
#[derive(Default)]
struct Reader {
    decoder: Decoder,
    extended: u32,
}

impl Reader {
    /// Feeds bytes; sends each 11-bit frame to `out`. Returns false once nobody receives.
    fn feed(&mut self, bytes: &[u8], out: &mpsc::UnboundedSender<Received>) -> bool {
        for &b in bytes {
            if let Some(Ok(Message::Frame(f))) = self.decoder.push(b) {
                match CanFrame::from_frame(&f) {
                    Some(frame) => {
                        if out.send(Ok(frame)).is_err() {
                            return false;
                        }
                    }
                    None => self.extended = self.extended.wrapping_add(1),
                }
            }
        }
        true
    }

    fn counters(&self) -> SlcanCounters {
        SlcanCounters { lines: self.decoder.counters(), extended: self.extended }
    }
}

/// The master's side of an slcan adapter.
///
/// ```no_run
/// # async fn demo() -> std::io::Result<()> {
/// use canopen_master::{slcan::Slcan, Master};
/// let master = Master::new(Slcan::open("tcp:127.0.0.1:5544").await?);
/// # Ok(()) }
/// ```
pub struct Slcan {
    writer: Writer,
    frames: tokio::sync::Mutex<mpsc::UnboundedReceiver<Received>>,
    reader: Arc<Mutex<Reader>>,
}

impl Slcan {
    /// Opens `spec`: `tcp:HOST:PORT` or a serial port's name, either followed by `@BITRATE` in bit/s
    /// (10000, 20000, 50000, 100000, 125000, 250000, 500000, 800000 or 1000000) to set the adapter's bit rate
    /// (`S`n); without it the adapter keeps its own. Then opens the channel (`C`, `S`n if a bit rate was given, `O`).
    ///
    /// ```no_run
    /// # async fn demo() -> std::io::Result<()> {
    /// let adapter = canopen_master::slcan::Slcan::open("/dev/ttyACM0@500000").await?;
    /// # Ok(()) }
    /// ```
    pub async fn open(spec: &str) -> io::Result<Self> {
        let (target, bitrate) = match spec.rsplit_once('@') {
            Some((t, rate)) => {
                let code = rate.parse().ok().and_then(bitrate_code).ok_or_else(|| {
                    invalid(format!("slcan bit rate {rate:?}: one of 10000, 20000, 50000, 100000, 125000, 250000, 500000, 800000, 1000000"))
                })?;
                (t, Some(code))
            }
            None => (spec, None),
        };
        let (tx, rx) = mpsc::unbounded_channel();
        let reader = Arc::new(Mutex::new(Reader::default()));
        let writer = match target.strip_prefix("tcp:") {
            Some(addr) => {
                let stream = tokio::net::TcpStream::connect(addr).await?;
                stream.set_nodelay(true)?;
                let (read, write) = stream.into_split();
                tokio::spawn(read_tcp(read, Arc::clone(&reader), tx));
                Writer::Tcp(tokio::sync::Mutex::new(write))
            }
            None => {
                if target.is_empty() {
                    return Err(invalid("slcan: no serial port or tcp:HOST:PORT given".into()));
                }
                let port = serialport::new(target, SERIAL_BAUD).timeout(Duration::from_millis(100)).open()?;
                // What the adapter sent before we opened (answers and frames of an earlier session, which a
                // tty keeps) is not for us: an old SDO response would be read as the answer to our request.
                port.clear(serialport::ClearBuffer::Input)?;
                let read = port.try_clone()?;
                let shared = Arc::clone(&reader);
                std::thread::Builder::new().name("slcan-reader".into()).spawn(move || read_serial(read, shared, tx))?;
                Writer::Serial(Arc::new(Mutex::new(port)))
            }
        };
        let slcan = Slcan { writer, frames: tokio::sync::Mutex::new(rx), reader };
        let mut start = vec![Message::Close];
        start.extend(bitrate.map(Message::Bitrate));
        start.push(Message::Open);
        for m in start {
            let mut line = [0u8; MAX_LINE];
            let n = m.encode(&mut line);
            slcan.write(line[..n].to_vec()).await?;
        }
        // Frames of an earlier session can still come in right after the channel opens, past the flush above
        // (the kernel's slcan on a pty delivered the frames sent while no program had the port open only
        // after this side wrote, in the with-vcan VM: an old SDO response then answered our first request).
        // Nothing can be an answer to us yet: drop what came in `SETTLE`.
        tokio::time::sleep(SETTLE).await;
        let mut frames = slcan.frames.lock().await;
        while let Ok(Ok(_)) = frames.try_recv() {}
        drop(frames);
        Ok(slcan)
    }

    /// What was skipped on receive so far (bad lines, 29-bit frames).
    ///
    /// ```no_run
    /// # async fn demo() -> std::io::Result<()> {
    /// let adapter = canopen_master::slcan::Slcan::open("tcp:127.0.0.1:5544").await?;
    /// println!("{} bad lines", adapter.counters().lines.skipped());
    /// # Ok(()) }
    /// ```
    pub fn counters(&self) -> SlcanCounters {
        lock(&self.reader).counters()
    }

    async fn write(&self, bytes: Vec<u8>) -> io::Result<()> {
        match &self.writer {
            Writer::Tcp(w) => w.lock().await.write_all(&bytes).await,
            Writer::Serial(port) => {
                let port = Arc::clone(port);
                // serialport's writes block: off the runtime's threads.
                tokio::task::spawn_blocking(move || lock(&port).write_all(&bytes))
                    .await
                    .map_err(|e| io::Error::other(format!("slcan writer: {e}")))?
            }
        }
    }
}

fn invalid(text: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, text)
}

/// A poisoned lock still holds consistent data here (counters, a port handle).
fn lock<T: ?Sized>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

async fn read_tcp(
    mut read: tokio::net::tcp::OwnedReadHalf,
    reader: Arc<Mutex<Reader>>,
    out: mpsc::UnboundedSender<Received>,
) {
    let mut buf = [0u8; 512];
    loop {
        match read.read(&mut buf).await {
            Ok(0) => {
                let _ = out.send(Err(io::Error::new(io::ErrorKind::UnexpectedEof, "slcan: the TCP port closed")));
                return;
            }
            Ok(n) => {
                if !lock(&reader).feed(&buf[..n], &out) {
                    return;
                }
            }
            Err(e) => {
                let _ = out.send(Err(e));
                return;
            }
        }
    }
}

fn read_serial(
    mut port: Box<dyn serialport::SerialPort>,
    reader: Arc<Mutex<Reader>>,
    out: mpsc::UnboundedSender<Received>,
) {
    let mut buf = [0u8; 512];
    loop {
        match port.read(&mut buf) {
            Ok(0) => {}
            Ok(n) => {
                if !lock(&reader).feed(&buf[..n], &out) {
                    return;
                }
            }
            // The read time-out only lets the thread notice that the master is gone.
            Err(e) if e.kind() == io::ErrorKind::TimedOut => {
                if out.is_closed() {
                    return;
                }
            }
            Err(e) => {
                let _ = out.send(Err(e));
                return;
            }
        }
    }
}

impl CanIo for Slcan {
    fn send<'a>(&'a self, frame: &'a CanFrame) -> IoFuture<'a, ()> {
        Box::pin(async move {
            let mut line = [0u8; MAX_LINE];
            let n = encode_frame(frame, &mut line);
            self.write(line[..n].to_vec()).await
        })
    }

    fn send_many<'a>(&'a self, frames: &'a [CanFrame]) -> IoFuture<'a, ()> {
        Box::pin(async move {
            // One write for a whole sub-block.
            let mut bytes = Vec::with_capacity(frames.len() * 24);
            for f in frames {
                let mut line = [0u8; MAX_LINE];
                let n = encode_frame(f, &mut line);
                bytes.extend_from_slice(&line[..n]);
            }
            self.write(bytes).await
        })
    }

    fn recv(&self) -> IoFuture<'_, CanFrame> {
        Box::pin(async move {
            match self.frames.lock().await.recv().await {
                Some(r) => r,
                None => Err(io::Error::new(io::ErrorKind::BrokenPipe, "slcan: the reader stopped")),
            }
        })
    }
}

/// A CAN interface by name: `slcan:SPEC` ([`Slcan::open`]) or, on Linux, a SocketCAN interface
/// (`SocketCan::open`).
///
/// ```no_run
/// # async fn demo() -> std::io::Result<()> {
/// use canopen_master::{slcan::Interface, Master};
/// let master = Master::new(Interface::open("slcan:tcp:127.0.0.1:5544").await?);
/// let other = Master::new(Interface::open("vcan0").await?);
/// # Ok(()) }
/// ```
pub enum Interface {
    /// A SocketCAN interface (Linux only).
    #[cfg(target_os = "linux")]
    SocketCan(SocketCan),
    /// An slcan adapter.
    Slcan(Slcan),
}

impl Interface {
    /// Opens `name`.
    ///
    /// ```no_run
    /// # async fn demo() -> std::io::Result<()> {
    /// let io = canopen_master::slcan::Interface::open("slcan:/dev/ttyACM0@250000").await?;
    /// # Ok(()) }
    /// ```
    pub async fn open(name: &str) -> io::Result<Self> {
        match name.strip_prefix("slcan:") {
            Some(spec) => Slcan::open(spec).await.map(Interface::Slcan),
            #[cfg(target_os = "linux")]
            None => SocketCan::open(name).map(Interface::SocketCan),
            #[cfg(not(target_os = "linux"))]
            None => Err(io::Error::new(
                io::ErrorKind::Unsupported,
                format!(
                    "{name}: SocketCAN exists on Linux only; an slcan adapter is slcan:PORT or slcan:tcp:HOST:PORT"
                ),
            )),
        }
    }
}

impl CanIo for Interface {
    fn send<'a>(&'a self, frame: &'a CanFrame) -> IoFuture<'a, ()> {
        match self {
            #[cfg(target_os = "linux")]
            Interface::SocketCan(io) => io.send(frame),
            Interface::Slcan(io) => io.send(frame),
        }
    }
    fn recv(&self) -> IoFuture<'_, CanFrame> {
        match self {
            #[cfg(target_os = "linux")]
            Interface::SocketCan(io) => io.recv(),
            Interface::Slcan(io) => io.recv(),
        }
    }
    fn send_many<'a>(&'a self, frames: &'a [CanFrame]) -> IoFuture<'a, ()> {
        match self {
            #[cfg(target_os = "linux")]
            Interface::SocketCan(io) => io.send_many(frames),
            Interface::Slcan(io) => io.send_many(frames),
        }
    }
    fn recv_many<'a>(&'a self, out: &'a mut Vec<CanFrame>) -> IoFuture<'a, usize> {
        match self {
            #[cfg(target_os = "linux")]
            Interface::SocketCan(io) => io.recv_many(out),
            Interface::Slcan(io) => io.recv_many(out),
        }
    }
    fn reopen(&self) -> IoFuture<'_, bool> {
        match self {
            #[cfg(target_os = "linux")]
            Interface::SocketCan(io) => io.reopen(),
            Interface::Slcan(io) => io.reopen(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tokio::net::TcpListener;

    /// A fake adapter on a local TCP port: returns the master, the adapter's end of the link.
    async fn pair(spec_tail: &str) -> (Slcan, tokio::net::TcpStream) {
        let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        let spec = format!("tcp:{addr}{spec_tail}");
        let (slcan, accepted) = tokio::join!(Slcan::open(&spec), listener.accept());
        (slcan.unwrap(), accepted.unwrap().0)
    }

    async fn read_exactly(peer: &mut tokio::net::TcpStream, n: usize) -> Vec<u8> {
        let mut buf = vec![0u8; n];
        peer.read_exact(&mut buf).await.unwrap();
        buf
    }

    #[tokio::test]
    async fn open_closes_sets_the_bit_rate_and_opens() {
        let (_slcan, mut peer) = pair("@500000").await;
        assert_eq!(read_exactly(&mut peer, 7).await, b"C\rS6\rO\r");
        let (_slcan, mut peer) = pair("").await;
        assert_eq!(read_exactly(&mut peer, 4).await, b"C\rO\r");
    }

    #[tokio::test]
    async fn a_bad_bit_rate_is_refused() {
        let e = Slcan::open("tcp:127.0.0.1:1@83333").await.err().unwrap();
        assert_eq!(e.kind(), io::ErrorKind::InvalidInput);
        assert_eq!(Slcan::open("").await.err().unwrap().kind(), io::ErrorKind::InvalidInput);
    }

    #[tokio::test]
    async fn frames_both_ways_and_bad_input_skipped_and_counted() {
        let (slcan, mut peer) = pair("").await;
        read_exactly(&mut peer, 4).await;
        slcan.send(&CanFrame::new(0x605, &[0x40, 0x00, 0x10, 0x00]).unwrap()).await.unwrap();
        assert_eq!(read_exactly(&mut peer, 14).await, b"t605440001000\r");
        let two = [CanFrame::new(0x80, &[]).unwrap(), CanFrame::new(0x000, &[1, 5]).unwrap()];
        slcan.send_many(&two).await.unwrap();
        assert_eq!(read_exactly(&mut peer, 16).await, b"t0800\rt00020105\r");

        // Answers, garbage, an over-long line, a lost CR, a 29-bit frame, then good frames.
        let long = format!("t{}\r", "7".repeat(60));
        let input = [b"\rz\r\x07hello\r".as_slice(), long.as_bytes(), b"t1230t1231AA\rT1FFFFFFF0\rt5850\rt7051\x7f\r"];
        for part in input {
            peer.write_all(part).await.unwrap();
        }
        peer.write_all(b"t70517F\r").await.unwrap();
        let first = slcan.recv().await.unwrap();
        assert_eq!((first.cob_id(), first.data()), (0x585, &[0u8; 0][..]));
        let second = slcan.recv().await.unwrap();
        assert_eq!((second.cob_id(), second.data()), (0x705, &[0x7F][..]));
        let c = slcan.counters();
        // hello: unknown; the 61-char line: over-long; the merged frames and "t7051\x7f": malformed.
        assert_eq!((c.lines.unknown, c.lines.overlong, c.lines.malformed, c.extended), (1, 1, 2, 1));
        assert_eq!(c.lines.commands, 3); // ok, z, BEL: answers, not frames

        drop(peer);
        assert!(slcan.recv().await.is_err(), "a closed port ends receiving");
    }

    #[tokio::test]
    async fn interface_opens_slcan_names() {
        let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        let name = format!("slcan:tcp:{addr}");
        let (io, _) = tokio::join!(Interface::open(&name), listener.accept());
        assert!(matches!(io.unwrap(), Interface::Slcan(_)));
    }
}
