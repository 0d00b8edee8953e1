//! The three ways the derive serves one struct (match arms, `#[od(compact)]` tables, `#[od(compact,
//! zerocopy)]` tables reached by offset, issue 41) give the same answer to any sequence of accesses: the
//! same values, the same abort codes (OD-08/OD-09 access, OD-11 limits, OD-16 unknown index or sub-index,
//! the length codes), the same hooks run, and the same PDO handles apart from their slot. A proptest drives
//! random accesses, with random indices, sub-indices, offsets and lengths, through all three and compares;
//! PDO handles forged with any slot are also fed to the table layouts, which must answer without a panic.

use canopen_core::od::{AbortCode, ObjectDictionary, PdoDir, PdoHandle};
use canopen_od_derive::ObjectDictionary;
use proptest::prelude::*;

// The dictionaries compared (shared with the fuzz target `od_layouts`).
include!("layouts/dictionaries.rs");

/// One access, with what it is given.
#[derive(Debug, Clone)]
enum Op {
    Info(u16, u8),
    Read(u16, u8, usize, usize),
    Write(u16, u8, Vec<u8>),
    ReadExpedited(u16, u8),
    WriteExpedited(u16, u8, [u8; 4], Option<usize>),
    /// Resolve, then read through the handle.
    PdoRead(u16, u8),
    /// Resolve, then write through the handle.
    PdoWrite(u16, u8, Vec<u8>),
    /// A handle with any slot: only the table layouts, answered without a panic.
    Forged(u16, u8, u16, u8, Vec<u8>),
    Restore,
}

/// An index near the dictionary's (and a few anywhere), a sub-index of 0..=6.
fn index() -> impl Strategy<Value = u16> {
    prop_oneof![4 => 0x1FFFu16..=0x2009, 1 => any::<u16>()]
}

/// Values at and beside the limits and the hook's refusal ([`edges`]), or random bytes.
fn data() -> impl Strategy<Value = Vec<u8>> + Clone {
    let edges = edges();
    prop_oneof![
        2 => proptest::collection::vec(any::<u8>(), 0..10),
        1 => proptest::sample::select(edges),
    ]
}

fn op() -> impl Strategy<Value = Op> {
    let sub = 0u8..=6;
    let data = data();
    prop_oneof![
        (index(), sub.clone()).prop_map(|(i, s)| Op::Info(i, s)),
        (index(), sub.clone(), 0usize..10, 0usize..10).prop_map(|(i, s, o, n)| Op::Read(i, s, o, n)),
        (index(), sub.clone(), data.clone()).prop_map(|(i, s, d)| Op::Write(i, s, d)),
        (index(), sub.clone()).prop_map(|(i, s)| Op::ReadExpedited(i, s)),
        (index(), sub.clone(), data.clone(), proptest::option::of(0usize..=4)).prop_map(|(i, s, d, n)| {
            let mut four = [0u8; 4];
            for (b, v) in four.iter_mut().zip(&d) {
                *b = *v;
            }
            Op::WriteExpedited(i, s, four, n)
        }),
        (index(), sub.clone()).prop_map(|(i, s)| Op::PdoRead(i, s)),
        (index(), sub.clone(), data.clone()).prop_map(|(i, s, d)| Op::PdoWrite(i, s, d)),
        (index(), sub, any::<u16>(), 0u8..=9, data).prop_map(|(i, s, slot, n, d)| Op::Forged(i, s, slot, n, d)),
        Just(Op::Restore),
    ]
}

/// Bytes read: how many, and the buffer.
type Bytes = Result<(usize, Vec<u8>), AbortCode>;

/// What an access answered, with the handle's slot left out (it is each layout's own).
#[derive(Debug, PartialEq)]
enum Answer {
    Info(Result<canopen_core::od::SubInfo, AbortCode>),
    Read(Bytes),
    Unit(Result<(), AbortCode>),
    Expedited(Result<(usize, usize, [u8; 4]), AbortCode>),
    Pdo(Result<(u8, Bytes), AbortCode>),
    PdoWrite(Result<(u8, Result<(), AbortCode>), AbortCode>),
    None,
}

