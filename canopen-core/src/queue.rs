//! A bounded first-in first-out queue of `Copy` items in fixed storage: the EMCY frames waiting for the
//! inhibit time or for the node to leave Stopped ([`ErrorState`](crate::emcy::ErrorState), EMCY-09, NMT-22).
//!
//! A ring over a [`Slots`] array with a 16-bit head and length: no `unsafe` (a slot always holds a value,
//! the filler given to [`Queue::new`] until an item overwrites it), 4 bytes of bookkeeping, and slot indices
//! taken modulo the capacity, a mask for a power of two, so a slot access has no bounds check. It replaces
//! `heapless::Deque` there: the Cortex-M4 firmware's node is 164 B of flash and 24 B of RAM smaller, and
//! the EMCY pump that every `poll_transmit` runs 3 to 6 instructions cheaper (`scripts/bench-node.sh`).
//!
//! The node's transmit and event queues (`heapless::Deque`) and the active errors and 1003h history of
//! [`ErrorState`](crate::emcy::ErrorState) (`heapless::Vec`) stay on `heapless`: as this ring (initialised
//! slots, with or without an `Option` niche) or as plain arrays with a count they measured larger in both
//! firmware builds of `scripts/footprint.sh` (node +184 to +464 B, minimal -8 to +264 B; the arrays, with
//! `ErrorState` padded to its old size so that the node's layout stays, node +16/+80 B, minimal +16 B).
//! `heapless` keeps its slots uninitialised, so building the node writes nothing there, where a safe ring
//! has to fill every slot, and its operations were no larger than this ring's. Part of each figure is
//! layout alone: an unused 4-byte field added to `ErrorState` costs node 64 B, minimal 24 B, in SDO and
//! driver code that never reads it, so compare a container change with the node's layout held fixed too.
//!
//! ```
//! use canopen_core::queue::Queue;
//! let mut q: Queue<u8, [u8; 2]> = Queue::new([0; 2]);
//! assert_eq!(q.push_back(1), Ok(()));
//! assert_eq!(q.push_back(2), Ok(()));
//! assert_eq!(q.push_back(3), Err(3)); // full: the newest item is refused
//! assert_eq!(q.pop_front(), Some(1));
//! assert_eq!(q.push_back(3), Ok(())); // wraps around
//! assert_eq!((q.pop_front(), q.pop_front(), q.pop_front()), (Some(2), Some(3), None));
//! ```

use core::marker::PhantomData;

use crate::sizes::Slots;

/// A FIFO of at most `S::LEN` items of `T` (at most 65,535) stored in `S` (an array `[T; N]`).
///
/// ```
/// use canopen_core::queue::Queue;
/// let mut q: Queue<u16, [u16; 4]> = Queue::new([0; 4]);
/// q.push_back(7).unwrap();
/// assert_eq!((q.len(), q.front()), (1, Some(&7)));
/// ```
#[derive(Debug, Clone)]
pub struct Queue<T, S> {
    slots: S,
    head: u16,
    len: u16,
    item: PhantomData<T>,
}

impl<T: Copy, S: Slots<T>> Queue<T, S> {
    /// An empty queue in `slots` (their values are never read before an item overwrites them).
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let q: Queue<u8, [u8; 3]> = Queue::new([0; 3]);
    /// assert!(q.is_empty());
    /// ```
    pub const fn new(slots: S) -> Self {
        const { assert!(S::LEN <= u16::MAX as usize, "a queue holds at most 65,535 items") };
        Queue { slots, head: 0, len: 0, item: PhantomData }
    }

    /// The number of items queued.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let mut q: Queue<u8, [u8; 3]> = Queue::new([0; 3]);
    /// q.push_back(1).unwrap();
    /// assert_eq!(q.len(), 1);
    /// ```
    #[inline]
    pub const fn len(&self) -> usize {
        self.len as usize
    }

    /// Whether nothing is queued.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// assert!(Queue::<u8, [u8; 1]>::new([0]).is_empty());
    /// ```
    #[inline]
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Whether the queue holds `S::LEN` items.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let mut q: Queue<u8, [u8; 1]> = Queue::new([0]);
    /// q.push_back(1).unwrap();
    /// assert!(q.is_full());
    /// ```
    #[inline]
    pub const fn is_full(&self) -> bool {
        self.len as usize >= S::LEN
    }

