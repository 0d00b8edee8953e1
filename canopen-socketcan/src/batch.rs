//! Batched socket calls for the runners and the async master (`canopen-master`): `recvmmsg` takes every
//! queued frame (up to [`BATCH`]) in one system call ([`BatchReceiver`]), `sendmmsg` sends a whole pass's
//! frames (or an SDO block transfer's sub-block) in one ([`send_frames`]), `ppoll` waits for the socket, the wake-up
//! socket and the next deadline together; plus the monotonic clock and the `timerfd` the tokio runner
//! sleeps on. The `socketcan` crate reads and writes one frame per call, so these calls go through `libc`
//! (and tokio's `AsyncFd::register` is `unsafe` too); this module is the adapter's only `unsafe` code.
//!
//! Safety argument, once for all three: every pointer handed to the kernel points into a buffer that this
//! function owns or borrows for the whole call (`msghdr`/`iovec`/`pollfd` arrays on the stack, the caller's
//! frame slice), every length is the length of that buffer, and the kernel writes only within the lengths
//! given. A `can_frame` is plain old data (integers and a byte array), so any bytes the kernel writes are a
//! valid value. A raw CAN socket without CAN FD enabled (the adapter never enables it) delivers exactly one
//! 16-byte `can_frame` per message.

#![allow(unsafe_code)]

use std::io;
use std::mem::MaybeUninit;
use std::os::fd::RawFd;

/// Frames taken or sent per system call at most.
pub const BATCH: usize = 64;

/// The `iovec`s and `mmsghdr`s of one send for the first `n` of `frames`, each message one frame. Only
/// those `n` entries are written (an expedited reply writes one, not 5 KiB).
fn messages(
    frames: *mut libc::can_frame,
    n: usize,
    iov: &mut [MaybeUninit<libc::iovec>; BATCH],
    msgs: &mut [MaybeUninit<libc::mmsghdr>; BATCH],
) {
    for i in 0..n.min(BATCH) {
        // `frames.wrapping_add(i)` stays within the caller's buffer of at least `n` frames.
        let base = frames.wrapping_add(i).cast();
        let v = iov[i].write(libc::iovec { iov_base: base, iov_len: std::mem::size_of::<libc::can_frame>() });
        // SAFETY: mmsghdr is plain old data; zeroed = no name, no control data.
        let mut m: libc::mmsghdr = unsafe { std::mem::zeroed() };
        m.msg_hdr.msg_iov = v;
        m.msg_hdr.msg_iovlen = 1;
        msgs[i].write(m);
    }
}

/// The buffers of [`Receiver::recv_frames`]: [`BATCH`] frames and the `iovec`s and `mmsghdr`s pointing at
/// them, written once (5 KiB: zeroing them on every call cost more instructions than the rest of a pass).
struct RecvBufs {
    frames: [libc::can_frame; BATCH],
    iov: [libc::iovec; BATCH],
    msgs: [libc::mmsghdr; BATCH],
}

/// Receive buffers for `recvmmsg` ([`BATCH`] frames and the kernel's message headers pointing at them),
/// set up once and reused by every call; on the heap so that the pointers between them stay valid wherever
/// the `BatchReceiver` moves. The runners keep one each; so does `canopen-master`'s receive task
/// ([`TokioBus::recv_many`](crate::TokioBus::recv_many)).
///
/// ```
/// use std::os::fd::AsRawFd;
/// use std::os::unix::net::UnixDatagram;
/// use canopen_socketcan::{send_frames, BatchReceiver};
/// // A datagram socket pair stands in for a CAN socket (one 16-byte can_frame per message).
/// let (a, b) = UnixDatagram::pair()?;
/// let frame = |i: usize| {
///     let mut f: libc::can_frame = unsafe { std::mem::zeroed() };
///     (f.can_id, f.can_dlc, f.data[0]) = (0x585, 1, i as u8);
///     Ok(f)
/// };
/// assert_eq!(send_frames(a.as_raw_fd(), 3, frame)?, 3); // one sendmmsg
/// let mut rx = BatchReceiver::new();
/// let mut got = Vec::new();
/// assert_eq!(rx.recv_frames(b.as_raw_fd(), |raw| got.extend(raw.iter().map(|f| f.data[0])))?, 3); // one recvmmsg
/// assert_eq!(got, [0, 1, 2]);
/// assert_eq!(rx.recv_frames(b.as_raw_fd(), |_| unreachable!())?, 0); // nothing queued
/// # Ok::<(), std::io::Error>(())
/// ```
pub struct BatchReceiver(Box<RecvBufs>);

