//! The node shared between the driver task and the application's tasks and interrupts.

use core::cell::RefCell;

use canopen_core::driver::Shared;
use embassy_sync::blocking_mutex::raw::CriticalSectionRawMutex;
use embassy_sync::blocking_mutex::Mutex;

/// A node shared between the driver task and the application's tasks (or interrupts): a blocking mutex on
/// a critical section. The driver holds the lock only while the node computes, never across an `.await`,
/// so an interrupt waits at most one frame's handling.
///
/// ```
/// use canopen_core::{driver::Shared, node::NoApplication, profile::NodeConfig, Node, NodeId};
/// use canopen_embassy::NodeCell;
///
/// let cell = NodeCell::new(Node::<NoApplication>::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication));
/// assert_eq!(cell.lock(|n| n.error_register()), 0);
/// ```
pub struct NodeCell<N>(Mutex<CriticalSectionRawMutex, RefCell<N>>);

impl<N> NodeCell<N> {
    /// Wraps `node` (usable in a `static` initialiser or a `StaticCell`).
    ///
    /// ```
    /// use canopen_embassy::NodeCell;
    /// static CELL: NodeCell<u32> = NodeCell::new(7);
    /// # use canopen_core::driver::Shared;
    /// assert_eq!(CELL.lock(|n| *n), 7);
    /// ```
    pub const fn new(node: N) -> Self {
        NodeCell(Mutex::new(RefCell::new(node)))
    }
}

impl<N> Shared<N> for NodeCell<N> {
    fn lock<R>(&self, f: impl FnOnce(&mut N) -> R) -> R {
        self.0.lock(|cell| f(&mut cell.borrow_mut()))
    }
}
