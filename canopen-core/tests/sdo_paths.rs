//! The SDO server builds its streamed-write and segmented-upload paths only for a node whose dictionary can
//! use them (`ObjectDictionary::STREAMS`, `ObjectDictionary::SEGMENTED_UPLOADS`, combined over the
//! communication profile and the application). Whichever half has the long entry, the transfer works; a
//! node without one answers as a server without the path (SDO-09). In the default build the communication
//! profile has its strings (1008h–100Ah); `cargo test -p canopen-core --no-default-features` runs the same
//! tests with the application's entries alone deciding.

#[cfg(not(feature = "manufacturer-strings"))]
use canopen_core::node::NoApplication;
use canopen_core::node::Node;
use canopen_core::od::{AbortCode, ObjectDictionary, VisibleString};
#[cfg(not(feature = "manufacturer-strings"))]
use canopen_core::profile::CommProfile;
use canopen_core::profile::NodeConfig;
#[cfg(not(feature = "manufacturer-strings"))]
use canopen_core::Sizes;
use canopen_core::{CanFrame, Instant, NodeId};
use canopen_od_derive::ObjectDictionary;

/// An application with a read-only string (2000h, 7 bytes), a writable one (2001h) and a number (2002h).
#[derive(ObjectDictionary, Default)]
struct Texts {
    #[od(index = 0x2000, access = "ro", default = "abcdefg")]
    name: VisibleString<8>,
    #[od(index = 0x2001)]
    label: VisibleString<8>,
    #[od(index = 0x2002)]
    value: u32,
}

/// Node 5 with `app`, booted (Reset Application set the defaults), transmit queue drained.
fn booted<A: ObjectDictionary>(app: A) -> Node<A> {
    let mut node: Node<A> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, app);
    node.handle_timeout(Instant::ZERO);
    while node.poll_transmit().is_some() {}
    node
}

/// The node's answers to one SDO request on 605h.
fn sdo<A: ObjectDictionary>(node: &mut Node<A>, req: [u8; 8]) -> Vec<[u8; 8]> {
    node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x605, &req).unwrap());
    core::iter::from_fn(|| node.poll_transmit())
        .map(|f| {
            assert_eq!(f.cob_id(), 0x585);
            <[u8; 8]>::try_from(f.data()).unwrap()
        })
        .collect()
}

fn abort(index: u16, sub: u8, code: AbortCode) -> [u8; 8] {
    let [i0, i1] = index.to_le_bytes();
    let [c0, c1, c2, c3] = code.code().to_le_bytes();
    [0x80, i0, i1, sub, c0, c1, c2, c3]
}

/// SDO-25..SDO-27: a 7-byte string of the application uploads segmented, size indicated, in one segment.
#[test]
fn an_application_string_uploads_segmented() {
    let mut node = booted(Texts::default());
    assert_eq!(sdo(&mut node, [0x40, 0x00, 0x20, 0x00, 0, 0, 0, 0]), [[0x41, 0x00, 0x20, 0x00, 7, 0, 0, 0]]);
    assert_eq!(sdo(&mut node, [0x60, 0, 0, 0, 0, 0, 0, 0]), [[0x01, b'a', b'b', b'c', b'd', b'e', b'f', b'g']]);
}

/// SDO-19..SDO-21: a string downloaded segmented (9 bytes announced for an 8-byte string: 0607 0012h) and
/// then in one 3-byte segment is streamed into the application.
#[test]
fn an_application_string_downloads_segmented() {
    let mut node = booted(Texts::default());
    assert_eq!(sdo(&mut node, [0x21, 0x01, 0x20, 0x00, 9, 0, 0, 0]), [abort(0x2001, 0, AbortCode::LengthTooHigh)]);
    assert_eq!(sdo(&mut node, [0x21, 0x01, 0x20, 0x00, 3, 0, 0, 0]), [[0x60, 0x01, 0x20, 0x00, 0, 0, 0, 0]]);
    // Last segment (c = 1), 3 bytes (n = 4).
    assert_eq!(sdo(&mut node, [0x09, b'x', b'y', b'z', 0, 0, 0, 0]), [[0x20, 0, 0, 0, 0, 0, 0, 0]]);
    assert_eq!(node.app().label.as_bytes(), b"xyz");
}

/// SDO-09: without a long entry anywhere (no manufacturer strings in this build), an upload segment
/// request answers 0504 0001h, as it does with none under way; uploads and segmented downloads of 1..=4
/// bytes work as ever.
#[cfg(not(feature = "manufacturer-strings"))]
#[test]
fn a_node_without_long_entries_has_the_short_paths() {
    const { assert!(!CommProfile::<Sizes>::SEGMENTED_UPLOADS && !NoApplication::SEGMENTED_UPLOADS) };
    let mut node = booted(NoApplication);
    assert_eq!(sdo(&mut node, [0x60, 0, 0, 0, 0, 0, 0, 0]), [abort(0, 0, AbortCode::InvalidCommandSpecifier)]);
    // 1000h, expedited.
    assert_eq!(sdo(&mut node, [0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0])[0][0], 0x43);
    // 1017h (2 bytes) downloaded segmented: 1 segment of 2 bytes (n = 5, c = 1).
    assert_eq!(sdo(&mut node, [0x21, 0x17, 0x10, 0x00, 2, 0, 0, 0]), [[0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0]]);
    assert_eq!(sdo(&mut node, [0x0B, 0xE8, 0x03, 0, 0, 0, 0, 0]), [[0x20, 0, 0, 0, 0, 0, 0, 0]]);
    assert_eq!(node.params().heartbeat_time_ms, 1000);
}
