//! SDO client transfers with a node's default server (600h/580h + node) through `canopen-core`'s sans-IO
//! client: typed reads and writes, bytes of any length, DOMAIN streaming, the scan of 1..=127, and what
//! happens when a transfer fails or is dropped (the server gets an abort, its line must go quiet before the
//! next transfer to it starts).

use std::io;
use std::sync::Arc;
use std::time::Duration;

use canopen_core::od::AbortCode;
use canopen_core::sdo::client::{Busy, SdoClient};
use canopen_core::sdo::SdoClientParams;
use canopen_core::wire::sdo::{abort_frame, Multiplexer};
use canopen_core::CanFrame;

use crate::bus::{sleep_until, Link, Route, Router};
use crate::data::{Data, ReaderSource, SliceSource, VecSink, WriterSink};
use crate::{node_id, CanIo, Error, Master, Mode, Progress, SdoValue};

/// Block transfer with CRC, 127 segments per sub-block, no protocol switch: the fastest mode for large
/// values (SDO-35..SDO-51).
///
/// ```
/// assert!(matches!(canopen_master::BLOCK, canopen_master::Mode::Block { crc: true, blksize: 127, .. }));
/// ```
pub const BLOCK: Mode = Mode::Block { crc: true, blksize: 127, pst: 0 };

/// The SDO time-out of a new master: each step of a transfer must be answered within it (SDO-31).
pub const DEFAULT_SDO_TIMEOUT: Duration = Duration::from_millis(1000);

/// How long the server's line must stay quiet after a failed transfer before the next transfer to it starts
/// (what it still sends for the failed one, e.g. the rest of a sub-block, is discarded).
pub const QUIET: Duration = Duration::from_millis(50);