    /// Appends `item`, or hands it back when the queue is full.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let mut q: Queue<u8, [u8; 1]> = Queue::new([0]);
    /// assert_eq!((q.push_back(1), q.push_back(2)), (Ok(()), Err(2)));
    /// ```
    #[inline]
    pub fn push_back(&mut self, item: T) -> Result<(), T> {
        if self.is_full() {
            return Err(item);
        }
        if let Some(slot) = self.slots.as_mut().get_mut(Self::wrap(usize::from(self.head) + usize::from(self.len))) {
            *slot = item;
        }
        self.len += 1;
        Ok(())
    }

    /// The oldest item, left in the queue.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let mut q: Queue<u8, [u8; 2]> = Queue::new([0; 2]);
    /// assert_eq!(q.front(), None);
    /// q.push_back(4).unwrap();
    /// assert_eq!(q.front(), Some(&4));
    /// ```
    #[inline]
    pub fn front(&self) -> Option<&T> {
        if self.is_empty() {
            return None;
        }
        self.slots.as_ref().get(Self::wrap(usize::from(self.head)))
    }

    /// The newest item, left in the queue.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let mut q: Queue<u8, [u8; 2]> = Queue::new([0; 2]);
    /// assert_eq!(q.back(), None);
    /// q.push_back(4).unwrap();
    /// q.push_back(5).unwrap();
    /// assert_eq!(q.back(), Some(&5));
    /// ```
    #[inline]
    pub fn back(&self) -> Option<&T> {
        self.get(self.len().checked_sub(1)?)
    }

    /// The `i`-th oldest item.
    fn get(&self, i: usize) -> Option<&T> {
        if i >= self.len() {
            return None;
        }
        self.slots.as_ref().get(Self::wrap(usize::from(self.head) + i))
    }

    /// Takes the oldest item out.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let mut q: Queue<u8, [u8; 2]> = Queue::new([0; 2]);
    /// q.push_back(4).unwrap();
    /// assert_eq!((q.pop_front(), q.pop_front()), (Some(4), None));
    /// ```
    #[inline]
    pub fn pop_front(&mut self) -> Option<T> {
        let item = *self.front()?;
        self.head = Self::wrap(usize::from(self.head) + 1) as u16;
        self.len -= 1;
        Some(item)
    }

    /// `i` (below `2 * S::LEN`) as a slot index: a mask for a power-of-two capacity, so that the slot
    /// access needs no bounds check.
    #[inline]
    const fn wrap(i: usize) -> usize {
        i % S::LEN
    }

    /// Appends `item`; when the queue is full the oldest item gives up its slot (the head moves on) and
    /// `true` says one was dropped. Nothing is copied out.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let mut q: Queue<u8, [u8; 2]> = Queue::new([0; 2]);
    /// assert!(!q.force_push_back(1));
    /// assert!(!q.force_push_back(2));
    /// assert!(q.force_push_back(3)); // full: 1 is dropped
    /// assert_eq!((q.pop_front(), q.pop_front(), q.pop_front()), (Some(2), Some(3), None));
    /// ```
    pub fn force_push_back(&mut self, item: T) -> bool {
        if S::LEN == 0 {
            return true; // no slot: the item itself is dropped
        }
        let full = self.is_full();
        // Full, head + len is the head itself: the oldest slot becomes the newest.
        if let Some(slot) = self.slots.as_mut().get_mut(Self::wrap(usize::from(self.head) + usize::from(self.len))) {
            *slot = item;
        }
        if full {
            self.head = Self::wrap(usize::from(self.head) + 1) as u16;
        } else {
            self.len += 1;
        }
        full
    }

    /// Drops every item but the newest and returns how many went: the head moves past them, nothing is
    /// copied.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let mut q: Queue<u8, [u8; 4]> = Queue::new([0; 4]);
    /// for i in 1..=3 {
    ///     q.push_back(i).unwrap();
    /// }
    /// assert_eq!(q.keep_newest(), 2);
    /// assert_eq!((q.pop_front(), q.pop_front()), (Some(3), None));
    /// assert_eq!(q.keep_newest(), 0); // empty: nothing to drop
    /// ```
    pub fn keep_newest(&mut self) -> usize {
        let dropped = self.len.saturating_sub(1);
        self.head = Self::wrap(usize::from(self.head) + usize::from(dropped)) as u16;
        self.len -= dropped;
        usize::from(dropped)
    }

    /// Empties the queue.
    ///
    /// ```
    /// use canopen_core::queue::Queue;
    /// let mut q: Queue<u8, [u8; 2]> = Queue::new([0; 2]);
    /// q.push_back(4).unwrap();
    /// q.clear();
    /// assert!(q.is_empty());
    /// ```
    #[inline]
    pub fn clear(&mut self) {
        self.head = 0;
        self.len = 0;
    }
}

