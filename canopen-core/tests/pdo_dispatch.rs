//! Which PDO a received frame goes to (PDO-02, PDO-04, PDO-29). Up to 8 PDOs of a direction the node
//! compares the PDOs' own CAN-IDs; above that it searches a table sorted by CAN-ID. Both must pick the same
//! PDO: the valid one (for a remote request, the one that allows RTR) with the frame's CAN-ID, the
//! lowest-numbered when two share it, and none for any other CAN-ID.

use canopen_core::node::{NoApplication, Node, NodeSizes};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::NodeConfig;
use canopen_core::{CanFrame, Event, Instant, NmtState, NodeId, Sizes};

/// 8 RPDOs and 8 TPDOs: matched by comparing the PDOs.
type Scanned = Sizes<0, 16, 16, 8, 8>;
/// 12 of each: matched through the sorted tables.
type Tabled = Sizes<0, 16, 16, 12, 12>;

/// An RPDO on `id` mapping one dummy byte (0005h, UNSIGNED8), applied at reception (FFh).
const fn rpdo(id: u16) -> PdoDefault {
    PdoDefault { can_id: Some(id), transmission_type: 255, mapping: &[0x0005_0008], ..PdoDefault::EVENT }
}

/// A TPDO on `id` sent only on a remote request (FDh), nothing mapped.
const fn tpdo(id: u16) -> PdoDefault {
    PdoDefault { can_id: Some(id), transmission_type: 253, ..PdoDefault::EVENT }
}

/// CAN-IDs out of order, RPDO 3 and RPDO 6 (k = 2, 5) on the same one, RPDO 7 on its own but not valid;
/// RPDO 12 (k = 11) exists only in the larger node.
static RPDOS: [PdoDefault; 12] = {
    let mut a = [PdoDefault::UNUSED; 12];
    a[0] = rpdo(0x250);
    a[2] = rpdo(0x230);
    a[5] = rpdo(0x230);
    a[6] = PdoDefault { valid: false, ..rpdo(0x240) };
    a[7] = rpdo(0x210);
    a[11] = rpdo(0x205);
    a
};

/// The same shape for TPDOs; TPDO 7 (k = 6) is valid but allows no remote request (COB-ID bit 30).
static TPDOS: [PdoDefault; 12] = {
    let mut a = [PdoDefault::UNUSED; 12];
    a[0] = tpdo(0x1D0);
    a[2] = tpdo(0x1B0);
    a[5] = tpdo(0x1B0);
    a[6] = PdoDefault { rtr_allowed: false, ..tpdo(0x1C0) };
    a[7] = tpdo(0x190);
    a[11] = tpdo(0x185);
    a
};

/// A node of sizes `Z` in Operational with the PDOs above.
fn operational<Z: NodeSizes>() -> Box<Node<NoApplication, Z>> {
    let cfg = NodeConfig { rpdo: &RPDOS, tpdo: &TPDOS, ..NodeConfig::DEFAULT };
    let mut node = Box::new(Node::new(NodeId::new(5).unwrap(), cfg, NoApplication));
    node.handle_timeout(Instant::ZERO);
    node.enter_state(NmtState::Operational);
    while node.poll_transmit().is_some() {}
    while node.poll_event().is_some() {}
    node
}

/// The RPDO numbers (0-based) that received a one-byte frame on each of `ids`, in order.
fn rpdos_receiving<Z: NodeSizes>(node: &mut Node<NoApplication, Z>, ids: &[u16]) -> Vec<Option<u16>> {
    ids.iter()
        .map(|&id| {
            node.handle_frame(Instant::ZERO, &CanFrame::new(id, &[0x11]).unwrap());
            let got = core::iter::from_fn(|| node.poll_event()).find_map(|e| match e {
                Event::RpdoReceived { pdo } => Some(pdo),
                _ => None,
            });
            while node.poll_transmit().is_some() {}
            got
        })
        .collect()
}

/// The CAN-IDs of the frames a remote request on each of `ids` made the node send.
#[cfg(feature = "pdo-rtr")]
fn rtr_answers<Z: NodeSizes>(node: &mut Node<NoApplication, Z>, ids: &[u16]) -> Vec<Vec<u16>> {
    ids.iter()
        .map(|&id| {
            node.handle_frame(Instant::ZERO, &CanFrame::new_rtr(id, 0).unwrap());
            core::iter::from_fn(|| node.poll_transmit()).map(|f| f.cob_id()).collect()
        })
        .collect()
}

const RPDO_IDS: [u16; 6] = [0x250, 0x230, 0x240, 0x210, 0x260, 0x205];
#[cfg(feature = "pdo-rtr")]
const TPDO_IDS: [u16; 6] = [0x1D0, 0x1B0, 0x1C0, 0x190, 0x1E0, 0x185];

/// PDO-02/PDO-04: the RPDO of each CAN-ID, the same whether matched by comparing or by table.
#[test]
fn an_rpdo_frame_goes_to_the_lowest_valid_rpdo_of_its_can_id() {
    let expected = [Some(0), Some(2), None, Some(7), None, None];
    assert_eq!(rpdos_receiving(&mut operational::<Scanned>(), &RPDO_IDS), expected);
    let mut tabled = operational::<Tabled>();
    let mut with_12th = expected;
    with_12th[5] = Some(11);
    assert_eq!(rpdos_receiving(&mut tabled, &RPDO_IDS), with_12th);
}

/// PDO-29: a remote request is answered by the TPDO of its CAN-ID that allows RTR, once (the lowest of two
/// on one CAN-ID), the same whether matched by comparing or by table.
#[cfg(feature = "pdo-rtr")]
#[test]
fn a_remote_request_is_answered_by_the_lowest_tpdo_that_allows_it() {
    let expected = vec![vec![0x1D0], vec![0x1B0], vec![], vec![0x190], vec![], vec![]];
    assert_eq!(rtr_answers(&mut operational::<Scanned>(), &TPDO_IDS), expected);
    let mut with_12th = expected;
    with_12th[5] = vec![0x185];
    assert_eq!(rtr_answers(&mut operational::<Tabled>(), &TPDO_IDS), with_12th);
}

/// A COB-ID changed by SDO moves the match, both ways: RPDO 1 (k = 0) from 250h to 260h (PDO-09: made
/// not valid first, then given the new CAN-ID).
#[test]
fn a_cob_id_changed_by_sdo_moves_the_match() {
    fn moved<Z: NodeSizes>() -> Vec<Option<u16>> {
        let mut node = operational::<Z>();
        for cob_id in [0x8000_0250u32, 0x0000_0260] {
            let v = cob_id.to_le_bytes();
            // Expedited download of 4 bytes to 1400h:01 on the default server (600h + 5).
            let request = [0x23, 0x00, 0x14, 0x01, v[0], v[1], v[2], v[3]];
            node.handle_frame(Instant::ZERO, &CanFrame::new(0x605, &request).unwrap());
            let response = node.poll_transmit().unwrap();
            assert_eq!((response.cob_id(), response.data()[0]), (0x585, 0x60), "{cob_id:08X}");
        }
        while node.poll_event().is_some() {}
        rpdos_receiving(&mut node, &[0x250, 0x260])
    }
    assert_eq!(moved::<Scanned>(), [None, Some(0)]);
    assert_eq!(moved::<Tabled>(), [None, Some(0)]);
}