impl Master {
    /// This master with another SDO time-out (per protocol step, SDO-31; zero waits for ever). Other clones
    /// keep theirs.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// use std::time::Duration;
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port()).with_sdo_timeout(Duration::from_millis(100));
    /// assert_eq!(m.sdo_timeout(), Duration::from_millis(100));
    /// # });
    /// ```
    pub fn with_sdo_timeout(mut self, timeout: Duration) -> Self {
        self.sdo_timeout = timeout;
        self
    }

    /// The SDO time-out.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// assert_eq!(m.sdo_timeout(), canopen_master::DEFAULT_SDO_TIMEOUT);
    /// # });
    /// ```
    pub fn sdo_timeout(&self) -> Duration {
        self.sdo_timeout
    }

    /// Reads a typed value (`u8`..`u64`, `i8`..`i64`, `f32`, `f64`, `bool`, `String`, `Vec<u8>`) from
    /// `index:sub` of `node`. A value of another size is [`Error::TypeMismatch`].
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let vendor: u32 = m.read(2, 0x1018, 1).await.unwrap();
    /// assert!(m.read::<u16>(2, 0x1018, 1).await.is_err()); // 4 bytes are no UNSIGNED16
    /// let e = m.read::<u32>(2, 0x1234, 0).await.unwrap_err();
    /// assert_eq!(e.abort_code(), Some(0x0602_0000));
    /// # });
    /// ```
    pub async fn read<T: SdoValue>(&self, node: u8, index: u16, sub: u8) -> Result<T, Error> {
        // A fixed-size type still takes a few bytes more, so that a wrong type is a type mismatch and not an
        // "out of memory" abort.
        let cap = T::SIZE.map_or(usize::MAX, |s| s.max(64));
        let mut sink = VecSink::upload(cap);
        let len = self.transfer(node, Multiplexer::new(index, sub), Start::Upload(Mode::Auto), &mut sink).await?;
        sink.buf.truncate(len);
        T::decode(&sink.buf)
    }

    /// Writes a typed value to `index:sub` of `node` (expedited up to 4 bytes, segmented above).
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// m.write(2, 0x1017, 0, 250u16).await.unwrap(); // producer heartbeat time
    /// assert_eq!(m.read::<u16>(2, 0x1017, 0).await.unwrap(), 250);
    /// # });
    /// ```
    pub async fn write<T: SdoValue>(&self, node: u8, index: u16, sub: u8, value: T) -> Result<(), Error> {
        self.download(node, index, sub, &value.encode(), Mode::Auto).await
    }

    /// Reads the bytes of `index:sub` (any length) in `mode` ([`Mode::Auto`], or [`BLOCK`] for large values).
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let name = m.upload(2, 0x1008, 0, canopen_master::BLOCK).await.unwrap();
    /// assert_eq!(name, NodeConfig::DEFAULT.device_name.as_bytes());
    /// # });
    /// ```
    pub async fn upload(&self, node: u8, index: u16, sub: u8, mode: Mode) -> Result<Vec<u8>, Error> {
        let mut sink = VecSink::upload(usize::MAX);
        let len = self.transfer(node, Multiplexer::new(index, sub), Start::Upload(mode), &mut sink).await?;
        sink.buf.truncate(len);
        Ok(sink.buf)
    }

    /// Writes `data` (any length up to 4 GiB - 1) to `index:sub` in `mode`.
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let e = m.download(2, 0x1000, 0, &[1, 2, 3, 4], canopen_master::Mode::Auto).await.unwrap_err();
    /// assert_eq!(e.abort_code(), Some(0x0601_0002)); // 1000h is read-only
    /// # });
    /// ```
    pub async fn download(&self, node: u8, index: u16, sub: u8, data: &[u8], mode: Mode) -> Result<(), Error> {
        let mut src = SliceSource { src: data, progress: None };
        let start = Start::Download(data.len(), mode);
        self.transfer(node, Multiplexer::new(index, sub), start, &mut src).await.map(|_| ())
    }

    /// Streams `index:sub` (a DOMAIN, a firmware image...) into `out` as it arrives, calling `progress` with
    /// the bytes received so far; returns the length. `out` is written from the async task (a file or a
    /// buffer; wrap a slow sink in a channel).
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let mut out = Vec::new();
    /// let mut seen = 0;
    /// let len = m.upload_to(2, 0x1008, 0, canopen_master::BLOCK, &mut out, Some(&mut |n| seen = n)).await.unwrap();
    /// assert_eq!((len, seen), (out.len() as u64, len));
    /// # });
    /// ```
    pub async fn upload_to(
        &self,
        node: u8,
        index: u16,
        sub: u8,
        mode: Mode,
        out: &mut (dyn io::Write + Send),
        progress: Option<Progress<'_>>,
    ) -> Result<u64, Error> {
        let mut sink = WriterSink { writer: out, written: 0, progress, error: None };
        let len = self.transfer(node, Multiplexer::new(index, sub), Start::Upload(mode), &mut sink).await?;
        Ok(len as u64)
    }

    /// Streams `len` bytes from `source` into `index:sub`, keeping only a few KiB of it in memory, calling
    /// `progress` with the bytes handed to the transfer so far. A source that fails or ends early aborts the
    /// transfer (0800 0000h) and returns its I/O error.
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let mut source: &[u8] = &[0xF4, 0x01]; // 500 ms
    /// m.download_from(2, 0x1017, 0, canopen_master::Mode::Segmented, &mut source, 2, None).await.unwrap();
    /// assert_eq!(m.read::<u16>(2, 0x1017, 0).await.unwrap(), 500);
    /// # });
    /// ```
    #[allow(clippy::too_many_arguments)]
    pub async fn download_from(
        &self,
        node: u8,
        index: u16,
        sub: u8,
        mode: Mode,
        source: &mut (dyn io::Read + Send),
        len: u64,
        progress: Option<Progress<'_>>,
    ) -> Result<(), Error> {
        let len = usize::try_from(len).map_err(|_| Error::InvalidArgument(format!("{len} bytes")))?;
        let mut src = ReaderSource::new(source, len, progress);
        self.transfer(node, Multiplexer::new(index, sub), Start::Download(len, mode), &mut src).await.map(|_| ())
    }

    /// Which of the nodes 1..=127 answer an SDO read of 1000h within `timeout` (all asked at once); a node
    /// that answers with an abort is there too.
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// use std::time::Duration;
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _a = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let _b = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(90).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// assert_eq!(m.scan(Duration::from_millis(100)).await.unwrap(), vec![2, 90]);
    /// # });
    /// ```
    pub async fn scan(&self, timeout: Duration) -> Result<Vec<u8>, Error> {
        let m = self.clone().with_sdo_timeout(timeout);
        let mut set = tokio::task::JoinSet::new();
        for node in 1..=127u8 {
            let m = m.clone();
            set.spawn(async move { (node, m.upload(node, 0x1000, 0, Mode::Auto).await) });
        }
        let mut found = Vec::new();
        while let Some(joined) = set.join_next().await {
            let (node, result) = joined.map_err(|e| Error::Io(io::Error::other(e)))?;
            match result {
                Ok(_) | Err(Error::Aborted { by_server: true, .. }) => found.push(node),
                Err(Error::Aborted { by_server: false, .. }) => {}
                Err(e) => return Err(e),
            }
        }
        found.sort_unstable();
        Ok(found)
    }

    /// One SDO transfer with `node`'s default server (600h/580h + node), driven to its end.
    async fn transfer(&self, node: u8, mux: Multiplexer, start: Start, data: &mut dyn Data) -> Result<usize, Error> {
        let params = SdoClientParams::for_server(node_id(node)?);
        let (tx_cob, rx_cob) = (params.tx_cob_id(), params.rx_cob_id());
        let router = &self.inner.router;
        if *router.link.borrow() == Link::Down {
            return Err(router.closed_error()); // at once, not after a time-out
        }
        let turn = router.turn(rx_cob).lock_owned().await;
        let mut route = router.route(rx_cob)?;
        let timeout = canopen_core::Duration::from_micros(self.sdo_timeout.as_micros() as u64);
        let mut client = SdoClient::new(params).with_timeout(timeout);
        let now = self.inner.clock.now();
        let started = match start {
            Start::Upload(mode) => client.start_upload(now, mux, mode),
            Start::Download(len, mode) if u32::try_from(len).is_ok() => client.start_download(now, mux, len, mode),
            Start::Download(len, _) => {
                return Err(Error::InvalidArgument(format!("{len} bytes: more than SDO's 4 GiB - 1")))
            }
        };
        started.map_err(|Busy| Error::InvalidArgument("the SDO client is busy".into()))?;
        let mut armed = AbortOnDrop { io: self.inner.io.clone(), cob: tx_cob, mux: Some(mux) };
        let result = self.run_client(&mut client, &mut route, data, tx_cob).await;
        armed.mux = None;
        if let Err(e) = &result {
            // A transfer cut off by the socket (the interface went down) leaves the server in it: once the
            // socket is back, abort it (0800 0000h), so that the next transfer finds the server idle.
            let cut_off = matches!(e, Error::Interrupted(_) | Error::Io(_))
                .then(|| CanFrame::from_parts(tx_cob, abort_frame(mux, AbortCode::GeneralError.code()), 8));
            let (io, router) = (self.inner.io.clone(), self.inner.router.clone());
            // What the server still sends for this transfer must not be taken for the next one's answer: the
            // next transfer to this server waits until its line has been quiet for QUIET; this one returns now.
            tokio::spawn(async move {
                if let Some(abort) = cut_off {
                    drop(route); // dead after an outage: routed anew below
                    route = match abort_after_outage(&*io, &router, rx_cob, &abort).await {
                        Some(r) => r,
                        None => return, // the master closed
                    };
                }
                while let Ok(Some(_)) = tokio::time::timeout(QUIET, route.rx.recv()).await {}
                drop((route, turn));
            });
        }
        result
    }

    async fn run_client(
        &self,
        client: &mut SdoClient,
        route: &mut Route,
        data: &mut dyn Data,
        tx_cob: u16,
    ) -> Result<usize, Error> {
        use canopen_core::sdo::client::ClientEvent;
        let clock = self.inner.clock;
        let mut out = Vec::new();
        let mut now = clock.now();
        loop {
            self.flush(client, data, tx_cob, now, &mut out).await?;
            if let Some(e) = data.take_error() {
                client.abort(AbortCode::GeneralError);
                self.flush(client, data, tx_cob, now, &mut out).await?;
                return Err(Error::Io(e));
            }
            let deadline = client.poll_timeout().map(|t| clock.to_tokio(t));
            let event = tokio::select! {
                frame = route.rx.recv() => match frame {
                    Some(f) => {
                        // One clock reading for every frame already routed to this transfer (a block
                        // upload's sub-block arrives as one batch); what the client answers in between
                        // is collected and sent in order after them.
                        now = clock.now();
                        let mut event = client.handle_response(now, f.data(), data);
                        while event.is_none() {
                            queue(client, data, tx_cob, now, &mut out);
                            match route.rx.try_recv() {
                                Ok(f) => event = client.handle_response(now, f.data(), data),
                                Err(_) => break,
                            }
                        }
                        event
                    }
                    None => return Err(self.inner.router.closed_error()),
                },
                _ = sleep_until(deadline) => {
                    now = clock.now();
                    client.handle_timeout(now)
                }
            };
            match event {
                None => {}
                Some(ClientEvent::Done { len }) => {
                    self.flush(client, data, tx_cob, now, &mut out).await?;
                    return match data.take_error() {
                        Some(e) => Err(Error::Io(e)),
                        None => Ok(len),
                    };
                }
                Some(ClientEvent::Failed(e)) => {
                    self.flush(client, data, tx_cob, now, &mut out).await?;
                    // A local write error (a file) is reported as itself, not only as its abort code.
                    return Err(data.take_error().map_or_else(|| e.into(), Error::Io));
                }
            }
        }
    }

    /// Sends what the client has to send (after what `out` already holds), in one
    /// [`CanIo::send_many`]: a block download's sub-block (up to 127 segments) goes out in two `sendmmsg`
    /// on one clock reading, `now` (the time of the frames just handled), so its time-out runs from there
    /// (scripts/bench-master.sh counts the system calls per frame).
    async fn flush(
        &self,
        client: &mut SdoClient,
        data: &mut dyn Data,
        tx_cob: u16,
        now: canopen_core::Instant,
        out: &mut Vec<CanFrame>,
    ) -> Result<(), Error> {
        queue(client, data, tx_cob, now, out);
        if !out.is_empty() {
            let sent = self.inner.io.send_many(out).await;
            out.clear();
            sent?;
        }
        Ok(())
    }
}

