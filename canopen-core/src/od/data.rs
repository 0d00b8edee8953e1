//! The dictionary as data: `const` tables that describe every object of a derived dictionary, and the one
//! generic path that serves SDO, PDO and Reset Application from them (issue 41).
//!
//! Covers OD-01/OD-03/OD-04 (an object is found by its 16-bit index, a VAR holds sub 00h, the count of an
//! ARRAY or RECORD is sub 00h, UNSIGNED8, `const` or `ro`), OD-08/OD-09 (the access rules, answered from
//! the row: 0601 0001h for a read of a write-only entry, 0601 0002h for a write of a read-only one),
//! OD-11 (limits and defaults as data) and OD-16 (0602 0000h for an unknown index, 0609 0011h for an
//! unknown sub-index).
//!
//! The shape follows CANopenNode's object dictionary (`OD_entry_t` plus a descriptor per VAR, ARRAY or
//! RECORD member, one `OD_find`): per object there are only bytes, and one function per service reaches
//! every object.
//!
//! - [`OdData::KEYS`]: the object index of each [`Row`], sorted; an interpolated guess, checked, finds an
//!   object, else a binary search ([`search`]). A dictionary of large RECORDs has a key per object instead,
//!   and [`OdData::FIRST_ROWS`] to say where each object's rows start.
//! - [`OdData::ROWS`]: one 3-byte [`PackedRow`] per VAR, per ARRAY (all its elements) and per RECORD member,
//!   with [`OdData::SHAPES`], the [`Shape`]s its rows share; a whole [`Row`] holds the
//!   data type, access, PDO mapping, where sub 00h's count comes from, and the field's number (or offset).
//! - [`OdData::DEFAULTS`]: the power-on values that are not zero, in row order, each as LEB128 (a small
//!   default is one byte), and [`OdData::DEFAULTED`], a bit per row saying which rows have one there.
//! - [`OdData::LIMITS`]: low/high limits of the shapes that have any (rows alike with the same limits
//!   share them), compared through one order key for every type ([`limits`]).
//!
//! The only per-field code is the way to the field. With `#[od(compact)]`, for each fixed-size type a
//! dictionary uses, one accessor of `&self` and one of `&mut self` (`var_unsigned32(f) -> Option<&u32>`,
//! and for arrays a slice), each a jump table whose arm adds the field's offset to `self`. With
//! `#[od(compact, zerocopy)]` none at all: the row holds the field's offset in the struct's bytes
//! ([`offset`] module). Strings and DOMAINs (variable size, streamed by SDO) keep generated code per field
//! (`special_*`), as do the application's hooks.
//! The `#[derive(ObjectDictionary)]` macro writes all of it; its `ObjectDictionary` methods call the
//! functions here ([`info`], [`read`], [`write()`], ...), which are generic over the dictionary, so each
//! dictionary type gets one copy of them and every object is a few bytes of its tables.

use super::{AbortCode, Access, DataType, OdValue, PdoDir, PdoHandle, PdoMapping, SubInfo};
use super::{TimeDifference, TimeOfDay};
use super::{I24, I40, I48, I56, U24, U40, U48, U56};

pub mod limits;
pub mod offset;
mod row;
pub mod search;

pub use offset::{as_bytes, as_bytes_mut};
use offset::{offset_slot, read_at, read_offset_slot, row_slot, slot_row, write_at, write_offset_slot};
pub use row::{any_checks, PackedRow, Row, Shape};

/// Calls `$m!` with every fixed-size data type: its [`DataType`], its Rust type and the names of its four
/// accessors (VAR `&`/`&mut`, ARRAY `&`/`&mut`).
macro_rules! fixed_types {
    ($m:ident) => {
        $m! {
            (Boolean, bool, var_boolean, var_boolean_mut, array_boolean, array_boolean_mut),
            (Integer8, i8, var_integer8, var_integer8_mut, array_integer8, array_integer8_mut),
            (Integer16, i16, var_integer16, var_integer16_mut, array_integer16, array_integer16_mut),
            (Integer24, I24, var_integer24, var_integer24_mut, array_integer24, array_integer24_mut),
            (Integer32, i32, var_integer32, var_integer32_mut, array_integer32, array_integer32_mut),
            (Integer40, I40, var_integer40, var_integer40_mut, array_integer40, array_integer40_mut),
            (Integer48, I48, var_integer48, var_integer48_mut, array_integer48, array_integer48_mut),
            (Integer56, I56, var_integer56, var_integer56_mut, array_integer56, array_integer56_mut),
            (Integer64, i64, var_integer64, var_integer64_mut, array_integer64, array_integer64_mut),
            (Unsigned8, u8, var_unsigned8, var_unsigned8_mut, array_unsigned8, array_unsigned8_mut),
            (Unsigned16, u16, var_unsigned16, var_unsigned16_mut, array_unsigned16, array_unsigned16_mut),
            (Unsigned24, U24, var_unsigned24, var_unsigned24_mut, array_unsigned24, array_unsigned24_mut),
            (Unsigned32, u32, var_unsigned32, var_unsigned32_mut, array_unsigned32, array_unsigned32_mut),
            (Unsigned40, U40, var_unsigned40, var_unsigned40_mut, array_unsigned40, array_unsigned40_mut),
            (Unsigned48, U48, var_unsigned48, var_unsigned48_mut, array_unsigned48, array_unsigned48_mut),
            (Unsigned56, U56, var_unsigned56, var_unsigned56_mut, array_unsigned56, array_unsigned56_mut),
            (Unsigned64, u64, var_unsigned64, var_unsigned64_mut, array_unsigned64, array_unsigned64_mut),
            (Real32, f32, var_real32, var_real32_mut, array_real32, array_real32_mut),
            (Real64, f64, var_real64, var_real64_mut, array_real64, array_real64_mut),
            (TimeOfDay, TimeOfDay, var_time_of_day, var_time_of_day_mut, array_time_of_day, array_time_of_day_mut),
            (TimeDifference, TimeDifference, var_time_difference, var_time_difference_mut,
                array_time_difference, array_time_difference_mut)
        }
    };
}

