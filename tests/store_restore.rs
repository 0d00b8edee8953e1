//! Store/restore (1010h/1011h, CHECKLIST STORE-01..11, NMT-06) through whole nodes: VECTORS §13, store →
//! reset → values back, restore → reset → defaults, and a storage that fails after every possible number
//! of written bytes leaves either the old or the new parameters after a power cycle, never a mix.

mod common;

use std::cell::RefCell;
use std::rc::Rc;

use canopen::core::{
    node::Node,
    pdo::PdoDefault,
    profile::NodeConfig,
    storage::{Storage, StorageError},
    CanFrame, NodeId,
};
use canopen::ObjectDictionary;
use common::{frame, ms, Bus};

#[derive(ObjectDictionary, Default, Debug)]
#[od(crate = "canopen::core")]
pub struct App {
    #[od(index = 0x2000, access = "rw", pdo = "both", default = 1)]
    byte: u8,
    #[od(index = 0x2001, access = "rw", pdo = "both")]
    word: u32,
}

/// Two RAM slots shared with the test (so a "power cycle" can build a new node on the same memory), with an
/// optional failure after a number of written bytes: the write that crosses it is torn (its first part
/// lands, the rest does not) and fails, as a power loss would leave it.
#[derive(Clone, Default)]
struct Ram(Rc<RefCell<RamInner>>);

#[derive(Default)]
struct RamInner {
    slots: [Vec<u8>; 2],
    fail_after: Option<usize>,
    written: usize,
}

const CAP: usize = 1024;

impl Storage for Ram {
    fn capacity(&self) -> usize {
        CAP
    }
    fn erase(&mut self, slot: u8) -> Result<(), StorageError> {
        let mut m = self.0.borrow_mut();
        if m.fail_after.is_some_and(|n| m.written >= n) {
            return Err(StorageError::Io);
        }
        m.slots[usize::from(slot)] = vec![0xFF; CAP];
        Ok(())
    }
    fn write(&mut self, slot: u8, offset: usize, data: &[u8]) -> Result<(), StorageError> {
        let mut m = self.0.borrow_mut();
        let allowed = m.fail_after.map_or(data.len(), |n| n.saturating_sub(m.written).min(data.len()));
        let s = &mut m.slots[usize::from(slot)];
        if s.len() < CAP {
            s.resize(CAP, 0xFF);
        }
        s[offset..offset + allowed].copy_from_slice(&data[..allowed]);
        m.written += allowed;
        if allowed < data.len() {
            return Err(StorageError::Io);
        }
        Ok(())
    }
    fn read(&mut self, slot: u8, offset: usize, buf: &mut [u8]) -> Result<(), StorageError> {
        let m = self.0.borrow();
        let s = &m.slots[usize::from(slot)];
        for (i, b) in buf.iter_mut().enumerate() {
            *b = s.get(offset + i).copied().unwrap_or(0xFF);
        }
        Ok(())
    }
}

type TestNode = Node<App, 2, 32, 64, 2, 2, Ram>;

const CFG: NodeConfig =
    NodeConfig { tpdo: &[PdoDefault { mapping: &[0x2000_0008], ..PdoDefault::EVENT }], ..NodeConfig::DEFAULT };

fn node(ram: &Ram) -> TestNode {
    // The power-on values of the application (the derive does not generate `restore_defaults` yet).
    Node::with_storage(NodeId::new(3).unwrap(), CFG, App { byte: 1, word: 0 }, ram.clone())
}

fn sdo(bus: &mut Bus<TestNode>, req: &str) -> CanFrame {
    bus.take_master_rx();
    bus.inject(frame(req));
    let r: Vec<CanFrame> =
        bus.take_master_rx().into_iter().map(|s| s.frame).filter(|f| f.cob_id() & 0x780 == 0x580).collect();
    assert_eq!(r.len(), 1, "{req}");
    r[0]
}

fn boot(ram: &Ram) -> Bus<TestNode> {
    let mut bus = Bus::new(vec![node(ram)]);
    bus.run_until(ms(0));
    bus.take_master_rx();
    bus
}

/// Changes one communication value (1017h), the TPDO1 mapping and two application values.
fn change_everything(bus: &mut Bus<TestNode>, hb: u8, word: u32) {
    let w = word.to_le_bytes();
    for req in [
        format!("603 [8] 2B 17 10 00 {hb:02X} 00 00 00"),
        "603 [8] 23 00 18 01 83 01 00 80".to_string(),
        "603 [8] 2F 00 1A 00 00 00 00 00".to_string(),
        "603 [8] 23 00 1A 01 20 00 01 20".to_string(),
        "603 [8] 2F 00 1A 00 01 00 00 00".to_string(),
        "603 [8] 23 00 18 01 83 01 00 00".to_string(),
        format!("603 [8] 2F 00 20 00 {hb:02X} 00 00 00"),
        format!("603 [8] 23 01 20 00 {:02X} {:02X} {:02X} {:02X}", w[0], w[1], w[2], w[3]),
    ] {
        assert_eq!(sdo(bus, &req).data()[0], 0x60, "{req}");
    }
}

/// (1017h, 1A00h:01, 2000h, 2001h) as the node sees them.
fn snapshot(n: &TestNode) -> (u16, u32, u8, u32) {
    (n.params().heartbeat_time_ms, n.params().tpdo_map[0].entries[0], n.app().byte, n.app().word)
}

const DEFAULTS: (u16, u32, u8, u32) = (0, 0x2000_0008, 1, 0);

