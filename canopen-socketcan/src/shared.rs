//! The node shared between a runner and the application's threads or tasks, whatever the runtime.

use std::sync::Mutex;

use canopen_core::driver::Shared;

/// The node in a `std::sync::Mutex`, shared between the driver and application tasks. A poisoned lock
/// (a panic in another task while it held the node) is taken over: the node's state machines never
/// leave a half-updated state visible across calls.
///
/// ```
/// use canopen_core::driver::Shared;
/// let s = canopen_socketcan::MutexShared::new(5u32);
/// s.with(|v| *v += 1);
/// assert_eq!(s.lock(|v| *v), 6);
/// ```
#[derive(Debug, Default)]
pub struct MutexShared<N>(Mutex<N>);

impl<N> MutexShared<N> {
    /// Wraps `node`.
    pub fn new(node: N) -> Self {
        MutexShared(Mutex::new(node))
    }

    /// Runs `f` with the node locked (the same as [`Shared::lock`], without importing the trait).
    pub fn with<R>(&self, f: impl FnOnce(&mut N) -> R) -> R {
        let mut guard = self.0.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        f(&mut guard)
    }
}

impl<N> Shared<N> for MutexShared<N> {
    fn lock<R>(&self, f: impl FnOnce(&mut N) -> R) -> R {
        self.with(f)
    }
}
