//! EDS → Rust at build time: [`generate`] for a build script, [`generate_into`] for anything else. The
//! crate docs show the whole path (Cargo.toml, build.rs, `include!`).

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use crate::codegen::LeftOut;
use crate::eds::{Eds, EdsError};
use crate::layout::{rust_module_as, StructLayout};

/// Why [`generate`] could not write the module.
///
/// ```
/// let out = std::env::temp_dir();
/// let e = canopen_eds::generate_into("no/such/device.eds".as_ref(), &out, &mut Vec::new()).unwrap_err();
/// assert!(e.to_string().starts_with("no/such/device.eds: cannot read it: "));
/// ```
#[derive(Debug)]
pub enum BuildError {
    /// `OUT_DIR` is not set: not run by cargo as a build script.
    NoOutDir,
    /// The EDS could not be read.
    Read(PathBuf, io::Error),
    /// The EDS is malformed: the error has its line.
    Parse(PathBuf, EdsError),
    /// The module or the cargo instructions could not be written.
    Write(PathBuf, io::Error),
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::NoOutDir => write!(f, "OUT_DIR is not set: canopen_eds::generate runs in a build script"),
            BuildError::Read(p, e) => write!(f, "{}: cannot read it: {e}", p.display()),
            BuildError::Parse(p, e) => write!(f, "{}:{}: [{}] {}", p.display(), e.line, e.section, e.what),
            BuildError::Write(p, e) => write!(f, "{}: cannot write it: {e}", p.display()),
        }
    }
}

impl std::error::Error for BuildError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            BuildError::NoOutDir => None,
            BuildError::Read(_, e) | BuildError::Write(_, e) => Some(e),
            BuildError::Parse(_, e) => Some(e),
        }
    }
}

/// In a build script: the dictionary module of the EDS at `eds` (a path relative to the package, as cargo
/// runs build scripts there) written as `$OUT_DIR/<name>.rs`, `<name>` being the file's stem as a Rust
/// identifier (`device` for `device.eds`, `my_drive_v2` for `My-Drive v2.eds`). Prints the cargo
/// instructions to stdout (see the module docs); returns the path written.
///
/// ```no_run
/// // build.rs
/// let module = canopen_eds::generate("device.eds").unwrap_or_else(|e| panic!("{e}"));
/// assert!(module.ends_with("device.rs"));
/// ```
pub fn generate(eds: impl AsRef<Path>) -> Result<PathBuf, BuildError> {
    generate_as(eds, StructLayout::Code)
}

/// [`generate`] with the struct in `layout` ([`StructLayout::Zerocopy`]: the least flash; the crate then
/// needs `zerocopy` with its `derive` feature among its dependencies).
///
/// ```no_run
/// // build.rs
/// let module = canopen_eds::generate_as("device.eds", canopen_eds::StructLayout::Zerocopy).unwrap_or_else(|e| panic!("{e}"));
/// assert!(module.ends_with("device.rs"));
/// ```
pub fn generate_as(eds: impl AsRef<Path>, layout: StructLayout) -> Result<PathBuf, BuildError> {
    let out_dir = std::env::var_os("OUT_DIR").ok_or(BuildError::NoOutDir)?;
    generate_into_as(eds.as_ref(), Path::new(&out_dir), layout, &mut io::stdout().lock())
}

/// [`generate`] with the output directory given and the cargo instructions written to `cargo` (what a test
/// or a tool that is no build script uses): `cargo:rerun-if-changed=<eds>`, then one
/// `cargo:warning=<file name>: <what>` per [`LeftOut`] of the module, in the order of the module.
///
/// ```
/// let dir = std::env::temp_dir().join("canopen-eds-doc-generate-into");
/// std::fs::create_dir_all(&dir).unwrap();
/// let eds = dir.join("Drive.eds");
/// std::fs::write(&eds, "[2001]\nParameterName=Complex\nDataType=0x40\n[2002]\nParameterName=Gain\nDataType=3\n").unwrap();
/// let mut cargo = Vec::new();
/// let module = canopen_eds::generate_into(&eds, &dir, &mut cargo).unwrap();
/// let rust = std::fs::read_to_string(&module).unwrap();
/// assert!(module.ends_with("drive.rs") && rust.contains("pub mod drive {") && rust.contains("pub gain_2002: i16,"));
/// let cargo = String::from_utf8(cargo).unwrap();
/// assert!(cargo.contains("cargo:warning=Drive.eds: 2001h Complex: data type 0040h is not supported; left out.\n"));
/// ```
pub fn generate_into(eds: &Path, out_dir: &Path, cargo: &mut dyn io::Write) -> Result<PathBuf, BuildError> {
    generate_into_as(eds, out_dir, StructLayout::Code, cargo)
}

