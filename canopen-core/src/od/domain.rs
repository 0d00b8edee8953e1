//! DOMAIN entries (DT-15): values of any length that are streamed, never buffered whole.
//!
//! A [`Domain`] is read at an offset and written in chunks, so a firmware image can be transferred by SDO
//! segmented or block transfer into flash without a RAM buffer of its size. The implementation decides
//! what "atomic" means for it (e.g. write into the inactive flash bank and switch at
//! [`end_write`](Domain::end_write)); [`abort_write`](Domain::abort_write) tells it to drop a transfer.
//! [`DomainBuf`] is a small in-memory implementation for tests and short generated data.

use super::value::{chunk_end, fits};
use super::{value::copy_streamed, AbortCode};

/// A streamed DOMAIN value.
///
/// ```
/// use canopen_core::od::{Domain, DomainBuf};
/// let mut d = DomainBuf::<16>::new();
/// d.begin_write(Some(4)).unwrap();
/// d.write_chunk(0, &[1, 2]).unwrap();
/// d.write_chunk(2, &[3, 4]).unwrap();
/// d.end_write(4).unwrap();
/// let mut buf = [0u8; 8];
/// assert_eq!(d.read(1, &mut buf), Ok(3));
/// assert_eq!(&buf[..3], &[2, 3, 4]);
/// ```
pub trait Domain {
    /// The current size in bytes, if known (an SDO upload announces it).
    fn size(&self) -> Option<usize>;

    /// Copies bytes `offset..` into `buf`; returns the number copied (0 at the end).
    fn read(&self, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode>;

    /// A download starts; `size` is the announced total if the client gave one. Refuse a size that can
    /// never fit here (0607 0012h) before any data moves.
    fn begin_write(&mut self, size: Option<usize>) -> Result<(), AbortCode>;

    /// Stores one chunk at `offset` (chunks come in increasing, contiguous offsets).
    fn write_chunk(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode>;

    /// The download completed with `total` bytes: validate and commit.
    fn end_write(&mut self, total: usize) -> Result<(), AbortCode>;

    /// The download was abandoned: discard what was received.
    fn abort_write(&mut self) {}
}

/// An in-memory DOMAIN of capacity `N`, committed at the end of a transfer (a refused or aborted transfer
/// leaves the old content).
///
/// ```
/// use canopen_core::od::{AbortCode, Domain, DomainBuf};
/// let mut d = DomainBuf::<4>::from_bytes(&[9]).unwrap();
/// assert_eq!(d.begin_write(Some(5)), Err(AbortCode::LengthTooHigh));
/// d.begin_write(None).unwrap();
/// d.write_chunk(0, &[1, 2]).unwrap();
/// d.abort_write();
/// assert_eq!(d.as_bytes(), &[9]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DomainBuf<const N: usize> {
    data: [u8; N],
    len: usize,
    staged: [u8; N],
}

impl<const N: usize> DomainBuf<N> {
    /// An empty domain.
    pub const fn new() -> Self {
        DomainBuf { data: [0; N], len: 0, staged: [0; N] }
    }

    /// A domain holding `bytes`; `None` if longer than `N`.
    pub fn from_bytes(bytes: &[u8]) -> Option<Self> {
        let mut d = Self::new();
        d.data.get_mut(..bytes.len())?.copy_from_slice(bytes);
        d.len = bytes.len();
        Some(d)
    }

    /// The committed content.
    pub fn as_bytes(&self) -> &[u8] {
        &self.data[..self.len]
    }
}

impl<const N: usize> Default for DomainBuf<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> Domain for DomainBuf<N> {
    fn size(&self) -> Option<usize> {
        Some(self.len)
    }

    fn read(&self, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        Ok(copy_streamed(self.as_bytes(), offset, buf))
    }

    fn begin_write(&mut self, size: Option<usize>) -> Result<(), AbortCode> {
        fits(size, N)
    }

    fn write_chunk(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        let end = chunk_end(offset, data.len(), N)?;
        self.staged[offset..end].copy_from_slice(data);
        Ok(())
    }

    fn end_write(&mut self, total: usize) -> Result<(), AbortCode> {
        if total > N {
            return Err(AbortCode::LengthTooHigh);
        }
        self.data[..total].copy_from_slice(&self.staged[..total]);
        self.len = total;
        Ok(())
    }
}
