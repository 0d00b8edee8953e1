//! Store/restore on NOR flash survives a power cut at every program and erase step (issue: "after the cut
//! the node starts with the old or the new parameters, never a mix, never nothing"; STORE-01, STORE-03,
//! NMT-06). A simulated flash with 8-byte program words (as on an STM32G4) and 2 KB sectors counts every
//! word programmed and every sector erased; at step `n` the power goes: that word or sector is left torn
//! (some of its bits changed, as a cut NOR operation leaves them) and nothing after it happens. Then a new
//! node boots on the same flash and must hold exactly the old or the new parameters. The simulated flash
//! also refuses to program a word twice between erases, which real flash (with ECC) cannot do either.

use std::cell::RefCell;
use std::rc::Rc;

use canopen_core::{
    lss::LssStore, node::NoApplication, profile::NodeConfig, wire::lss::BitRate, CanFrame, Instant, Node, NodeId,
};
use canopen_embassy::flash::FlashStorage;
use embedded_storage::nor_flash::{ErrorType, NorFlash, NorFlashErrorKind, ReadNorFlash};

const SECTOR: usize = 2048;
const WORD: usize = 8;

#[derive(Default)]
struct Chip {
    mem: Vec<u8>,
    /// Steps left before the power goes (`None`: no cut).
    budget: Option<usize>,
    /// Steps taken since the budget was set.
    steps: usize,
    dead: bool,
    /// A little pseudo-random state for torn bits.
    seed: u32,
}

impl Chip {
    /// One more program/erase step; `false` when the power goes now (the caller tears what it was doing).
    fn step(&mut self) -> bool {
        self.steps += 1;
        match &mut self.budget {
            Some(0) => {
                self.dead = true;
                false
            }
            Some(n) => {
                *n -= 1;
                true
            }
            None => true,
        }
    }
    fn noise(&mut self) -> u8 {
        self.seed = self.seed.wrapping_mul(1_103_515_245).wrapping_add(12_345);
        (self.seed >> 16) as u8
    }
}

#[derive(Clone)]
struct SimFlash(Rc<RefCell<Chip>>);

impl SimFlash {
    fn new(sectors: usize) -> Self {
        SimFlash(Rc::new(RefCell::new(Chip { mem: vec![0xFF; sectors * SECTOR], seed: 7, ..Chip::default() })))
    }
}

impl ErrorType for SimFlash {
    type Error = NorFlashErrorKind;
}

impl ReadNorFlash for SimFlash {
    const READ_SIZE: usize = 1;
    fn read(&mut self, offset: u32, bytes: &mut [u8]) -> Result<(), Self::Error> {
        let c = self.0.borrow();
        let o = offset as usize;
        bytes.copy_from_slice(c.mem.get(o..o + bytes.len()).ok_or(NorFlashErrorKind::OutOfBounds)?);
        Ok(())
    }
    fn capacity(&self) -> usize {
        self.0.borrow().mem.len()
    }
}

impl NorFlash for SimFlash {
    const WRITE_SIZE: usize = WORD;
    const ERASE_SIZE: usize = SECTOR;
    fn erase(&mut self, from: u32, to: u32) -> Result<(), Self::Error> {
        let mut c = self.0.borrow_mut();
        assert!(from as usize % SECTOR == 0 && to as usize % SECTOR == 0, "unaligned erase {from}..{to}");
        for s in (from as usize..to as usize).step_by(SECTOR) {
            if c.dead {
                return Err(NorFlashErrorKind::Other);
            }
            if !c.step() {
                // Cut mid-erase: some bits of the sector are set, the others keep their old value.
                for i in s..s + SECTOR {
                    let n = c.noise();
                    c.mem[i] |= n;
                }
                return Err(NorFlashErrorKind::Other);
            }
            c.mem[s..s + SECTOR].fill(0xFF);
        }
        Ok(())
    }
    fn write(&mut self, offset: u32, bytes: &[u8]) -> Result<(), Self::Error> {
        let mut c = self.0.borrow_mut();
        let o = offset as usize;
        assert!(o % WORD == 0 && bytes.len() % WORD == 0, "unaligned program at {o}, {} bytes", bytes.len());
        for (k, word) in bytes.chunks(WORD).enumerate() {
            let at = o + k * WORD;
            if c.dead {
                return Err(NorFlashErrorKind::Other);
            }
            assert!(c.mem[at..at + WORD].iter().all(|&b| b == 0xFF), "word at {at} programmed twice");
            if !c.step() {
                // Cut mid-program: some of the bits to clear are cleared.
                for (i, &b) in word.iter().enumerate() {
                    let n = c.noise();
                    c.mem[at + i] = b | n;
                }
                return Err(NorFlashErrorKind::Other);
            }
            c.mem[at..at + WORD].copy_from_slice(word);
        }
        Ok(())
    }
}

type FlashNode = Node<NoApplication, canopen_core::Sizes, FlashStorage<SimFlash>>;