// SAFETY: the raw pointers in `RecvBufs` point only into the same heap allocation, which moves (between
// threads too) with the `BatchReceiver` that owns it and is used only through `&mut self`.
unsafe impl Send for BatchReceiver {}

impl Default for BatchReceiver {
    fn default() -> Self {
        BatchReceiver::new()
    }
}

impl std::fmt::Debug for BatchReceiver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("BatchReceiver")
    }
}

impl BatchReceiver {
    /// Buffers for [`BATCH`] frames (about 5 KiB, one allocation).
    ///
    /// ```
    /// let rx = canopen_socketcan::BatchReceiver::new();
    /// ```
    pub fn new() -> Self {
        // SAFETY: can_frame, iovec and mmsghdr are plain old data; all-zero bytes are valid values (null
        // pointers, no name, no control data).
        let mut b: Box<RecvBufs> = Box::new(unsafe { std::mem::zeroed() });
        let bufs = &mut *b;
        for i in 0..BATCH {
            bufs.iov[i] = libc::iovec {
                iov_base: (&mut bufs.frames[i] as *mut libc::can_frame).cast(),
                iov_len: std::mem::size_of::<libc::can_frame>(),
            };
            bufs.msgs[i].msg_hdr.msg_iov = &mut bufs.iov[i];
            bufs.msgs[i].msg_hdr.msg_iovlen = 1;
        }
        BatchReceiver(b)
    }

    /// Takes up to [`BATCH`] queued frames from the socket `fd` without waiting (one `recvmmsg`), oldest
    /// first, and hands them to `take` (not called when none is queued). Returns how many were taken:
    /// `Ok(0)` when none is queued; fewer than [`BATCH`] means the queue was empty at the end of the call.
    /// Messages that are not a whole `can_frame` (impossible on a CAN_RAW socket) end the batch.
    ///
    /// ```no_run
    /// # fn demo(fd: std::os::fd::RawFd) -> std::io::Result<()> {
    /// let mut rx = canopen_socketcan::BatchReceiver::new();
    /// let n = rx.recv_frames(fd, |frames| println!("{} frames", frames.len()))?;
    /// # Ok(()) }
    /// ```
    pub fn recv_frames(&mut self, fd: RawFd, take: impl FnOnce(&[libc::can_frame])) -> io::Result<usize> {
        let size = std::mem::size_of::<libc::can_frame>();
        let bufs = &mut *self.0;
        loop {
            // SAFETY: see the module docs; `msgs` point at `iov`, which point at `frames`, all in `bufs`,
            // borrowed mutably for the call.
            let r = unsafe {
                libc::recvmmsg(
                    fd,
                    bufs.msgs.as_mut_ptr(),
                    BATCH as libc::c_uint,
                    libc::MSG_DONTWAIT,
                    std::ptr::null_mut(),
                )
            };
            if r >= 0 {
                let got = r as usize;
                // A short message (not a whole can_frame) cannot come from a CAN_RAW socket; drop it
                // rather than hand on a partly written frame.
                let whole = bufs.msgs[..got].iter().position(|m| m.msg_len as usize != size).unwrap_or(got);
                if whole > 0 {
                    take(&bufs.frames[..whole]);
                }
                return Ok(whole);
            }
            let e = io::Error::last_os_error();
            match e.kind() {
                io::ErrorKind::WouldBlock => return Ok(0),
                io::ErrorKind::Interrupted => continue,
                _ => return Err(e),
            }
        }
    }
}

