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
