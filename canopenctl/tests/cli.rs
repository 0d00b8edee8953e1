//! The `canopenctl` binary: usage errors and a missing interface here; against the example node
//! (`examples/node.rs`, the binary NODE_BIN, default target/debug/examples/node) over vcan0 in the tests
//! `#[ignore]`d with the reason, which scripts/test-interop.sh runs inside the VM with `--include-ignored`.

use std::path::PathBuf;
use std::process::{Child, Command, Output, Stdio};
use std::time::Duration;

fn ctl(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_canopenctl")).args(args).output().expect("run canopenctl")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Run `args`, which must succeed; its standard output.
fn ok(args: &[&str]) -> String {
    let o = ctl(args);
    assert!(o.status.success(), "canopenctl {args:?} failed: {}{}", stdout(&o), stderr(&o));
    stdout(&o)
}

/// Run `args`, which must fail with status 1; its standard error.
fn fails(args: &[&str]) -> String {
    let o = ctl(args);
    assert_eq!(o.status.code(), Some(1), "canopenctl {args:?}: {}{}", stdout(&o), stderr(&o));
    stderr(&o)
}

#[test]
fn usage_errors_exit_2_with_the_reason() {
    let o = ctl(&["read", "0x80", "0x1000", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("node-ID 0x80 is not in 1..=127"), "{}", stderr(&o));
    let o = ctl(&["read", "5", "0x10000", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("0x10000 is out of range"), "{}", stderr(&o));
    let o = ctl(&["read", "5", "Setpoint", "0"]);
    assert!(o.status.code() == Some(2) && stderr(&o).contains("names need --eds"), "{}", stderr(&o));
    let o = ctl(&["dump", "5"]);
    assert!(o.status.code() == Some(2) && stderr(&o).contains("--eds"), "{}", stderr(&o));
    let o = ctl(&["read", "5", "0x1000", "0", "--type", "u33"]);
    assert!(stderr(&o).contains("unknown type"), "{}", stderr(&o));
    let help = stdout(&ctl(&["--help"]));
    for cmd in ["scan", "read", "write", "nmt", "lss", "monitor", "upload", "download", "bench"] {
        assert!(help.contains(cmd), "--help lacks {cmd}: {help}");
    }
    // What the retired `examples/master.rs` checked of its help: what it is for, and one command line.
    assert!(help.contains("CANopen (CiA 301) master") && help.contains("Example: canopenctl"), "{help}");
    let o = ctl(&["nmt", "start", "all", "--wait"]);
    assert!(o.status.code() == Some(2) && stderr(&o).contains("--wait needs one node"), "{}", stderr(&o));
    let o = ctl(&["bench", "5", "--chunk", "0"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn a_missing_interface_says_how_to_create_one() {
    let e = fails(&["--iface", "nocan7", "read", "5", "0x1000", "0"]);
    assert!(e.contains("ip link add dev nocan7 type vcan"), "{e}");
}

/// The example node's binary: NODE_BIN, else target/debug/examples/node.
fn node_bin() -> PathBuf {
    let bin = std::env::var_os("NODE_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../target/debug/examples/node")));
    assert!(bin.exists(), "no example node at {} (cargo build --example node, or set NODE_BIN)", bin.display());
    bin
}

/// An example node process on vcan0, killed when dropped.
struct NodeProcess(Child);

impl NodeProcess {
    fn start(args: &[&str]) -> Self {
        assert!(
            std::path::Path::new("/sys/class/net/vcan0").exists(),
            "no vcan0: run where it is up (scripts/vcan-run.sh)"
        );
        let child =
            Command::new(node_bin()).args(args).arg("--quiet").stdout(Stdio::null()).spawn().expect("start the node");
        // The VM's first start of a debug binary reads it all through its host filesystem: give it time.
        std::thread::sleep(Duration::from_millis(1000));
        NodeProcess(child)
    }
}

impl Drop for NodeProcess {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Every SDO command against the example node: scan, reads of numbers and strings, writes with negative
/// numbers sized by the object, strings, typed values, the node's refusals with their abort code and meaning
/// (exit 1), NMT with the monitor seeing the new state, and a DOMAIN file moved both ways.
#[test]
#[ignore = "needs SocketCAN (vcan0) and the example node: scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn the_cli_drives_the_example_node() {
    let _node = NodeProcess::start(&["--node-id", "5", "--heartbeat", "100"]);
    let scan = ok(&["scan"]);
    assert!(scan.contains("node 5 (0x05): device type 0x000F0191, \"canopen example node\""), "{scan}");
    assert_eq!(ok(&["read", "5", "0x1018", "4"]).trim(), "1 (0x00000001)");
    assert_eq!(ok(&["read", "0x05", "4120", "0x04"]).trim(), "1 (0x00000001)"); // 1018h in decimal
    assert_eq!(ok(&["read", "5", "0x1008", "0"]).trim(), "\"canopen example node\"");
    ok(&["write", "5", "0x2001", "0", "-100"]);
    assert_eq!(ok(&["read", "5", "0x2001", "0", "--type", "i16"]).trim(), "-100");
    ok(&["write", "5", "0x2001", "0", "-0x10", "--type", "i16"]);
    assert_eq!(ok(&["read", "5", "0x2001", "0", "--type", "i16"]).trim(), "-16");
    ok(&["write", "5", "0x2003", "0", "-2.5"]);
    assert_eq!(ok(&["read", "5", "0x2003", "0", "--type", "f32"]).trim(), "-2.5");
    ok(&["write", "5", "0x2004", "0", "hello world"]);
    assert_eq!(ok(&["read", "5", "0x2004", "0"]).trim(), "\"hello world\"");
    let e = fails(&["write", "5", "0x2001", "0", "5000"]);
    assert!(e.contains("0609 0031h: value of parameter written too high"), "{e}");
    let e = fails(&["read", "5", "0x1234", "0"]);
    assert!(e.contains("SDO aborted by the server: 0602 0000h: object does not exist"), "{e}");
    let e = fails(&["--timeout", "200", "read", "9", "0x1000", "0"]);
    assert!(e.contains("0504 0000h: SDO protocol timed out"), "{e}");

    ok(&["nmt", "start", "5"]);
    let seen = ok(&["monitor", "--duration", "0.5"]);
    assert!(seen.contains("  vcan0  705   [1]  05") && seen.contains("heartbeat node 5: operational"), "{seen}");
    ok(&["nmt", "preop", "all"]);
    let seen = ok(&["monitor", "--count", "1"]);
    assert!(seen.contains("heartbeat node 5: pre-operational"), "{seen}");

    domain_round_trip(50_000, &[(None, "segmented")]);
}

/// Moves `len` bytes into the 2005h DOMAIN of node 5 and back with `canopenctl download` and `upload`, once per
/// (download mode, or the default; upload mode), and checks every byte.
fn domain_round_trip(len: u32, modes: &[(Option<&str>, &str)]) {
    let dir = std::env::temp_dir().join(format!("canopenctl-{}-{len}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (src, back) = (dir.join("in.bin"), dir.join("out.bin"));
    let data: Vec<u8> = (0..len).map(|i| (i * 7 % 251) as u8).collect();
    std::fs::write(&src, &data).unwrap();
    let (s, b) = (src.to_str().unwrap(), back.to_str().unwrap());
    let moved = format!("{len} bytes");
    for &(down, up) in modes {
        let _ = std::fs::remove_file(&back);
        let mut args = vec!["download", "5", "0x2005", "0", s];
        args.extend(down.map(|m| ["--mode", m]).iter().flatten());
        assert!(ok(&args).contains(&moved), "{down:?}");
        assert!(ok(&["upload", "5", "0x2005", "0", b, "--mode", up]).contains(&moved), "{up}");
        assert!(std::fs::read(&back).unwrap() == data, "{down:?}/{up}: the DOMAIN came back different");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// What `canopenctl` took over from the retired `examples/master.rs`: `bench` (block with CRC and segmented,
/// every byte checked, the frames on the bus and the node's CPU time per frame), `nmt --wait` (the state the
/// node's heartbeat reports, boot-up after a reset, exit 1 when it never comes), `write --segmented`, and
/// files moved by block transfer without CRC and in `auto` mode.
#[test]
#[ignore = "needs SocketCAN (vcan0) and the example node: scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn the_cli_does_what_the_master_example_did() {
    let node = NodeProcess::start(&["--node-id", "5", "--heartbeat", "100"]);
    let pid = node.0.id().to_string();
    let out = ok(&["bench", "5", "--size", "10000", "--chunk", "4096", "--segmented-size", "3000", "--node-pid", &pid]);
    for line in [
        "bench block+CRC download: 10000 bytes in 3 transfers",
        "bench block+CRC upload: 5424 bytes in 3 transfers",
        "bench segmented download: 3000 bytes in 1 transfers",
        "bench segmented upload: 3000 bytes in 1 transfers",
    ] {
        assert!(out.contains(line), "no '{line}' in:\n{out}");
    }
    assert_eq!(out.matches("us/frame").count(), 4, "{out}");
    assert!(!out.contains(" 0 frames"), "{out}");

    assert_eq!(ok(&["nmt", "start", "5", "--wait"]).trim(), "node 5 reports Operational");
    assert_eq!(ok(&["nmt", "reset-comm", "5", "--wait"]).trim(), "node 5 reports BootUp");
    let e = fails(&["nmt", "stop", "9", "--wait"]);
    assert!(e.contains("node 9 did not report Stopped within 3 s"), "{e}");

    ok(&["write", "5", "0x2001", "0", "-3", "--type", "i16", "--segmented"]);
    assert_eq!(ok(&["read", "5", "0x2001", "0", "--type", "i16"]).trim(), "-3");
    domain_round_trip(20_000, &[(Some("block-no-crc"), "auto"), (Some("auto"), "block-no-crc")]);
}

/// CiA 302-3 program download through OUR SDO client (canopenctl on canopen-master; PRG-01, PRG-02, PRG-05,
/// PRG-06): the program is stopped and cleared (1F57h: no valid program), an image goes into 1F50h:01 by
/// block transfer with CRC and then segmented, the example node writes it to its `--program` file, 1F56h
/// reports the file's CRC-32 and 1F57h a valid program, and the program starts (1F51h reads 01h).
#[test]
#[ignore = "needs SocketCAN (vcan0) and the example node: scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn the_cli_downloads_a_program_image() {
    assert_eq!(crc32(b"123456789"), 0xCBF4_3926, "the test's own CRC-32 (ISO-HDLC check value)");
    let dir = std::env::temp_dir().join(format!("canopenctl-program-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (program, src) = (dir.join("image.bin"), dir.join("in.bin"));
    let _node = NodeProcess::start(&["--node-id", "5", "--heartbeat", "0", "--program", program.to_str().unwrap()]);
    for (mode, seed) in [("block", 3u32), ("segmented", 5)] {
        let data: Vec<u8> = (0..40_000u32).map(|i| ((i * seed + i / 7) % 253) as u8).collect();
        std::fs::write(&src, &data).unwrap();
        ok(&["write", "5", "0x1F51", "1", "0", "--type", "u8"]); // stop
        ok(&["write", "5", "0x1F51", "1", "3", "--type", "u8"]); // clear
        assert_eq!(read_number(&["read", "5", "0x1F57", "1"]), 2, "{mode}: 1F57h after clear: error 1, no program");
        let done = ok(&["download", "5", "0x1F50", "1", src.to_str().unwrap(), "--mode", mode]);
        assert!(done.contains("40000 bytes"), "{mode}: {done}");
        assert_eq!(read_number(&["read", "5", "0x1F57", "1"]), 0, "{mode}: 1F57h after the download: valid");
        assert!(std::fs::read(&program).unwrap() == data, "{mode}: the --program file differs from the image");
        assert_eq!(read_number(&["read", "5", "0x1F56", "1"]), u64::from(crc32(&data)), "{mode}: 1F56h");
        ok(&["write", "5", "0x1F51", "1", "1", "--type", "u8"]); // start
        assert_eq!(read_number(&["read", "5", "0x1F51", "1"]), 1, "{mode}: 1F51h after start");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The number `canopenctl read` prints first (`40000 (0x00009C40)`).
fn read_number(args: &[&str]) -> u64 {
    let out = ok(args);
    out.split_whitespace().next().and_then(|n| n.parse().ok()).unwrap_or_else(|| panic!("{args:?}: {out}"))
}

/// CRC-32 ISO-HDLC (zlib's), bit by bit: the test's own, independent of the node's table.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

/// LSS (CiA 305) through the CLI: a node started without a node-ID is found by fastscan, gets node-ID 30h,
/// boots with it after `lss switch waiting`, and answers SDO there.
#[test]
#[ignore = "needs SocketCAN (vcan0) and the example node: scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn lss_configures_a_node_without_a_node_id() {
    let _node = NodeProcess::start(&["--node-id", "255", "--serial", "0x00C0FFEE", "--heartbeat", "100"]);
    let found = ok(&["lss", "fastscan"]);
    assert!(found.contains("serial 0x00C0FFEE"), "{found}");
    ok(&["lss", "set-id", "0x30"]);
    // Inquire node-ID answers the active one: none until the node resets into its new one (CiA 305).
    let inquired = ok(&["lss", "inquire"]);
    assert!(inquired.contains("serial 0x00C0FFEE node-ID none"), "{inquired}");
    ok(&["lss", "switch", "waiting"]);
    std::thread::sleep(Duration::from_millis(200));
    assert_eq!(ok(&["read", "0x30", "0x1018", "4"]).trim(), "12648430 (0x00C0FFEE)");
}

/// `--eds` (CiA 306, the EDS the example node writes with `--eds`): objects by name, values typed by the EDS
/// (a negative INTEGER16 without --type, a REAL32), and `dump` of every readable entry with its name.
#[test]
#[ignore = "needs SocketCAN (vcan0) and the example node: scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn the_eds_names_and_types_objects() {
    let dir = std::env::temp_dir().join(format!("canopenctl-eds-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let eds = dir.join("io_module.eds");
    let e = eds.to_str().unwrap();
    let wrote = Command::new(node_bin()).args(["--eds", e]).output().expect("run the node");
    assert!(wrote.status.success() && eds.exists(), "the node wrote no EDS: {}", stderr(&wrote));
    let _node = NodeProcess::start(&["--node-id", "7", "--heartbeat", "0"]);
    ok(&["--eds", e, "write", "7", "Setpoint", "0", "-7"]);
    assert_eq!(ok(&["--eds", e, "read", "7", "0x2001", "0"]).trim(), "-7");
    assert_eq!(ok(&["--eds", e, "read", "7", "Identity object", "Serial number"]).trim(), "1 (0x00000001)");
    assert_eq!(ok(&["--eds", e, "read", "7", "Gain", "0"]).trim(), "1.5");
    let o = ctl(&["--eds", e, "read", "7", "No such object", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no object named 'No such object'"), "{}", stderr(&o));
    let dump = ok(&["--eds", e, "dump", "7"]);
    assert!(
        dump.contains("1008h:00 Manufacturer device name (VISIBLE_STRING, const) = canopen example node"),
        "{dump}"
    );
    assert!(dump.contains("2001h:00 Setpoint (INTEGER16, rw) = -7"), "{dump}");
    assert!(dump.contains("6000h:08"), "{dump}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `eds-to-rust` needs no bus: it prints the module tests/eds_to_rust.rs compiles and round-trips.
#[test]
fn eds_to_rust_prints_the_module() {
    let eds = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/eds_to_rust/io_module.eds");
    let rust = ok(&["--iface", "nocan7", "eds-to-rust", eds]);
    assert!(rust == include_str!("../../tests/data/eds_to_rust/io_module.rs"), "{rust}");
    let e = fails(&["eds-to-rust", "/nonexistent.eds"]);
    assert!(e.contains("/nonexistent.eds"), "{e}");
    // What a module leaves out is also said on stderr, one line each (shapes.eds leaves out one object).
    let shapes = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/eds_to_rust/shapes.eds");
    let o = ctl(&["eds-to-rust", shapes]);
    assert!(o.status.success());
    assert_eq!(
        stderr(&o),
        "canopenctl: shapes.eds: 2040h Complex: data type 0040h is not supported; left out.\n",
        "{}",
        stderr(&o)
    );
    // A malformed EDS: the file and the line.
    let dir = std::env::temp_dir().join(format!("canopenctl-bad-eds-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.eds");
    std::fs::write(&bad, "[2001]\nParameterName=x\nDataType=seven\n").unwrap();
    let e = fails(&["eds-to-rust", bad.to_str().unwrap()]);
    assert!(e.contains("bad.eds: line 3: [2001] DataType 'seven' is not a number"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
