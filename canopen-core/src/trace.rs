//! Trace points for the optional `defmt` (firmware) and `log` (std) features. Without either feature every
//! function here is empty and inlines to nothing.
//!
//! Every event of a node run by [`crate::driver::run`] passes through [`event`], so NMT state changes and SDO
//! aborts are logged at one place, outside the node's lock; frames in and out are logged at trace level.

use crate::event::Event;
#[cfg(any(feature = "defmt", feature = "log"))]
use crate::frame::CanFrame;

/// Logs an event: NMT state changes at info, SDO aborts at warn, the rest at debug.
#[inline]
pub(crate) fn event(e: &Event) {
    #[cfg(feature = "defmt")]
    match e {
        Event::StateChanged { from, to } => defmt::info!("NMT {} -> {}", from, to),
        Event::SdoAborted { index, sub, code, by_client } => defmt::warn!(
            "SDO abort {=u16:04X}h:{=u8:02X}h code {=u32:08X}h (by client: {=bool})",
            index,
            sub,
            code,
            by_client
        ),
        _ => defmt::debug!("event {}", e),
    }
    #[cfg(feature = "log")]
    match e {
        Event::StateChanged { from, to } => log::info!("NMT {from:?} -> {to:?}"),
        Event::SdoAborted { index, sub, code, by_client } => {
            log::warn!("SDO abort {index:04X}h:{sub:02X}h code {code:08X}h (by client: {by_client})")
        }
        _ => log::debug!("event {e:?}"),
    }
    #[cfg(not(any(feature = "defmt", feature = "log")))]
    let _ = e;
}

/// Logs a frame received (`dir` "rx") or about to be sent ("tx"), trace level.
#[cfg(any(feature = "defmt", feature = "log"))]
#[inline]
pub(crate) fn frame(dir: &'static str, f: &CanFrame) {
    #[cfg(feature = "defmt")]
    defmt::trace!("{=str} {}", dir, f);
    #[cfg(feature = "log")]
    log::trace!("{dir} {f:?}");
}

/// Logs why the driver stopped (warn level): a receive or a transmit error.
#[inline]
pub(crate) fn driver_error(receive: bool) {
    #[cfg(feature = "defmt")]
    defmt::warn!("CAN driver stopped: {} error", if receive { "receive" } else { "transmit" });
    #[cfg(feature = "log")]
    log::warn!("CAN driver stopped: {} error", if receive { "receive" } else { "transmit" });
    #[cfg(not(any(feature = "defmt", feature = "log")))]
    let _ = receive;
}
