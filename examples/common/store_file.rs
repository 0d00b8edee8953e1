//! The example node's `--store FILE`: one storage scheme ([`FileStorage`], atomic whole-file replacement)
//! for the parameters of 1010h/1011h (`FILE.a`/`FILE.b`) and for the LSS configuration of CiA 305 "store
//! configuration" (`FILE.lss.a`), checked at start ([`check`]).

use std::fs::{self, OpenOptions};
use std::path::{Path, PathBuf};

use canopen_core::lss::{LssStore, StoreError};
use canopen_core::storage::{slot_status, SlotStatus, Storage};
use canopen_core::wire::lss::BitRate;
use canopen_socketcan::FileStorage;

/// LSS record: magic `LSS`, format version 1, node-ID (1..=127 or FFh), bit rate table index, CRC-8.
const LSS_MAGIC: [u8; 4] = *b"LSS\x01";
const LSS_LEN: usize = 7;

/// CRC-8 (polynomial 07h, initial 00h) over the record.
fn crc8(bytes: &[u8]) -> u8 {
    bytes.iter().fold(0u8, |mut c, &b| {
        c ^= b;
        for _ in 0..8 {
            c = if c & 0x80 != 0 { (c << 1) ^ 0x07 } else { c << 1 };
        }
        c
    })
}

/// The LSS configuration in `FILE.lss.a`, one [`FileStorage`] slot.
#[derive(Debug)]
pub struct LssFile(FileStorage);

impl LssFile {
    /// The LSS store beside the parameter store `base`.
    pub fn new(base: &str) -> Self {
        LssFile(FileStorage::new(format!("{base}.lss")))
    }

    /// The file holding the record.
    pub fn path(&self) -> PathBuf {
        self.0.slot_path(0).map(Path::to_path_buf).unwrap_or_default()
    }

    /// The stored `(node-ID, bit rate index)`; `Ok(None)` when nothing is stored, `Err` says what is wrong
    /// with the record. A file that cannot be read is an error of the outer `Result` (the OS error).
    pub fn load(&mut self) -> Result<Result<Option<(u8, u8)>, String>, String> {
        let mut rec = [0u8; LSS_LEN];
        if self.0.read(0, 0, &mut rec).is_err() {
            return Err(self.0.last_error().unwrap_or("read error").to_owned());
        }
        Ok(Self::parse(&rec))
    }

    fn parse(rec: &[u8; LSS_LEN]) -> Result<Option<(u8, u8)>, String> {
        if rec.iter().all(|&b| b == 0xFF) {
            return Ok(None);
        }
        if rec[..4] != LSS_MAGIC {
            return Err("format check failed (not an LSS record of format 1)".into());
        }
        if crc8(&rec[..6]) != rec[6] {
            return Err("CRC check failed".into());
        }
        if !matches!(rec[4], 1..=127 | 0xFF) {
            return Err(format!("format check failed (node-ID {:02X}h out of range)", rec[4]));
        }
        Ok(Some((rec[4], rec[5])))
    }
}

impl LssStore for LssFile {
    fn store(&mut self, node_id: u8, bit_rate: BitRate) -> Result<(), StoreError> {
        let mut rec = [0u8; LSS_LEN];
        rec[..4].copy_from_slice(&LSS_MAGIC);
        rec[4] = node_id;
        rec[5] = bit_rate.index();
        rec[6] = crc8(&rec[..6]);
        // Offset 0 replaces the file at once (temp file, fsync, rename).
        match self.0.erase(0).and_then(|()| self.0.write(0, 0, &rec)) {
            Ok(()) => {
                println!("node: LSS configuration (node-ID {node_id}) stored in {}", self.path().display());
                Ok(())
            }
            Err(_) => {
                eprintln!("node: LSS store configuration: {}", self.0.last_error().unwrap_or("write error"));
                Err(StoreError::MediaAccess)
            }
        }
    }
}

/// What [`check`] found in a usable store.
#[derive(Debug, Default)]
pub struct Checked {
    /// One line per damaged file (the file, what failed, where it was kept).
    pub reports: Vec<String>,
    /// Whether a valid parameter record remains (else the node starts on defaults).
    pub params_valid: bool,
    /// The stored LSS `(node-ID, bit rate index)`, if any.
    pub lss: Option<(u8, u8)>,
}

/// Checks `--store base` before the node starts: `Err` (a message naming the path and the OS error) when
/// the store cannot be created or written; a file failing its format or CRC check is reported and moved to
/// `<file>.bad`, so the node starts on defaults without overwriting it unseen.
pub fn check(base: &str) -> Result<Checked, String> {
    let params = FileStorage::new(base);
    let probe = {
        let mut p = params.slot_path(0).map(Path::as_os_str).unwrap_or_default().to_os_string();
        p.push(".tmp");
        PathBuf::from(p)
    };
    // The same file FileStorage writes before renaming it over FILE.a.
    OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(true)
        .open(&probe)
        .and_then(|_| fs::remove_file(&probe))
        .map_err(|e| format!("--store {base}: cannot create {}: {e}", probe.display()))?;
    let mut out = Checked::default();
    let mut params = params;
    let mut bad = Vec::new();
    for slot in 0..2 {
        let path = params.slot_path(slot).map(Path::to_path_buf).unwrap_or_default();
        match slot_status(&mut params, slot) {
            Ok(SlotStatus::Valid) => out.params_valid = true,
            Ok(SlotStatus::Erased) => {}
            Ok(SlotStatus::BadFormat) => bad.push((path, "format check failed (not a parameter record)".to_owned())),
            Ok(SlotStatus::BadCrc) => bad.push((path, "CRC check failed".to_owned())),
            Err(_) => return Err(format!("--store {base}: {}", params.last_error().unwrap_or("read error"))),
        }
    }
    drop(params);
    let mut lss = LssFile::new(base);
    match lss.load().map_err(|e| format!("--store {base}: {e}"))? {
        Ok(found) => out.lss = found,
        Err(what) => bad.push((lss.path(), what)),
    }
    for (path, what) in bad {
        let mut kept = path.clone().into_os_string();
        kept.push(".bad");
        let kept = PathBuf::from(kept);
        fs::rename(&path, &kept).map_err(|e| format!("--store {base}: cannot move {} aside: {e}", path.display()))?;
        out.reports.push(format!("store {}: {what}; kept as {}", path.display(), kept.display()));
    }
    Ok(out)
}