/// V-STO-01..07.
#[test]
fn store_restore_vectors_and_resets() {
    let ram = Ram::default();
    let mut bus = boot(&ram);
    assert_eq!(sdo(&mut bus, "603 [8] 40 10 10 01 00 00 00 00"), frame("583 [8] 43 10 10 01 01 00 00 00")); // V-STO-04
    assert_eq!(sdo(&mut bus, "603 [8] 40 11 10 01 00 00 00 00"), frame("583 [8] 43 11 10 01 01 00 00 00")); // V-STO-07
    assert_eq!(sdo(&mut bus, "603 [8] 40 10 10 00 00 00 00 00"), frame("583 [8] 4F 10 10 00 03 00 00 00"));
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 00"), frame("583 [8] 80 10 10 01 20 00 00 08")); // V-STO-02
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 04 73 61 76 65"), frame("583 [8] 80 10 10 04 11 00 09 06"));
    change_everything(&mut bus, 0x64, 0xCAFE);
    let changed = (100, 0x2001_0020, 0x64, 0xCAFE);
    assert_eq!(snapshot(&bus.stations[0]), changed);
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65"), frame("583 [8] 60 10 10 01 00 00 00 00")); // V-STO-01
                                                                                                            // Reset node: application and communication values come back from storage (NMT-06).
    bus.inject(frame("000 [2] 81 03"));
    assert_eq!(snapshot(&bus.stations[0]), changed);
    // Power cycle: the same.
    let mut bus = boot(&ram);
    assert_eq!(snapshot(&bus.stations[0]), changed);
    // V-STO-06: restore communication defaults; active only after reset communication (STORE-10).
    assert_eq!(sdo(&mut bus, "603 [8] 23 11 10 02 6C 6F 61 64"), frame("583 [8] 60 11 10 02 00 00 00 00"));
    assert_eq!(snapshot(&bus.stations[0]), changed);
    bus.inject(frame("000 [2] 82 03"));
    assert_eq!(snapshot(&bus.stations[0]), (0, 0x2000_0008, 0x64, 0xCAFE));
    bus.inject(frame("000 [2] 81 03"));
    assert_eq!(snapshot(&bus.stations[0]), (0, 0x2000_0008, 0x64, 0xCAFE)); // application still stored
                                                                            // V-STO-05: restore everything; active after reset node.
    assert_eq!(sdo(&mut bus, "603 [8] 23 11 10 01 6C 6F 61 64"), frame("583 [8] 60 11 10 01 00 00 00 00"));
    assert_eq!(bus.stations[0].app().byte, 0x64);
    bus.inject(frame("000 [2] 81 03"));
    // Communication defaults are back; application values come back through `restore_defaults`, which the
    // derive does not generate yet, so they come back at the next power-on.
    assert_eq!(snapshot(&bus.stations[0]).0, DEFAULTS.0);
    let mut bus = boot(&ram);
    assert_eq!(snapshot(&bus.stations[0]), DEFAULTS);
    // Saving only the application group (sub 03h) keeps the communication defaults.
    change_everything(&mut bus, 0x20, 7);
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 03 73 61 76 65").data()[0], 0x60);
    let bus = boot(&ram);
    assert_eq!(snapshot(&bus.stations[0]), (0, 0x2000_0008, 0x20, 7));
}

/// V-STO-03 (STORE-04): a storage failure is 0606 0000h; a node without storage reads 0 and refuses.
#[test]
fn storage_failure_and_no_storage() {
    let ram = Ram::default();
    let mut bus = boot(&ram);
    ram.0.borrow_mut().fail_after = Some(0);
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65"), frame("583 [8] 80 10 10 01 00 00 06 06"));
    let mut plain = Bus::new(vec![Node::<App>::new(NodeId::new(3).unwrap(), CFG, App::default())]);
    plain.run_until(ms(0));
    plain.take_master_rx();
    plain.inject(frame("603 [8] 40 10 10 01 00 00 00 00"));
    plain.inject(frame("603 [8] 23 10 10 01 73 61 76 65"));
    let r: Vec<CanFrame> = plain.take_master_rx().into_iter().map(|s| s.frame).collect();
    assert_eq!(r, [frame("583 [8] 43 10 10 01 00 00 00 00"), frame("583 [8] 80 10 10 01 00 00 06 06")]);
}

/// A power loss in the middle of a save (the storage stops after `n` bytes, for every `n`) leaves either
/// the old or the new parameters after the next power-on, never a mix; the A/B slots of `storage.rs`.
#[test]
fn torn_save_leaves_old_or_new() {
    let old = (0x11, 0x2001_0020, 0x11, 1);
    let new = (0x22, 0x2001_0020, 0x22, 2);
    let mut total = None;
    for n in 0.. {
        let ram = Ram::default();
        let mut bus = boot(&ram);
        change_everything(&mut bus, 0x11, 1);
        assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65").data()[0], 0x60);
        // A second save first, so that both slots hold records and the torn write overwrites the older one.
        assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65").data()[0], 0x60);
        change_everything(&mut bus, 0x22, 2);
        {
            let mut m = ram.0.borrow_mut();
            m.written = 0;
            m.fail_after = Some(n);
        }
        let reply = sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65");
        ram.0.borrow_mut().fail_after = None;
        let after = snapshot(&boot(&ram).stations[0]);
        if reply.data()[0] == 0x60 {
            assert_eq!(after, new, "complete save at n = {n}");
            total = Some(n);
            break;
        }
        assert_eq!(reply, frame("583 [8] 80 10 10 01 00 00 06 06"));
        assert_eq!(after, old, "torn after {n} bytes");
    }
    // The record is a few hundred bytes: every prefix of it was tried.
    assert!(total.is_some_and(|t| t > 50), "{total:?}");
}