macro_rules! od_data_trait {
    ($(($dt:ident, $t:ty, $var:ident, $var_mut:ident, $arr:ident, $arr_mut:ident)),*) => {
        /// A dictionary held as data ([module docs](self)): what `#[derive(ObjectDictionary)]` implements, and
        /// what the functions of this module serve every access from.
        ///
        /// The accessors (hidden from these docs) are the one piece of code per field: the derive overrides
        /// those of the types the struct uses; the others answer `None`, and the generic path's arm for
        /// that type compiles away. A hand-written dictionary implements
        /// [`ObjectDictionary`](super::ObjectDictionary) instead.
        ///
        /// ```
        /// use canopen_core::od::{data::OdData, AbortCode, ObjectDictionary};
        /// use canopen_od_derive::ObjectDictionary;
        ///
        /// #[derive(ObjectDictionary, Default)]
        /// #[od(compact)]
        /// struct App {
        ///     #[od(index = 0x2000, access = "rw", default = 7)]
        ///     speed: u32,
        ///     #[od(index = 0x2001, sub = 1..=4, access = "ro")]
        ///     inputs: [u16; 4],
        /// }
        ///
        /// assert_eq!(<App as OdData>::KEYS, &[0x2000, 0x2001]);
        /// assert!(<App as OdData>::FIRST_ROWS.is_empty()); // a key per row
        /// let mut app = App::default();
        /// app.restore_defaults();
        /// assert_eq!(app.speed, 7);
        /// assert_eq!(app.write(0x2001, 1, &[1, 0]), Err(AbortCode::WriteOfReadOnly));
        /// ```
        pub trait OdData {
            /// The object index of each row of [`ROWS`](Self::ROWS), in increasing order (the members of a
            /// RECORD repeat their index); or, with [`FIRST_ROWS`](Self::FIRST_ROWS), of each object.
            const KEYS: &'static [u16];
            /// One row per VAR, ARRAY and RECORD member, in (index, sub-index) order.
            const ROWS: &'static [PackedRow];
            /// The shapes of [`ROWS`](Self::ROWS), each once (at most 256).
            const SHAPES: &'static [Shape];
            /// Empty, or where each object of [`KEYS`](Self::KEYS) starts in [`ROWS`](Self::ROWS), and after
            /// them the end of the rows, as one byte each that [`search::rows_of`] reads with
            /// [`FIRST_ROW_WRAPS`](Self::FIRST_ROW_WRAPS): object `k` is rows `rows_of(k)`.
            /// The derive emits it when RECORDs have so many members that a key per object and this table
            /// take fewer bytes than a key per row (a drive's dictionary: python canopen's `e35.eds` has 636
            /// rows in 178 objects).
            const FIRST_ROWS: &'static [u8] = &[];
            /// With [`FIRST_ROWS`](Self::FIRST_ROWS): the objects from which its bytes count 256 more rows
            /// again ([`search::rows_of`]); empty in a dictionary of fewer than 256 RECORD members beyond
            /// the first of each.
            const FIRST_ROW_WRAPS: &'static [u16] = &[];
            /// Empty when the dictionary numbers its entries the regular way (a VAR at sub 00h, each ARRAY
            /// from sub 01h, each RECORD's members 01h, 02h... in order): a row's
            /// sub-index then follows from its shape and its place in its object ([`PackedRow`]). Otherwise
            /// the sub-index of each row of [`ROWS`](Self::ROWS) (a VAR's 0, an ARRAY's first element's).
            const SUBS: &'static [u8] = &[];
            /// The default values of the fixed-size rows whose default is not zero ([`DEFAULTED`](Self::DEFAULTED)),
            /// in row order: one value per VAR and RECORD member, one per ARRAY (every element gets it);
            /// strings and DOMAINs have none here. Each as LEB128 of its little-endian bytes read as a
            /// number, a signed integer zigzag-encoded first: `7` and `-3` take one byte whatever the type's
            /// width (a REAL or a TIME value is read as its bits).
            const DEFAULTS: &'static [u8];
            /// One bit per row (bit `r % 8` of byte `r / 8`): set when [`DEFAULTS`](Self::DEFAULTS) holds the
            /// row's default, clear when it is zero (no bytes for the most common default).
            const DEFAULTED: &'static [u8];
            /// Where the limits of each shape that has any start in [`LIMIT_VALUES`](Self::LIMIT_VALUES):
            /// those shapes come first in [`SHAPES`](Self::SHAPES), so shape `s` has limits when `s <
            /// LIMITS.len()` (rows of one data type, access and mapping but other limits have other shapes).
            const LIMITS: &'static [u16];
            /// The limit values [`LIMITS`](Self::LIMITS) points into: per limited shape the low limit, then
            /// the high one, each encoded in the shape's data type (a side without a limit holds the type's
            /// extreme).
            const LIMIT_VALUES: &'static [u8];
            /// The scale of the interpolated first guess of a search of [`KEYS`](Self::KEYS)
            /// ([`search::scale`]), computed at compile time.
            const SCALE: u32 = search::scale(Self::KEYS);
            /// Whether no index repeats in [`KEYS`](Self::KEYS) (no RECORD of more than one member, or a key
            /// per object; [`search::unique`], computed at compile time): a search's hit needs no look at
            /// the key before.
            const UNIQUE_KEYS: bool = search::unique(Self::KEYS);
            /// Whether any row has [`Row::CHECKS`] ([`any_checks`], computed at compile time): without, the
            /// path of limits and hooks compiles away.
            const CHECKED: bool = any_checks(Self::SHAPES);

            /// Whether [`Row::field`] of a fixed-size row is the byte offset of its value in
            /// [`bytes`](Self::bytes) (`#[od(compact, zerocopy)]`): no accessor is then generated, every
            /// fixed-size value is reached through the struct's byte view.
            const BY_OFFSET: bool = false;

            /// The struct as bytes (native byte order), with [`BY_OFFSET`](Self::BY_OFFSET); see
            /// [`as_bytes`].
            #[doc(hidden)]
            #[inline]
            fn bytes(&self) -> &[u8] {
                &[]
            }

            /// The struct as mutable bytes, with [`BY_OFFSET`](Self::BY_OFFSET); see [`as_bytes_mut`].
            #[doc(hidden)]
            #[inline]
            fn bytes_mut(&mut self) -> &mut [u8] {
                &mut []
            }

            /// The application's check of a new value of the row at `row` (before it is stored; an error
            /// refuses the write). The derive calls the field's `check` method.
            #[inline]
            fn check(&self, row: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
                let _ = (row, sub, data);
                Ok(())
            }

            /// The application's reaction to a stored value (the derive calls the field's `on_write`).
            #[inline]
            fn on_write(&mut self, row: u16, sub: u8) {
                let _ = (row, sub);
            }

            /// The current size of a string or DOMAIN.
            #[doc(hidden)]
            #[inline]
            fn special_size(&self, field: u16, elem: u8) -> usize {
                let _ = (field, elem);
                0
            }

            /// The size a string or DOMAIN marked mappable moves in a PDO (0: not mappable now).
            #[doc(hidden)]
            #[inline]
            fn special_map_size(&self, field: u16, elem: u8) -> usize {
                let _ = (field, elem);
                0
            }

            /// Bytes `offset..` of a string or DOMAIN.
            #[doc(hidden)]
            #[inline]
            fn special_read(&self, field: u16, elem: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
                let _ = (field, elem, offset, buf);
                Err(AbortCode::ObjectDoesNotExist)
            }

            /// A whole write of a string or DOMAIN (checks and hooks included).
            #[doc(hidden)]
            #[inline]
            fn special_write(&mut self, field: u16, elem: u8, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
                let _ = (field, elem, sub, data);
                Err(AbortCode::UnsupportedAccess)
            }

            /// Starts a streamed write of a string or DOMAIN.
            #[doc(hidden)]
            #[inline]
            fn special_begin(&mut self, field: u16, elem: u8, size: Option<usize>) -> Result<(), AbortCode> {
                let _ = (field, elem, size);
                Err(AbortCode::UnsupportedAccess)
            }

            /// One chunk of a streamed write.
            #[doc(hidden)]
            #[inline]
            fn special_chunk(&mut self, field: u16, elem: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
                let _ = (field, elem, offset, data);
                Err(AbortCode::UnsupportedAccess)
            }

            /// Ends a streamed write of `total` bytes (checks and hooks included).
            #[doc(hidden)]
            #[inline]
            fn special_end(&mut self, field: u16, elem: u8, sub: u8, total: usize) -> Result<(), AbortCode> {
                let _ = (field, elem, sub, total);
                Err(AbortCode::UnsupportedAccess)
            }

            /// A streamed write was abandoned.
            #[doc(hidden)]
            #[inline]
            fn special_abort(&mut self, field: u16, elem: u8) {
                let _ = (field, elem);
            }

            /// Every string gets its default (Reset Application); DOMAINs are the application's.
            #[doc(hidden)]
            #[inline]
            fn special_restore(&mut self) {}

            $(
                #[doc(hidden)]
                #[inline]
                fn $var(&self, field: u16) -> Option<&$t> {
                    let _ = field;
                    None
                }
                #[doc(hidden)]
                #[inline]
                fn $var_mut(&mut self, field: u16) -> Option<&mut $t> {
                    let _ = field;
                    None
                }
                #[doc(hidden)]
                #[inline]
                fn $arr(&self, field: u16) -> Option<&[$t]> {
                    let _ = field;
                    None
                }
                #[doc(hidden)]
                #[inline]
                fn $arr_mut(&mut self, field: u16) -> Option<&mut [$t]> {
                    let _ = field;
                    None
                }
            )*
        }

        /// Bytes `offset..` of the fixed-size value at `row`/`elem`; `None` for a string or DOMAIN.
        #[inline]
        fn read_fixed<D: OdData + ?Sized>(d: &D, row: &Row, elem: u8, offset: usize, buf: &mut [u8]) -> Option<Result<usize, AbortCode>> {
            if D::BY_OFFSET {
                return read_at(d, row, elem, offset, buf);
            }
            let e = usize::from(elem);
            Some(match row.data_type {
                $(DataType::$dt => {
                    let v = if row.is_array() { d.$arr(row.field).and_then(|a| a.get(e)) } else { d.$var(row.field) };
                    v.map(|v| OdValue::read_bytes(v, offset, buf)).ok_or(AbortCode::ObjectDoesNotExist)
                })*
                _ => return None,
            })
        }

        /// Decodes and stores a fixed-size value at `row`/`elem`, after its limits and the application's
        /// check when `checked` (a write; Reset Application stores defaults unchecked); `None` for a string
        /// or DOMAIN.
        #[inline]
        fn write_fixed<D: OdData + ?Sized>(
            d: &mut D,
            pos: u16,
            row: &Row,
            elem: u8,
            sub: u8,
            data: &[u8],
            checked: bool,
        ) -> Option<Result<(), AbortCode>> {
            let hooks = checked && D::CHECKED && row.checks();
            if D::BY_OFFSET {
                return write_at(d, pos, row, elem, sub, data, hooks);
            }
            let e = usize::from(elem);
            Some(match row.data_type {
                $(DataType::$dt => (|| {
                    let v = <$t as OdValue>::decode(data)?;
                    if hooks {
                        limits::check(d, pos, row.data_type, sub, data)?;
                    }
                    let place = if row.is_array() { d.$arr_mut(row.field).and_then(|a| a.get_mut(e)) } else { d.$var_mut(row.field) };
                    *place.ok_or(AbortCode::ObjectDoesNotExist)? = v;
                    if hooks {
                        d.on_write(pos, sub);
                    }
                    Ok(())
                })(),)*
                _ => return None,
            })
        }
    };
}