/// Sends `count` frames on the socket `fd`, the `i`th made by `frame(i)`, in order without waiting, one
/// `sendmmsg` per [`BATCH`] frames. Returns how many went out: a prefix (the rest must be sent again, in
/// order, e.g. after a back-off when the queue is full). An error is returned only when not even the first
/// frame went out (`ENOBUFS`/`EAGAIN` for a full queue, `ENETDOWN` for an interface that went down), or
/// when `frame` failed. See [`BatchReceiver`] for an example.
///
/// ```no_run
/// # fn demo(fd: std::os::fd::RawFd, frames: &[libc::can_frame]) -> std::io::Result<()> {
/// let sent = canopen_socketcan::send_frames(fd, frames.len(), |i| Ok(frames[i]))?;
/// # Ok(()) }
/// ```
pub fn send_frames(fd: RawFd, count: usize, frame: impl Fn(usize) -> io::Result<libc::can_frame>) -> io::Result<usize> {
    let mut sent = 0;
    while sent < count {
        let n = (count - sent).min(BATCH);
        let mut buf = [MaybeUninit::<libc::can_frame>::uninit(); BATCH];
        for (i, b) in buf[..n].iter_mut().enumerate() {
            b.write(frame(sent + i)?);
        }
        let mut iov = [MaybeUninit::<libc::iovec>::uninit(); BATCH];
        let mut msgs = [MaybeUninit::<libc::mmsghdr>::uninit(); BATCH];
        // The kernel only reads through iov_base for a send.
        messages(buf.as_mut_ptr().cast(), n, &mut iov, &mut msgs);
        // SAFETY: see the module docs; `msgs[..n]`, `iov[..n]` and `buf[..n]` are written and point at each
        // other in that order.
        let r = unsafe { libc::sendmmsg(fd, msgs.as_mut_ptr().cast(), n as libc::c_uint, libc::MSG_DONTWAIT) };
        if r < 0 {
            let e = io::Error::last_os_error();
            if e.kind() == io::ErrorKind::Interrupted {
                continue;
            }
            return if sent == 0 { Err(e) } else { Ok(sent) };
        }
        sent += r as usize;
        if (r as usize) < n {
            return Ok(sent); // the queue filled up part-way
        }
    }
    Ok(sent)
}

/// Waits until one of `fds` is readable or `timeout` (µs; `None` = forever) passed. Returns, per fd,
/// whether it is readable (all false on time-out or a signal).
pub(crate) fn wait_readable<const K: usize>(fds: [RawFd; K], timeout_us: Option<u64>) -> io::Result<[bool; K]> {
    let mut pfds = fds.map(|fd| libc::pollfd { fd, events: libc::POLLIN, revents: 0 });
    let ts = timeout_us.map(|us| libc::timespec {
        tv_sec: (us / 1_000_000).min(i64::MAX as u64) as libc::time_t,
        tv_nsec: ((us % 1_000_000) * 1000) as libc::c_long,
    });
    let ts_ptr = ts.as_ref().map_or(std::ptr::null(), |t| t as *const libc::timespec);
    // SAFETY: see the module docs; `pfds` has K entries, `ts_ptr` is null or points at `ts`.
    let r = unsafe { libc::ppoll(pfds.as_mut_ptr(), K as libc::nfds_t, ts_ptr, std::ptr::null()) };
    if r < 0 {
        let e = io::Error::last_os_error();
        return if e.kind() == io::ErrorKind::Interrupted { Ok([false; K]) } else { Err(e) };
    }
    Ok(pfds.map(|p| p.revents & (libc::POLLIN | libc::POLLERR | libc::POLLHUP) != 0))
}

/// `CLOCK_MONOTONIC` in microseconds (the clock `std::time::Instant` reads on Linux).
pub(crate) fn monotonic_us() -> u64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: `ts` is a timespec alive for the call; CLOCK_MONOTONIC always exists on Linux.
    unsafe { libc::clock_gettime(libc::CLOCK_MONOTONIC, &mut ts) };
    ts.tv_sec as u64 * 1_000_000 + ts.tv_nsec as u64 / 1000
}

