//! EDS import and `eds-to-rust` on real EDS files nobody here wrote (issue 23 item 3): python canopen's
//! test and example files (sample.eds, datatypes.eds, e35.eds), which scripts/fetch-eds.sh unpacks from the
//! PyPI sdist of the pinned version into target/real-eds (their licence beside them; none of it is
//! committed). For every `.eds` found there (or under `CANOPEN_REAL_EDS_DIR`):
//!
//! 1. it parses, the EDS writer's text of it parses to the same, and `rust_module` gives a module and the
//!    list of what it leaves out;
//! 2. the modules compile as they are, with only canopen-core and canopen-od-derive: they are written into a
//!    small crate (target/real-eds/check) that this test builds with cargo, like trybuild does, whose
//!    program writes the EDS of each module's dictionary;
//! 3. each EDS written back equals the original on every entry, except exactly what was listed as left out.
//!
//! Each file goes through all three layouts `eds-to-rust` writes (`--layout code|compact|zerocopy`): the
//! EDS written back reads every default and every access rule through that layout's path (issue 41: the
//! tables of a real drive's dictionary, e35.eds, with a key per object, rows without sub-indices and
//! FIRST_ROWS past 256, answer as the match arms do).
//!
//! No files: a counted skip (printed), or a failure when `CANOPEN_REQUIRE_REAL_EDS=1` (.ci/run sets it
//! after running scripts/fetch-eds.sh).

#[path = "common/eds_compare.rs"]
mod eds_compare;

use std::path::{Path, PathBuf};
use std::process::Command;

use canopen_eds::{rust_module_as, Dropped, Eds, StructLayout};

fn eds_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            eds_files(&p, out);
        } else if p.extension().is_some_and(|x| x.eq_ignore_ascii_case("eds")) {
            out.push(p);
        }
    }
}

/// The crate that compiles the generated modules: `mods` are (module name, Rust text).
fn write_check_crate(dir: &Path, mods: &[(String, String)]) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let src = dir.join("src");
    let _ = std::fs::remove_dir_all(&src);
    std::fs::create_dir_all(&src).unwrap();
    let manifest = format!(
        "[package]\nname = \"real-eds-check\"\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n\
         [dependencies]\ncanopen-core = {{ path = {:?} }}\ncanopen-od-derive = {{ path = {:?} }}\n\
         zerocopy = {{ version = \"0.8\", features = [\"derive\"] }}\n\n[workspace]\n",
        root.join("canopen-core"),
        root.join("canopen-od-derive"),
    );
    std::fs::write(dir.join("Cargo.toml"), manifest).unwrap();
    // The workspace's versions of syn, quote, heapless...: builds offline from what `cargo test` fetched.
    std::fs::copy(root.join("Cargo.lock"), dir.join("Cargo.lock")).unwrap();
    let mut main = format!("#[path = {:?}]\nmod eds_of;\n", root.join("tests/common/eds_of.rs"));
    for (name, rust) in mods {
        std::fs::write(src.join(format!("{name}.rs")), rust).unwrap();
        main += &format!("mod {name};\n");
    }
    main += "\nfn main() {\n    let out = std::path::PathBuf::from(std::env::args().nth(1).unwrap());\n";
    for (name, _) in mods {
        main += &format!(
            "    std::fs::write(out.join(\"{name}.eds\"), eds_of::eds_of({name}::Device::default(), {name}::CONFIG)).unwrap();\n\
             std::fs::write(out.join(\"{name}.answers\"), eds_of::answers({name}::Device::default())).unwrap();\n"
        );
    }
    main += "}\n";
    std::fs::write(src.join("main.rs"), main).unwrap();
}