fixed_types!(od_data_trait);

/// Where an (index, sub-index) lies in a data dictionary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum At {
    /// A value: the row's position, the row, and the element of an ARRAY (0 otherwise).
    Value(u16, Row, u8),
    /// Sub 00h of an ARRAY or RECORD: the highest sub-index, and whether it is `ro` (else `const`).
    Count(u8, bool),
}

/// Finds `index`/`sub` (OD-16: 0602 0000h for no such object, 0609 0011h for no such sub-index).
#[inline]
fn find<D: OdData + ?Sized>(index: u16, sub: u8) -> Result<At, AbortCode> {
    let key = search::locate(D::KEYS, D::SCALE, D::UNIQUE_KEYS, index);
    if D::KEYS.get(key) != Some(&index) {
        return Err(AbortCode::ObjectDoesNotExist);
    }
    // With a key per row the key's position is the object's first row, and its rows run while the key
    // repeats ([`find_member`]); with a key per object, FIRST_ROWS says where they are.
    let (first, end) = match D::FIRST_ROWS {
        [] => (key, 0),
        low => match search::rows_of(low, D::FIRST_ROW_WRAPS, key) {
            Some(rows) => rows,
            None => return Err(AbortCode::ObjectDoesNotExist),
        },
    };
    let Some(row) = row_at::<D>(first) else {
        return Err(AbortCode::ObjectDoesNotExist);
    };
    let count_ro = row.flags & Row::COUNT_RO != 0;
    if row.n != 0 {
        if row.sub == 0 {
            return if sub == 0 { Ok(At::Value(first as u16, row, 0)) } else { Err(AbortCode::SubIndexDoesNotExist) };
        }
        if sub == 0 {
            return Ok(At::Count(row.sub.wrapping_add(row.n - 1), count_ro));
        }
        let elem = sub.wrapping_sub(row.sub);
        return if elem < row.n {
            Ok(At::Value(first as u16, row, elem))
        } else {
            Err(AbortCode::SubIndexDoesNotExist)
        };
    }
    find_member::<D>(index, sub, first, end, count_ro)
}