fn apply<D: ObjectDictionary>(d: &mut D, op: &Op, forged: bool) -> Answer {
    match op {
        Op::Info(i, s) => Answer::Info(d.info(*i, *s)),
        Op::Read(i, s, offset, n) => {
            let mut buf = vec![0u8; *n];
            Answer::Read(d.read(*i, *s, *offset, &mut buf).map(|k| (k, buf)))
        }
        Op::Write(i, s, data) => Answer::Unit(d.write(*i, *s, data)),
        Op::ReadExpedited(i, s) => {
            let mut buf = [0u8; 4];
            Answer::Expedited(d.read_expedited(*i, *s, &mut buf).map(|(a, b)| (a, b, buf)))
        }
        Op::WriteExpedited(i, s, data, n) => Answer::Unit(d.write_expedited(*i, *s, data, *n)),
        Op::PdoRead(i, s) => Answer::Pdo(d.pdo_resolve(*i, *s, PdoDir::Tpdo).map(|h| {
            let mut buf = [0u8; 8];
            (h.size, d.pdo_read(&h, &mut buf).map(|n| (n, buf.to_vec())))
        })),
        Op::PdoWrite(i, s, data) => {
            Answer::PdoWrite(d.pdo_resolve(*i, *s, PdoDir::Rpdo).map(|h| (h.size, d.pdo_write(&h, data))))
        }
        Op::Forged(index, sub, slot, size, data) => {
            if forged {
                let h = PdoHandle { index: *index, sub: *sub, size: *size, slot: *slot };
                let mut buf = [0u8; 8];
                let _ = d.pdo_read(&h, &mut buf);
                let _ = d.pdo_read(&h, &mut buf[..usize::from(*size).min(8)]);
                let _ = d.pdo_write(&h, data);
            }
            Answer::None
        }
        Op::Restore => {
            d.restore_defaults();
            Answer::None
        }
    }
}

/// Every readable value of the dictionary, as SDO reads it (what the three must hold alike).
fn state<D: ObjectDictionary>(d: &D) -> Vec<Result<Vec<u8>, AbortCode>> {
    let mut out = Vec::new();
    for index in 0x2000..=0x2008u16 {
        for sub in 0..=6u8 {
            let mut buf = [0u8; 8];
            out.push(d.read(index, sub, 0, &mut buf).map(|n| buf[..n].to_vec()));
        }
    }
    out
}

fn fresh<D: ObjectDictionary + Default>() -> D {
    let mut d = D::default();
    d.restore_defaults();
    d
}

