//! The command line of the examples that only write an EDS (`write_eds`, `qemu_m4_eds`): `--help`, or the EDS
//! (CiA 306) of one dictionary to the file named by the first argument, or to stdout without one. A failure
//! is a message on stderr and exit status 1.

use canopen_core::od::OdDescribe;
use canopen_core::profile::eds::{write_eds, EdsInfo};

/// Runs the example: prints `help` on `--help` or `-h`, otherwise writes the EDS of the dictionary `od`
/// builds, with the file-level information `info`. `od` runs only when the EDS is written.
pub fn run<D: OdDescribe>(help: &str, info: &EdsInfo, od: impl FnOnce() -> D) {
    if std::env::args().skip(1).any(|a| a == "--help" || a == "-h") {
        println!("{help}");
        return;
    }
    let mut text = String::new();
    if let Err(e) = write_eds(&mut text, info, &od()) {
        eprintln!("EDS formatting failed: {e}");
        std::process::exit(1);
    }
    match std::env::args().nth(1) {
        Some(path) => {
            if let Err(e) = std::fs::write(&path, text) {
                eprintln!("cannot write {path}: {e}");
                std::process::exit(1);
            }
        }
        None => print!("{text}"),
    }
}
