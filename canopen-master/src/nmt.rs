//! NMT node control and the error-control streams: NMT commands to one node or all, heartbeat and boot-up
//! messages (and waiting for a node to report a state), and emergency messages.

use std::time::Duration;

use canopen_core::wire::emcy::Emergency;
use canopen_core::CanFrame;
use tokio::sync::broadcast;

use crate::{node_id, Error, Master, NmtCommand, StateCode};

/// A heartbeat or boot-up message (700h + node, one byte; NMT-23, HB-02).
///
/// ```
/// use canopen_master::{Heartbeat, StateCode};
/// let hb = Heartbeat { node: 5, state: 0x7F };
/// assert_eq!(hb.state(), Some(StateCode::PreOperational));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Heartbeat {
    /// The node-ID.
    pub node: u8,
    /// The state byte (bit 7 is the toggle of a node-guarding reply, 0 in a heartbeat).
    pub state: u8,
}

impl Heartbeat {
    /// The NMT state it reports, `None` for an undefined code.
    ///
    /// ```
    /// assert_eq!(canopen_master::Heartbeat { node: 1, state: 0 }.state(), Some(canopen_master::StateCode::BootUp));
    /// ```
    pub fn state(&self) -> Option<StateCode> {
        StateCode::from_code(self.state & 0x7F)
    }
}

/// An emergency message of a node (80h + node, EMCY-04).
///
/// ```
/// use canopen_master::EmcyEvent;
/// use canopen_core::wire::emcy::Emergency;
/// let e = EmcyEvent { node: 5, emergency: Emergency { code: 0x8130, register: 0x11, manufacturer: [0; 5] } };
/// assert_eq!(e.emergency.code, 0x8130);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EmcyEvent {
    /// The node-ID (the COB-ID minus 80h).
    pub node: u8,
    /// The message.
    pub emergency: Emergency,
}

impl Master {
    /// Every heartbeat and boot-up message received from now on.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let mut heartbeats = m.heartbeats();
    /// # });
    /// ```
    pub fn heartbeats(&self) -> broadcast::Receiver<Heartbeat> {
        self.inner.router.heartbeat.subscribe()
    }

    /// Every emergency message received from now on.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let mut emcy = m.emergencies();
    /// # });
    /// ```
    pub fn emergencies(&self) -> broadcast::Receiver<EmcyEvent> {
        self.inner.router.emcy.subscribe()
    }

    /// Sends an NMT node-control command (NMT-07..NMT-13) to `node`, or to every node with `node` 0.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// use canopen_master::{Master, NmtCommand};
    /// let m = Master::new(canopen_master::sim::SimBus::new().port());
    /// m.nmt(0, NmtCommand::Start).await.unwrap(); // all nodes
    /// assert!(m.nmt(128, NmtCommand::Start).await.is_err());
    /// # });
    /// ```
    pub async fn nmt(&self, node: u8, command: NmtCommand) -> Result<(), Error> {
        if node != 0 {
            node_id(node)?;
        }
        self.send(&CanFrame::from_parts(0, [command as u8, node, 0, 0, 0, 0, 0, 0], 2)).await
    }

    /// Waits up to `timeout` for a heartbeat of `node` reporting `state` (heartbeats with other states, sent
    /// before the node acted on a command, are skipped); [`Error::Timeout`] if none comes.
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// use std::time::Duration;
    /// use canopen_master::{Master, NmtCommand, StateCode};
    /// let bus = canopen_master::sim::SimBus::new();
    /// let config = NodeConfig { heartbeat_time_ms: 100, ..NodeConfig::DEFAULT };
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(4).unwrap(), config, NoApplication));
    /// let m = Master::new(bus.port());
    /// m.nmt(4, NmtCommand::Start).await.unwrap();
    /// m.wait_for_state(4, StateCode::Operational, Duration::from_secs(1)).await.unwrap();
    /// # });
    /// ```
    pub async fn wait_for_state(&self, node: u8, state: StateCode, timeout: Duration) -> Result<(), Error> {
        let mut rx = self.heartbeats();
        let wait = async {
            loop {
                match rx.recv().await {
                    Ok(hb) if hb.node == node && hb.state() == Some(state) => return Ok(()),
                    Ok(_) | Err(broadcast::error::RecvError::Lagged(_)) => {}
                    Err(broadcast::error::RecvError::Closed) => return Err(self.inner.router.closed_error()),
                }
            }
        };
        tokio::time::timeout(timeout, wait).await.unwrap_or(Err(Error::Timeout))
    }
}