/// [`generate_into`] with the struct in `layout`.
///
/// ```
/// use canopen_eds::StructLayout;
/// let dir = std::env::temp_dir().join("canopen-eds-doc-generate-into-as");
/// std::fs::create_dir_all(&dir).unwrap();
/// let eds = dir.join("axis.eds");
/// std::fs::write(&eds, "[2002]\nParameterName=Gain\nDataType=3\nAccessType=rw\n").unwrap();
/// let module = canopen_eds::generate_into_as(&eds, &dir, StructLayout::Zerocopy, &mut Vec::new()).unwrap();
/// assert!(std::fs::read_to_string(module).unwrap().contains("#[od(compact, zerocopy)]"));
/// ```
pub fn generate_into_as(
    eds: &Path,
    out_dir: &Path,
    layout: StructLayout,
    cargo: &mut dyn io::Write,
) -> Result<PathBuf, BuildError> {
    let text = std::fs::read_to_string(eds).map_err(|e| BuildError::Read(eds.to_owned(), e))?;
    let parsed = Eds::parse(&text).map_err(|e| BuildError::Parse(eds.to_owned(), e))?;
    let file = eds.file_name().map_or_else(|| eds.display().to_string(), |n| n.to_string_lossy().into_owned());
    let name = module_name(eds);
    let g = rust_module_as(&parsed, &file, layout);
    let out = out_dir.join(format!("{name}.rs"));
    let module = format!(
        "// Written by canopen_eds::generate from {file} at build time: include! it, do not edit it.\n\
         pub mod {name} {{\n{}}}\n",
        g.rust
    );
    // Written only when it changes, so that a build that reran the script for another reason does not
    // recompile the crate.
    if std::fs::read_to_string(&out).ok().as_deref() != Some(module.as_str()) {
        std::fs::write(&out, module).map_err(|e| BuildError::Write(out.clone(), e))?;
    }
    let lines = cargo_lines(eds, &file, &g.left_out);
    cargo.write_all(lines.as_bytes()).map_err(|e| BuildError::Write(PathBuf::from("stdout"), e))?;
    Ok(out)
}

/// The cargo instructions for an EDS whose module leaves out `left_out`. A warning is one line: a line
/// break in a name from the file would end it early, so none is kept.
fn cargo_lines(eds: &Path, file: &str, left_out: &[LeftOut]) -> String {
    let mut s = format!("cargo:rerun-if-changed={}\n", eds.display());
    for l in left_out {
        let note = l.note.replace(['\r', '\n'], " ");
        s += &format!("cargo:warning={file}: {note}\n");
    }
    s
}

/// The module's name: the file stem, lower-case, every run of other characters one `_`, a leading digit or
/// an empty stem behind `eds_`, a keyword with a trailing `_`.
fn module_name(eds: &Path) -> String {
    let stem = eds.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let mut name = String::new();
    for c in stem.chars() {
        if c.is_ascii_alphanumeric() {
            name.push(c.to_ascii_lowercase());
        } else if !name.ends_with('_') {
            name.push('_');
        }
    }
    let name = name.trim_matches('_');
    if name.is_empty() || name.starts_with(|c: char| c.is_ascii_digit()) {
        format!("eds_{name}")
    } else if KEYWORDS.contains(&name) {
        format!("{name}_")
    } else {
        name.to_owned()
    }
}

/// Rust's keywords, which a module cannot be named.
const KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern", "false", "fn",
    "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return", "self",
    "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where", "while", "abstract", "become",
    "box", "do", "final", "macro", "override", "priv", "try", "typeof", "unsized", "virtual", "yield",
];

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("canopen-eds-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// The cargo warnings are the module's left-out list, one per item, in order; the rerun line names the
    /// EDS; the module is the generator's text inside `pub mod`.
    #[test]
    fn warnings_are_the_left_out_list() {
        let dir = temp_dir("warnings");
        let eds = dir.join("io-module 2.eds");
        let text = "[2001]\nParameterName=Complex\nDataType=0x40\n[2002]\nParameterName=Id\nDataType=7\n\
                    DefaultValue=$NODEID+1\n[2003]\nParameterName=Blob\nDataType=0xF\nAccessType=ro\n\
                    [2004]\nParameterName=Kept\nDataType=5\n";
        std::fs::write(&eds, text).unwrap();
        let mut cargo = Vec::new();
        let out = generate_into(&eds, &dir, &mut cargo).unwrap();
        assert_eq!(out, dir.join("io_module_2.rs"));
        let g = crate::rust_module(&Eds::parse(text).unwrap(), "io-module 2.eds");
        assert_eq!(g.left_out.len(), 3);
        let mut want = format!("cargo:rerun-if-changed={}\n", eds.display());
        for l in &g.left_out {
            want += &format!("cargo:warning=io-module 2.eds: {l}\n");
        }
        assert_eq!(String::from_utf8(cargo).unwrap(), want);
        assert!(want.contains("2002h Id: default $NODEID+1 not carried"), "{want}");
        let module = std::fs::read_to_string(&out).unwrap();
        assert!(module.contains(&format!("pub mod io_module_2 {{\n{}}}\n", g.rust)));
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A malformed EDS is an error with the file and line, a missing one names the file.
    #[test]
    fn errors_name_the_file_and_line() {
        let dir = temp_dir("errors");
        let eds = dir.join("bad.eds");
        std::fs::write(&eds, "[FileInfo]\n\n[2001]\nParameterName=x\nDataType=0xZZ\n").unwrap();
        let e = generate_into(&eds, &dir, &mut Vec::new()).unwrap_err().to_string();
        assert_eq!(e, format!("{}:5: [2001] DataType '0xZZ' is not a number", eds.display()));
        let missing = dir.join("missing.eds");
        let e = generate_into(&missing, &dir, &mut Vec::new()).unwrap_err().to_string();
        assert!(e.starts_with(&format!("{}: cannot read it", missing.display())), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn module_names_are_identifiers() {
        for (file, name) in [
            ("device.eds", "device"),
            ("My-Drive v2.EDS", "my_drive_v2"),
            ("3f.eds", "eds_3f"),
            ("--.eds", "eds_"),
            ("dir/type.eds", "type_"),
        ] {
            assert_eq!(module_name(Path::new(file)), name);
        }
    }
}
