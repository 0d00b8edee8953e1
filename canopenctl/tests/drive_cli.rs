//! `canopenctl drive ...` (canopen-master's `Drive402`): usage errors here; against the example drive
//! (`examples/drive.rs`, the binary DRIVE_BIN, default target/debug/examples/drive) over vcan0 in the test
//! `#[ignore]`d with the reason, which scripts/test-drive.sh runs inside the VM with `--include-ignored`.

use std::path::PathBuf;
use std::process::{Child, Command, Output, Stdio};
use std::time::Duration;

fn ctl(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_canopenctl")).args(args).output().expect("run canopenctl")
}

fn text(o: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}

fn ok(args: &[&str]) -> String {
    let o = ctl(args);
    assert!(o.status.success(), "canopenctl {args:?} failed: {}", text(&o));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn drive_usage_errors_exit_2() {
    for args in [&["drive", "6", "mode", "torque"][..], &["drive", "0", "state"], &["drive", "6", "move"]] {
        let o = ctl(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
    }
    let help = text(&ctl(&["drive", "6", "--help"]));
    for cmd in ["enable", "disable", "quick-stop", "fault-reset", "mode", "move", "velocity", "home", "stream"] {
        assert!(help.contains(cmd), "drive --help lacks {cmd}: {help}");
    }
}

/// The example drive on vcan0, killed when dropped.
struct DriveProcess(Child);

impl Drop for DriveProcess {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn number_after(out: &str, key: &str) -> i32 {
    let rest = out.split(key).nth(1).unwrap_or_else(|| panic!("no '{key}' in {out}"));
    rest.split_whitespace().next().and_then(|n| n.parse().ok()).unwrap_or_else(|| panic!("{out}"))
}

#[test]
#[ignore = "needs vcan0 and the example drive (scripts/test-drive.sh runs it in the with-vcan VM)"]
fn every_drive_command_against_the_example_drive() {
    let bin = std::env::var_os("DRIVE_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../target/debug/examples/drive")));
    assert!(std::path::Path::new("/sys/class/net/vcan0").exists(), "no vcan0: run through scripts/vcan-run.sh");
    let child = Command::new(bin)
        .args(["--node-id", "6", "--heartbeat", "0", "--quiet"])
        .stdout(Stdio::null())
        .spawn()
        .expect("start the drive");
    let _drive = DriveProcess(child);
    std::thread::sleep(Duration::from_millis(1000));

    assert!(ok(&["drive", "6", "state"]).contains("SWITCH ON DISABLED"));
    // Homing on the current position with a home offset.
    ok(&["drive", "6", "mode", "hm"]);
    assert_eq!(ok(&["drive", "6", "enable"]).trim(), "OPERATION ENABLED");
    ok(&["write", "6", "0x607C", "0", "250", "--type", "i32"]);
    assert_eq!(number_after(&ok(&["drive", "6", "home", "--method", "37", "--wait", "5"]), "value"), 250);
    // Quick stop, staying in Quick stop active (605Ah = 6), then back.
    ok(&["write", "6", "0x605A", "0", "6", "--type", "i16"]);
    assert_eq!(ok(&["drive", "6", "quick-stop"]).trim(), "QUICK STOP ACTIVE");
    ok(&["drive", "6", "enable"]);
    // A fault (2100h: the simulated axis reports 2310h) that cannot be reset while it is there.
    ok(&["write", "6", "0x2100", "0", "0x2310", "--type", "u16"]);
    std::thread::sleep(Duration::from_millis(100));
    assert!(ok(&["drive", "6", "state"]).starts_with("FAULT "));
    assert_eq!(ctl(&["drive", "6", "fault-reset"]).status.code(), Some(1));
    ok(&["write", "6", "0x2100", "0", "0", "--type", "u16"]);
    assert_eq!(ok(&["drive", "6", "fault-reset"]).trim(), "SWITCH ON DISABLED");
    // A profile position move that ends with target reached.
    ok(&["drive", "6", "mode", "pp"]);
    ok(&["drive", "6", "enable"]);
    let at = number_after(&ok(&["drive", "6", "move", "5250", "--wait", "10"]), "value");
    assert!((at - 5_250).abs() <= 10, "{at}");
    let at = number_after(&ok(&["drive", "6", "move", "--relative", "-1000"]), "value");
    assert!((at - 4_250).abs() <= 10, "{at}");
    // Profile velocity.
    ok(&["drive", "6", "mode", "pv"]);
    let v = number_after(&ok(&["drive", "6", "velocity", "2000"]), "value");
    assert!((v - 2_000).abs() <= 50, "{v}");
    ok(&["drive", "6", "velocity", "0"]);
    // Cyclic synchronous position: the drive must be Operational for RPDOs.
    ok(&["nmt", "start", "6"]);
    ok(&["drive", "6", "mode", "csp"]);
    let here = number_after(&format!("x {}", ok(&["read", "6", "0x6064", "0", "--type", "i32"])), "x");
    let to = (here + 2_000).to_string();
    let out = ok(&["drive", "6", "stream", "position", &here.to_string(), &to]);
    assert!(out.contains("201 set-point(s) sent"), "{out}");
    std::thread::sleep(Duration::from_millis(100));
    assert_eq!(ok(&["read", "6", "0x6062", "0", "--type", "i32"]).trim(), to);
    assert_eq!(ok(&["drive", "6", "disable"]).trim(), "SWITCH ON DISABLED");
}