fn boot(flash: &SimFlash) -> FlashNode {
    let st = FlashStorage::new(flash.clone(), 0..2 * SECTOR as u32, 2 * SECTOR as u32..4 * SECTOR as u32)
        .and_then(|s| s.with_lss(4 * SECTOR as u32..5 * SECTOR as u32))
        .expect("layout");
    let id = NodeId::new(3).expect("node-ID");
    let mut node = Node::with_storage(id, NodeConfig::DEFAULT, NoApplication, st);
    node.handle_timeout(Instant::ZERO);
    while node.poll_transmit().is_some() {}
    node
}

/// One SDO request to node 3, its answer.
fn sdo(node: &mut FlashNode, data: [u8; 8]) -> [u8; 8] {
    let req = CanFrame::new(0x603, &data).expect("frame");
    node.handle_frame(Instant::from_millis(1), &req);
    let reply = node.poll_transmit().expect("an SDO answer");
    assert_eq!(reply.cob_id(), 0x583);
    reply.data().try_into().expect("8 bytes")
}

fn download_u16(node: &mut FlashNode, index: u16, sub: u8, v: u16) {
    let [i0, i1] = index.to_le_bytes();
    let [v0, v1] = v.to_le_bytes();
    assert_eq!(sdo(node, [0x2B, i0, i1, sub, v0, v1, 0, 0])[0], 0x60, "{index:04X}h:{sub}");
}

fn upload_u16(node: &mut FlashNode, index: u16, sub: u8) -> u16 {
    let [i0, i1] = index.to_le_bytes();
    let r = sdo(node, [0x40, i0, i1, sub, 0, 0, 0, 0]);
    u16::from_le_bytes([r[4], r[5]])
}

/// Heartbeat time (1017h) and the inhibit and event times of TPDO 1 (1800h:03, 1800h:05): three objects in
/// different places of the record, so a mix of two records would show.
fn set_all(node: &mut FlashNode, v: u16) {
    download_u16(node, 0x1017, 0, v);
    download_u16(node, 0x1800, 3, v + 1);
    download_u16(node, 0x1800, 5, v + 2);
}

fn snapshot(node: &mut FlashNode) -> (u16, u16, u16) {
    (upload_u16(node, 0x1017, 0), upload_u16(node, 0x1800, 3), upload_u16(node, 0x1800, 5))
}

const SAVE: [u8; 8] = [0x23, 0x10, 0x10, 0x01, 0x73, 0x61, 0x76, 0x65];

#[test]
fn save_and_restore_through_flash() {
    let flash = SimFlash::new(5);
    let mut node = boot(&flash);
    let defaults = snapshot(&mut node);
    set_all(&mut node, 100);
    assert_eq!(sdo(&mut node, SAVE)[0], 0x60);
    assert_eq!(snapshot(&mut boot(&flash)), (100, 101, 102));
    assert_ne!(defaults, (100, 101, 102));
}

#[test]
fn a_power_cut_at_any_step_leaves_old_or_new() {
    let mut complete_at = None;
    for n in 0.. {
        let flash = SimFlash::new(5);
        let mut node = boot(&flash);
        set_all(&mut node, 100);
        assert_eq!(sdo(&mut node, SAVE)[0], 0x60);
        // A second save, so that both slots hold records and the cut one replaces the older.
        assert_eq!(sdo(&mut node, SAVE)[0], 0x60);
        set_all(&mut node, 200);
        {
            let mut c = flash.0.borrow_mut();
            c.budget = Some(n);
            c.steps = 0;
        }
        let reply = sdo(&mut node, SAVE);
        {
            let mut c = flash.0.borrow_mut();
            c.budget = None;
            c.dead = false; // power back
        }
        let after = snapshot(&mut boot(&flash));
        if reply[0] == 0x60 {
            assert_eq!(after, (200, 201, 202), "complete save at n = {n}");
            complete_at = Some(n);
            break;
        }
        assert_eq!(reply, [0x80, 0x10, 0x10, 0x01, 0x00, 0x00, 0x06, 0x06], "0606 0000h at n = {n}");
        assert_eq!(after, (100, 101, 102), "cut at step {n}");
    }
    // One erase plus the record's words: every step of it was cut once.
    assert!(complete_at.is_some_and(|n| n > 5), "{complete_at:?}");
}

#[test]
fn lss_configuration_survives_a_power_cycle_or_is_lost_whole() {
    let flash = SimFlash::new(5);
    let mut node = boot(&flash);
    assert_eq!(node.storage_mut().lss_config(), None);
    node.storage_mut().store(0x22, BitRate::K125).expect("stored");
    assert_eq!(boot(&flash).storage_mut().lss_config(), Some((0x22, BitRate::K125)));
    // Cut at the erase and at the program step of a new store: never a wrong node-ID.
    for n in 0..2 {
        flash.0.borrow_mut().budget = Some(n);
        assert!(boot(&flash).storage_mut().store(0x33, BitRate::K50).is_err());
        {
            let mut c = flash.0.borrow_mut();
            c.budget = None;
            c.dead = false;
        }
        assert_eq!(boot(&flash).storage_mut().lss_config(), None, "cut at step {n}");
    }
}
