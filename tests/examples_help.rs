//! Every example's `--help` says what the example is for and shows one command line to run it (issue 16
//! item 3), checked by running the built examples as a user would.

use std::path::{Path, PathBuf};
use std::process::Command;

/// `target/<profile>/examples/<name>`, built first.
fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    let profile_dir = exe.parent().and_then(Path::parent).expect("target/<profile>").to_path_buf();
    let mut build = Command::new(env!("CARGO"));
    build.args(["build", "--quiet", "--example", name, "--manifest-path"]);
    build.arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml"));
    if profile_dir.file_name().is_some_and(|n| n == "release") {
        build.arg("--release");
    }
    assert!(build.status().expect("run cargo build").success(), "cargo build --example {name} failed");
    profile_dir.join("examples").join(name)
}

fn help(name: &str) -> String {
    let out = Command::new(example(name)).arg("--help").output().expect("run the example");
    assert!(out.status.success(), "{name} --help exited with {:?}", out.status);
    String::from_utf8(out.stdout).expect("UTF-8 help")
}

/// Every example of the repository (examples/*.rs).
const EXAMPLES: [&str; 5] = ["drive", "master_bench", "node", "qemu_m4_eds", "write_eds"];

#[test]
fn every_example_says_what_it_is_for_and_how_to_run_it() {
    for (name, purpose) in [
        ("node", "CANopen node"),
        ("master_bench", "throughput bench"),
        ("write_eds", "writes the EDS"),
        ("drive", "CiA 402 drive"),
    ] {
        let text = help(name);
        assert!(text.contains(purpose), "{name} --help does not say what it is for:\n{text}");
        let line = format!("cargo run --example {name}");
        assert!(text.contains(&line), "{name} --help shows no command line ({line}):\n{text}");
        // And every example it names exists (the node's help once sent users to a retired `master`).
        for named in text.split("cargo run --example ").skip(1) {
            let named: String = named.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            assert!(EXAMPLES.contains(&named.as_str()), "{name} --help names a missing example {named}:\n{text}");
        }
    }
}

/// The example list above is every example of the repository (a new one must get a help text too).
#[test]
fn the_list_covers_every_example() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut found: Vec<String> = std::fs::read_dir(&dir)
        .expect("examples/")
        .filter_map(|e| e.ok())
        .filter_map(|e| e.file_name().to_str().and_then(|n| n.strip_suffix(".rs")).map(str::to_owned))
        .collect();
    found.sort();
    assert_eq!(found, EXAMPLES);
}
