//! Parameter storage (1010h/1011h) in files: [`FileStorage`], the Linux implementation of the core's
//! two-slot [`Storage`] trait.
//!
//! # How it meets the core's contract
//!
//! The core ([`canopen_core::storage`]) asks for two slots where **writing one slot never changes the
//! other**, and tolerates a write torn at any byte; it builds atomic saves on top (A/B records with a
//! sequence number and a CRC-32, payload first, header last).
//!
//! `FileStorage::new(path)` keeps slot 0 in `path.a` and slot 1 in `path.b`: separate files, so a write to
//! one slot cannot touch the other. Each slot is held in memory and written to its file by replacing the
//! whole file: the image goes to `path.X.tmp`, is `fsync`ed, renamed over `path.X` (atomic on POSIX file
//! systems) and the directory is `fsync`ed. A slot file therefore always holds either its old or its new
//! content, never a torn mix, which is stronger than the contract asks.
//!
//! Writes are collected in memory and the file is replaced when the write covers the record header (the
//! first [`HEADER_LEN`] bytes, which the core writes **last**, so that a save costs one file replacement
//! instead of one per item), before the other slot or this one is read, on [`flush`](FileStorage::flush)
//! and on drop. Until then the file keeps its previous content, which is exactly what a power loss before
//! these writes would leave: the slot being written is never the one holding the newest valid record, so
//! the previous parameters stay loadable. When the node answers the 1010h download, the record is on disk.
//!
//! A missing file reads as erased (`FFh`); a file longer than the capacity is cut to it.

use std::fs::{self, File, OpenOptions};
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};

use canopen_core::storage::{Storage, StorageError, HEADER_LEN};

/// Default bytes per slot: room for the communication profile with PDOs and a few KiB of application data.
pub const DEFAULT_CAPACITY: usize = 16 * 1024;

/// Two-slot parameter storage in the files `PATH.a` and `PATH.b` (see the [module docs](self)).
///
/// ```no_run
/// use canopen_core::storage::Storage;
/// use canopen_socketcan::FileStorage;
/// let mut st = FileStorage::new("/var/lib/mynode/params");
/// st.erase(0).unwrap();
/// st.write(0, 0, b"hello").unwrap(); // offset 0: the file is replaced now (temp file, fsync, rename)
/// ```
#[derive(Debug)]
pub struct FileStorage {
    paths: [PathBuf; 2],
    capacity: usize,
    /// The in-memory image of each slot once loaded, and whether it differs from the file.
    slots: [Option<(Vec<u8>, bool)>; 2],
    /// The last I/O error, for diagnostics (the core only sees [`StorageError::Io`]).
    last_error: Option<String>,
}

impl FileStorage {
    /// Storage in `path.a` / `path.b` with [`DEFAULT_CAPACITY`] bytes per slot. Nothing is touched until
    /// the node reads or saves.
    pub fn new(path: impl AsRef<Path>) -> Self {
        Self::with_capacity(path, DEFAULT_CAPACITY)
    }

    /// Storage with `capacity` bytes per slot.
    pub fn with_capacity(path: impl AsRef<Path>, capacity: usize) -> Self {
        let base = path.as_ref().as_os_str();
        let slot = |suffix: &str| {
            let mut p = base.to_os_string();
            p.push(suffix);
            PathBuf::from(p)
        };
        FileStorage { paths: [slot(".a"), slot(".b")], capacity, slots: [None, None], last_error: None }
    }

    /// The file of `slot` (0 or 1).
    pub fn slot_path(&self, slot: u8) -> Option<&Path> {
        self.paths.get(usize::from(slot)).map(PathBuf::as_path)
    }

    /// The last file error, if any (the core maps every failure to SDO abort 0606 0000h).
    pub fn last_error(&self) -> Option<&str> {
        self.last_error.as_deref()
    }

    /// Writes every slot whose image differs from its file.
    pub fn flush(&mut self) -> Result<(), StorageError> {
        for slot in 0..2 {
            self.persist(slot)?;
        }
        Ok(())
    }