/// [`find`] out of line: the one copy that the paths off a frame's way share (SDO `info`, segmented
/// `read`/`write`, the streamed-write refusals, PDO mapping, `slot`), where each inlined its own search
/// (node-data's `info`, `read`, `write`, `streamed` and `resolve_into` carried one each). The expedited
/// SDO paths keep theirs inline, a frame's instructions unchanged (through this one the zerocopy bench's
/// expedited download took 340 instructions instead of 284, for 444 B less in node-data).
#[inline(never)]
fn find_shared<D: OdData + ?Sized>(index: u16, sub: u8) -> Result<At, AbortCode> {
    find::<D>(index, sub)
}

/// [`find`] among the members of the RECORD `index` whose first row is `first`: rows `first..end` with a
/// key per object, the rows whose key is `index` with a key per row.
#[inline(never)]
fn find_member<D: OdData + ?Sized>(
    index: u16,
    sub: u8,
    first: usize,
    end: usize,
    count_ro: bool,
) -> Result<At, AbortCode> {
    let mut highest = 0;
    let mut i = first;
    while let Some(row) = row_at::<D>(i) {
        let member = match D::FIRST_ROWS {
            [] => D::KEYS.get(i) == Some(&index),
            _ => i < end,
        };
        if !member {
            break;
        }
        // A regularly numbered RECORD's members are 01h, 02h... from its first row.
        let member_sub = match D::SUBS {
            [] => (i - first + 1) as u8,
            _ => row.sub,
        };
        if member_sub == sub && sub != 0 {
            return Ok(At::Value(i as u16, Row { sub, ..row }, 0));
        }
        highest = member_sub;
        i += 1;
    }
    if sub == 0 {
        Ok(At::Count(highest, count_ro))
    } else {
        Err(AbortCode::SubIndexDoesNotExist)
    }
}

/// The row at `pos` of [`OdData::ROWS`], with its shape and, from [`OdData::SUBS`] when the numbering
/// is not regular, its sub-index (a member of a regular RECORD has 0 here: [`find_member`] knows its place).
#[inline(always)]
fn row_at<D: OdData + ?Sized>(pos: usize) -> Option<Row> {
    let row = D::ROWS.get(pos)?.unpack(D::SHAPES)?;
    match D::SUBS {
        [] => Some(row),
        subs => Some(Row { sub: *subs.get(pos)?, ..row }),
    }
}

/// What SDO and PDO see of sub 00h of an ARRAY or RECORD.
const fn count_info(ro: bool) -> SubInfo {
    SubInfo {
        data_type: DataType::Unsigned8,
        access: if ro { Access::Ro } else { Access::Const },
        pdo: PdoMapping::No,
        size: 1,
    }
}

/// The current size of a value: its type's, or a string's or DOMAIN's current length.
#[inline]
fn size<D: OdData + ?Sized>(d: &D, row: &Row, elem: u8) -> usize {
    match row.data_type.fixed_size() {
        0 => d.special_size(row.field, elem),
        n => n,
    }
}

/// Bytes `offset..` of a value. The one place the `&self` accessors are inlined into: each field's arm is
/// then one add and a branch, in one copy (inlined into every caller, an accessor was a copy per path).
#[inline(never)]
fn read_value<D: OdData + ?Sized>(
    d: &D,
    row: &Row,
    elem: u8,
    offset: usize,
    buf: &mut [u8],
) -> Result<usize, AbortCode> {
    match read_fixed(d, row, elem, offset, buf) {
        Some(r) => r,
        None => d.special_read(row.field, elem, offset, buf),
    }
}

/// A whole write of a value (all checks first, so a refused write changes nothing). The one place the
/// `&mut self` accessors are inlined into (see [`read_value`]).
#[inline(never)]
fn write_value<D: OdData + ?Sized>(
    d: &mut D,
    pos: u16,
    row: &Row,
    elem: u8,
    sub: u8,
    data: &[u8],
    checked: bool,
) -> Result<(), AbortCode> {
    match write_fixed(d, pos, row, elem, sub, data, checked) {
        Some(r) => r,
        None => d.special_write(row.field, elem, sub, data),
    }
}

/// A row that SDO may write, as [`find`] or [`find_shared`] found it: 0601 0002h for a read-only one and
/// for sub 00h of an ARRAY or RECORD.
#[inline]
fn writable(found: Result<At, AbortCode>) -> Result<(u16, Row, u8), AbortCode> {
    match found? {
        At::Value(pos, row, elem) if row.writable() => Ok((pos, row, elem)),
        _ => Err(AbortCode::WriteOfReadOnly),
    }
}

