//! The example node's `--store` checks and LSS storage (issue 16 items 1 and 2), run as a user would: the
//! binary `examples/node` with bad input, checking the message and the exit code. No CAN interface is needed:
//! the store is checked before the socket is opened, and `--iface nosuchcan9` makes every run end at the
//! socket (exit code 2) right after the store was dealt with.

#[path = "../examples/common/store_file.rs"]
#[allow(dead_code)]
mod store_file;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

use canopen_core::lss::LssStore;
use canopen_core::wire::lss::BitRate;

/// `target/<profile>/examples/node`, built once (this test binary lives in `target/<profile>/deps`).
fn node_bin() -> &'static Path {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        let exe = std::env::current_exe().expect("test executable path");
        let profile_dir = exe.parent().and_then(Path::parent).expect("target/<profile>").to_path_buf();
        let mut build = Command::new(env!("CARGO"));
        build.args(["build", "--quiet", "--example", "node", "--manifest-path"]);
        build.arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml"));
        if profile_dir.file_name().is_some_and(|n| n == "release") {
            build.arg("--release");
        }
        let status = build.status().expect("run cargo build --example node");
        assert!(status.success(), "cargo build --example node failed");
        profile_dir.join("examples").join("node")
    })
}

/// A fresh directory under the system temp dir, removed at the end.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().as_nanos();
        let p = std::env::temp_dir().join(format!("canopen-cli-{name}-{}-{nanos}", std::process::id()));
        std::fs::create_dir_all(&p).unwrap();
        TempDir(p)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn run_node(args: &[&str]) -> (Output, String, String) {
    let out = Command::new(node_bin()).args(["--iface", "nosuchcan9"]).args(args).output().expect("run node");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    (out, stdout, stderr)
}

/// The run got past the store to the socket (which does not exist here).
fn reached_the_socket(out: &Output, stderr: &str) {
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("no SocketCAN interface 'nosuchcan9'"), "{stderr}");
}

