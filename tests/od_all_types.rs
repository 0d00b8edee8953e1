//! Every entry of the all-types dictionary read and written through the derive-generated dispatch, with
//! each abort code of OD-16 / ABORT-09..11, 17..23 and the comm profile merged in (OD-12).

mod common {
    pub mod all_types;
}

use canopen_core::od::{
    AbortCode, Access, DataType, ObjectCode, ObjectDictionary, OdDescribe, PdoDir, PdoHandle, PdoMapping,
    TimeDifference, TimeOfDay, Value,
};
use canopen_core::profile::eds::{write_eds, EdsInfo};
use common::all_types::{node_od, AllTypes};

fn read(od: &impl ObjectDictionary, index: u16, sub: u8) -> Result<Vec<u8>, AbortCode> {
    let mut buf = [0u8; 128];
    let n = od.read(index, sub, 0, &mut buf)?;
    Ok(buf[..n].to_vec())
}

/// (index, sub, an encoded value to write, its data type).
fn samples() -> Vec<(u16, u8, Vec<u8>, DataType)> {
    use DataType::*;
    vec![
        (0x2000, 0, vec![0], Boolean),
        (0x2001, 0, vec![0x9C], Integer8), // -100
        (0x2002, 0, (-266i16).to_le_bytes().to_vec(), Integer16),
        (0x2003, 0, vec![0xF6, 0xFE, 0xFF], Integer24),
        (0x2004, 0, (-5i32).to_le_bytes().to_vec(), Integer32),
        (0x2005, 0, vec![1, 2, 3, 4, 0x85], Integer40),
        (0x2006, 0, vec![1, 2, 3, 4, 5, 0x86], Integer48),
        (0x2007, 0, vec![1, 2, 3, 4, 5, 6, 0x87], Integer56),
        (0x2008, 0, i64::MIN.to_le_bytes().to_vec(), Integer64),
        (0x2010, 0, vec![200], Unsigned8),
        (0x2011, 0, vec![0x0A, 0x01], Unsigned16),
        (0x2012, 0, vec![1, 2, 3], Unsigned24),
        (0x2013, 0, vec![4, 3, 2, 1], Unsigned32),
        (0x2014, 0, vec![1, 2, 3, 4, 5], Unsigned40),
        (0x2015, 0, vec![1, 2, 3, 4, 5, 6], Unsigned48),
        (0x2016, 0, vec![1, 2, 3, 4, 5, 6, 7], Unsigned56),
        (0x2017, 0, u64::MAX.to_le_bytes().to_vec(), Unsigned64),
        (0x2018, 0, vec![0x00, 0x00, 0x00, 0x40], Real32), // 2.0
        (0x2019, 0, 6.25f64.to_le_bytes().to_vec(), Real64),
        (0x2020, 0, b"visible text".to_vec(), VisibleString),
        (0x2021, 0, vec![0, 0xFF, 0x10], OctetString),
        (0x2022, 0, vec![0x41, 0, 0xE9, 0], UnicodeString),
        (0x2023, 0, vec![0x00, 0x2E, 0x93, 0x02, 0xB9, 0x26], TimeOfDay), // 2011-02-21 12:00:00.000
        (0x2024, 0, vec![0x95, 0x2C, 0xB3, 0x02, 0xD4, 0x16], TimeDifference),
        (0x2025, 0, (0..40).collect(), Domain),
        (0x2100, 1, 0.5f32.to_le_bytes().to_vec(), Real32),
        (0x2100, 2, 9.5f32.to_le_bytes().to_vec(), Real32),
        (0x2100, 3, vec![3], Unsigned8),
        (0x6200, 1, (-10i16).to_le_bytes().to_vec(), Integer16),
        (0x6200, 4, 10i16.to_le_bytes().to_vec(), Integer16),
    ]
}