/// Sub 00h's one byte from `offset`, as one byte store: through `copy_at` the constant one-byte source
/// became a call to `memset` (220 B in a firmware that needs it nowhere else; the match-arm layout's count
/// rows do the same).
fn read_count(highest: u8, offset: usize, buf: &mut [u8]) -> usize {
    match (offset, buf.first_mut()) {
        (0, Some(b)) => {
            *b = highest;
            1
        }
        _ => 0,
    }
}

/// [`ObjectDictionary::info`](super::ObjectDictionary::info) of a data dictionary.
///
/// ```
/// use canopen_core::od::{data, AbortCode, Access, DataType};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2001, sub = 1..=4, access = "ro", count_access = "ro")] inputs: [u16; 4] }
/// let app = App::default();
/// assert_eq!(data::info(&app, 0x2001, 4).map(|i| i.data_type), Ok(DataType::Unsigned16));
/// assert_eq!(data::info(&app, 0x2001, 0).map(|i| (i.access, i.size)), Ok((Access::Ro, 1)));
/// assert_eq!(data::info(&app, 0x2001, 5), Err(AbortCode::SubIndexDoesNotExist));
/// assert_eq!(data::info(&app, 0x2002, 0), Err(AbortCode::ObjectDoesNotExist));
/// ```
pub fn info<D: OdData + ?Sized>(d: &D, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
    Ok(match find_shared::<D>(index, sub)? {
        At::Count(_, ro) => count_info(ro),
        At::Value(_, row, elem) => {
            SubInfo { data_type: row.data_type, access: row.access(), pdo: row.pdo(), size: size(d, &row, elem) }
        }
    })
}

/// [`ObjectDictionary::read`](super::ObjectDictionary::read): 0601 0001h for a write-only entry.
///
/// ```
/// use canopen_core::od::{data, AbortCode};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000, access = "wo")] password: u32, #[od(index = 0x2001, default = 9)] x: u8 }
/// let mut app = App::default();
/// app.x = 9;
/// let mut buf = [0u8; 4];
/// assert_eq!(data::read(&app, 0x2000, 0, 0, &mut buf), Err(AbortCode::ReadOfWriteOnly));
/// assert_eq!(data::read(&app, 0x2001, 0, 0, &mut buf), Ok(1));
/// assert_eq!(buf[0], 9);
/// ```
pub fn read<D: OdData + ?Sized>(d: &D, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
    match find_shared::<D>(index, sub)? {
        At::Count(highest, _) => Ok(read_count(highest, offset, buf)),
        At::Value(_, row, _) if !row.readable() => Err(AbortCode::ReadOfWriteOnly),
        At::Value(_, row, elem) => read_value(d, &row, elem, offset, buf),
    }
}

/// [`ObjectDictionary::write`](super::ObjectDictionary::write): access, length, limits and the
/// application's check first; a refused write changes nothing.
///
/// ```
/// use canopen_core::od::{data, AbortCode};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000, min = -10, max = 10)] x: i16 }
/// let mut app = App::default();
/// assert_eq!(data::write(&mut app, 0x2000, 0, &5i16.to_le_bytes()), Ok(()));
/// assert_eq!(data::write(&mut app, 0x2000, 0, &11i16.to_le_bytes()), Err(AbortCode::ValueTooHigh));
/// assert_eq!(data::write(&mut app, 0x2000, 0, &[1]), Err(AbortCode::LengthTooLow));
/// assert_eq!(app.x, 5);
/// ```
pub fn write<D: OdData + ?Sized>(d: &mut D, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
    let (pos, row, elem) = writable(find_shared::<D>(index, sub))?;
    write_value(d, pos, &row, elem, sub, data, true)
}

/// [`ObjectDictionary::read_expedited`](super::ObjectDictionary::read_expedited): the size and, when it
/// is 1..=4 bytes, the bytes, from one search.
///
/// ```
/// use canopen_core::od::data;
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000)] x: u16 }
/// let app = App { x: 0x1234 };
/// let mut buf = [0u8; 4];
/// assert_eq!(data::read_expedited(&app, 0x2000, 0, &mut buf), Ok((2, 2)));
/// assert_eq!(&buf[..2], &[0x34, 0x12]);
/// ```
pub fn read_expedited<D: OdData + ?Sized>(
    d: &D,
    index: u16,
    sub: u8,
    buf: &mut [u8; 4],
) -> Result<(usize, usize), AbortCode> {
    match find::<D>(index, sub)? {
        At::Count(highest, _) => {
            buf[0] = highest;
            Ok((1, 1))
        }
        At::Value(_, row, _) if !row.readable() => Err(AbortCode::ReadOfWriteOnly),
        At::Value(_, row, elem) => {
            let size = size(d, &row, elem);
            match buf.get_mut(..size) {
                Some(dst) if size > 0 => Ok((size, read_value(d, &row, elem, 0, dst)?)),
                _ => Ok((size, 0)),
            }
        }
    }
}

/// [`ObjectDictionary::write_expedited`](super::ObjectDictionary::write_expedited): `len` bytes of
/// `data` (not indicated: the type's size up to 4, or 4 for a string or DOMAIN).
///
/// ```
/// use canopen_core::od::{data, AbortCode};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000)] x: u16, #[od(index = 0x2001, access = "ro")] y: u16 }
/// let mut app = App::default();
/// assert_eq!(data::write_expedited(&mut app, 0x2000, 0, &[0x34, 0x12, 0, 0], None), Ok(()));
/// assert_eq!(app.x, 0x1234);
/// assert_eq!(data::write_expedited(&mut app, 0x2001, 0, &[1, 0, 0, 0], Some(2)), Err(AbortCode::WriteOfReadOnly));
/// ```
pub fn write_expedited<D: OdData + ?Sized>(
    d: &mut D,
    index: u16,
    sub: u8,
    data: &[u8; 4],
    len: Option<usize>,
) -> Result<(), AbortCode> {
    let (pos, row, elem) = writable(find::<D>(index, sub))?;
    match row.data_type.fixed_size() {
        0 => write_special_whole(d, &row, elem, sub, data.get(..len.unwrap_or(4)).unwrap_or(data)),
        n => write_value(d, pos, &row, elem, sub, data.get(..len.unwrap_or(n.min(4))).unwrap_or(data), true),
    }
}

