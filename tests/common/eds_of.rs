//! The EDS a derived dictionary writes, for the EDS → Rust → EDS round trips (tests/eds_to_rust.rs, and
//! the check crate tests/eds_real.rs builds from python canopen's files). Only canopen-core.
#![allow(dead_code)]

use canopen_core::od::ObjectDictionary;

/// The EDS of a generated module's dictionary (its defaults restored), as the core writes it.
pub fn eds_of<A: canopen_core::od::OdDescribe + ObjectDictionary>(
    mut app: A,
    config: canopen_core::profile::NodeConfig,
) -> String {
    app.restore_defaults();
    let comm = canopen_core::profile::CommProfile::<canopen_core::Sizes>::new(config);
    let od = canopen_core::od::Merged { comm, app };
    let mut text = String::new();
    canopen_core::profile::eds::write_eds(&mut text, &canopen_core::profile::eds::EdsInfo::DEFAULT, &od).unwrap();
    text
}

/// What a dictionary answers (its defaults restored) for every sub-index 00h..FFh of each of its objects:
/// `info`, a read, and a TPDO handle's read, one line each. The check crate of tests/eds_real.rs writes
/// it for each layout of one EDS, and the test requires the three alike: the tables' paths (rows found
/// by key, by place in a RECORD, by a PDO handle's position) answer as the match arms do.
pub fn answers<A: canopen_core::od::OdDescribe + ObjectDictionary>(mut app: A) -> String {
    use canopen_core::od::PdoDir;
    app.restore_defaults();
    let mut text = String::new();
    for n in 0..app.object_count() {
        let Some(index) = app.object_index(n) else { continue };
        for sub in 0..=255u8 {
            let mut buf = [0u8; 64];
            let read = app.read(index, sub, 0, &mut buf).map(|k| buf[..k.min(64)].to_vec());
            let mut pdo = [0u8; 8];
            let mapped = app.pdo_resolve(index, sub, PdoDir::Tpdo).map(|h| (h.size, app.pdo_read(&h, &mut pdo), pdo));
            text += &format!("{index:04X}:{sub:02X} {:?} {read:?} {mapped:?}\n", app.info(index, sub));
        }
    }
    text
}
