//! Where a transfer's bytes come from and go to: the core client's [`ClientData`] over a `Vec`, a slice,
//! a [`std::io::Read`] (DOMAIN download streamed through a small window) and a [`std::io::Write`] (upload
//! streamed straight out), with progress.

use std::io;

use canopen_core::od::{copy_at, AbortCode};
use canopen_core::sdo::client::ClientData;

/// Progress of a transfer: called with the bytes moved so far.
pub type Progress<'a> = &'a mut (dyn FnMut(u64) + Send);

/// [`ClientData`] that can also fail on the local side (a file that cannot be read or written).
pub(crate) trait Data: ClientData + Send {
    /// The local I/O error that stopped the data, taken once.
    fn take_error(&mut self) -> Option<io::Error> {
        None
    }
}

/// Upload into a growing `Vec` of at most `cap` bytes (more aborts with 0504 0005h).
pub(crate) struct VecSink {
    pub(crate) buf: Vec<u8>,
    cap: usize,
}

impl VecSink {
    pub(crate) fn upload(cap: usize) -> Self {
        VecSink { buf: Vec::new(), cap }
    }
}

impl ClientData for VecSink {
    fn download_len(&self) -> usize {
        0
    }
    fn read(&mut self, _offset: usize, _buf: &mut [u8]) -> usize {
        0
    }
    fn write(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        let end = offset.checked_add(data.len()).filter(|&e| e <= self.cap).ok_or(AbortCode::OutOfMemory)?;
        if self.buf.len() < end {
            self.buf.resize(end, 0);
        }
        self.buf[offset..end].copy_from_slice(data);
        Ok(())
    }
}

impl Data for VecSink {}

/// Download from a slice.
pub(crate) struct SliceSource<'a> {
    pub(crate) src: &'a [u8],
    pub(crate) progress: Option<Progress<'a>>,
}

impl ClientData for SliceSource<'_> {
    fn download_len(&self) -> usize {
        self.src.len()
    }
    fn read(&mut self, offset: usize, buf: &mut [u8]) -> usize {
        let n = copy_at(self.src, offset, buf);
        if let Some(p) = self.progress.as_mut() {
            p((offset + n) as u64);
        }
        n
    }
    fn write(&mut self, _offset: usize, _data: &[u8]) -> Result<(), AbortCode> {
        Err(AbortCode::GeneralError)
    }
}

impl Data for SliceSource<'_> {}

/// How far back a streamed download keeps bytes it has read: a block download resends at most one sub-block
/// (127 × 7 = 889 bytes) from the last acknowledged one.
const KEEP: usize = 4096;

/// Download `len` bytes from a reader, keeping only a window of the bytes already read.
pub(crate) struct ReaderSource<'a, 'p> {
    pub(crate) reader: &'a mut (dyn io::Read + Send),
    pub(crate) len: usize,
    pub(crate) window: Vec<u8>,
    /// Offset of `window[0]`.
    pub(crate) start: usize,
    pub(crate) progress: Option<Progress<'p>>,
    pub(crate) error: Option<io::Error>,
}

impl<'a, 'p> ReaderSource<'a, 'p> {
    pub(crate) fn new(reader: &'a mut (dyn io::Read + Send), len: usize, progress: Option<Progress<'p>>) -> Self {
        ReaderSource { reader, len, window: Vec::new(), start: 0, progress, error: None }
    }

    fn fill_to(&mut self, end: usize) -> io::Result<()> {
        let mut chunk = [0u8; KEEP];
        while self.start + self.window.len() < end {
            // Read ahead in chunks, never past the announced length (`end` <= `len`, so this is not 0).
            let remaining = self.len - (self.start + self.window.len());
            let n = self.reader.read(&mut chunk[..remaining.min(KEEP)])?;
            if n == 0 {
                return Err(io::Error::new(
                    io::ErrorKind::UnexpectedEof,
                    format!("the source ended after {} of {} bytes", self.start + self.window.len(), self.len),
                ));
            }
            self.window.extend_from_slice(&chunk[..n]);
        }
        Ok(())
    }
}

impl ClientData for ReaderSource<'_, '_> {
    fn download_len(&self) -> usize {
        self.len
    }