/// A string or DOMAIN written in one streamed step (an expedited download of one): begin, chunk, end,
/// and abort when a step after the first fails. Out of line: the fixed-size path keeps no registers for it.
#[inline(never)]
fn write_special_whole<D: OdData + ?Sized>(
    d: &mut D,
    row: &Row,
    elem: u8,
    sub: u8,
    bytes: &[u8],
) -> Result<(), AbortCode> {
    d.special_begin(row.field, elem, Some(bytes.len()))?;
    let r = d.special_chunk(row.field, elem, 0, bytes).and_then(|()| d.special_end(row.field, elem, sub, bytes.len()));
    if r.is_err() {
        d.special_abort(row.field, elem);
    }
    r
}

/// A streamed write's target: writable, and a string or DOMAIN (0601 0000h for a fixed-size value,
/// which is written whole).
fn streamed<D: OdData + ?Sized>(index: u16, sub: u8) -> Result<(Row, u8), AbortCode> {
    let (_, row, elem) = writable(find_shared::<D>(index, sub))?;
    match row.data_type.fixed_size() {
        0 => Ok((row, elem)),
        _ => Err(AbortCode::UnsupportedAccess),
    }
}

/// [`ObjectDictionary::begin_write`](super::ObjectDictionary::begin_write) of a string or DOMAIN.
///
/// ```
/// use canopen_core::od::{data, AbortCode, VisibleString};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000)] name: VisibleString<4>, #[od(index = 0x2001)] x: u32 }
/// let mut app = App::default();
/// assert_eq!(data::begin_write(&mut app, 0x2000, 0, Some(5)), Err(AbortCode::LengthTooHigh));
/// assert_eq!(data::begin_write(&mut app, 0x2001, 0, Some(4)), Err(AbortCode::UnsupportedAccess));
/// ```
pub fn begin_write<D: OdData + ?Sized>(d: &mut D, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
    let (row, elem) = streamed::<D>(index, sub)?;
    d.special_begin(row.field, elem, size)
}

/// [`ObjectDictionary::write_chunk`](super::ObjectDictionary::write_chunk) of a string or DOMAIN.
///
/// ```
/// use canopen_core::od::{data, VisibleString};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000)] name: VisibleString<8> }
/// let mut app = App::default();
/// data::begin_write(&mut app, 0x2000, 0, None).unwrap();
/// data::write_chunk(&mut app, 0x2000, 0, 0, b"abc").unwrap();
/// data::end_write(&mut app, 0x2000, 0, 3).unwrap();
/// assert_eq!(app.name.as_str(), "abc");
/// ```
pub fn write_chunk<D: OdData + ?Sized>(
    d: &mut D,
    index: u16,
    sub: u8,
    offset: usize,
    data: &[u8],
) -> Result<(), AbortCode> {
    let (row, elem) = streamed::<D>(index, sub)?;
    d.special_chunk(row.field, elem, offset, data)
}

/// [`ObjectDictionary::end_write`](super::ObjectDictionary::end_write) of a string or DOMAIN (see
/// [`write_chunk`]).
///
/// ```
/// use canopen_core::od::{data, AbortCode, VisibleString};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000)] name: VisibleString<8> }
/// let mut app = App::default();
/// assert_eq!(data::end_write(&mut app, 0x2001, 0, 3), Err(AbortCode::ObjectDoesNotExist));
/// ```
pub fn end_write<D: OdData + ?Sized>(d: &mut D, index: u16, sub: u8, total: usize) -> Result<(), AbortCode> {
    let (row, elem) = streamed::<D>(index, sub)?;
    d.special_end(row.field, elem, sub, total)
}

/// [`ObjectDictionary::abort_write`](super::ObjectDictionary::abort_write) of a string or DOMAIN.
///
/// ```
/// use canopen_core::od::{data, VisibleString};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000, default = "old")] name: VisibleString<8> }
/// let mut app = App::default();
/// data::restore_defaults(&mut app);
/// data::begin_write(&mut app, 0x2000, 0, None).unwrap();
/// data::write_chunk(&mut app, 0x2000, 0, 0, b"new").unwrap();
/// data::abort_write(&mut app, 0x2000, 0);
/// assert_eq!(app.name.as_str(), "old");
/// ```
pub fn abort_write<D: OdData + ?Sized>(d: &mut D, index: u16, sub: u8) {
    // Without a writable string or DOMAIN row `streamed` never answers `Ok`: nothing to look up (the node's
    // SDO server calls this after a refused stream; footprint.sh node-data links `streamed` once less).
    if !const { streams(D::SHAPES) } {
        return;
    }
    if let Ok((row, elem)) = streamed::<D>(index, sub) {
        d.special_abort(row.field, elem);
    }
}

/// [`ObjectDictionary::restore_defaults`](super::ObjectDictionary::restore_defaults) (NMT-04 Reset
/// Application): every fixed-size value and string gets its default, or its type's default where it has
/// none; DOMAINs are left to the application.
///
/// ```
/// use canopen_core::od::data;
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000, sub = 1..=3, default = 4)] a: [i8; 3], #[od(index = 0x2001)] b: u8 }
/// let mut app = App { a: [0; 3], b: 9 };
/// data::restore_defaults(&mut app);
/// assert_eq!((app.a, app.b), ([4; 3], 0));
/// ```
pub fn restore_defaults<D: OdData + ?Sized>(d: &mut D) {
    let mut at = 0;
    for pos in 0..D::ROWS.len() {
        let Some(row) = row_at::<D>(pos) else { continue };
        let size = row.data_type.fixed_size();
        if size == 0 {
            continue;
        }
        let mut value = [0u8; 8];
        if D::DEFAULTED.get(pos / 8).is_some_and(|b| b >> (pos % 8) & 1 != 0) {
            value = next_default(row.data_type, D::DEFAULTS, &mut at);
        }
        let default = value.get(..size).unwrap_or(&value);
        for elem in 0..row.n.max(1) {
            let _ = write_value(d, pos as u16, &row, elem, row.sub, default, false);
        }
    }
    d.special_restore();
}