/// Applies `ops` to the three layouts of one struct and requires the same answers, values and hook runs.
fn agree<C, P, O>(ops: &[Op]) -> Result<(), TestCaseError>
where
    C: ObjectDictionary + Default + Writes,
    P: ObjectDictionary + Default + Writes,
    O: ObjectDictionary + Default + Writes,
{
    let (mut code, mut compact, mut offsets) = (fresh::<C>(), fresh::<P>(), fresh::<O>());
    for op in ops {
        let a = apply(&mut code, op, false);
        // Forged handles: the table layouts (a match-arm dictionary's slot is its own arm number).
        let b = apply(&mut compact, op, true);
        let c = apply(&mut offsets, op, true);
        if !matches!(op, Op::Forged(..)) {
            prop_assert_eq!(&a, &b, "compact differs on {:?}", op);
            prop_assert_eq!(&a, &c, "zerocopy differs on {:?}", op);
            prop_assert_eq!(state(&code), state(&compact), "compact's values after {:?}", op);
            prop_assert_eq!(state(&code), state(&offsets), "zerocopy's values after {:?}", op);
            prop_assert_eq!(
                (code.writes(), compact.writes()),
                (offsets.writes(), offsets.writes()),
                "hooks after {:?}",
                op
            );
        } else {
            // What a forged handle wrote is not compared; start the table layouts over from the code one.
            compact = fresh::<P>();
            offsets = fresh::<O>();
            code = fresh::<C>();
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// The same answers and the same values after every access, in all three layouts.
    #[test]
    fn the_three_layouts_answer_alike(ops in proptest::collection::vec(op(), 1..40)) {
        agree::<Code, Compact, Offsets>(&ops)?;
    }

    /// The same with a key per object (OD-01, OD-04, OD-16): RECORD members, their counts and the gaps
    /// between their sub-indices are found through `FIRST_ROWS`.
    #[test]
    fn the_three_layouts_answer_alike_with_a_key_per_object(ops in proptest::collection::vec(op(), 1..40)) {
        agree::<CodeRecords, CompactRecords, OffsetRecords>(&ops)?;
    }

    /// The same for regularly numbered dictionaries, whose tables hold no sub-index (OD-03, OD-04, OD-16):
    /// with a key per row and with a key per object.
    #[test]
    fn the_three_layouts_answer_alike_without_stored_sub_indices(ops in proptest::collection::vec(op(), 1..40)) {
        agree::<CodeRegular, CompactRegular, OffsetRegular>(&ops)?;
        agree::<CodeRegularRecords, CompactRegularRecords, OffsetRegularRecords>(&ops)?;
    }
}

/// Only an irregular numbering stores sub-indices (OD-03, OD-04): the dictionaries above with gaps (and a RECORD whose
/// members are not in order) have one per row; the regular ones none, a key per row or per object alike.
#[test]
fn sub_indices_are_stored_only_when_irregular() {
    use canopen_core::od::data::OdData;
    assert_eq!(<OffsetRecords as OdData>::SUBS, &[0, 1, 2, 5, 1, 1, 2, 3, 1, 2, 4, 6]);
    assert_eq!(<Compact as OdData>::SUBS.len(), <Compact as OdData>::ROWS.len());
    assert!(<CompactRegular as OdData>::SUBS.is_empty() && <CompactRegular as OdData>::FIRST_ROWS.is_empty());
    assert!(<OffsetRegular as OdData>::SUBS.is_empty());
    assert!(<CompactRegularRecords as OdData>::SUBS.is_empty());
    assert!(
        !<OffsetRegularRecords as OdData>::FIRST_ROWS.is_empty() && <OffsetRegularRecords as OdData>::SUBS.is_empty()
    );
    // The ARRAY of one element is an ARRAY (sub 01h, a count at 00h), the VAR before it a VAR.
    let mut d = fresh::<OffsetRegularRecords>();
    let mut buf = [0u8; 4];
    assert_eq!((d.read(0x2001, 0, 0, &mut buf), buf[0]), (Ok(1), 1));
    assert_eq!((d.read(0x2001, 1, 0, &mut buf), buf), (Ok(4), 3u32.to_le_bytes()));
    assert_eq!(d.read(0x2001, 2, 0, &mut buf), Err(AbortCode::SubIndexDoesNotExist));
    assert_eq!(d.read(0x2000, 1, 0, &mut buf), Err(AbortCode::SubIndexDoesNotExist));
    // Members by their place: the fourth of 2006h, the count, one past the last.
    assert_eq!((d.read(0x2006, 4, 0, &mut buf), buf), (Ok(4), 9u32.to_le_bytes()));
    assert_eq!((d.read(0x2006, 6, 0, &mut buf), buf), (Ok(4), 12u32.to_le_bytes()));
    assert_eq!((d.read(0x2006, 0, 0, &mut buf), buf[0]), (Ok(1), 7));
    assert_eq!(d.read(0x2006, 8, 0, &mut buf), Err(AbortCode::SubIndexDoesNotExist));
    assert_eq!(d.read(0x2006, 2, 0, &mut buf), Err(AbortCode::ReadOfWriteOnly));
    // A member's PDO handle reaches it by position: the hook and the limit apply (OD-11).
    let h = d.pdo_resolve(0x2002, 1, PdoDir::Rpdo).unwrap();
    assert_eq!(d.pdo_write(&h, &11i32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(d.pdo_write(&h, &(-7i32).to_le_bytes()), Ok(()));
    assert_eq!((d.axis_a, d.writes), (-7, 1));
    // Limits belong to shapes: 2002h sub 1 and 2004h sub 1 (same type, access, mapping and limits) share
    // one, 2004h sub 2 (other limits) has its own; the limited shapes come first.
    let shape = |pos: usize| <OffsetRegularRecords as OdData>::ROWS[pos].shape;
    assert_eq!((shape(2), shape(5), shape(6)), (0, 0, 1));
    // 2006h sub 7 has 2004h sub 2's limits but another access and no PDO mapping: a shape of its own, whose
    // limit values are the ones already stored.
    assert_eq!((shape(6), shape(14)), (1, 2));
    assert_eq!(<OffsetRegularRecords as OdData>::LIMITS, &[0, 8, 8]);
    assert_eq!(<OffsetRegularRecords as OdData>::LIMIT_VALUES.len(), 16);
    assert_eq!(d.write(0x2006, 7, &4i32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(d.write(0x2006, 7, &(-4i32).to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(d.write(0x2006, 7, &(-3i32).to_le_bytes()), Ok(()));
    assert_eq!(d.write(0x2004, 2, &4i32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(d.write(0x2004, 1, &4i32.to_le_bytes()), Ok(()));
    assert_eq!(d.write(0x2004, 1, &11i32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(d.write(0x2004, 2, &(-4i32).to_le_bytes()), Err(AbortCode::ValueTooLow));
    let h = d.pdo_resolve(0x2006, 4, PdoDir::Tpdo).unwrap();
    let mut out = [0u8; 8];
    assert_eq!((d.pdo_read(&h, &mut out), &out[..4]), (Ok(4), &9u32.to_le_bytes()[..]));
}

/// The record dictionary has a key per object and where each one's rows start (the RECORD at 2002h has
/// three rows, 2004h three, 2006h four); the one above, whose only RECORD has two members, a key per row.
#[test]
fn many_record_members_get_a_key_per_object() {
    use canopen_core::od::data::OdData;
    let keys = [0x2000, 0x2002, 0x2003, 0x2004, 0x2006];
    // Where each starts (rows 0, 1, 4, 5, 8, and 12 rows), less one row per object before it.
    let first_rows = [0, 0, 2, 2, 4, 7];
    assert_eq!(
        (<CompactRecords as OdData>::KEYS, <CompactRecords as OdData>::FIRST_ROWS),
        (&keys[..], &first_rows[..])
    );
    assert_eq!((<OffsetRecords as OdData>::KEYS, <OffsetRecords as OdData>::FIRST_ROWS), (&keys[..], &first_rows[..]));
    assert_eq!(<Compact as OdData>::KEYS.len(), <Compact as OdData>::ROWS.len());
    // Rows alike share a shape: the three UNSIGNED16 members of 2006h are one; 12 rows, 10 shapes.
    assert_eq!((<OffsetRecords as OdData>::ROWS.len(), <OffsetRecords as OdData>::SHAPES.len()), (12, 10));
    let pair = &<OffsetRecords as OdData>::ROWS[9..12];
    assert!(pair.iter().all(|r| r.shape == pair[0].shape) && <OffsetRecords as OdData>::SUBS[9..12] == [2, 4, 6]);
    assert!(<Offsets as OdData>::FIRST_ROWS.is_empty());
    // Each kind of answer through FIRST_ROWS: a member past the first, a gap, the count, the object after.
    let mut d = fresh::<OffsetRecords>();
    let mut buf = [0u8; 4];
    assert_eq!(d.read(0x2006, 4, 0, &mut buf), Ok(2));
    assert_eq!(buf[..2], 6u16.to_le_bytes());
    assert_eq!(d.read(0x2006, 3, 0, &mut buf), Err(AbortCode::SubIndexDoesNotExist));
    assert_eq!(d.read(0x2006, 7, 0, &mut buf), Err(AbortCode::SubIndexDoesNotExist));
    assert_eq!(d.read(0x2006, 0, 0, &mut buf), Ok(1));
    assert_eq!(buf[0], 6);
    assert_eq!(d.read(0x2002, 5, 0, &mut buf), Err(AbortCode::ReadOfWriteOnly));
    assert_eq!(d.write(0x2004, 1, &11i32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(d.write(0x2004, 1, &(-10i32).to_le_bytes()), Ok(()));
    assert_eq!(d.writes, 1);
    assert_eq!(d.read(0x2004, 2, 0, &mut buf), Ok(4));
    assert_eq!(buf, (-3i32).to_le_bytes());
    assert_eq!(d.read(0x2005, 0, 0, &mut buf), Err(AbortCode::ObjectDoesNotExist));
    assert_eq!(d.read(0x2007, 0, 0, &mut buf), Err(AbortCode::ObjectDoesNotExist));
}

/// The accesses above reach every kind of answer: a value, each limit, a hook's refusal, the access and
/// existence codes, so that the proptest compares more than errors.
#[test]
fn the_dictionary_answers_each_kind() {
    let mut d = fresh::<Offsets>();
    let mut buf = [0u8; 8];
    assert_eq!(d.read(0x2008, 0, 0, &mut buf), Ok(8));
    assert_eq!(d.write(0x2008, 0, &(-5_000_000_001i64).to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(d.write(0x2006, 0, &3.0f32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(d.write(0x2001, 0, &13i16.to_le_bytes()), Err(AbortCode::InvalidValue));
    assert_eq!(d.write(0x2001, 0, &12i16.to_le_bytes()), Ok(()));
    assert_eq!(d.writes, 1);
    assert_eq!(d.read(0x2002, 0, 0, &mut buf), Err(AbortCode::ReadOfWriteOnly));
    assert_eq!(d.write(0x2003, 0, &[1]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(d.read(0x2005, 2, 0, &mut buf), Err(AbortCode::SubIndexDoesNotExist));
    assert_eq!(d.read(0x2005, 0, 0, &mut buf), Ok(1));
    assert_eq!(buf[0], 3);
    assert_eq!(d.read(0x2009, 0, 0, &mut buf), Err(AbortCode::ObjectDoesNotExist));
    assert_eq!(d.write(0x2000, 0, &[1, 2]), Err(AbortCode::LengthTooLow));
}

/// Defaults at the ends of every width (NMT-04): the table layouts keep them compressed (LEB128, zigzag for
/// the signed types), and restore the same values as the match arms.
macro_rules! extremes {
    ($name:ident $(, $attr:meta)*) => {
        #[derive(ObjectDictionary, Default, Debug, PartialEq)]
        $(#[$attr])*
        struct $name {
            #[od(index = 0x2000, default = -9223372036854775808)]
            i64_min: i64,
            #[od(index = 0x2001, default = 18446744073709551615)]
            u64_max: u64,
            #[od(index = 0x2002, default = -1)]
            i64_minus_one: i64,
            #[od(index = 0x2003, default = 1e300)]
            real64: f64,
            #[od(index = 0x2004, default = -2147483648)]
            i32_min: i32,
            #[od(index = 0x2005, default = 4294967295)]
            u32_max: u32,
            #[od(index = 0x2006, default = -0.5)]
            real32: f32,
            #[od(index = 0x2007, sub = 1..=2, default = 300)]
            u16s: [u16; 2],
            #[od(index = 0x2008, default = -32768)]
            i16_min: i16,
            #[od(index = 0x2009, default = 32767)]
            i16_max: i16,
            #[od(index = 0x200A, default = -128)]
            i8_min: i8,
            #[od(index = 0x200B, default = 255)]
            u8_max: u8,
            /// Not in the dictionary: the tail a `repr(C)` struct would pad.
            _pad: [u8; 2],
        }
    };
}
extremes!(ExtremesCode);
extremes!(ExtremesCompact, od(compact));
extremes!(
    ExtremesOffsets,
    od(compact, zerocopy),
    derive(zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable),
    repr(C)
);

/// The types without a byte view, in the compact layout.
macro_rules! wide_types {
    ($name:ident $(, $attr:meta)*) => {
        #[derive(ObjectDictionary, Default, Debug, PartialEq)]
        $(#[$attr])*
        struct $name {
            #[od(index = 0x2000, default = -8388608)]
            i24: canopen_core::od::I24,
            #[od(index = 0x2001, default = 72057594037927935)]
            u56: canopen_core::od::U56,
            #[od(index = 0x2002, default = -549755813888)]
            i40: canopen_core::od::I40,
            #[od(index = 0x2003, default = true)]
            flag: bool,
            #[od(index = 0x2004, default = 1234)]
            u24: canopen_core::od::U24,
        }
    };
}
wide_types!(WideCode);
wide_types!(WideCompact, od(compact));

#[test]
fn defaults_at_the_ends_of_every_width_restore_alike() {
    let (code, compact, offsets) = (fresh::<ExtremesCode>(), fresh::<ExtremesCompact>(), fresh::<ExtremesOffsets>());
    assert_eq!((offsets.i64_min, offsets.u64_max, offsets.i64_minus_one), (i64::MIN, u64::MAX, -1));
    assert_eq!((offsets.real64, offsets.i32_min, offsets.u32_max, offsets.real32), (1e300, i32::MIN, u32::MAX, -0.5));
    assert_eq!(
        (offsets.u16s, offsets.i16_min, offsets.i16_max, offsets.i8_min, offsets.u8_max),
        ([300; 2], i16::MIN, i16::MAX, -128, 255)
    );
    let a = extremes_state(&code);
    assert_eq!(a, extremes_state(&compact));
    assert_eq!(a, extremes_state(&offsets));
    let (code, compact) = (fresh::<WideCode>(), fresh::<WideCompact>());
    assert!(compact.flag && compact.i24.get() == -8388608 && compact.u56.get() == (1 << 56) - 1);
    assert_eq!((compact.i40.get(), compact.u24.get()), (-549755813888, 1234));
    assert_eq!(state_of(&code, 0x2000..=0x2004), state_of(&compact, 0x2000..=0x2004));
}

/// The values of 2000h..200Bh of the extremes dictionaries (2007h: its first element), as SDO reads them.
fn extremes_state<D: ObjectDictionary>(d: &D) -> Vec<Result<Vec<u8>, AbortCode>> {
    let mut out = state_of(d, 0x2000..=0x2006);
    let mut b = [0u8; 8];
    out.push(d.read(0x2007, 1, 0, &mut b).map(|n| b[..n].to_vec()));
    out.extend(state_of(d, 0x2008..=0x200B));
    out
}

/// The values of `indices` (sub 00h), as SDO reads them.
fn state_of<D: ObjectDictionary>(d: &D, indices: core::ops::RangeInclusive<u16>) -> Vec<Result<Vec<u8>, AbortCode>> {
    indices
        .map(|i| {
            let mut b = [0u8; 8];
            d.read(i, 0, 0, &mut b).map(|n| b[..n].to_vec())
        })
        .collect()
}