    fn read(&mut self, offset: usize, buf: &mut [u8]) -> usize {
        if self.error.is_some() {
            return 0;
        }
        if offset < self.start {
            self.error = Some(io::Error::other(format!("the client went back to byte {offset}, before the window")));
            return 0;
        }
        let end = offset.saturating_add(buf.len()).min(self.len);
        if end <= offset {
            return 0;
        }
        if let Err(e) = self.fill_to(end) {
            self.error = Some(e);
            return 0;
        }
        let n = end - offset;
        buf[..n].copy_from_slice(&self.window[offset - self.start..end - self.start]);
        if offset - self.start > 2 * KEEP {
            let drop = offset - KEEP - self.start;
            self.window.drain(..drop);
            self.start += drop;
        }
        if let Some(p) = self.progress.as_mut() {
            p(end as u64);
        }
        n
    }

    fn write(&mut self, _offset: usize, _data: &[u8]) -> Result<(), AbortCode> {
        Err(AbortCode::GeneralError)
    }
}

impl Data for ReaderSource<'_, '_> {
    fn take_error(&mut self) -> Option<io::Error> {
        self.error.take()
    }
}

/// Upload streamed into a writer.
pub(crate) struct WriterSink<'a, 'p> {
    pub(crate) writer: &'a mut (dyn io::Write + Send),
    pub(crate) written: usize,
    pub(crate) progress: Option<Progress<'p>>,
    pub(crate) error: Option<io::Error>,
}

impl ClientData for WriterSink<'_, '_> {
    fn download_len(&self) -> usize {
        0
    }
    fn read(&mut self, _offset: usize, _buf: &mut [u8]) -> usize {
        0
    }
    fn write(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        // Offsets only increase and never rewind past what was written (ClientData's contract): write the
        // part not written yet.
        let end = offset.saturating_add(data.len());
        if end <= self.written {
            return Ok(());
        }
        let new = data.get(self.written.saturating_sub(offset)..).unwrap_or(&[]);
        if let Err(e) = self.writer.write_all(new) {
            self.error = Some(e);
            return Err(AbortCode::CannotStore);
        }
        self.written = end;
        if let Some(p) = self.progress.as_mut() {
            p(end as u64);
        }
        Ok(())
    }
}

impl Data for WriterSink<'_, '_> {
    fn take_error(&mut self) -> Option<io::Error> {
        self.error.take()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reader window serves re-reads from the last sub-block (a block download's retransmission) and
    /// keeps its memory bounded however long the source is.
    #[test]
    fn a_streamed_source_rereads_within_its_window() {
        let data: Vec<u8> = (0..100_000u32).map(|i| (i % 251) as u8).collect();
        let mut r = &data[..];
        let mut src = ReaderSource::new(&mut r, data.len(), None);
        let mut buf = [0u8; 7];
        let mut offset = 0;
        while offset < data.len() {
            let n = src.read(offset, &mut buf);
            assert_eq!(&buf[..n], &data[offset..offset + n]);
            // Every 127 segments, go back 889 bytes once, as a retransmitted sub-block does.
            if offset % 889 == 882 && offset > 889 {
                let back = offset - 889;
                assert_eq!(src.read(back, &mut buf), 7);
                assert_eq!(&buf[..], &data[back..back + 7]);
            }
            offset += n;
            assert!(src.window.len() <= 3 * KEEP + 7, "window grew to {}", src.window.len());
        }
        assert!(src.take_error().is_none());
    }

    #[test]
    fn a_short_source_is_an_error_not_a_short_transfer() {
        let mut r: &[u8] = &[1, 2, 3];
        let mut src = ReaderSource::new(&mut r, 10, None);
        let mut buf = [0u8; 7];
        assert_eq!(src.read(0, &mut buf), 0);
        assert_eq!(src.take_error().map(|e| e.kind()), Some(io::ErrorKind::UnexpectedEof));
    }

    #[test]
    fn a_writer_sink_skips_what_it_already_wrote() {
        let mut out = Vec::new();
        let mut sink = WriterSink { writer: &mut out, written: 0, progress: None, error: None };
        sink.write(0, &[1, 2, 3]).unwrap();
        sink.write(1, &[2, 3, 4, 5]).unwrap();
        sink.write(2, &[3]).unwrap();
        assert_eq!(sink.written, 5);
        assert_eq!(out, vec![1, 2, 3, 4, 5]);
    }
}