/// A non-blocking `timerfd` on `CLOCK_MONOTONIC`, disarmed.
#[cfg(any(feature = "tokio", test))]
pub(crate) fn timerfd() -> io::Result<std::os::fd::OwnedFd> {
    // SAFETY: no pointers; a returned descriptor is a fresh one this process owns.
    let fd = unsafe { libc::timerfd_create(libc::CLOCK_MONOTONIC, libc::TFD_NONBLOCK | libc::TFD_CLOEXEC) };
    if fd < 0 {
        return Err(io::Error::last_os_error());
    }
    // SAFETY: `fd` was just returned by timerfd_create and is owned by nobody else.
    Ok(unsafe { <std::os::fd::OwnedFd as std::os::fd::FromRawFd>::from_raw_fd(fd) })
}

/// When a [`timerfd`] fires.
#[cfg(any(feature = "tokio", test))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Expiry {
    /// At this `CLOCK_MONOTONIC` time (µs; a past one fires at once).
    At(u64),
    /// This many µs from now (at least 1).
    In(u64),
    /// Never (disarmed).
    Never,
}

/// Arms or disarms a [`timerfd`] (one-shot). Arming also clears an expiry not yet read, so the descriptor
/// is readable only after the new expiry.
#[cfg(any(feature = "tokio", test))]
pub(crate) fn set_timerfd(fd: RawFd, expiry: Expiry) -> io::Result<()> {
    let ts = |us: u64| libc::timespec {
        tv_sec: (us / 1_000_000).min(i64::MAX as u64) as libc::time_t,
        tv_nsec: ((us % 1_000_000) * 1000) as libc::c_long,
    };
    // An all-zero it_value disarms: an expiry at or in 0 µs is 1 µs.
    let (flags, value) = match expiry {
        Expiry::At(us) => (libc::TFD_TIMER_ABSTIME, ts(us.max(1))),
        Expiry::In(us) => (0, ts(us.max(1))),
        Expiry::Never => (0, ts(0)),
    };
    let spec = libc::itimerspec { it_interval: ts(0), it_value: value };
    // SAFETY: `spec` is an itimerspec alive for the call; the old value is not asked for (null).
    if unsafe { libc::timerfd_settime(fd, flags, &spec, std::ptr::null_mut()) } != 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(())
}

/// Sets the socket's receive buffer to at least `bytes` (`SO_RCVBUFFORCE` when privileged, else
/// `SO_RCVBUF`, which the kernel caps at `net.core.rmem_max`). Returns the size the kernel reports.
pub(crate) fn grow_receive_buffer(fd: RawFd, bytes: usize) -> io::Result<usize> {
    let val = bytes.min(i32::MAX as usize / 2) as libc::c_int;
    let len = std::mem::size_of::<libc::c_int>() as libc::socklen_t;
    let p = (&val as *const libc::c_int).cast();
    // SAFETY: `p` points at a c_int of `len` bytes, alive for the call.
    if unsafe { libc::setsockopt(fd, libc::SOL_SOCKET, libc::SO_RCVBUFFORCE, p, len) } != 0 {
        // SAFETY: as above.
        if unsafe { libc::setsockopt(fd, libc::SOL_SOCKET, libc::SO_RCVBUF, p, len) } != 0 {
            return Err(io::Error::last_os_error());
        }
    }
    let mut got: libc::c_int = 0;
    let mut got_len = len;
    // SAFETY: `got` is a c_int of `got_len` bytes, alive for the call.
    if unsafe {
        libc::getsockopt(fd, libc::SOL_SOCKET, libc::SO_RCVBUF, (&mut got as *mut libc::c_int).cast(), &mut got_len)
    } != 0
    {
        return Err(io::Error::last_os_error());
    }
    Ok(got as usize)
}

/// Registers a non-blocking descriptor (the CAN socket, the runner's `timerfd`) with tokio's reactor
/// (inside a tokio runtime), for readability only: with write interest too, every send makes the socket's
/// "writable" edge wake the runtime for nothing (seen with strace: one extra `epoll_wait` and three clock
/// reads of tokio per frame sent). A full send queue is retried after a back-off instead
/// ([`ENOBUFS_BACKOFF`](crate::ENOBUFS_BACKOFF)).
#[cfg(feature = "tokio")]
pub(crate) fn register<T: Owns>(owner: T) -> io::Result<tokio::io::unix::AsyncFd<T>> {
    // SAFETY: `T: Owns` owns its descriptor: it stays open, and `as_raw_fd` returns the same one, until
    // `owner` is dropped, which the `AsyncFd` that owns it does last.
    unsafe { tokio::io::unix::AsyncFd::register_with_interest(owner, tokio::io::Interest::READABLE) }
        .map_err(|e| e.into_parts().1)
}

