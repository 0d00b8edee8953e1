//! Store/restore (1010h/1011h, STORE-01..11, NMT-06) through whole nodes: store →
//! reset → values back, restore → reset → defaults, and a storage that fails after every possible number
//! of written bytes leaves either the old or the new parameters after a power cycle, never a mix.

mod common;

use std::cell::RefCell;
use std::rc::Rc;

use canopen::core::{
    node::Node,
    pdo::PdoDefault,
    profile::NodeConfig,
    storage::{slot_status, SlotStatus, Storage, StorageError},
    CanFrame, NodeId, Sizes,
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
    /// Every `read` fails (STORE-09).
    fail_read: bool,
    /// Every `erase` fails (STORE-09).
    fail_erase: bool,
}

const CAP: usize = 1024;

impl Storage for Ram {
    fn capacity(&self) -> usize {
        CAP
    }
    fn erase(&mut self, slot: u8) -> Result<(), StorageError> {
        let mut m = self.0.borrow_mut();
        if m.fail_erase || m.fail_after.is_some_and(|n| m.written >= n) {
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
        if m.fail_read {
            return Err(StorageError::Io);
        }
        let s = &m.slots[usize::from(slot)];
        for (i, b) in buf.iter_mut().enumerate() {
            *b = s.get(offset + i).copied().unwrap_or(0xFF);
        }
        Ok(())
    }
}

type TestNode = Node<App, Sizes<2, 32, 64, 2, 2>, Ram>;

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

/// STORE-02 (1010h sub 01h all, 02h communication, 03h application: saving only 03h keeps
/// the communication defaults; restoring 02h only the communication ones), STORE-03 ("save" is 73 61 76 65;
/// 73 61 76 00 is refused), STORE-05 and STORE-11 (1010h:01 and 1011h:01 read 1: on command), STORE-06 (the
/// sub-entries are written). ABORT-27: a wrong "save" signature is answered 0800 0020h.
#[test]
fn store_restore_vectors_and_resets() {
    let ram = Ram::default();
    let mut bus = boot(&ram);
    assert_eq!(sdo(&mut bus, "603 [8] 40 10 10 01 00 00 00 00"), frame("583 [8] 43 10 10 01 01 00 00 00")); // saves on command
    assert_eq!(sdo(&mut bus, "603 [8] 40 11 10 01 00 00 00 00"), frame("583 [8] 43 11 10 01 01 00 00 00")); // 1011h:01 reads 1
    assert_eq!(sdo(&mut bus, "603 [8] 40 10 10 00 00 00 00 00"), frame("583 [8] 4F 10 10 00 03 00 00 00"));
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 00"), frame("583 [8] 80 10 10 01 20 00 00 08")); // bad signature
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 04 73 61 76 65"), frame("583 [8] 80 10 10 04 11 00 09 06"));
    change_everything(&mut bus, 0x64, 0xCAFE);
    let changed = (100, 0x2001_0020, 0x64, 0xCAFE);
    assert_eq!(snapshot(&bus.stations[0]), changed);
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65"), frame("583 [8] 60 10 10 01 00 00 00 00")); // "save"
                                                                                                            // Reset node: application and communication values come back from storage (NMT-06).
    bus.inject(frame("000 [2] 81 03"));
    assert_eq!(snapshot(&bus.stations[0]), changed);
    // Power cycle: the same.
    let mut bus = boot(&ram);
    assert_eq!(snapshot(&bus.stations[0]), changed);
    // Restore communication defaults; active only after reset communication (STORE-10).
    assert_eq!(sdo(&mut bus, "603 [8] 23 11 10 02 6C 6F 61 64"), frame("583 [8] 60 11 10 02 00 00 00 00"));
    assert_eq!(snapshot(&bus.stations[0]), changed);
    bus.inject(frame("000 [2] 82 03"));
    assert_eq!(snapshot(&bus.stations[0]), (0, 0x2000_0008, 0x64, 0xCAFE));
    bus.inject(frame("000 [2] 81 03"));
    assert_eq!(snapshot(&bus.stations[0]), (0, 0x2000_0008, 0x64, 0xCAFE)); // application still stored
                                                                            // Restore everything; active after reset node.
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

/// STORE-04: a storage failure is 0606 0000h; a node without storage reads 0 and refuses.
/// ABORT-16: 0606 0000h is the answer to a store the hardware failed.
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

/// STORE-08: 1011h restores only on the signature "load" (6C 6F 61 64 on the wire). Near misses (the bytes
/// reversed, "save", one byte off, the right bytes in a 2-byte write) answer 0800 0020h and change nothing:
/// the stored values still come back after a reset node. 1010h likewise only on "save".
#[test]
fn restore_only_on_load_signature_store_08() {
    let ram = Ram::default();
    let mut bus = boot(&ram);
    change_everything(&mut bus, 0x33, 3);
    let stored = (0x33, 0x2001_0020, 0x33, 3);
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65").data()[0], 0x60);
    for req in [
        "603 [8] 23 11 10 01 64 61 6F 6C", // "load" as a big-endian number
        "603 [8] 23 11 10 01 73 61 76 65", // "save"
        "603 [8] 23 11 10 01 6C 6F 61 65",
        "603 [8] 23 11 10 01 4C 4F 41 44", // "LOAD"
        "603 [8] 23 11 10 01 00 00 00 00",
        "603 [8] 23 11 10 02 6C 6F 61 00",
        "603 [8] 23 11 10 03 64 61 6F 6C",
        "603 [8] 23 10 10 01 65 76 61 73", // 1010h: "save" reversed
        "603 [8] 23 10 10 01 6C 6F 61 64", // 1010h: "load"
    ] {
        let f = frame(req);
        let d = f.data();
        assert_eq!(
            sdo(&mut bus, req),
            CanFrame::new(0x583, &[0x80, d[1], d[2], d[3], 0x20, 0, 0, 8]).unwrap(),
            "{req}"
        );
    }
    let raw = ram.0.borrow().slots.clone();
    bus.inject(frame("000 [2] 81 03"));
    assert_eq!(snapshot(&bus.stations[0]), stored);
    assert_eq!(ram.0.borrow().slots, raw, "a refused command touched the storage");
    let bus = boot(&ram);
    assert_eq!(snapshot(&bus.stations[0]), stored);
    // The right signature does restore (so the refusals above are about the signature alone).
    let mut bus = bus;
    assert_eq!(sdo(&mut bus, "603 [8] 23 11 10 01 6C 6F 61 64").data()[0], 0x60);
    assert_eq!(snapshot(&boot(&ram).stations[0]), DEFAULTS);
}

/// STORE-09/STORE-10: "load" (1011h) with nothing stored succeeds without touching the storage (no erase,
/// no write: the defaults are what the next reset loads anyway); after a save, "load" of one group drops
/// only that group from the record.
#[test]
fn restore_with_nothing_stored_writes_nothing_store_09() {
    let ram = Ram::default();
    let mut bus = boot(&ram);
    ram.0.borrow_mut().fail_erase = true; // an erase would now fail the command
    for sub in ["01", "02", "03"] {
        let req = format!("603 [8] 23 11 10 {sub} 6C 6F 61 64");
        assert_eq!(sdo(&mut bus, &req).data()[0], 0x60, "{req}");
    }
    assert_eq!(ram.0.borrow().written, 0);
    ram.0.borrow_mut().fail_erase = false;
    change_everything(&mut bus, 0x44, 4);
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65").data()[0], 0x60);
    assert_eq!(sdo(&mut bus, "603 [8] 23 11 10 03 6C 6F 61 64").data()[0], 0x60); // drop the application
    assert_eq!(snapshot(&boot(&ram).stations[0]), (0x44, 0x2001_0020, DEFAULTS.2, DEFAULTS.3));
}

/// STORE-09 (success → download response; failure → 0606 0000h) for a storage failing at each of its steps:
/// every read, every erase, a write (torn after 0 bytes; every later byte count is `torn_save_leaves_old_or_new`),
/// for a save (1010h) and for a restore (1011h). Each failure is answered 0606 0000h, loses nothing (after a
/// power cycle the last stored values come back, the storage's good record untouched), and once the storage
/// works again the same command succeeds. A node booting on a storage whose reads fail comes up with its
/// defaults instead of panicking.
#[test]
fn storage_failing_at_each_step_store_09() {
    #[derive(Debug, Clone, Copy)]
    enum Step {
        Read,
        Erase,
        Write,
    }
    let stored = (0x44, 0x2001_0020, 0x44, 4);
    for step in [Step::Read, Step::Erase, Step::Write] {
        for (what, req) in [("save", "603 [8] 23 10 10 01 73 61 76 65"), ("restore", "603 [8] 23 11 10 01 6C 6F 61 64")]
        {
            let ram = Ram::default();
            let mut bus = boot(&ram);
            change_everything(&mut bus, 0x44, 4);
            assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65").data()[0], 0x60);
            change_everything(&mut bus, 0x55, 5);
            let set = |ram: &Ram, on: bool| {
                let mut m = ram.0.borrow_mut();
                match step {
                    Step::Read => m.fail_read = on,
                    Step::Erase => m.fail_erase = on,
                    Step::Write => {
                        m.written = 0;
                        m.fail_after = on.then_some(0);
                    }
                }
            };
            set(&ram, true);
            let f = frame(req);
            let d = f.data();
            let expect = CanFrame::new(0x583, &[0x80, d[1], d[2], d[3], 0x00, 0x00, 0x06, 0x06]).unwrap();
            assert_eq!(sdo(&mut bus, req), expect, "{what} with {step:?} failing");
            set(&ram, false);
            assert_eq!(snapshot(&boot(&ram).stations[0]), stored, "{what} with {step:?} failing lost the record");
            // The storage works again: the same command now succeeds.
            assert_eq!(sdo(&mut bus, req).data()[0], 0x60, "{what} after {step:?} recovered");
            let after = snapshot(&boot(&ram).stations[0]);
            if what == "save" {
                assert_eq!(after, (0x55, 0x2001_0020, 0x55, 5));
            } else {
                assert_eq!(after, DEFAULTS);
            }
        }
    }
    // Power-on with unreadable storage: defaults, no panic, and the node answers.
    let ram = Ram::default();
    let mut bus = boot(&ram);
    change_everything(&mut bus, 0x66, 6);
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65").data()[0], 0x60);
    ram.0.borrow_mut().fail_read = true;
    let mut bus = boot(&ram);
    assert_eq!(snapshot(&bus.stations[0]), DEFAULTS);
    assert_eq!(sdo(&mut bus, "603 [8] 40 17 10 00 00 00 00 00"), frame("583 [8] 4B 17 10 00 00 00 00 00"));
}

/// STORE-01 (1010h store parameters: an ARRAY of UNSIGNED32 whose sub 00h is const, here 03h) and STORE-07
/// (1011h restore default parameters: the same layout and grouping): sub 00h reads 03h and cannot be
/// written (0601 0002h); subs 01h–03h are 4-byte entries reading 1 (on command); sub 04h does not exist.
#[test]
fn store_and_restore_object_layout_store_01_store_07() {
    let ram = Ram::default();
    let mut bus = boot(&ram);
    for index in [0x10u8, 0x11] {
        let read0 = format!("603 [8] 40 {index:02X} 10 00 00 00 00 00");
        assert_eq!(sdo(&mut bus, &read0), frame(&format!("583 [8] 4F {index:02X} 10 00 03 00 00 00")));
        let write0 = format!("603 [8] 2F {index:02X} 10 00 03 00 00 00");
        assert_eq!(sdo(&mut bus, &write0), frame(&format!("583 [8] 80 {index:02X} 10 00 02 00 01 06")));
        for sub in 1..=3u8 {
            let req = format!("603 [8] 40 {index:02X} 10 {sub:02X} 00 00 00 00");
            assert_eq!(sdo(&mut bus, &req), frame(&format!("583 [8] 43 {index:02X} 10 {sub:02X} 01 00 00 00")));
        }
        let req = format!("603 [8] 40 {index:02X} 10 04 00 00 00 00");
        assert_eq!(sdo(&mut bus, &req), frame(&format!("583 [8] 80 {index:02X} 10 04 11 00 09 06")));
    }
}

/// `slot_status` (used by the example node's `--store` check, issue 16): erased, a saved record valid, one
/// flipped payload byte a CRC failure, a broken magic a format failure.
#[test]
fn slot_status_tells_valid_crc_and_format_failures() {
    let mut ram = Ram::default();
    ram.0.borrow_mut().slots = [vec![0xFF; CAP], vec![0xFF; CAP]];
    assert_eq!(slot_status(&mut ram, 0), Ok(SlotStatus::Erased));
    let mut bus = boot(&ram);
    assert_eq!(sdo(&mut bus, "603 [8] 23 10 10 01 73 61 76 65"), frame("583 [8] 60 10 10 01 00 00 00 00"));
    assert_eq!(slot_status(&mut ram, 0), Ok(SlotStatus::Valid));
    assert_eq!(slot_status(&mut ram, 1), Ok(SlotStatus::Erased));
    ram.0.borrow_mut().slots[0][canopen::core::storage::HEADER_LEN] ^= 0x01;
    assert_eq!(slot_status(&mut ram, 0), Ok(SlotStatus::BadCrc));
    ram.0.borrow_mut().slots[0][0] ^= 0x01;
    assert_eq!(slot_status(&mut ram, 0), Ok(SlotStatus::BadFormat));
    ram.0.borrow_mut().fail_read = true;
    assert_eq!(slot_status(&mut ram, 0), Err(StorageError::Io));
}

/// STORE-13, SDO-55: the additional SDO servers' records are never stored: 1201h configured with the dyn
/// bit (dynamically allocated) and 1017h written, "save" all (1010h:01); after a power cycle on the same
/// memory 1017h comes back from storage, 1201h is invalid (8000_0000h) and its COB-ID is not served.
#[test]
fn sdo_server_records_are_never_stored_store_13() {
    type WithServer = Node<App, canopen::core::node::WithSdoServers<Sizes<2, 32, 64, 2, 2>, 1>, Ram>;
    let ram = Ram::default();
    let power_on = |ram: &Ram| -> WithServer {
        let mut n: WithServer = Node::with_storage(NodeId::new(3).unwrap(), CFG, App { byte: 1, word: 0 }, ram.clone());
        n.handle_timeout(canopen::core::Instant::ZERO);
        while n.poll_transmit().is_some() {}
        n
    };
    let ex = |n: &mut WithServer, req: &str| {
        n.handle_frame(canopen::core::Instant::ZERO, &frame(req));
        core::iter::from_fn(|| n.poll_transmit()).collect::<Vec<CanFrame>>()
    };
    let mut n = power_on(&ram);
    assert_eq!(ex(&mut n, "603 [8] 23 01 12 02 D3 06 00 40"), vec![frame("583 [8] 60 01 12 02 00 00 00 00")]);
    assert_eq!(ex(&mut n, "603 [8] 23 01 12 01 C3 06 00 40"), vec![frame("583 [8] 60 01 12 01 00 00 00 00")]);
    assert_eq!(ex(&mut n, "6C3 [8] 40 01 12 01 00 00 00 00"), vec![frame("6D3 [8] 43 01 12 01 C3 06 00 40")]);
    assert_eq!(ex(&mut n, "603 [8] 2B 17 10 00 2C 01 00 00"), vec![frame("583 [8] 60 17 10 00 00 00 00 00")]);
    assert_eq!(ex(&mut n, "603 [8] 23 10 10 01 73 61 76 65"), vec![frame("583 [8] 60 10 10 01 00 00 00 00")]);
    let mut n = power_on(&ram);
    assert_eq!(ex(&mut n, "603 [8] 40 17 10 00 00 00 00 00"), vec![frame("583 [8] 4B 17 10 00 2C 01 00 00")]);
    assert_eq!(ex(&mut n, "603 [8] 40 01 12 01 00 00 00 00"), vec![frame("583 [8] 43 01 12 01 00 00 00 80")]);
    assert!(ex(&mut n, "6C3 [8] 40 01 12 01 00 00 00 00").is_empty());
}