/// Two queues are equal when they hold the same items in the same order (whatever the slots beside them
/// hold).
///
/// ```
/// use canopen_core::queue::Queue;
/// let mut a: Queue<u8, [u8; 2]> = Queue::new([0; 2]);
/// let mut b: Queue<u8, [u8; 2]> = Queue::new([9; 2]);
/// a.push_back(1).unwrap();
/// a.push_back(2).unwrap();
/// a.pop_front();
/// b.push_back(2).unwrap();
/// assert_eq!(a, b);
/// ```
impl<T: Copy + PartialEq, S: Slots<T>> PartialEq for Queue<T, S> {
    fn eq(&self, other: &Self) -> bool {
        self.len == other.len && (0..self.len()).all(|i| self.get(i) == other.get(i))
    }
}

impl<T: Copy + Eq, S: Slots<T>> Eq for Queue<T, S> {}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::collections::VecDeque;

    /// The queue against `VecDeque` bounded to the same capacity, over every push/pop sequence of length 12
    /// on capacities 1..=4 (wrap-around at each position, full and empty at each position).
    #[test]
    fn behaves_as_a_bounded_vecdeque() {
        fn check<const N: usize>() {
            for ops in 0u32..1 << 12 {
                let mut q: Queue<u32, [u32; N]> = Queue::new([0; N]);
                let mut model = VecDeque::new();
                for step in 0..12u32 {
                    if ops >> step & 1 == 1 {
                        let expect = if model.len() < N { Ok(()) } else { Err(step) };
                        if expect.is_ok() {
                            model.push_back(step);
                        }
                        assert_eq!(q.push_back(step), expect);
                    } else {
                        assert_eq!(q.pop_front(), model.pop_front());
                    }
                    assert_eq!(q.len(), model.len());
                    assert_eq!(q.front(), model.front());
                    assert_eq!(q.back(), model.back());
                    assert_eq!((q.is_empty(), q.is_full()), (model.is_empty(), model.len() == N));
                }
            }
        }
        check::<1>();
        check::<2>();
        check::<3>();
        check::<4>();
    }

    /// `force_push_back` against `VecDeque` (pop the oldest when full, then push) over every sequence of 8
    /// pushes, forced pushes and pops on capacities 1..=4.
    #[test]
    fn force_push_back_drops_the_oldest() {
        fn check<const N: usize>() {
            for mut ops in 0u32..3u32.pow(8) {
                let mut q: Queue<u32, [u32; N]> = Queue::new([0; N]);
                let mut model = VecDeque::new();
                for step in 0..8u32 {
                    match ops % 3 {
                        0 => assert_eq!(q.pop_front(), model.pop_front()),
                        1 => {
                            let expect = if model.len() < N { Ok(()) } else { Err(step) };
                            if expect.is_ok() {
                                model.push_back(step);
                            }
                            assert_eq!(q.push_back(step), expect);
                        }
                        _ => {
                            let full = model.len() == N;
                            if full {
                                model.pop_front();
                            }
                            model.push_back(step);
                            assert_eq!(q.force_push_back(step), full);
                        }
                    }
                    ops /= 3;
                    assert_eq!((q.len(), q.front(), q.back()), (model.len(), model.front(), model.back()));
                }
            }
        }
        check::<1>();
        check::<2>();
        check::<3>();
        check::<4>();
        let mut empty: Queue<u32, [u32; 0]> = Queue::new([]);
        assert!(empty.force_push_back(1));
        assert_eq!(empty.pop_front(), None);
    }

    /// `keep_newest` at every fill level and head position of a 4-slot queue: only the newest item stays,
    /// the count of the others is returned, and the queue goes on in order after it.
    #[test]
    fn keep_newest_keeps_only_the_back() {
        for start in 0..4u32 {
            for n in 0..=4u32 {
                let mut q: Queue<u32, [u32; 4]> = Queue::new([0; 4]);
                for i in 0..start {
                    assert_eq!(q.push_back(i), Ok(()));
                    assert_eq!(q.pop_front(), Some(i));
                }
                for i in 0..n {
                    assert_eq!(q.push_back(10 + i), Ok(()));
                }
                let newest = q.back().copied();
                assert_eq!(q.keep_newest(), n.saturating_sub(1) as usize);
                assert_eq!((q.len(), q.front().copied(), q.back().copied()), (n.min(1) as usize, newest, newest));
                assert_eq!(q.push_back(99), Ok(()));
                assert_eq!((q.pop_front(), q.pop_front()), if n == 0 { (Some(99), None) } else { (newest, Some(99)) });
            }
        }
    }
}