/// Every writable entry of every data type takes a value and reads it back byte for byte, with the size of
/// what was written: DT-10 (OCTET_STRING is plain UNSIGNED8s, 00h and FFh included), DT-11 (a
/// VISIBLE_STRING needs no terminating zero: 12 characters are 12 bytes), DT-12 (UNICODE_STRING is an array
/// of little-endian UNSIGNED16: 41 00 E9 00 is 'A', 'é'), DT-14 (TIME_DIFFERENCE has the TIME_OF_DAY layout:
/// 28-bit milliseconds, 4 reserved bits, 16-bit days), DT-15 (a DOMAIN holds a block of any length up to
/// its capacity and any content). OD-09: the `rww` (2002h) and `rwr` (2003h) entries are read and written,
/// through the dictionary calls the SDO server makes,
/// like rw; their PDO direction is `pdo_handles`'s and `table_is_const_and_sorted`'s.
#[test]
fn every_writable_entry_round_trips() {
    let mut od = AllTypes::default();
    for (index, sub, bytes, dt) in samples() {
        let info = od.info(index, sub).unwrap();
        assert_eq!(info.data_type, dt, "{index:04X}:{sub}");
        od.write(index, sub, &bytes).unwrap_or_else(|e| panic!("{index:04X}:{sub} {e}"));
        assert_eq!(read(&od, index, sub).unwrap(), bytes, "{index:04X}:{sub}");
        assert_eq!(od.info(index, sub).unwrap().size, bytes.len());
        if let Some(size) = dt.size() {
            assert_eq!(size, bytes.len());
        }
    }
    assert_eq!(od.int16, -266);
    assert_eq!(od.int24.get(), -266);
    assert_eq!(od.int40.get(), -0x7A_FBFC_FDFF);
    assert_eq!(od.uint24.get(), 0x03_0201);
    assert_eq!(od.time_of_day, TimeOfDay::new(9913, 43_200_000).unwrap());
    assert_eq!(od.time_diff, TimeDifference::new(0x16D4, 0x02B3_2C95).unwrap()); // 5844 days, 45 296 789 ms
    assert_eq!(od.octets.as_bytes(), &[0, 0xFF, 0x10]);
    assert_eq!(od.firmware.as_bytes(), (0..40).collect::<Vec<u8>>());
    assert_eq!(od.visible.as_str(), "visible text");
    assert_eq!(od.unicode.units(), &[0x41, 0xE9]);
    assert_eq!(od.firmware.as_bytes().len(), 40);
    assert_eq!((od.kp, od.ki, od.mode), (0.5, 9.5, 3));
    assert_eq!(od.outputs, [-10, 0, 0, 10]);
    assert_eq!(od.real32, 2.0);
    // Reading at an offset (SDO segmented upload) and past the end.
    let mut b = [0u8; 4];
    assert_eq!(od.read(0x2020, 0, 8, &mut b), Ok(4));
    assert_eq!(&b, b"text");
    assert_eq!(od.read(0x2020, 0, 12, &mut b), Ok(0));
    assert_eq!(od.read(0x2025, 0, 38, &mut b), Ok(2));
}

#[test]
fn read_only_entries_and_counts() {
    let mut od = AllTypes::with_defaults();
    od.inputs = [1, 2, 3, 4, 5, 6, 7, 8];
    od.read_only = 0x1234;
    od.label.set(b"lbl").unwrap();
    // OD-04: sub 0 of ARRAY and RECORD = highest sub-index, UNSIGNED8 const.
    assert_eq!(read(&od, 0x6000, 0).unwrap(), [8]);
    assert_eq!(read(&od, 0x6200, 0).unwrap(), [4]);
    assert_eq!(read(&od, 0x2100, 0).unwrap(), [4]);
    let info = od.info(0x6000, 0).unwrap();
    assert_eq!((info.data_type, info.access), (DataType::Unsigned8, Access::Const));
    for i in 1..=8u8 {
        assert_eq!(read(&od, 0x6000, i).unwrap(), [i]);
    }
    assert_eq!(read(&od, 0x2031, 0).unwrap(), [0x34, 0x12]);
    assert_eq!(read(&od, 0x2032, 0).unwrap(), [7]);
    assert_eq!(read(&od, 0x2100, 4).unwrap(), b"lbl");
    assert_eq!(read(&od, 0x2021, 0).unwrap(), b"AB");
}