/// The default of a `dt` row at `*at` in [`OdData::DEFAULTS`] (LEB128, zigzag for a signed type), as
/// little-endian bytes, and `*at` moved past it. Out of line: Reset Application's loop stays small.
#[inline(never)]
fn next_default(dt: DataType, defaults: &[u8], at: &mut usize) -> [u8; 8] {
    let (mut v, mut shift) = (0u64, 0u32);
    while let Some(&b) = defaults.get(*at) {
        *at += 1;
        v |= u64::from(b & 0x7F).checked_shl(shift).unwrap_or(0);
        shift += 7;
        if b & 0x80 == 0 {
            break;
        }
    }
    if limits::class(dt) == limits::SIGNED {
        v = (v >> 1) ^ (v & 1).wrapping_neg();
    }
    v.to_le_bytes()
}

/// [`ObjectDictionary::slot`](super::ObjectDictionary::slot): the row's position.
///
/// ```
/// use canopen_core::od::{data, PdoHandle};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000)] a: u8, #[od(index = 0x2001)] b: u8 }
/// assert_eq!(data::slot(&App::default(), 0x2001, 0), 1);
/// assert_eq!(data::slot(&App::default(), 0x2002, 0), PdoHandle::NO_SLOT);
/// ```
pub fn slot<D: OdData + ?Sized>(d: &D, index: u16, sub: u8) -> u16 {
    let _ = d;
    match find_shared::<D>(index, sub) {
        Ok(At::Value(pos, ..)) => pos,
        _ => PdoHandle::NO_SLOT,
    }
}

/// The value at a row position and sub-index that [`slot`] (or a PDO handle) gave: `None` when the
/// position is out of range or names sub 00h. A member of a regularly numbered RECORD is taken at its
/// position, as the handle's slot says (its sub-index was checked when [`slot`] or [`pdo_resolve`] gave it).
#[inline]
fn at_slot<D: OdData + ?Sized>(slot: u16, sub: u8) -> Option<(Row, u8)> {
    let row = row_at::<D>(usize::from(slot))?;
    if row.is_array() {
        let elem = sub.wrapping_sub(row.sub);
        (elem < row.n).then_some((row, elem))
    } else if row.n == 0 && D::SUBS.is_empty() {
        (sub != 0).then_some((Row { sub, ..row }, 0))
    } else {
        (sub == row.sub).then_some((row, 0))
    }
}

/// [`ObjectDictionary::read_slot`](super::ObjectDictionary::read_slot): an SDO upload segment, straight
/// to the row `slot` names (its access is checked again, not its key).
///
/// ```
/// use canopen_core::od::{data, AbortCode, VisibleString};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000, default = "abcdefgh")] s: VisibleString<8> }
/// let mut app = App::default();
/// data::restore_defaults(&mut app);
/// let mut seg = [0u8; 7];
/// let slot = data::slot(&app, 0x2000, 0);
/// assert_eq!(data::read_slot(&app, 0x2000, 0, slot, 1, &mut seg), Ok(()));
/// assert_eq!(&seg, b"bcdefgh");
/// assert_eq!(data::read_slot(&app, 0x2000, 0, slot, 2, &mut seg), Err(AbortCode::LengthMismatch));
/// ```
pub fn read_slot<D: OdData + ?Sized>(
    d: &D,
    index: u16,
    sub: u8,
    slot: u16,
    offset: usize,
    buf: &mut [u8],
) -> Result<(), AbortCode> {
    let n = match at_slot::<D>(slot, sub) {
        Some((row, _)) if !row.readable() => return Err(AbortCode::ReadOfWriteOnly),
        Some((row, elem)) => read_value(d, &row, elem, offset, buf)?,
        None => read(d, index, sub, offset, buf)?,
    };
    super::filled(n, buf.len())
}

/// [`ObjectDictionary::pdo_resolve`](super::ObjectDictionary::pdo_resolve): mappable in `dir` (0604 0041h
/// otherwise), with its size; a string moves its capacity and a DOMAIN its size now, when 1 to 8 bytes
/// (PDO-33).
///
/// ```
/// use canopen_core::od::{data, AbortCode, PdoDir};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000, access = "ro", pdo = "tpdo")] a: u16 }
/// let app = App::default();
/// assert_eq!(data::pdo_resolve(&app, 0x2000, 0, PdoDir::Tpdo).map(|h| (h.size, h.slot)), Ok((2, 0)));
/// assert_eq!(data::pdo_resolve(&app, 0x2000, 0, PdoDir::Rpdo), Err(AbortCode::NotMappable));
/// ```
pub fn pdo_resolve<D: OdData + ?Sized>(d: &D, index: u16, sub: u8, dir: PdoDir) -> Result<PdoHandle, AbortCode> {
    let (pos, row, elem) = match find_shared::<D>(index, sub)? {
        At::Value(pos, row, elem) => (pos, row, elem),
        At::Count(_, ro) => return PdoHandle::check(index, sub, &count_info(ro), dir, PdoHandle::NO_SLOT),
    };
    let info = SubInfo { data_type: row.data_type, access: row.access(), pdo: row.pdo(), size: 0 };
    if row.data_type.fixed_size() != 0 {
        return PdoHandle::check(index, sub, &info, dir, offset_slot::<D>(&row, elem).unwrap_or(row_slot::<D>(pos)));
    }
    let ok = match dir {
        PdoDir::Tpdo => info.pdo.tpdo() && info.access.readable(),
        PdoDir::Rpdo => info.pdo.rpdo() && info.access.writable(),
    };
    match u8::try_from(d.special_map_size(row.field, elem)) {
        Ok(size @ 1..=8) if ok => Ok(PdoHandle { index, sub, size, slot: row_slot::<D>(pos) }),
        _ => Err(AbortCode::NotMappable),
    }
}

