//! What the node tells the application (drained with `Node::poll_event`).

#[cfg(feature = "guarding")]
use crate::guarding::LifeGuardingEvent;
use crate::heartbeat::ConsumerEvent;
#[cfg(feature = "lss")]
use crate::lss::LssEvent;
use crate::nmt::NmtState;
#[cfg(feature = "time")]
use crate::od::TimeOfDay;
use crate::wire::emcy::Emergency;

/// An event for the application.
///
/// ```
/// use canopen_core::{event::Event, nmt::NmtState};
/// let e = Event::StateChanged { from: NmtState::PreOperational, to: NmtState::Operational };
/// assert!(matches!(e, Event::StateChanged { to: NmtState::Operational, .. }));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Event {
    /// The NMT state changed (by a command, a reset, local control or the error behaviour).
    StateChanged {
        /// The state before.
        from: NmtState,
        /// The state now.
        to: NmtState,
    },
    /// Reset Application ran: application values were set back to their power-on values (NMT-04).
    ResetApplication,
    /// Reset Communication ran: communication parameters were set back to their power-on values (NMT-05).
    ResetCommunication,
    /// A heartbeat consumer observation (HB-10, HB-11).
    Heartbeat(ConsumerEvent),
    /// A life-guarding observation (GUARD-10).
    #[cfg(feature = "guarding")]
    LifeGuarding(LifeGuardingEvent),
    /// An SDO download completed: the entry holds its new value (side effects of communication objects have
    /// already been applied).
    ObjectWritten {
        /// Index.
        index: u16,
        /// Sub-index.
        sub: u8,
    },
    /// An SDO transfer was aborted, by this server (`by_client == false`, the abort frame was sent) or by the
    /// client.
    SdoAborted {
        /// Index of the transfer.
        index: u16,
        /// Sub-index of the transfer.
        sub: u8,
        /// The abort code (a client may send codes outside Table 22).
        code: u32,
        /// Whether the client aborted.
        by_client: bool,
    },
    /// An LSS (CiA 305) observation: state change, node-ID or bit rate configured, bit-rate switch
    /// instants, store requested.
    #[cfg(feature = "lss")]
    Lss(LssEvent),
    /// An RPDO's data was written into the dictionary (at reception for FEh/FFh, at the SYNC for
    /// synchronous RPDOs).
    RpdoReceived {
        /// RPDO number, 0-based (RPDO 1 = 0, 1400h + pdo).
        pdo: u16,
    },
    /// A SYNC was received or produced (Pre-operational and Operational).
    Sync {
        /// The SYNC counter, when 1019h enables it.
        counter: Option<u8>,
    },
    /// A TIME message was received (TIME-04; 1012h bit 31 set).
    #[cfg(feature = "time")]
    Time(TimeOfDay),
    /// Another node's EMCY was received (EMCY-11: the reaction is the application's).
    Emergency {
        /// The producer's node-ID (the CAN-ID minus 80h).
        node: u8,
        /// The message.
        emcy: Emergency,
    },
    /// An MPDO consumer (feature `mpdo`) wrote a received value into the dictionary (MPDO-02 DAM: the
    /// object the frame names; MPDO-03 SAM: the local object the dispatching list 1FD0h maps it to).
    #[cfg(feature = "mpdo")]
    MpdoWritten {
        /// RPDO number, 0-based.
        pdo: u16,
        /// The local object's index.
        index: u16,
        /// The local object's sub-index.
        sub: u8,
    },
    /// An RPDO's event timer expired without reception (PDO-12; EMCY 8250h was raised).
    RpdoTimeout {
        /// RPDO number, 0-based.
        pdo: u16,
    },
}
