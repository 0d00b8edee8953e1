//! CAN-01 and CAN-06 at the frame boundary: what the core accepts from a driver and what it can send.

use canopen_core::{frame::MAX_STANDARD_ID, CanFrame};
use embedded_can::{ExtendedId, Frame, Id, StandardId};

/// A driver's frame, 11- or 29-bit, as a CAN controller would hand it over.
#[derive(Debug)]
struct DriverFrame {
    id: Id,
    rtr: bool,
    dlc: usize,
    data: [u8; 8],
}

impl Frame for DriverFrame {
    fn new(id: impl Into<Id>, data: &[u8]) -> Option<Self> {
        let mut buf = [0u8; 8];
        buf.get_mut(..data.len())?.copy_from_slice(data);
        Some(DriverFrame { id: id.into(), rtr: false, dlc: data.len(), data: buf })
    }
    fn new_remote(id: impl Into<Id>, dlc: usize) -> Option<Self> {
        (dlc <= 8).then(|| DriverFrame { id: id.into(), rtr: true, dlc, data: [0; 8] })
    }
    fn is_extended(&self) -> bool {
        matches!(self.id, Id::Extended(_))
    }
    fn is_remote_frame(&self) -> bool {
        self.rtr
    }
    fn id(&self) -> Id {
        self.id
    }
    fn dlc(&self) -> usize {
        self.dlc
    }
    fn data(&self) -> &[u8] {
        if self.rtr {
            &[]
        } else {
            &self.data[..self.dlc]
        }
    }
}

/// CAN-01 (CANopen runs on 11-bit base frames; 29-bit frames need not be supported): every 11-bit
/// identifier converts both ways, 7FFh is the largest; a 29-bit frame from the driver does not convert (so
/// the stack never sees it, even when its low 11 bits are a CANopen ID such as 605h), and the core cannot
/// build one.
#[test]
fn eleven_bit_identifiers_only_can_01() {
    for id in [0u16, 0x080, 0x605, MAX_STANDARD_ID] {
        let d = DriverFrame::new(StandardId::new(id).unwrap(), &[1, 2]).unwrap();
        let f = CanFrame::from_frame(&d).unwrap();
        assert_eq!((f.cob_id(), f.data()), (id, &[1u8, 2][..]));
        let back: DriverFrame = f.to_frame().unwrap();
        assert_eq!((back.id, back.data()), (Id::Standard(StandardId::new(id).unwrap()), &[1u8, 2][..]));
    }
    assert!(CanFrame::new(MAX_STANDARD_ID + 1, &[]).is_none());
    for raw in [0x605u32, 0x1FFF_FFFF] {
        let ext = DriverFrame::new(ExtendedId::new(raw).unwrap(), &[0x40, 0, 0x10, 0]).unwrap();
        assert!(CanFrame::from_frame(&ext).is_none(), "{raw:08X}");
        assert!(<CanFrame as Frame>::new(ExtendedId::new(raw).unwrap(), &[]).is_none());
        assert!(<CanFrame as Frame>::new_remote(ExtendedId::new(raw).unwrap(), 0).is_none());
    }
    assert!(!CanFrame::new(0x605, &[]).unwrap().is_extended());
}

/// CAN-06 (a data frame carries 0 to 8 bytes; a remote frame carries none): 0 to 8 bytes make frames of
/// that length, 9 do not; an RTR frame keeps its DLC but has no data, whichever way it is built.
#[test]
fn data_length_and_remote_frames_can_06() {
    for n in 0..=8usize {
        let data: Vec<u8> = (1..=n as u8).collect();
        let f = CanFrame::new(0x181, &data).unwrap();
        assert_eq!((f.dlc() as usize, f.data()), (n, &data[..]));
        assert!(!f.is_rtr());
    }
    assert!(CanFrame::new(0x181, &[0; 9]).is_none());
    for dlc in 0..=8u8 {
        let r = CanFrame::new_rtr(0x705, dlc).unwrap();
        assert_eq!((r.is_rtr(), r.dlc(), r.data()), (true, dlc, &[][..]));
        let d = DriverFrame::new_remote(StandardId::new(0x705).unwrap(), dlc.into()).unwrap();
        let c = CanFrame::from_frame(&d).unwrap();
        assert_eq!((c.is_rtr(), c.dlc(), c.data()), (true, dlc, &[][..]));
    }
    assert!(CanFrame::new_rtr(0x705, 9).is_none());
    assert!(<CanFrame as Frame>::new_remote(StandardId::new(0x705).unwrap(), 9).is_none());
}
