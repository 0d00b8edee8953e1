//! LSS (CiA 305) through the core's sans-IO LSS master: switch, configure node-ID and bit timing, store,
//! inquire, identify, fastscan, and the commissioning sequence that gives every unconfigured slave a
//! node-ID. Requests go out on 7E5h; only the holder of the [`Lss`] handle receives the 7E4h answers.

use std::time::Duration;

use canopen_core::lss::master::{Commissioning, CommissioningEvent, LssMaster, MasterEvent};
use canopen_core::wire::lss::{BitRate, IdentityField, LssMode, Status};
use canopen_core::{CanFrame, Instant, NodeId};

use crate::{Error, Master, Route};

pub use canopen_core::lss::Identity;

/// How long a new [`Lss`] handle waits for each answer (python canopen waits 0.5 s; a fastscan waits this
/// long for every bit that is 1).
pub const DEFAULT_LSS_TIMEOUT: Duration = Duration::from_millis(100);

/// How long the master waits after an LSS answer for copies of it from other slaves (a virtual bus delivers
/// the answers of several slaves as separate frames; on a real bus they merge into one):
/// [`Lss::with_settle`].
pub const DEFAULT_LSS_SETTLE: Duration = Duration::from_millis(2);

/// The LSS master: exclusive use of 7E4h while held (from [`Master::lss`]).
pub struct Lss {
    master: Master,
    route: Route,
    timeout: Duration,
    settle: Duration,
    _turn: tokio::sync::OwnedMutexGuard<()>,
}

/// The sans-IO LSS state machines the handle drives.
trait Machine {
    type Event;
    fn poll_transmit(&mut self, now: Instant) -> Option<[u8; 8]>;
    fn poll_timeout(&self) -> Option<Instant>;
    fn handle_response(&mut self, now: Instant, data: &[u8]) -> Option<Self::Event>;
    fn handle_timeout(&mut self, now: Instant) -> Option<Self::Event>;
    /// Whether the machine is done without an event (an unconfirmed service, once sent).
    fn finished(&self) -> bool;
}

impl Machine for LssMaster {
    type Event = MasterEvent;
    fn poll_transmit(&mut self, now: Instant) -> Option<[u8; 8]> {
        LssMaster::poll_transmit(self, now)
    }
    fn poll_timeout(&self) -> Option<Instant> {
        LssMaster::poll_timeout(self)
    }
    fn handle_response(&mut self, now: Instant, data: &[u8]) -> Option<MasterEvent> {
        LssMaster::handle_response(self, now, data)
    }
    fn handle_timeout(&mut self, now: Instant) -> Option<MasterEvent> {
        LssMaster::handle_timeout(self, now)
    }
    fn finished(&self) -> bool {
        self.is_idle()
    }
}

impl Machine for Commissioning {
    type Event = CommissioningEvent;
    fn poll_transmit(&mut self, now: Instant) -> Option<[u8; 8]> {
        Commissioning::poll_transmit(self, now)
    }
    fn poll_timeout(&self) -> Option<Instant> {
        Commissioning::poll_timeout(self)
    }
    fn handle_response(&mut self, now: Instant, data: &[u8]) -> Option<CommissioningEvent> {
        Commissioning::handle_response(self, now, data)
    }
    fn handle_timeout(&mut self, now: Instant) -> Option<CommissioningEvent> {
        Commissioning::handle_timeout(self, now)
    }
    fn finished(&self) -> bool {
        self.is_done()
    }
}

impl Master {
    /// The LSS master; waits while another task holds it.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let mut lss = m.lss().await.unwrap();
    /// assert_eq!(lss.fastscan().await.unwrap(), None); // nobody unconfigured on this bus
    /// # });
    /// ```
    pub async fn lss(&self) -> Result<Lss, Error> {
        let turn = self.inner.router.turn(0x7E4).lock_owned().await;
        let route = self.inner.router.route(0x7E4)?;
        Ok(Lss { master: self.clone(), route, timeout: DEFAULT_LSS_TIMEOUT, settle: DEFAULT_LSS_SETTLE, _turn: turn })
    }
}

impl Lss {
    /// Sets the time-out for each answer.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let lss = m.lss().await.unwrap().with_timeout(std::time::Duration::from_millis(20));
    /// # });
    /// ```
    pub fn with_timeout(mut self, timeout: Duration) -> Self {
        self.timeout = timeout;
        self
    }

