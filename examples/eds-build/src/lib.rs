//! A device whose object dictionary is generated from its EDS at build time: build.rs writes
//! `$OUT_DIR/device.rs` from `device.eds` with `canopen_eds::generate`, and this crate includes it. The
//! module `device` holds `Device` (the application objects 2000h–FFFFh, a derived dictionary) and `CONFIG`
//! (what the EDS says of 1000h–1FFFh: device type, identity, name, heartbeat, TPDO 1).
#![no_std]
#![forbid(unsafe_code)]

use canopen_core::{Node, NodeId};

include!(concat!(env!("OUT_DIR"), "/device.rs"));
include!(concat!(env!("OUT_DIR"), "/axis.rs"));

pub use device::{Device, CONFIG};

/// The axis's node at `id` (axis.eds, generated `#[od(compact, zerocopy)]`: its values reached by offset).
pub fn axis_node(id: NodeId) -> Node<axis::Device> {
    Node::new(id, axis::CONFIG, axis::Device::default())
}

/// The device's node at `id`, every entry at its EDS default once it boots (`handle_timeout`).
pub fn node(id: NodeId) -> Node<Device> {
    Node::new(id, CONFIG, Device::default())
}

#[cfg(test)]
mod tests {
    use canopen_core::{CanFrame, Instant, NodeId};

    /// An SDO expedited upload of `index:sub` from node 5, booted: the reply's data bytes.
    fn sdo_read(index: u16, sub: u8) -> [u8; 4] {
        let mut node = super::node(NodeId::new(5).unwrap());
        node.handle_timeout(Instant::ZERO);
        while node.poll_transmit().is_some() {} // the boot-up
        read_of(&mut node, index, sub)
    }

    /// The axis's node 5, booted.
    fn axis() -> canopen_core::Node<super::axis::Device> {
        let mut node = super::axis_node(NodeId::new(5).unwrap());
        node.handle_timeout(Instant::ZERO);
        while node.poll_transmit().is_some() {}
        node
    }

    /// The one reply to an SDO request.
    fn request<A: canopen_core::od::ObjectDictionary>(node: &mut canopen_core::Node<A>, req: [u8; 8]) -> [u8; 8] {
        node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x605, &req).unwrap());
        let reply = node.poll_transmit().expect("an SDO reply");
        reply.data().try_into().expect("8 bytes")
    }

    /// `sdo_read` on a booted node of any dictionary.
    fn read_of<A: canopen_core::od::ObjectDictionary>(
        node: &mut canopen_core::Node<A>,
        index: u16,
        sub: u8,
    ) -> [u8; 4] {
        let [lo, hi] = index.to_le_bytes();
        node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x605, &[0x40, lo, hi, sub, 0, 0, 0, 0]).unwrap());
        let reply = node.poll_transmit().expect("an SDO reply");
        assert_eq!(reply.cob_id(), 0x585);
        let d = reply.data();
        assert_eq!(&d[1..4], &[lo, hi, sub], "the reply names {index:04X}h:{sub:02X}");
        assert!(d[0] & 0xE3 == 0x43, "an expedited upload reply, not an abort: {d:02X?}");
        [d[4], d[5], d[6], d[7]]
    }

    /// The values the EDS gives come back by SDO: application objects from the derived struct (a VAR, a
    /// RECORD entry, an ARRAY's count), the communication profile from CONFIG.
    #[test]
    fn the_generated_dictionary_answers_sdo() {
        assert_eq!(i16::from_le_bytes([sdo_read(0x2000, 0)[0], sdo_read(0x2000, 0)[1]]), 100);
        assert_eq!(f32::from_le_bytes(sdo_read(0x2100, 1)), 1.5);
        assert_eq!(i32::from_le_bytes(sdo_read(0x2100, 2)), -20);
        assert_eq!(sdo_read(0x6000, 0)[0], 4);
        assert_eq!(u32::from_le_bytes(sdo_read(0x1000, 0)), 0x000F_0191);
        assert_eq!(u32::from_le_bytes(sdo_read(0x1018, 2)), 0x4242);
        assert_eq!(u16::from_le_bytes([sdo_read(0x1017, 0)[0], sdo_read(0x1017, 0)[1]]), 500);
        assert_eq!(u32::from_le_bytes(sdo_read(0x1A00, 1)), 0x6000_0108);
    }

    /// The object whose data type the derive cannot hold is left out (and build.rs warned of it).
    #[test]
    fn the_left_out_object_is_not_in_the_dictionary() {
        let mut node = super::node(NodeId::new(5).unwrap());
        node.handle_timeout(Instant::ZERO);
        while node.poll_transmit().is_some() {}
        node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x605, &[0x40, 0x00, 0x22, 0, 0, 0, 0, 0]).unwrap());
        let reply = node.poll_transmit().expect("an SDO reply");
        assert_eq!(reply.data(), &[0x80, 0x00, 0x22, 0x00, 0x00, 0x00, 0x02, 0x06]);
        // 0602 0000h: no object
    }

    /// The axis, reached by offset: its EDS defaults by SDO, a write, a limit's abort code, sub 00h counts.
    #[test]
    fn the_zerocopy_dictionary_answers_sdo() {
        let mut node = axis();
        assert_eq!(i16::from_le_bytes([read_of(&mut node, 0x2000, 0)[0], read_of(&mut node, 0x2000, 0)[1]]), 100);
        assert_eq!(f32::from_le_bytes(read_of(&mut node, 0x2100, 1)), 1.5);
        assert_eq!(i32::from_le_bytes(read_of(&mut node, 0x2100, 2)), -20);
        assert_eq!(read_of(&mut node, 0x6000, 0)[0], 4);
        assert_eq!(u32::from_le_bytes(read_of(&mut node, 0x1000, 0)), 0x0002_0192);
        // 607Ah = 0x12345678, then read back.
        assert_eq!(request(&mut node, [0x23, 0x7A, 0x60, 0, 0x78, 0x56, 0x34, 0x12])[0], 0x60);
        assert_eq!(node.app().target_position_607a, 0x1234_5678);
        assert_eq!(read_of(&mut node, 0x607A, 0), [0x78, 0x56, 0x34, 0x12]);
        // 2000h = 2000 is above its HighLimit: 0609 0031h, and the value stays.
        let [lo, hi] = 2000i16.to_le_bytes();
        assert_eq!(
            request(&mut node, [0x2B, 0x00, 0x20, 0, lo, hi, 0, 0]),
            [0x80, 0x00, 0x20, 0, 0x31, 0x00, 0x09, 0x06]
        );
        assert_eq!(node.app().gain_2000, 100);
    }
}