#[test]
fn a_store_path_that_cannot_be_created_ends_the_program_before_the_node_starts() {
    let dir = TempDir::new("nodir");
    let store = dir.0.join("no/such/dir/state");
    let (out, stdout, stderr) = run_node(&["--store", store.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    let line = stderr.lines().next().unwrap_or_default();
    assert!(line.contains(&format!("{}.a.tmp", store.display())), "names the path: {line}");
    assert!(line.contains("No such file or directory (os error 2)"), "names the OS error: {line}");
    assert!(!stderr.contains("SocketCAN"), "ends before the socket: {stderr}");
    assert!(stdout.is_empty(), "{stdout}");
}

#[test]
fn a_store_that_is_a_directory_is_refused_with_the_os_error() {
    let dir = TempDir::new("isdir");
    let store = dir.0.join("state");
    std::fs::create_dir_all(dir.0.join("state.a.tmp")).unwrap();
    let (out, _, stderr) = run_node(&["--store", store.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(&format!("cannot create {}.a.tmp: Is a directory", store.display())), "{stderr}");
}

#[test]
fn a_garbage_parameter_file_is_reported_kept_as_bad_and_the_node_starts_on_defaults() {
    let dir = TempDir::new("garbage");
    let store = dir.0.join("s");
    std::fs::write(dir.0.join("s.a"), b"garbage, not a record").unwrap();
    let (out, _, stderr) = run_node(&["--store", store.to_str().unwrap()]);
    let a = dir.0.join("s.a");
    assert!(
        stderr.contains(&format!(
            "store {}: format check failed (not a parameter record); kept as {}.bad",
            a.display(),
            a.display()
        )),
        "{stderr}"
    );
    assert!(stderr.contains("starting on defaults"), "{stderr}");
    assert_eq!(std::fs::read(dir.0.join("s.a.bad")).unwrap(), b"garbage, not a record");
    assert!(!a.exists(), "moved aside, not left to be overwritten unseen");
    reached_the_socket(&out, &stderr);
}

#[test]
fn a_parameter_record_failing_its_crc_is_reported() {
    let dir = TempDir::new("crc");
    // A record header of format 1 (magic "COSR", version 1, groups COMM, seq 1, no payload), wrong CRC.
    let mut rec = b"COSR\x01\x01\0\0".to_vec();
    rec.extend_from_slice(&1u32.to_le_bytes());
    rec.extend_from_slice(&0u32.to_le_bytes());
    rec.extend_from_slice(&0xDEAD_BEEFu32.to_le_bytes());
    std::fs::write(dir.0.join("s.b"), &rec).unwrap();
    let (out, _, stderr) = run_node(&["--store", dir.0.join("s").to_str().unwrap()]);
    let b = dir.0.join("s.b");
    assert!(
        stderr.contains(&format!("store {}: CRC check failed; kept as {}.bad", b.display(), b.display())),
        "{stderr}"
    );
    assert_eq!(std::fs::read(dir.0.join("s.b.bad")).unwrap(), rec);
    reached_the_socket(&out, &stderr);
}

#[test]
fn a_damaged_lss_record_is_reported_and_the_node_id_argument_is_used() {
    let dir = TempDir::new("lssbad");
    std::fs::write(dir.0.join("s.lss.a"), b"LSS\x01\x2a\x04X").unwrap(); // CRC byte wrong
    let (out, stdout, stderr) = run_node(&["--store", dir.0.join("s").to_str().unwrap(), "--node-id", "5"]);
    let f = dir.0.join("s.lss.a");
    assert!(
        stderr.contains(&format!("store {}: CRC check failed; kept as {}.bad", f.display(), f.display())),
        "{stderr}"
    );
    assert!(!stdout.contains("from the LSS store"), "{stdout}");
    assert!(dir.0.join("s.lss.a.bad").exists());
    reached_the_socket(&out, &stderr);
}

/// LSS-09, CiA 305 store configuration: what LSS stored is used at the next power-on over `--node-id` (the factory
/// default), written through the node's own store code and read back by the binary.
#[test]
fn a_stored_lss_node_id_wins_over_the_node_id_argument_at_the_next_start() {
    let dir = TempDir::new("lss");
    let base = dir.0.join("s");
    let base = base.to_str().unwrap();
    let mut lss = store_file::LssFile::new(base);
    lss.store(42, BitRate::K125).unwrap();
    assert_eq!(lss.load(), Ok(Ok(Some((42, BitRate::K125.index())))));
    drop(lss);
    let (out, stdout, stderr) = run_node(&["--store", base, "--node-id", "5"]);
    assert!(
        stdout.contains(&format!(
            "node-ID 42 from the LSS store (bit rate table index {}), not --node-id 5",
            BitRate::K125.index()
        )),
        "{stdout}"
    );
    assert!(!stderr.contains("check failed"), "{stderr}");
    reached_the_socket(&out, &stderr);
    // Without a store the argument is used.
    let (out, stdout, stderr) = run_node(&["--node-id", "5"]);
    assert!(!stdout.contains("LSS store"), "{stdout}");
    reached_the_socket(&out, &stderr);
}

/// LSS-09: a store that fails while the node runs (its directory gone) is answered with error 02h
/// (storage media access error), not a panic.
#[test]
fn an_lss_store_that_cannot_be_written_answers_a_media_access_error() {
    let dir = TempDir::new("lssgone");
    let base = dir.0.join("gone/s");
    let mut lss = store_file::LssFile::new(base.to_str().unwrap());
    assert_eq!(lss.store(42, BitRate::K125), Err(canopen_core::lss::StoreError::MediaAccess));
    // Nothing half-stored is read back as a configuration: the error names the file and the OS error.
    let expected = format!("writing {}.lss.a: No such file or directory (os error 2)", base.display());
    assert_eq!(lss.load(), Err(expected));
}