/// Appends what the client has to send at `now` to `out`.
fn queue(
    client: &mut SdoClient,
    data: &mut dyn Data,
    tx_cob: u16,
    now: canopen_core::Instant,
    out: &mut Vec<CanFrame>,
) {
    out.extend(std::iter::from_fn(|| client.poll_transmit(now, data)).map(|b| CanFrame::from_parts(tx_cob, b, 8)));
}

/// Sends `abort` for a transfer an outage cut off, once the socket is up again and
/// 2 × [`REOPEN_POLL`](crate::canio::REOPEN_POLL) later (a send that fails because
/// the receive task has not seen the outage yet is retried after it has, up to three times), and returns
/// a route for the server's COB-ID `cob` to discard what it still sends; `None` when the master closed.
async fn abort_after_outage(io: &dyn CanIo, router: &Arc<Router>, cob: u16, abort: &CanFrame) -> Option<Route> {
    let mut link = router.link.subscribe();
    for _ in 0..3 {
        if !matches!(link.wait_for(|l| *l != Link::Down).await.map(|l| *l), Ok(Link::Up)) {
            return None;
        }
        // Nodes on the same interface (vcan) reopen their sockets too, polling as often as the master
        // (canopen-socketcan's runners): an abort sent before they did would be lost.
        tokio::time::sleep(2 * crate::canio::REOPEN_POLL).await;
        if io.send(abort).await.is_ok() {
            break;
        }
        // Not an outage after all, or one the receive task has not seen yet: wait a little for it.
        let _ = tokio::time::timeout(Duration::from_secs(1), link.changed()).await;
    }
    router.route(cob).ok()
}

enum Start {
    Upload(Mode),
    Download(usize, Mode),
}

/// Sends the server an abort when a transfer's future is dropped before its end.
struct AbortOnDrop {
    io: Arc<dyn CanIo>,
    cob: u16,
    mux: Option<Multiplexer>,
}

impl Drop for AbortOnDrop {
    fn drop(&mut self) {
        if let (Some(mux), Ok(rt)) = (self.mux.take(), tokio::runtime::Handle::try_current()) {
            let io = self.io.clone();
            let frame = CanFrame::from_parts(self.cob, abort_frame(mux, AbortCode::GeneralError.code()), 8);
            rt.spawn(async move {
                let _ = io.send(&frame).await;
            });
        }
    }
}
