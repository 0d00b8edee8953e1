//! A node with more RPDOs than a byte counts (CiA 301 allows 512): the RPDO number an EMCY carries in its
//! first manufacturer byte (PDO-39/EEC-16 8210h, PDO-12/EEC-20 8250h, EEC-17 8220h, EEC-18 8230h) must not
//! overflow, whatever frame arrives.

use canopen_core::node::{NoApplication, Node};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::NodeConfig;
use canopen_core::{CanFrame, Duration, Instant, NmtState, NodeId, Sizes};

/// 256 RPDOs; RPDO 256 (k = 255) and RPDO 255 (k = 254) valid, each mapping one dummy byte, with an
/// event timer of 100 ms.
static RPDOS: [PdoDefault; 256] = {
    let mut a = [PdoDefault { valid: false, ..PdoDefault::EVENT }; 256];
    a[254] = PdoDefault {
        valid: true,
        can_id: Some(0x2FF),
        event_timer_ms: 100,
        mapping: &[0x0005_0008],
        ..PdoDefault::EVENT
    };
    a[255] = PdoDefault {
        valid: true,
        can_id: Some(0x300),
        event_timer_ms: 100,
        mapping: &[0x0005_0008],
        ..PdoDefault::EVENT
    };
    a
};

type ManyRpdos = Node<NoApplication, Sizes<4, 16, 16, 256, 1>>;

/// The manufacturer bytes of the EMCY frames sent since the last call, with their codes.
fn emcys(node: &mut ManyRpdos) -> Vec<(u16, [u8; 5])> {
    core::iter::from_fn(|| node.poll_transmit())
        .filter(|f| f.cob_id() == 0x085)
        .map(|f| {
            let d = f.data();
            (u16::from_le_bytes([d[0], d[1]]), [d[3], d[4], d[5], d[6], d[7]])
        })
        .collect()
}

/// PDO-39 (EEC-16) and PDO-12 (EEC-20) on RPDO 255 and RPDO 256: the number is 255 for both (a byte holds
/// no more), and neither panics.
#[test]
fn rpdo_numbers_above_255_saturate_in_the_emcy() {
    let cfg = NodeConfig { rpdo: &RPDOS, ..NodeConfig::DEFAULT };
    let mut node: Box<ManyRpdos> = Box::new(Node::new(NodeId::new(5).unwrap(), cfg, NoApplication));
    node.handle_timeout(Instant::ZERO);
    node.enter_state(NmtState::Operational);
    emcys(&mut node);
    let t = Instant::ZERO + Duration::from_millis(1);
    // Too short for RPDO 255's mapping: 8210h, RPDO number 255.
    node.handle_frame(t, &CanFrame::new(0x2FF, &[]).unwrap());
    assert_eq!(emcys(&mut node), [(0x8210, [255, 0, 0, 0, 0])]);
    // The same on RPDO 256: no overflow, 255 again (the code is active already: no second EMCY until it
    // is cleared), so clear it with a good frame on RPDO 255 first.
    node.handle_frame(t, &CanFrame::new(0x2FF, &[1]).unwrap());
    assert_eq!(emcys(&mut node), [(0, [0; 5])]);
    node.handle_frame(t, &CanFrame::new(0x300, &[]).unwrap());
    assert_eq!(emcys(&mut node), [(0x8210, [255, 0, 0, 0, 0])]);
    // Too long on RPDO 256 (EEC-17): 8220h, 255.
    node.handle_frame(t, &CanFrame::new(0x300, &[1, 2]).unwrap());
    assert_eq!(emcys(&mut node), [(0x8220, [255, 0, 0, 0, 0])]);
    // No frame for the 100 ms event timer (PDO-12, EEC-20): 8250h, 255.
    node.handle_timeout(t + Duration::from_millis(150));
    assert_eq!(emcys(&mut node), [(0x8250, [255, 0, 0, 0, 0])]);
}