/// A type that owns the descriptor it returns from `as_raw_fd` (closes it on drop, never swaps it).
#[cfg(feature = "tokio")]
pub(crate) trait Owns: std::os::fd::AsRawFd {}
#[cfg(feature = "tokio")]
impl Owns for socketcan::CanSocket {}
#[cfg(feature = "tokio")]
impl Owns for std::os::fd::OwnedFd {}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::fd::AsRawFd;
    use std::os::unix::net::UnixDatagram;

    fn frame(id: u32, b: u8) -> libc::can_frame {
        // SAFETY: can_frame is plain old data; all-zero bytes are a valid value.
        let mut f: libc::can_frame = unsafe { std::mem::zeroed() };
        f.can_id = id;
        f.can_dlc = 1;
        f.data[0] = b;
        f
    }

    /// Batches keep their order, a partial send reports the prefix that went out, nothing queued reads as
    /// 0, and the wait reports which fd is readable. A datagram socket pair stands in for a CAN socket
    /// (one message per frame, as CAN_RAW delivers them).
    #[test]
    fn batches_keep_order_and_report_partial_sends() {
        let (a, b) = UnixDatagram::pair().unwrap();
        let frames: Vec<libc::can_frame> = (0..100).map(|i| frame(0x100 + i, i as u8)).collect();
        let mut sent = 0;
        let mut got = Vec::new();
        let mut rx = BatchReceiver::new();
        while sent < frames.len() {
            // A small socket queue makes sends partial; the prefix rule lets the caller resume in order.
            match send_frames(a.as_raw_fd(), frames.len() - sent, |i| Ok(frames[sent + i])) {
                Ok(n) => sent += n,
                Err(e) => assert_eq!(e.kind(), io::ErrorKind::WouldBlock),
            }
            rx.recv_frames(b.as_raw_fd(), |raw| got.extend(raw.iter().map(|f| (f.can_id, f.data[0])))).unwrap();
        }
        while rx.recv_frames(b.as_raw_fd(), |raw| got.extend(raw.iter().map(|f| (f.can_id, f.data[0])))).unwrap() > 0 {}
        let want: Vec<(u32, u8)> = frames.iter().map(|f| (f.can_id, f.data[0])).collect();
        assert_eq!(got, want);
        assert_eq!(wait_readable([a.as_raw_fd(), b.as_raw_fd()], Some(1000)).unwrap(), [false, false]);
        send_frames(b.as_raw_fd(), 1, |_| Ok(frame(1, 1))).unwrap();
        assert_eq!(wait_readable([b.as_raw_fd(), a.as_raw_fd()], None).unwrap(), [false, true]);
        assert!(grow_receive_buffer(a.as_raw_fd(), 1 << 16).unwrap() > 0);
    }

    /// The timerfd fires at an absolute time, after a relative delay, never when disarmed, and re-arming
    /// clears an expiry that was not read.
    #[test]
    fn timerfd_fires_when_armed_and_rearming_clears_it() {
        let t = timerfd().unwrap();
        let fd = t.as_raw_fd();
        let readable = |ms: u64| wait_readable([fd], Some(ms * 1000)).unwrap()[0];
        assert!(!readable(5), "a fresh timerfd is disarmed");
        set_timerfd(fd, Expiry::At(monotonic_us() + 2_000)).unwrap();
        assert!(readable(1000));
        set_timerfd(fd, Expiry::Never).unwrap();
        assert!(!readable(10), "disarming cleared the unread expiry");
        let start = monotonic_us();
        set_timerfd(fd, Expiry::In(20_000)).unwrap();
        assert!(readable(1000));
        assert!(monotonic_us() - start >= 20_000);
        set_timerfd(fd, Expiry::At(0)).unwrap(); // in the past: at once
        assert!(readable(1000));
    }
}