#[test]
fn real_eds_files_import_generate_compile_and_round_trip() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::env::var_os("CANOPEN_REAL_EDS_DIR").map_or_else(|| root.join("target/real-eds"), PathBuf::from);
    let mut files = Vec::new();
    eds_files(&dir, &mut files);
    files.retain(|f| !f.starts_with(dir.join("check")));
    files.sort();
    if files.is_empty() {
        assert!(
            std::env::var("CANOPEN_REQUIRE_REAL_EDS").as_deref() != Ok("1"),
            "no .eds under {} but CANOPEN_REQUIRE_REAL_EDS=1: run scripts/fetch-eds.sh",
            dir.display()
        );
        eprintln!("SKIPPED 1: no real EDS files under {} (run scripts/fetch-eds.sh)", dir.display());
        return;
    }

    // 1. Parse and generate.
    let mut parsed = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let eds = Eds::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let file = f.file_name().unwrap().to_string_lossy().into_owned();
        let name: String = file
            .trim_end_matches(".eds")
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '_' })
            .collect();
        let layouts =
            [("", StructLayout::Code), ("_compact", StructLayout::Compact), ("_zerocopy", StructLayout::Zerocopy)];
        let generated: Vec<_> = layouts.iter().map(|&(tail, l)| (tail, rust_module_as(&eds, &file, l))).collect();
        // The writer (canopen-eds): what it writes parses to the same description.
        let written = eds.to_string();
        assert!(Eds::parse(&written).as_ref() == Ok(&eds), "{file}: written and parsed again differs:\n{written}");
        assert!(eds.objects.len() > 5, "{file}: only {} objects parsed", eds.objects.len());
        for (tail, g) in generated {
            parsed.push((format!("m_{name}{tail}"), file.clone(), eds.clone(), g));
        }
    }

    // 2. Compile the modules and write their dictionaries' EDS.
    let check = dir.join("check");
    let mods: Vec<(String, String)> = parsed.iter().map(|(m, _, _, g)| (m.clone(), g.rust.clone())).collect();
    write_check_crate(&check, &mods);
    let out = check.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .args(["run", "--quiet", "--offline", "--manifest-path"])
        .arg(check.join("Cargo.toml"))
        .arg("--")
        .arg(&out)
        .env("CARGO_TARGET_DIR", check.join("target"))
        .status()
        .unwrap();
    assert!(status.success(), "the generated modules in {} do not compile or run", check.display());

    // 3. Round trip.
    for (m, file, eds, g) in &parsed {
        let back = std::fs::read_to_string(out.join(format!("{m}.eds"))).unwrap();
        let back = Eds::parse(&back).unwrap();
        let n = eds_compare::compare(file, eds, &back, &g.left_out);
        let entries = g.left_out.iter().filter(|l| l.dropped == Dropped::Entry).count();
        eprintln!(
            "{file} ({m}): {n} entries equal after EDS -> Rust -> EDS; {} left out: {entries} objects/entries, {} attributes",
            g.left_out.len(),
            g.left_out.len() - entries
        );
        for l in &g.left_out {
            eprintln!(
                "  {:04X}h{} {:?}: {}",
                l.index,
                l.sub.map(|s| format!(":{s:02X}")).unwrap_or_default(),
                l.dropped,
                l.why
            );
        }
        assert!(n > 10, "{file}: only {n} entries compared");
    }

    // 4. The three layouts of each file answer alike, entry by entry.
    for (m, file, ..) in parsed.iter().filter(|(m, ..)| !m.ends_with("_compact") && !m.ends_with("_zerocopy")) {
        let code = std::fs::read_to_string(out.join(format!("{m}.answers"))).unwrap();
        assert!(code.lines().count() >= 256 * 5, "{file}: too few answers");
        for tail in ["_compact", "_zerocopy"] {
            let other = std::fs::read_to_string(out.join(format!("{m}{tail}.answers"))).unwrap();
            let first = code.lines().zip(other.lines()).find(|(a, b)| a != b);
            assert!(
                first.is_none() && code.lines().count() == other.lines().count(),
                "{file}: the {tail} layout answers otherwise than match arms: {first:?}"
            );
        }
        eprintln!("{file}: the three layouts give the same {} answers", code.lines().count());
    }
}