    /// Records the error `e` of `what` (opening, reading, writing) on the file of slot `i`.
    fn fail(&mut self, what: &str, i: usize, e: io::Error) -> StorageError {
        self.last_error = Some(format!("{what} {}: {e}", self.paths[i].display()));
        StorageError::Io
    }

    /// The image of `slot` and whether it differs from the file (dirty), loaded from its file on first use.
    fn image(&mut self, slot: u8) -> Result<&mut (Vec<u8>, bool), StorageError> {
        let i = usize::from(slot);
        if i > 1 {
            return Err(StorageError::Io);
        }
        let entry = match self.slots[i].take() {
            Some(entry) => entry,
            None => (self.load(i)?, false),
        };
        Ok(self.slots[i].insert(entry))
    }

    /// The content of the file of slot `i`, at most `capacity` bytes; empty when there is no file yet.
    fn load(&mut self, i: usize) -> Result<Vec<u8>, StorageError> {
        let mut data = Vec::new();
        match File::open(&self.paths[i]) {
            Ok(mut f) => {
                if let Err(e) = f.read_to_end(&mut data) {
                    return Err(self.fail("reading", i, e));
                }
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => return Err(self.fail("opening", i, e)),
        }
        data.truncate(self.capacity);
        Ok(data)
    }

    /// Replaces the file of `slot` with its image if they differ: temp file, fsync, rename, fsync of the
    /// directory.
    fn persist(&mut self, slot: u8) -> Result<(), StorageError> {
        let i = usize::from(slot);
        let Some((data, dirty)) = self.slots.get(i).and_then(Option::as_ref) else {
            return Ok(());
        };
        if !dirty {
            return Ok(());
        }
        let path = self.paths[i].clone();
        let mut tmp = path.clone().into_os_string();
        tmp.push(".tmp");
        let tmp = PathBuf::from(tmp);
        let result = (|| {
            let mut f = OpenOptions::new().write(true).create(true).truncate(true).open(&tmp)?;
            f.write_all(data)?;
            f.sync_all()?;
            drop(f);
            fs::rename(&tmp, &path)?;
            let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
            File::open(dir)?.sync_all()
        })();
        match result {
            Ok(()) => {
                if let Some((_, dirty)) = self.slots[i].as_mut() {
                    *dirty = false;
                }
                Ok(())
            }
            Err(e) => Err(self.fail("writing", i, e)),
        }
    }
}

impl Storage for FileStorage {
    fn capacity(&self) -> usize {
        self.capacity
    }

    fn erase(&mut self, slot: u8) -> Result<(), StorageError> {
        let (image, dirty) = self.image(slot)?;
        image.clear();
        *dirty = true;
        Ok(())
    }

    fn write(&mut self, slot: u8, offset: usize, data: &[u8]) -> Result<(), StorageError> {
        let end = offset.checked_add(data.len()).filter(|&e| e <= self.capacity).ok_or(StorageError::TooLarge)?;
        // Another slot's pending writes go out first, so the files never fall behind the order of writes.
        self.persist(1 - slot.min(1))?;
        let (image, dirty) = self.image(slot)?;
        if image.len() < end {
            image.resize(end, 0xFF);
        }
        image[offset..end].copy_from_slice(data);
        *dirty = true;
        if offset < HEADER_LEN {
            self.persist(slot)?;
        }
        Ok(())
    }