/// [`ObjectDictionary::pdo_read`](super::ObjectDictionary::pdo_read): the handle's row, without a search.
///
/// ```
/// use canopen_core::od::{data, PdoDir};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000, sub = 1..=2, access = "ro", pdo = "tpdo")] a: [u16; 2] }
/// let app = App { a: [1, 0x0302] };
/// let h = data::pdo_resolve(&app, 0x2000, 2, PdoDir::Tpdo).unwrap();
/// let mut buf = [0u8; 2];
/// assert_eq!(data::pdo_read(&app, &h, &mut buf), Ok(2));
/// assert_eq!(buf, [2, 3]);
/// ```
#[inline(always)]
pub fn pdo_read<D: OdData + ?Sized>(d: &D, handle: &PdoHandle, buf: &mut [u8]) -> Result<usize, AbortCode> {
    if D::BY_OFFSET {
        if let Some(r) = read_offset_slot(d, handle, buf) {
            return r;
        }
        return pdo_read_row_out_of_line(d, handle, buf);
    }
    pdo_read_row(d, handle, buf)
}

/// [`pdo_read`] by the handle's row: the path of the table layout, and the rare one of the offset layout
/// (a value with limits or hooks), kept out of its offset path's way.
#[inline(always)]
fn pdo_read_row<D: OdData + ?Sized>(d: &D, handle: &PdoHandle, buf: &mut [u8]) -> Result<usize, AbortCode> {
    match at_slot::<D>(slot_row::<D>(handle.slot), handle.sub) {
        Some((row, elem)) => read_value(d, &row, elem, 0, buf),
        None => read(d, handle.index, handle.sub, 0, buf),
    }
}

#[inline(never)]
fn pdo_read_row_out_of_line<D: OdData + ?Sized>(d: &D, handle: &PdoHandle, buf: &mut [u8]) -> Result<usize, AbortCode> {
    pdo_read_row(d, handle, buf)
}

/// [`ObjectDictionary::pdo_write`](super::ObjectDictionary::pdo_write): limits and hooks apply as for
/// [`write()`]; a read-only row is 0601 0002h whatever the handle says.
///
/// ```
/// use canopen_core::od::{data, PdoDir};
/// # use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000, pdo = "rpdo", max = 100)] a: u8 }
/// let mut app = App::default();
/// let h = data::pdo_resolve(&app, 0x2000, 0, PdoDir::Rpdo).unwrap();
/// assert!(data::pdo_write(&mut app, &h, &[101]).is_err());
/// assert_eq!(data::pdo_write(&mut app, &h, &[100]), Ok(()));
/// assert_eq!(app.a, 100);
/// ```
pub fn pdo_write<D: OdData + ?Sized>(d: &mut D, handle: &PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
    if D::BY_OFFSET {
        if let Some(r) = write_offset_slot(d, handle, data) {
            return r;
        }
        return pdo_write_row_out_of_line(d, handle, data);
    }
    pdo_write_row(d, handle, data)
}

/// [`pdo_write`] by the handle's row (see [`pdo_read_row`]).
#[inline(always)]
fn pdo_write_row<D: OdData + ?Sized>(d: &mut D, handle: &PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
    let pos = slot_row::<D>(handle.slot);
    match at_slot::<D>(pos, handle.sub) {
        Some((row, _)) if !row.writable() => Err(AbortCode::WriteOfReadOnly),
        Some((row, elem)) => write_value(d, pos, &row, elem, handle.sub, data, true),
        None => write(d, handle.index, handle.sub, data),
    }
}

#[inline(never)]
fn pdo_write_row_out_of_line<D: OdData + ?Sized>(d: &mut D, handle: &PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
    pdo_write_row(d, handle, data)
}

/// Whether a row of one of `shapes` is a writable string or DOMAIN ([`ObjectDictionary::STREAMS`]).
///
/// [`ObjectDictionary::STREAMS`]: super::ObjectDictionary::STREAMS
///
/// ```
/// use canopen_core::od::{data::{streams, Row, Shape}, Access, DataType, PdoMapping};
/// let var = |dt, a| Shape::of(Row::var(0, dt, a, PdoMapping::No));
/// assert!(!streams(&[var(DataType::Unsigned8, Access::Rw)]));
/// assert!(streams(&[var(DataType::VisibleString, Access::Rw)]));
/// assert!(!streams(&[var(DataType::VisibleString, Access::Ro)]));
/// ```
pub const fn streams(shapes: &[Shape]) -> bool {
    let mut i = 0;
    while i < shapes.len() {
        if shapes[i].writable() && shapes[i].data_type.fixed_size() == 0 {
            return true;
        }
        i += 1;
    }
    false
}

/// Whether a readable row of one of `shapes` has no fixed size of 1..=4 bytes, so that an SDO upload of it
/// is segmented ([`ObjectDictionary::SEGMENTED_UPLOADS`]).
///
/// [`ObjectDictionary::SEGMENTED_UPLOADS`]: super::ObjectDictionary::SEGMENTED_UPLOADS
///
/// ```
/// use canopen_core::od::{data::{segmented_uploads, Row, Shape}, Access, DataType, PdoMapping};
/// let var = |dt, a| Shape::of(Row::var(0, dt, a, PdoMapping::No));
/// assert!(!segmented_uploads(&[var(DataType::Unsigned32, Access::Ro)]));
/// assert!(segmented_uploads(&[var(DataType::Unsigned64, Access::Ro)]));
/// assert!(!segmented_uploads(&[var(DataType::Unsigned64, Access::Wo)]));
/// ```
pub const fn segmented_uploads(shapes: &[Shape]) -> bool {
    let mut i = 0;
    while i < shapes.len() {
        let n = shapes[i].data_type.fixed_size();
        if shapes[i].readable() && (n == 0 || n > 4) {
            return true;
        }
        i += 1;
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    /// OD-08/OD-09: every access type survives the flag encoding, and every PDO mapping.
    #[test]
    fn flags_round_trip() {
        for a in [Access::Ro, Access::Wo, Access::Rw, Access::Rwr, Access::Rww, Access::Const] {
            for p in [PdoMapping::No, PdoMapping::Tpdo, PdoMapping::Rpdo, PdoMapping::Both] {
                let r = Row::var(0, DataType::Unsigned8, a, p).with(Row::COUNT_RO | Row::CHECKS);
                assert_eq!((r.access(), r.pdo()), (a, p));
                assert_eq!((r.readable(), r.writable()), (a.readable(), a.writable()));
            }
        }
    }
}
