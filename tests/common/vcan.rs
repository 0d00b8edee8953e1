//! The interface the vcan tests run on, and their check that it is up: they are `#[ignore]`d and run only
//! where vcan0 is up (scripts/vcan-run.sh), so a missing interface is a failure, not a skip.

/// The SocketCAN interface of the vcan tests.
pub const IFACE: &str = "vcan0";

/// Fails the test when [`IFACE`] does not exist.
pub fn require_vcan() {
    assert!(
        std::path::Path::new(&format!("/sys/class/net/{IFACE}")).exists(),
        "no SocketCAN interface {IFACE}: run where it is up (scripts/vcan-run.sh)"
    );
}