/// OD-16 (access errors give the fixed abort codes of Table 22): read of a wo entry 0601 0001h; write of
/// ro, const and sub 00h 0601 0002h; unknown index 0602 0000h; unknown sub-index 0609 0011h; length
/// 0607 0010h/0012h/0013h; value 0609 0030h/0031h/0032h, and a refused write changes nothing. OD-08 (the
/// access types): wo is writable but not readable, ro and const are readable but not writable (rw entries
/// round-trip in `every_writable_entry_round_trips`). DT-11: a VISIBLE_STRING refuses a non-visible
/// character (07h).
#[test]
fn abort_codes() {
    let mut od = AllTypes::with_defaults();
    // 0609 0031h / 0609 0032h: limits (ABORT-22/23).
    assert_eq!(od.write(0x2001, 0, &[101]), Err(AbortCode::ValueTooHigh));
    assert_eq!(od.write(0x2001, 0, &[(-101i8) as u8]), Err(AbortCode::ValueTooLow));
    assert_eq!(od.write(0x2011, 0, &9u16.to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(od.write(0x2018, 0, &3.0f32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(od.write(0x2018, 0, &f32::NAN.to_le_bytes()), Err(AbortCode::InvalidValue));
    assert_eq!(od.write(0x2100, 3, &[0]), Err(AbortCode::ValueTooLow));
    assert_eq!(od.write(0x6200, 2, &11i16.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    // 0609 0030h: invalid value (ABORT-21): BOOLEAN 2, non-visible char, and the application hook.
    assert_eq!(od.write(0x2000, 0, &[2]), Err(AbortCode::InvalidValue));
    assert_eq!(od.write(0x2020, 0, &[0x41, 0x07]), Err(AbortCode::InvalidValue));
    assert_eq!(od.write(0x2002, 0, &13i16.to_le_bytes()), Err(AbortCode::InvalidValue));
    assert_eq!(od.int16_writes, 0);
    // 0607 0012h / 0607 0013h / 0607 0010h: length (ABORT-17..19).
    assert_eq!(od.write(0x2011, 0, &[1, 2, 3]), Err(AbortCode::LengthTooHigh));
    assert_eq!(od.write(0x2011, 0, &[1]), Err(AbortCode::LengthTooLow));
    assert_eq!(od.write(0x2020, 0, &[b'a'; 17]), Err(AbortCode::LengthTooHigh));
    assert_eq!(od.write(0x2022, 0, &[1, 2, 3]), Err(AbortCode::LengthMismatch));
    assert_eq!(od.write(0x2025, 0, &[0; 65]), Err(AbortCode::LengthTooHigh));
    // 0601 0001h: read of a write-only entry (ABORT-09).
    assert_eq!(read(&od, 0x2030, 0), Err(AbortCode::ReadOfWriteOnly));
    od.write(0x2030, 0, &[1, 0, 0, 0]).unwrap();
    assert_eq!(od.write_only, 1);
    // 0601 0002h: write of ro / const / sub 0 (ABORT-10).
    assert_eq!(od.write(0x2031, 0, &[0, 0]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(od.write(0x2032, 0, &[0]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(od.write(0x6000, 1, &[0]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(od.write(0x6000, 0, &[8]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(od.write(0x2100, 4, b"x"), Err(AbortCode::WriteOfReadOnly));
    // 0602 0000h / 0609 0011h (ABORT-11, ABORT-20).
    assert_eq!(read(&od, 0x2009, 0), Err(AbortCode::ObjectDoesNotExist));
    assert_eq!(read(&od, 0x1FFF, 0), Err(AbortCode::ObjectDoesNotExist));
    assert_eq!(read(&od, 0xFFFF, 0), Err(AbortCode::ObjectDoesNotExist));
    assert_eq!(od.write(0x3000, 0, &[0]), Err(AbortCode::ObjectDoesNotExist));
    assert_eq!(read(&od, 0x2001, 1), Err(AbortCode::SubIndexDoesNotExist));
    assert_eq!(read(&od, 0x6000, 9), Err(AbortCode::SubIndexDoesNotExist));
    assert_eq!(read(&od, 0x2100, 5), Err(AbortCode::SubIndexDoesNotExist));
    assert_eq!(od.info(0x6200, 0xFF).err(), Some(AbortCode::SubIndexDoesNotExist));
    // A refused write changes nothing.
    let before = format!("{od:?}");
    for (index, sub, data) in [
        (0x2001u16, 0u8, &[101u8][..]),
        (0x2002, 0, &13i16.to_le_bytes()[..]),
        (0x2020, 0, &[0x41, 0x07][..]),
        (0x2011, 0, &[1][..]),
        (0x2025, 0, &[0; 65][..]),
        (0x2031, 0, &[0, 0][..]),
    ] {
        assert!(od.write(index, sub, data).is_err());
    }
    assert_eq!(format!("{od:?}"), before);
    // The on_write hook sees every accepted write.
    od.write(0x2002, 0, &14i16.to_le_bytes()).unwrap();
    assert_eq!(od.int16_writes, 1);
}

#[test]
fn streamed_writes() {
    let mut od = AllTypes::default();
    // DOMAIN streamed in chunks (a firmware image without a buffer of its size).
    od.begin_write(0x2025, 0, Some(10)).unwrap();
    od.write_chunk(0x2025, 0, 0, &[1; 7]).unwrap();
    od.write_chunk(0x2025, 0, 7, &[2; 3]).unwrap();
    od.end_write(0x2025, 0, 10).unwrap();
    assert_eq!(od.firmware.as_bytes(), &[1, 1, 1, 1, 1, 1, 1, 2, 2, 2]);
    assert_eq!(od.begin_write(0x2025, 0, Some(100)), Err(AbortCode::LengthTooHigh));
    od.begin_write(0x2025, 0, None).unwrap();
    od.write_chunk(0x2025, 0, 0, &[9; 4]).unwrap();
    od.abort_write(0x2025, 0);
    assert_eq!(od.firmware.as_bytes().len(), 10);
    // Strings stream too.
    od.begin_write(0x2020, 0, Some(11)).unwrap();
    od.write_chunk(0x2020, 0, 0, b"hello ").unwrap();
    od.write_chunk(0x2020, 0, 6, b"world").unwrap();
    od.end_write(0x2020, 0, 11).unwrap();
    assert_eq!(od.visible.as_str(), "hello world");
    assert_eq!(od.begin_write(0x2020, 0, Some(17)), Err(AbortCode::LengthTooHigh));
    // Fixed-size values are written whole; read-only entries refuse before any data.
    assert_eq!(od.begin_write(0x2013, 0, Some(4)), Err(AbortCode::UnsupportedAccess));
    assert_eq!(od.begin_write(0x2031, 0, Some(2)), Err(AbortCode::WriteOfReadOnly));
}

#[test]
fn pdo_handles() {
    let mut od = AllTypes::with_defaults();
    let h = od.pdo_resolve(0x6000, 3, PdoDir::Tpdo).unwrap();
    assert_eq!(h.size, 1);
    od.inputs[2] = 0x55;
    let mut b = [0u8; 8];
    assert_eq!(od.pdo_read(&h, &mut b), Ok(1));
    assert_eq!(b[0], 0x55);
    assert_eq!(od.pdo_resolve(0x6000, 3, PdoDir::Rpdo), Err(AbortCode::NotMappable));
    // A read-only entry has no write path at all, not even through a (TPDO) handle (OD-08).
    assert_eq!(od.pdo_write(&h, &[0xAA]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(od.inputs[2], 0x55);
    assert_eq!(od.pdo_resolve(0x2020, 0, PdoDir::Tpdo), Err(AbortCode::NotMappable));
    assert_eq!(od.pdo_resolve(0x2005, 0, PdoDir::Tpdo), Err(AbortCode::NotMappable));
    assert_eq!(od.pdo_resolve(0x2030, 0, PdoDir::Tpdo), Err(AbortCode::NotMappable)); // wo
    assert_eq!(od.pdo_resolve(0x2040, 0, PdoDir::Tpdo), Err(AbortCode::ObjectDoesNotExist));
    let r = od.pdo_resolve(0x2002, 0, PdoDir::Rpdo).unwrap();
    od.pdo_write(&r, &500i16.to_le_bytes()).unwrap();
    assert_eq!(od.int16, 500);
    assert_eq!(od.pdo_write(&r, &2000i16.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(od.int16, 500);
    let t = od.pdo_resolve(0x2023, 0, PdoDir::Tpdo).unwrap();
    assert_eq!(t.size, 6);
    let u = od.pdo_resolve(0x2017, 0, PdoDir::Tpdo).unwrap();
    assert_eq!(od.pdo_read(&u, &mut b), Ok(8));
    assert_eq!(b, [0xFF; 8]);
    // The slot is the derive's own: a handle without one (a dictionary that uses the provided
    // `pdo_resolve`) is looked up by index and sub-index instead.
    let by_index = PdoHandle { slot: PdoHandle::NO_SLOT, ..h };
    assert_eq!(od.pdo_read(&by_index, &mut b), Ok(1));
    assert_eq!(b[0], 0x55);
    let by_index = PdoHandle { slot: PdoHandle::NO_SLOT, ..r };
    od.pdo_write(&by_index, &(-7i16).to_le_bytes()).unwrap();
    assert_eq!(od.int16, -7);
}

/// SDO-26: an upload's segments read the entry at the position looked up once (`slot`), as `read` would.
#[test]
fn segments_read_through_a_slot() {
    let od = AllTypes::with_defaults();
    let slot = od.slot(0x2020, 0);
    assert_ne!(slot, PdoHandle::NO_SLOT);
    let (mut a, mut b) = ([0u8; 4], [0u8; 4]);
    assert_eq!(od.read_slot(0x2020, 0, slot, 1, &mut a), Ok(()));
    assert_eq!(od.read(0x2020, 0, 1, &mut b), Ok(4));
    assert_eq!((&a, &b), (b"ello", b"ello"));
    // It fills the buffer or fails: fewer bytes than asked for are 0607 0010h (the size announced was wrong).
    let mut a = [0u8; 7];
    assert_eq!(od.read_slot(0x2020, 0, slot, 1, &mut a), Err(AbortCode::LengthMismatch));
    // No such entry: no slot, and the read by index answers as `read` does.
    assert_eq!(od.slot(0x2020, 1), PdoHandle::NO_SLOT);
    assert_eq!(od.read_slot(0x2020, 1, PdoHandle::NO_SLOT, 0, &mut a), Err(AbortCode::SubIndexDoesNotExist));
    // The access is checked at the slot too (0601 0001h for a write-only entry).
    let wo = od.slot(0x2030, 0);
    assert_eq!(od.read_slot(0x2030, 0, wo, 0, &mut a), Err(AbortCode::ReadOfWriteOnly));
}

#[test]
fn table_is_const_and_sorted() {
    assert!(canopen_core::od::is_sorted(AllTypes::OD_ENTRIES));
    assert_eq!(AllTypes::OD_OBJECTS.len(), 31);
    let e = AllTypes::OD_ENTRIES.iter().find(|e| e.index == 0x2002).unwrap();
    assert_eq!((e.low, e.high, e.default), (Some(Value::Int(-1000)), Some(Value::Int(1000)), Some(Value::Int(0))));
    assert_eq!(e.pdo, PdoMapping::Rpdo);
    assert_eq!(e.access, Access::Rww);
    let rec = AllTypes::OD_OBJECTS.iter().find(|o| o.index == 0x2100).unwrap();
    assert_eq!((rec.code, rec.name, rec.subs), (ObjectCode::Record, "PID controller", 5));
    let arr = AllTypes::OD_OBJECTS.iter().find(|o| o.index == 0x6000).unwrap();
    assert_eq!((arr.code, arr.subs), (ObjectCode::Array, 9));
    assert_eq!(AllTypes::OD_MAX_VALUE_SIZE, 16);
    const ENTRIES: usize = AllTypes::OD_ENTRIES.len();
    assert_eq!(ENTRIES, 28 + 5 + 9 + 5);
}

#[test]
fn merged_with_the_comm_profile() {
    let mut od = node_od();
    assert_eq!(read(&od, 0x1000, 0).unwrap(), [0x91, 0x01, 0x01, 0x00]);
    assert_eq!(read(&od, 0x1018, 2).unwrap(), [0x34, 0x12, 0, 0]);
    assert_eq!(read(&od, 0x1008, 0).unwrap(), b"canopener all types");
    assert_eq!(read(&od, 0x2010, 0).unwrap(), [200]);
    od.write(0x1017, 0, &[0x64, 0]).unwrap();
    assert_eq!(od.comm.params.heartbeat_time_ms, 100);
    od.write(0x1016, 1, &[0x64, 0, 2, 0]).unwrap();
    assert_eq!(od.write(0x1016, 2, &[0xC8, 0, 2, 0]), Err(AbortCode::ParameterIncompatibility));
    assert_eq!(od.write(0x1001, 0, &[1]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(read(&od, 0x1005, 0).unwrap(), [0x80, 0, 0, 0]); // 1005h default 0000 0080h
    assert_eq!(read(&od, 0x1004, 0), Err(AbortCode::ObjectDoesNotExist));
    od.write(0x2002, 0, &[5, 0]).unwrap();
    assert_eq!(od.app.int16, 5);
    let h = od.pdo_resolve(0x1001, 0, PdoDir::Tpdo).unwrap();
    od.comm.params.error_register = 0x11;
    let mut b = [0u8; 1];
    assert_eq!(od.pdo_read(&h, &mut b), Ok(1));
    assert_eq!(b, [0x11]);
    assert_eq!(od.object_count(), 22 + 16 + 31 + od.comm.optional.object_count()); // + 1002h/1013h/1020h/1028h/1FA0h/1FD0h
    let indices: Vec<u16> = (0..od.object_count()).map(|n| od.object(n).unwrap().index).collect();
    assert!(indices.windows(2).all(|w| w[0] < w[1]));
    // Through references too.
    let mut view = canopen_core::od::Merged { comm: &mut od.comm, app: &mut od.app };
    view.write(0x2010, 0, &[1]).unwrap();
    assert_eq!(od.app.uint8, 1);
}

/// `object_index` (what store/restore walks) is `object(n)`'s index for every `n`, in the derived
/// dictionary, the communication profile and the two merged.
#[test]
fn object_index_agrees_with_object() {
    fn agree(od: &impl OdDescribe) {
        for n in 0..=od.object_count() {
            assert_eq!(od.object_index(n), od.object(n).map(|o| o.index), "object {n}");
        }
    }
    let od = node_od();
    agree(&od.app);
    agree(&od.comm);
    agree(&od);
}

/// STORE-02: a save (1010h sub 01h) holds every storable entry and nothing else: the readable and
/// writable, non-DOMAIN entries of the EDS description (`object`/`entry`), except 1010h/1011h and the
/// error history, each with its current value, in increasing (index, sub) order (1028h entries only when
/// not at their default). The walk reads only the
/// indices and `info`; this checks it against the full description.
#[test]
fn a_save_holds_every_storable_entry_of_the_description() {
    use canopen_core::storage::{save, Groups, RamStorage, HEADER_LEN};
    let od = node_od();
    let mut expected = Vec::new();
    for o in (0..od.object_count()).filter_map(|n| od.object(n)) {
        if matches!(o.index, 0x1003 | 0x1010 | 0x1011 | 0x1013) {
            continue; // the history, the commands and a clock are never stored
        }
        for sub in 0..=255u8 {
            let Some(e) = od.entry(o.index, sub) else { continue };
            if e.access.writable() && e.access.readable() && e.data_type != DataType::Domain {
                let Ok(v) = read(&od, o.index, sub) else { continue };
                let le = v.iter().rev().fold(0u64, |n, &b| n << 8 | u64::from(b));
                if o.index == 0x1028 && e.default == Some(Value::Uint(le)) {
                    continue; // 1028h entries at their default are left out (a load sets them anyway)
                }
                expected.push((o.index, sub, v));
            }
        }
    }
    let mut ram = RamStorage::<8192>::new();
    save(&mut ram, Groups::ALL, &od.comm, &od.app).unwrap();
    let slot = ram.slot(0);
    let len = u32::from_le_bytes(slot[12..16].try_into().unwrap()) as usize;
    let (mut items, mut at) = (Vec::new(), HEADER_LEN);
    while at < HEADER_LEN + len {
        let (index, sub, n) = (u16::from_le_bytes([slot[at], slot[at + 1]]), slot[at + 2], usize::from(slot[at + 3]));
        items.push((index, sub, slot[at + 4..at + 4 + n].to_vec()));
        at += 4 + n;
    }
    assert!(expected.iter().any(|e| e.0 == 0x1017) && expected.iter().any(|e| e.0 >= 0x2000));
    assert_eq!(items, expected);
}

/// NMT-04: Reset Application gives every entry its `default =` value (or its type's default), leaving
/// DOMAINs alone; the result equals the struct built with the documented defaults.
#[test]
fn restore_defaults_gives_the_declared_defaults() {
    let fresh = AllTypes::with_defaults();
    let mut od = AllTypes::with_defaults();
    for (index, sub, bytes, _) in samples() {
        od.write(index, sub, &bytes).unwrap();
    }
    let domain_before = read(&od, 0x2025, 0).unwrap();
    od.restore_defaults();
    for e in AllTypes::OD_ENTRIES {
        if e.data_type == DataType::Domain {
            continue;
        }
        assert_eq!(read(&od, e.index, e.sub), read(&fresh, e.index, e.sub), "{:04X}h:{}", e.index, e.sub);
    }
    assert_eq!(read(&od, 0x2025, 0).unwrap(), domain_before);
    // Spot checks against the attributes themselves.
    assert_eq!(read(&od, 0x2001, 0).unwrap(), vec![0xFF]); // default = -1
    assert_eq!(read(&od, 0x2018, 0).unwrap(), 1.25f32.to_le_bytes().to_vec());
    assert_eq!(read(&od, 0x2020, 0).unwrap(), b"hello".to_vec());
    assert_eq!(read(&od, 0x2022, 0).unwrap(), vec![b'h', 0, b'i', 0]);
    assert_eq!(read(&od, 0x2006, 0).unwrap(), vec![0; 6]); // no default: the type's default
}

/// The EDS text of the whole node dictionary.
fn eds() -> String {
    let mut s = String::new();
    write_eds(&mut s, &EdsInfo::DEFAULT, &node_od()).unwrap();
    s
}

/// The `[name]` section of an EDS, up to the blank line.
fn section<'a>(eds: &'a str, name: &str) -> &'a str {
    let start = eds.find(&format!("\n[{name}]\n")).unwrap_or_else(|| panic!("[{name}] missing")) + 1;
    let rest = &eds[start..];
    &rest[..rest.find("\n\n").unwrap_or(rest.len())]
}

/// DT-17 (the basic data types have the fixed indices of Table 44): the entry of each type is described in
/// the EDS with exactly that index, and the dictionary reports the same type.
#[test]
fn data_type_indices_dt_17() {
    let table: [(u16, u16); 25] = [
        (0x2000, 0x0001), // BOOLEAN
        (0x2001, 0x0002), // INTEGER8
        (0x2002, 0x0003), // INTEGER16
        (0x2003, 0x0010), // INTEGER24
        (0x2004, 0x0004), // INTEGER32
        (0x2005, 0x0012), // INTEGER40
        (0x2006, 0x0013), // INTEGER48
        (0x2007, 0x0014), // INTEGER56
        (0x2008, 0x0015), // INTEGER64
        (0x2010, 0x0005), // UNSIGNED8
        (0x2011, 0x0006), // UNSIGNED16
        (0x2012, 0x0016), // UNSIGNED24
        (0x2013, 0x0007), // UNSIGNED32
        (0x2014, 0x0018), // UNSIGNED40
        (0x2015, 0x0019), // UNSIGNED48
        (0x2016, 0x001A), // UNSIGNED56
        (0x2017, 0x001B), // UNSIGNED64
        (0x2018, 0x0008), // REAL32
        (0x2019, 0x0011), // REAL64
        (0x2020, 0x0009), // VISIBLE_STRING
        (0x2021, 0x000A), // OCTET_STRING
        (0x2022, 0x000B), // UNICODE_STRING
        (0x2023, 0x000C), // TIME_OF_DAY
        (0x2024, 0x000D), // TIME_DIFFERENCE
        (0x2025, 0x000F), // DOMAIN
    ];
    let eds = eds();
    let od = node_od();
    for (index, code) in table {
        let s = section(&eds, &format!("{index:04X}"));
        assert!(s.contains(&format!("\nDataType=0x{code:04X}\n")), "{index:04X}: {s}");
        assert_eq!(od.info(index, 0).unwrap().data_type as u16, code, "{index:04X}");
    }
}

/// OD-06 (object codes VAR 07h, ARRAY 08h, RECORD 09h; this dictionary defines no NULL, DEFTYPE or
/// DEFSTRUCT objects, DT-19) and OD-11 (each object carries name, object code and, per entry, data type,
/// access, PDO mapping, value range and default; the category is the EDS object list, OD-10): VARs
/// (1017h, 2001h), ARRAYs (1016h, 6000h) and RECORDs (1018h, 2100h) are described with those codes, both by
/// the dictionary and in the EDS, and one VAR and one record member are described completely.
#[test]
fn object_codes_and_descriptions_od_06_od_11() {
    let eds = eds();
    let od = node_od();
    for (index, code, value) in [
        (0x1017u16, ObjectCode::Var, 7u8),
        (0x2001, ObjectCode::Var, 7),
        (0x1016, ObjectCode::Array, 8),
        (0x6000, ObjectCode::Array, 8),
        (0x1018, ObjectCode::Record, 9),
        (0x2100, ObjectCode::Record, 9),
    ] {
        let o = (0..od.object_count()).filter_map(|n| od.object(n)).find(|o| o.index == index).unwrap();
        assert_eq!((o.code, o.code as u8), (code, value), "{index:04X}");
        let s = section(&eds, &format!("{index:04X}"));
        assert!(s.contains(&format!("\nObjectType=0x{value:X}\n")), "{index:04X}: {s}");
    }
    assert_eq!(
        section(&eds, "2001"),
        "[2001]\nParameterName=Integer8\nObjectType=0x7\nDataType=0x0002\nAccessType=rw\nDefaultValue=-1\n\
         PDOMapping=1\nLowLimit=-100\nHighLimit=100"
    );
    let mode = section(&eds, "2100sub3");
    for line in [
        "ObjectType=0x7",
        "DataType=0x0005",
        "AccessType=rw",
        "DefaultValue=",
        "PDOMapping=0",
        "LowLimit=",
        "HighLimit=",
    ] {
        assert!(mode.contains(line), "{line}: {mode}");
    }
    assert!(mode.starts_with("[2100sub3]\nParameterName=Mode"), "{mode}");
}

/// OD-02 (the index space is split into fixed areas): the node dictionary has no object in 0000h–0FFFh
/// (data types; 0000h unused), its communication objects are in 1000h–1FFFh, the application's in
/// 2000h–5FFFh (the EDS's ManufacturerObjects) and 6000h–9FFFh (standardized profile), and nothing at or
/// above A000h; reads anywhere else (0000h, 0260h reserved, A000h, C000h reserved, FFFFh) are 0602 0000h.
#[test]
fn index_areas_od_02() {
    let od = node_od();
    for n in 0..od.object_count() {
        let o = od.object(n).unwrap();
        let area_ok = (0x1000..=0x9FFF).contains(&o.index);
        assert!(area_ok, "{:04X}", o.index);
    }
    let eds = eds();
    let listed = |name: &str| -> Vec<u16> {
        section(&eds, name)
            .lines()
            .filter_map(|l| l.split_once("=0x").filter(|(k, _)| k.parse::<u16>().is_ok()))
            .map(|(_, v)| u16::from_str_radix(v, 16).unwrap())
            .collect()
    };
    let manufacturer = listed("ManufacturerObjects");
    assert!(!manufacturer.is_empty() && manufacturer.iter().all(|i| (0x2000..=0x5FFF).contains(i)));
    for i in listed("MandatoryObjects").into_iter().chain(listed("OptionalObjects")) {
        assert!((0x1000..=0x1FFF).contains(&i) || (0x6000..=0x9FFF).contains(&i), "{i:04X}");
    }
    for index in [0x0000u16, 0x0260, 0x0FFF, 0xA000, 0xC000, 0xFFFF] {
        assert_eq!(read(&od, index, 0), Err(AbortCode::ObjectDoesNotExist), "{index:04X}");
    }
}