    /// After an answer, discards the copies of it that other slaves send, before the next request goes out.
    ///
    /// Several slaves answer an identify or fastscan step at once. On a real bus their identical frames
    /// merge into one; on a virtual bus (vcan, [`sim`](crate::sim)) each is its own frame, and a copy that
    /// came after the next request would be taken as that request's answer (a fastscan would read a bit
    /// as 0 that is 1).
    async fn settle(&mut self) {
        let until = tokio::time::Instant::now() + self.settle;
        while let Ok(Some(_)) = tokio::time::timeout_at(until, self.route.rx.recv()).await {}
    }

    /// Sets how long the master waits after an answer for copies of it from other slaves before the next
    /// request (default [`DEFAULT_LSS_SETTLE`]; see the note on virtual buses there).
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let lss = m.lss().await.unwrap().with_settle(std::time::Duration::ZERO); // a real bus
    /// # });
    /// ```
    pub fn with_settle(mut self, settle: Duration) -> Self {
        self.settle = settle;
        self
    }

    fn core_timeout(&self) -> canopen_core::Duration {
        canopen_core::Duration::from_micros(self.timeout.as_micros() as u64)
    }

    /// Drives `m` until it reports an event (`Some`) or is done without one (`None`); `on_event` sees every
    /// event and says whether it ends the run.
    async fn run<M: Machine>(
        &mut self,
        m: &mut M,
        mut ends: impl FnMut(&M::Event) -> bool,
    ) -> Result<Option<M::Event>, Error> {
        let clock = self.master.inner.clock;
        loop {
            while let Some(bytes) = m.poll_transmit(clock.now()) {
                self.master.send(&CanFrame::from_parts(0x7E5, bytes, 8)).await?;
            }
            if m.finished() && m.poll_timeout().is_none() {
                return Ok(None);
            }
            let deadline = m.poll_timeout().map(|t| clock.to_tokio(t));
            let event = tokio::select! {
                frame = self.route.rx.recv() => match frame {
                    Some(f) => {
                        let event = m.handle_response(clock.now(), f.data());
                        self.settle().await;
                        event
                    }
                    None => return Err(self.master.inner.router.closed_error()),
                },
                _ = crate::sleep_until(deadline) => m.handle_timeout(clock.now()),
            };
            if let Some(e) = event {
                if ends(&e) {
                    return Ok(Some(e));
                }
            }
        }
    }

    async fn service(
        &mut self,
        start: impl FnOnce(&mut LssMaster) -> Result<(), canopen_core::lss::master::Busy>,
    ) -> Result<Option<MasterEvent>, Error> {
        let mut m = LssMaster::new(self.core_timeout());
        start(&mut m).map_err(|_| Error::InvalidArgument("LSS master busy".into()))?;
        self.run(&mut m, |_| true).await
    }

    async fn confirmed(
        &mut self,
        start: impl FnOnce(&mut LssMaster) -> Result<(), canopen_core::lss::master::Busy>,
    ) -> Result<MasterEvent, Error> {
        match self.service(start).await? {
            Some(MasterEvent::Timeout) | None => Err(Error::Timeout),
            Some(e) => Ok(e),
        }
    }

    /// Switch state global (LSS-…, unconfirmed): every slave to `mode`.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// use canopen_core::wire::lss::LssMode;
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// m.lss().await.unwrap().switch_global(LssMode::Waiting).await.unwrap();
    /// # });
    /// ```
    pub async fn switch_global(&mut self, mode: LssMode) -> Result<(), Error> {
        self.service(|m| m.switch_global(mode)).await.map(|_| ())
    }

    /// Switch state selective: the slave with this LSS address to configuration; [`Error::Timeout`] if no
    /// slave answers.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let id = canopen_master::lss::Identity { vendor_id: 1, product_code: 2, revision: 3, serial: 4 };
    /// assert!(m.lss().await.unwrap().switch_selective(&id).await.unwrap_err().is_timeout());
    /// # });
    /// ```
    pub async fn switch_selective(&mut self, id: &Identity) -> Result<(), Error> {
        self.confirmed(|m| m.switch_selective(id)).await.map(|_| ())
    }