    fn read(&mut self, slot: u8, offset: usize, buf: &mut [u8]) -> Result<(), StorageError> {
        self.persist(slot)?;
        let (image, _) = self.image(slot)?;
        buf.fill(0xFF);
        if let Some(src) = image.get(offset..) {
            let n = src.len().min(buf.len());
            buf[..n].copy_from_slice(&src[..n]);
        }
        Ok(())
    }
}

impl Drop for FileStorage {
    fn drop(&mut self) {
        let _ = self.flush();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh directory under the system temp dir, removed at the end.
    struct TempDir(PathBuf);

    impl TempDir {
        fn new(name: &str) -> Self {
            let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().as_nanos();
            let p = std::env::temp_dir().join(format!("canopen-fs-{name}-{}-{nanos}", std::process::id()));
            fs::create_dir_all(&p).unwrap();
            TempDir(p)
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = fs::remove_dir_all(&self.0);
        }
    }

    fn read(st: &mut FileStorage, slot: u8, offset: usize, n: usize) -> Vec<u8> {
        let mut b = vec![0; n];
        st.read(slot, offset, &mut b).unwrap();
        b
    }

    #[test]
    fn missing_files_read_as_erased() {
        let dir = TempDir::new("missing");
        let mut st = FileStorage::with_capacity(dir.0.join("p"), 64);
        assert_eq!(st.capacity(), 64);
        assert_eq!(read(&mut st, 0, 10, 4), [0xFF; 4]);
        assert_eq!(read(&mut st, 1, 60, 8), [0xFF; 8]); // past the capacity: still "erased", no error
        assert!(!dir.0.join("p.a").exists());
    }

    /// A file that cannot be read is an I/O error that names the file (the core answers 0606 0000h), and
    /// the slot is not taken as erased: once the file reads, its content is there.
    #[test]
    fn unreadable_file_fails_and_a_later_read_retries() {
        let dir = TempDir::new("unreadable");
        let base = dir.0.join("p");
        let mut st = FileStorage::with_capacity(&base, 64);
        fs::create_dir(dir.0.join("p.a")).unwrap(); // opens, but reading a directory fails
        let mut buf = [0u8; 4];
        assert_eq!(st.read(0, 0, &mut buf), Err(StorageError::Io));
        assert!(st.last_error().is_some_and(|e| e.starts_with("reading ") && e.contains("p.a")));
        assert_eq!(st.erase(0), Err(StorageError::Io));
        assert_eq!(st.read(2, 0, &mut buf), Err(StorageError::Io)); // only slots 0 and 1 exist
        fs::remove_dir(dir.0.join("p.a")).unwrap();
        fs::write(dir.0.join("p.a"), [1, 2, 3]).unwrap();
        assert_eq!(read(&mut st, 0, 0, 4), [1, 2, 3, 0xFF]);
    }

    #[test]
    fn writing_slot_a_leaves_slot_b_intact() {
        let dir = TempDir::new("ab");
        let base = dir.0.join("params");
        let mut st = FileStorage::with_capacity(&base, 128);
        st.erase(1).unwrap();
        st.write(1, 20, b"payload B").unwrap();
        st.write(1, 0, b"header B").unwrap();
        let b_file = fs::read(dir.0.join("params.b")).unwrap();
        st.erase(0).unwrap();
        st.write(0, 20, b"payload A, longer").unwrap();
        st.write(0, 0, b"header A").unwrap();
        assert_eq!(fs::read(dir.0.join("params.b")).unwrap(), b_file, "slot B's file is untouched");
        assert_eq!(read(&mut st, 1, 0, 8), b"header B");
        assert_eq!(read(&mut st, 0, 20, 17), b"payload A, longer");
        // Erasing and rewriting A again still leaves B alone.
        st.erase(0).unwrap();
        st.write(0, 0, b"x").unwrap();
        assert_eq!(read(&mut st, 1, 20, 9), b"payload B");
        assert_eq!(read(&mut st, 0, 0, 2), [b'x', 0xFF]);
        assert!(!dir.0.join("params.a.tmp").exists(), "the temp file was renamed");
    }

    #[test]
    fn header_write_makes_the_record_durable_and_a_new_instance_reads_it() {
        let dir = TempDir::new("durable");
        let base = dir.0.join("p");
        let mut st = FileStorage::with_capacity(&base, 256);
        st.erase(0).unwrap();
        st.write(0, HEADER_LEN, &[1, 2, 3]).unwrap();
        // Payload only: the file is not replaced yet (a power loss now leaves the old slot content).
        assert!(!dir.0.join("p.a").exists());
        st.write(0, 0, &[9; HEADER_LEN]).unwrap();
        // Like a killed process: no drop, no flush.
        std::mem::forget(st);
        let mut again = FileStorage::with_capacity(&base, 256);
        assert_eq!(read(&mut again, 0, HEADER_LEN, 3), [1, 2, 3]);
        assert_eq!(read(&mut again, 0, 0, 2), [9, 9]);
    }
}
