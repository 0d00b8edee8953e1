//! The node's capacities as one type: [`Sizes`] names them once (heartbeat consumer entries, transmit and
//! event queue lengths, RPDOs, TPDOs), so a [`Node`](crate::Node), its [`CommProfile`](crate::profile::CommProfile)
//! and its [`HeartbeatConsumer`](crate::heartbeat::HeartbeatConsumer) take one type parameter instead of five
//! numbers.
//!
//! Each layer reads the sizes through its own trait, implemented for [`Sizes`] beside the layer's code:
//! [`ConsumerSizes`](crate::heartbeat::ConsumerSizes) (services), [`ProfileSizes`](crate::profile::ProfileSizes)
//! (profile) and [`NodeSizes`](crate::node::NodeSizes) (node). Their associated types are the concrete
//! containers (`[Rpdo; RPDO]`, `heapless` storage of `TXQ` frames, ...): stable Rust cannot yet size an array
//! by an associated *constant*, but it can name an array type chosen by the implementation, and after
//! monomorphisation the code is the same as with the numbers spelled out.
//!
//! ```
//! use canopen_core::{node::{Node, NoApplication}, profile::NodeConfig, NodeId, Sizes};
//! // 2 consumer entries, 8-frame transmit queue, 8 events, 1 RPDO, 1 TPDO:
//! type Small = Sizes<2, 8, 8, 1, 1>;
//! let node: Node<NoApplication, Small> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
//! assert_eq!(node.params().heartbeat_consumers.len(), 2);
//! ```

use core::ops::{Index, IndexMut};

/// The capacities of a node: `HB` heartbeat consumer entries (1016h), a transmit queue of `TXQ` frames, an
/// event queue of `EVQ` events, `RPDO` receive and `TPDO` transmit PDOs. `Sizes` (all defaults) is a
/// complete CiA 301 device with 4 + 4 PDOs.
///
/// ```
/// use canopen_core::{node::NodeSizes, profile::ProfileSizes, heartbeat::ConsumerSizes, Sizes};
/// assert_eq!(<Sizes as ConsumerSizes>::HB, 4);
/// assert_eq!(<Sizes<0, 32> as NodeSizes>::TXQ, 32);
/// assert_eq!(<Sizes<0, 8, 8, 2, 3> as ProfileSizes>::TPDO, 3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sizes<
    const HB: usize = 4,
    const TXQ: usize = 16,
    const EVQ: usize = 16,
    const RPDO: usize = 4,
    const TPDO: usize = 4,
>;

/// A fixed number of `T` in place (an array `[T; N]`): what the size traits' associated types are, indexed
/// like an array or read as a slice.
///
/// ```
/// use canopen_core::sizes::Slots;
/// fn total<S: Slots<u32>>(s: &S) -> u32 {
///     s.as_ref().iter().sum()
/// }
/// assert_eq!(total(&[1, 2, 3]), 6);
/// assert_eq!(<[u8; 5] as Slots<u8>>::LEN, 5);
/// assert_eq!(<[usize; 3]>::from_fn(|i| i * 2), [0, 2, 4]);
/// ```
pub trait Slots<T>: AsRef<[T]> + AsMut<[T]> + Index<usize, Output = T> + IndexMut<usize> {
    /// The number of slots.
    const LEN: usize;
    /// Slot `i` holds `f(i)` (`core::array::from_fn`).
    fn from_fn(f: impl FnMut(usize) -> T) -> Self;
}

impl<T, const N: usize> Slots<T> for [T; N] {
    const LEN: usize = N;
    fn from_fn(f: impl FnMut(usize) -> T) -> Self {
        core::array::from_fn(f)
    }
}