    /// Configure node-ID (the slave in configuration; FFh = unconfigured). The slave's status comes back;
    /// [`Status::is_success`] tells whether it took it.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// assert!(m.lss().await.unwrap().configure_node_id(5).await.unwrap_err().is_timeout());
    /// # });
    /// ```
    pub async fn configure_node_id(&mut self, node_id: u8) -> Result<Status, Error> {
        match self.confirmed(|m| m.configure_node_id(node_id)).await? {
            MasterEvent::Configured(s) => Ok(s),
            other => Err(Error::Protocol(format!("unexpected LSS answer {other:?}"))),
        }
    }

    /// Configure bit timing (CiA 301 table, index of `rate`).
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// use canopen_core::wire::lss::BitRate;
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// assert!(m.lss().await.unwrap().configure_bit_timing(BitRate::K500).await.is_err());
    /// # });
    /// ```
    pub async fn configure_bit_timing(&mut self, rate: BitRate) -> Result<Status, Error> {
        match self.confirmed(|m| m.configure_bit_timing(rate)).await? {
            MasterEvent::Configured(s) => Ok(s),
            other => Err(Error::Protocol(format!("unexpected LSS answer {other:?}"))),
        }
    }

    /// Store configuration (node-ID and bit timing into the slave's non-volatile memory).
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// assert!(m.lss().await.unwrap().store().await.unwrap_err().is_timeout());
    /// # });
    /// ```
    pub async fn store(&mut self) -> Result<Status, Error> {
        match self.confirmed(|m| m.store()).await? {
            MasterEvent::Configured(s) => Ok(s),
            other => Err(Error::Protocol(format!("unexpected LSS answer {other:?}"))),
        }
    }

    /// Inquire one field of the LSS address of the slave in configuration.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// use canopen_core::wire::lss::IdentityField;
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// assert!(m.lss().await.unwrap().inquire(IdentityField::Serial).await.is_err());
    /// # });
    /// ```
    pub async fn inquire(&mut self, field: IdentityField) -> Result<u32, Error> {
        match self.confirmed(|m| m.inquire(field)).await? {
            MasterEvent::Identity(_, v) => Ok(v),
            other => Err(Error::Protocol(format!("unexpected LSS answer {other:?}"))),
        }
    }

    /// Inquire the node-ID of the slave in configuration (FFh = none).
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// assert!(m.lss().await.unwrap().inquire_node_id().await.is_err());
    /// # });
    /// ```
    pub async fn inquire_node_id(&mut self) -> Result<u8, Error> {
        match self.confirmed(|m| m.inquire_node_id()).await? {
            MasterEvent::NodeId(id) => Ok(id),
            other => Err(Error::Protocol(format!("unexpected LSS answer {other:?}"))),
        }
    }

    /// Fastscan: the LSS address of one unconfigured slave, which is then in configuration; `None` when no
    /// unconfigured slave answers.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// assert_eq!(m.lss().await.unwrap().fastscan().await.unwrap(), None);
    /// # });
    /// ```
    pub async fn fastscan(&mut self) -> Result<Option<Identity>, Error> {
        match self.service(|m| m.fastscan()).await? {
            Some(MasterEvent::Fastscan(found)) => Ok(found),
            Some(MasterEvent::Timeout) | None => Err(Error::Timeout),
            Some(other) => Err(Error::Protocol(format!("unexpected LSS answer {other:?}"))),
        }
    }

    /// Gives every unconfigured slave a node-ID from `first` upwards (fastscan, configure, store when asked,
    /// back to waiting so it boots), and returns what each got.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let first = canopen_core::NodeId::new(0x20).unwrap();
    /// assert!(m.lss().await.unwrap().commission(first, false).await.unwrap().is_empty());
    /// # });
    /// ```
    pub async fn commission(&mut self, first: NodeId, store: bool) -> Result<Vec<(Identity, NodeId)>, Error> {
        let mut c = Commissioning::new(self.core_timeout(), first, store);
        let mut assigned = Vec::new();
        let end = self
            .run(&mut c, |e| {
                if let CommissioningEvent::Assigned { identity, node_id } = e {
                    assigned.push((*identity, *node_id));
                    return false;
                }
                true
            })
            .await?;
        match end {
            Some(CommissioningEvent::Failed { cause }) => {
                Err(Error::Protocol(format!("LSS commissioning failed after {} slaves: {cause:?}", assigned.len())))
            }
            _ => Ok(assigned),
        }
    }
}
