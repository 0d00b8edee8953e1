//! The SYNC producer: the master's side of 1005h/1006h/1019h, a SYNC on 80h every period (with a counter
//! when asked), the trigger of the nodes' synchronous PDOs (their mapping is configured in
//! [`pdo`](crate::pdo)).

use std::time::Duration;

use canopen_core::CanFrame;
use tokio::task::JoinHandle;

use crate::{Error, Master};

impl Master {
    /// Starts a SYNC producer (1005h/1006h/1019h on the master's side): a SYNC on 80h every `period`, with a
    /// counter 1..=`overflow` in one data byte when `overflow` is 2..=240 (SYNC-04), without data when it is
    /// 0. It runs until the returned handle is dropped.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// use std::time::Duration;
    /// let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::Master::new(bus.port());
    /// let watcher = canopen_master::Master::new(bus.port());
    /// let mut frames = watcher.frames();
    /// let sync = m.start_sync(Duration::from_millis(10), 3).unwrap();
    /// for counter in [1, 2, 3, 1] {
    ///     assert_eq!(frames.recv().await.unwrap().data(), &[counter]);
    /// }
    /// # });
    /// ```
    pub fn start_sync(&self, period: Duration, overflow: u8) -> Result<SyncProducer, Error> {
        if overflow == 1 || overflow > 240 {
            return Err(Error::InvalidArgument(format!("SYNC counter overflow {overflow} is not 0 or 2..=240")));
        }
        if period.is_zero() {
            return Err(Error::InvalidArgument("a SYNC period of 0".into()));
        }
        let io = self.inner.io.clone();
        let task = tokio::spawn(async move {
            let mut tick = tokio::time::interval(period);
            tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
            let mut counter = 0u8;
            loop {
                tick.tick().await;
                let frame = if overflow == 0 {
                    CanFrame::from_parts(0x80, [0; 8], 0)
                } else {
                    counter = if counter >= overflow { 1 } else { counter + 1 };
                    CanFrame::from_parts(0x80, [counter, 0, 0, 0, 0, 0, 0, 0], 1)
                };
                if io.send(&frame).await.is_err() {
                    return;
                }
            }
        });
        Ok(SyncProducer { task })
    }
}

/// A running SYNC producer ([`Master::start_sync`]); dropping it stops the SYNCs.
///
/// ```
/// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
/// # rt.block_on(async {
/// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
/// let sync = m.start_sync(std::time::Duration::from_millis(10), 0).unwrap();
/// drop(sync); // stops
/// # });
/// ```
pub struct SyncProducer {
    task: JoinHandle<()>,
}

impl Drop for SyncProducer {
    fn drop(&mut self) {
        self.task.abort();
    }
}
