//! The rows of a data dictionary (OD-03, OD-04, OD-08, OD-09, OD-11): what one VAR, ARRAY or RECORD member
//! is, and where its limits are. A [`Row`] is stored as a 3-byte [`PackedRow`] (where the value is; the
//! sub-index follows from the row's place, or from a table when the numbering is not regular) and a [`Shape`] (data type, access, PDO mapping, count) that the rows alike share: a drive's
//! dictionary has a few dozen shapes for hundreds of rows.

use crate::od::{Access, DataType, PdoMapping};

/// One row of a data dictionary: a VAR, a whole ARRAY, or one member of a RECORD (OD-03, OD-04).
///
/// | object | `sub` | `n` |
/// |---|---|---|
/// | VAR | 0 | 1 |
/// | ARRAY | its first element's sub-index (1 or more) | its number of elements |
/// | RECORD member | the member's sub-index (1 or more) | 0 |
///
/// Sub-index 00h of an ARRAY or RECORD has no row: its value is the highest sub-index (the ARRAY's last
/// element, the RECORD's last member) and its access `const`, or `ro` with [`Row::COUNT_RO`].
///
/// ```
/// use canopen_core::od::{Access, DataType, PdoMapping};
/// use canopen_core::od::data::Row;
/// const VAR: Row = Row::var(0, DataType::Unsigned32, Access::Rw, PdoMapping::Both);
/// assert!(VAR.readable() && VAR.writable() && !VAR.is_array());
/// assert_eq!((VAR.access(), VAR.pdo()), (Access::Rw, PdoMapping::Both));
/// const ARRAY: Row = Row::array(2, DataType::Unsigned16, Access::Ro, PdoMapping::Tpdo, 1, 4);
/// assert!(ARRAY.is_array() && !ARRAY.writable());
/// assert_eq!(core::mem::size_of::<Row>(), 6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Row {
    /// The field's number among the dictionary's fields of this data type (what its accessors match on);
    /// for a string or DOMAIN, its number among those.
    pub field: u16,
    /// The data type of the value (of each element of an ARRAY).
    pub data_type: DataType,
    /// Access, PDO mapping and the other bits ([`Row::READ`] ...).
    pub flags: u8,
    /// VAR: 0; ARRAY: the first element's sub-index; RECORD member: its sub-index. (A row reached by its
    /// position alone, as a PDO handle reaches it, has 0 for a member of a regularly numbered dictionary:
    /// see [`PackedRow`].)
    pub sub: u8,
    /// ARRAY: the number of elements; VAR: 1; RECORD member: 0.
    pub n: u8,
}

impl Row {
    /// SDO may read it.
    pub const READ: u8 = 1 << 0;
    /// SDO may write it.
    pub const WRITE: u8 = 1 << 1;
    /// With READ alone: `const`; with READ and WRITE: `rwr` (an input).
    pub const VARIANT_A: u8 = 1 << 2;
    /// With READ and WRITE: `rww` (an output).
    pub const VARIANT_B: u8 = 1 << 3;
    /// Mappable into a TPDO.
    pub const TPDO: u8 = 1 << 4;
    /// Mappable into an RPDO.
    pub const RPDO: u8 = 1 << 5;
    /// Sub-index 00h of this ARRAY (or of the RECORD whose first member this is) is `ro`, not `const`.
    pub const COUNT_RO: u8 = 1 << 6;
    /// A write goes through the shape's limits ([`OdData::LIMITS`](super::OdData::LIMITS)) and the application's hooks ([`OdData::check`](super::OdData::check),
    /// [`OdData::on_write`](super::OdData::on_write)).
    pub const CHECKS: u8 = 1 << 7;

    /// The flags of an access type and a PDO mapping.
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// assert_eq!(Row::flags(Access::Rw, PdoMapping::Rpdo), Row::READ | Row::WRITE | Row::RPDO);
    /// assert_eq!(Row::flags(Access::Const, PdoMapping::No), Row::READ | Row::VARIANT_A);
    /// ```
    pub const fn flags(access: Access, pdo: PdoMapping) -> u8 {
        let a = match access {
            Access::Ro => Self::READ,
            Access::Const => Self::READ | Self::VARIANT_A,
            Access::Wo => Self::WRITE,
            Access::Rw => Self::READ | Self::WRITE,
            Access::Rwr => Self::READ | Self::WRITE | Self::VARIANT_A,
            Access::Rww => Self::READ | Self::WRITE | Self::VARIANT_B,
        };
        let p = match pdo {
            PdoMapping::No => 0,
            PdoMapping::Tpdo => Self::TPDO,
            PdoMapping::Rpdo => Self::RPDO,
            PdoMapping::Both => Self::TPDO | Self::RPDO,
        };
        a | p
    }

    /// A VAR (sub 00h).
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// let r = Row::var(4, DataType::Integer16, Access::Rw, PdoMapping::Both);
    /// assert_eq!((r.field, r.sub, r.n), (4, 0, 1));
    /// ```
    pub const fn var(field: u16, data_type: DataType, access: Access, pdo: PdoMapping) -> Row {
        Row { field, data_type, flags: Self::flags(access, pdo), sub: 0, n: 1 }
    }

    /// An ARRAY of `n` elements at sub-indices `first..first + n`.
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// let r = Row::array(0, DataType::Unsigned8, Access::Ro, PdoMapping::Tpdo, 1, 8);
    /// assert!(r.is_array() && r.readable() && !r.writable());
    /// ```
    pub const fn array(field: u16, data_type: DataType, access: Access, pdo: PdoMapping, first: u8, n: u8) -> Row {
        Row { field, data_type, flags: Self::flags(access, pdo), sub: first, n }
    }

    /// A RECORD member at sub-index `sub`.
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// let r = Row::member(1, DataType::Unsigned32, Access::Wo, PdoMapping::No, 3);
    /// assert!((r.sub, r.n) == (3, 0) && !r.is_array() && !r.readable());
    /// ```
    pub const fn member(field: u16, data_type: DataType, access: Access, pdo: PdoMapping, sub: u8) -> Row {
        Row { field, data_type, flags: Self::flags(access, pdo), sub, n: 0 }
    }

    /// The same row with more flags ([`Row::COUNT_RO`], [`Row::CHECKS`]).
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// let r = Row::var(0, DataType::Unsigned8, Access::Rw, PdoMapping::No).with(Row::CHECKS);
    /// assert!(r.checks());
    /// ```
    pub const fn with(mut self, flags: u8) -> Row {
        self.flags |= flags;
        self
    }

    /// Whether SDO may read it.
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// assert!(!Row::var(0, DataType::Unsigned8, Access::Wo, PdoMapping::No).readable());
    /// ```
    #[inline]
    pub const fn readable(&self) -> bool {
        self.flags & Self::READ != 0
    }

    /// Whether SDO may write it.
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// assert!(Row::var(0, DataType::Unsigned8, Access::Rww, PdoMapping::No).writable());
    /// ```
    #[inline]
    pub const fn writable(&self) -> bool {
        self.flags & Self::WRITE != 0
    }

    /// Whether writes go through limits and hooks.
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// assert!(!Row::var(0, DataType::Unsigned8, Access::Rw, PdoMapping::No).checks());
    /// ```
    #[inline]
    pub const fn checks(&self) -> bool {
        self.flags & Self::CHECKS != 0
    }

    /// Whether this row is an ARRAY (its accessors give a slice).
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// assert!(!Row::member(0, DataType::Unsigned8, Access::Rw, PdoMapping::No, 1).is_array());
    /// ```
    #[inline]
    pub const fn is_array(&self) -> bool {
        self.sub != 0 && self.n != 0
    }

    /// The access type.
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// assert_eq!(Row::var(0, DataType::Unsigned8, Access::Rwr, PdoMapping::No).access(), Access::Rwr);
    /// ```
    pub const fn access(&self) -> Access {
        match self.flags & 0x0F {
            0x01 => Access::Ro,
            0x05 => Access::Const,
            0x02 => Access::Wo,
            0x07 => Access::Rwr,
            0x0B => Access::Rww,
            _ => Access::Rw,
        }
    }

    /// The PDO mapping.
    /// ```
    /// use canopen_core::od::{data::Row, Access, DataType, PdoMapping};
    /// assert_eq!(Row::var(0, DataType::Unsigned8, Access::Ro, PdoMapping::Tpdo).pdo(), PdoMapping::Tpdo);
    /// ```
    pub const fn pdo(&self) -> PdoMapping {
        match (self.flags & Self::TPDO != 0, self.flags & Self::RPDO != 0) {
            (false, false) => PdoMapping::No,
            (true, false) => PdoMapping::Tpdo,
            (false, true) => PdoMapping::Rpdo,
            (true, true) => PdoMapping::Both,
        }
    }
}

/// What rows have in common: the data type, the flags ([`Row::READ`] ...) and what kind of row it is (a
/// VAR, an ARRAY of so many elements, a RECORD member). A dictionary lists each shape its rows have once
/// ([`OdData::SHAPES`](super::OdData::SHAPES)).
///
/// ```
/// use canopen_core::od::{data::{Row, Shape}, Access, DataType, PdoMapping};
/// let s = Shape::of(Row::var(7, DataType::Unsigned32, Access::Rw, PdoMapping::Both));
/// assert_eq!((s.data_type, s.flags, s.n), (DataType::Unsigned32, Row::READ | Row::WRITE | Row::TPDO | Row::RPDO, Shape::VAR));
/// assert_eq!(core::mem::size_of::<Shape>(), 3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shape {
    /// [`Row::data_type`].
    pub data_type: DataType,
    /// [`Row::flags`].
    pub flags: u8,
    /// An ARRAY's number of elements (1 to 254), [`Shape::VAR`] for a VAR, 0 for a RECORD member: unlike
    /// [`Row::n`] it tells a VAR from an ARRAY of one element without the sub-index.
    pub n: u8,
}

impl Shape {
    /// [`Shape::n`] of a VAR (no ARRAY has 255 elements: sub-index FFh is not an element).
    pub const VAR: u8 = 0xFF;

    /// The shape of `row`.
    /// ```
    /// use canopen_core::od::{data::{Row, Shape}, Access, DataType, PdoMapping};
    /// let r = Row::array(3, DataType::Integer16, Access::Ro, PdoMapping::No, 1, 4);
    /// assert_eq!(Shape::of(r).n, 4);
    /// let one = Row::array(3, DataType::Integer16, Access::Ro, PdoMapping::No, 1, 1);
    /// assert_eq!(Shape::of(one).n, 1);
    /// ```
    pub const fn of(row: Row) -> Shape {
        let n = if row.sub == 0 && row.n == 1 { Self::VAR } else { row.n };
        Shape { data_type: row.data_type, flags: row.flags, n }
    }

    /// Whether SDO may read rows of this shape.
    /// ```
    /// use canopen_core::od::{data::{Row, Shape}, Access, DataType, PdoMapping};
    /// assert!(!Shape::of(Row::var(0, DataType::Unsigned8, Access::Wo, PdoMapping::No)).readable());
    /// ```
    pub const fn readable(&self) -> bool {
        self.flags & Row::READ != 0
    }

    /// Whether SDO may write rows of this shape.
    /// ```
    /// use canopen_core::od::{data::{Row, Shape}, Access, DataType, PdoMapping};
    /// assert!(Shape::of(Row::var(0, DataType::Unsigned8, Access::Rw, PdoMapping::No)).writable());
    /// ```
    pub const fn writable(&self) -> bool {
        self.flags & Row::WRITE != 0
    }
}

/// A row as [`OdData::ROWS`](super::OdData::ROWS) stores it: the [`Row::field`] and the position of its
/// [`Shape`] in [`OdData::SHAPES`](super::OdData::SHAPES); three bytes (packed: a drive's dictionary has
/// hundreds of rows).
///
/// The sub-index is not stored here. Most dictionaries number their entries the regular way: a VAR at
/// sub 00h, an ARRAY's elements from sub 01h, a RECORD's members 01h, 02h, 03h... in order. Then a row's
/// sub-index follows from its shape and its place in its object, and [`OdData::SUBS`](super::OdData::SUBS)
/// is empty. Otherwise `SUBS` holds every row's.
///
/// ```
/// use canopen_core::od::{data::{PackedRow, Row, Shape}, Access, DataType, PdoMapping};
/// let row = Row::array(12, DataType::Unsigned16, Access::Ro, PdoMapping::Tpdo, 1, 4);
/// let shapes = [Shape::of(row)];
/// let packed = PackedRow { field: 12, shape: 0 };
/// assert_eq!(packed.unpack(&shapes), Some(row)); // an ARRAY of more than one element: from sub 01h
/// assert_eq!(PackedRow { shape: 1, ..packed }.unpack(&shapes), None);
/// assert_eq!(core::mem::size_of::<PackedRow>(), 3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C, packed)]
pub struct PackedRow {
    /// [`Row::field`].
    pub field: u16,
    /// Its [`Shape`]'s position in [`OdData::SHAPES`](super::OdData::SHAPES).
    pub shape: u8,
}

impl PackedRow {
    /// The whole row, with its shape from `shapes` and the sub-index a regularly numbered dictionary gives
    /// it: 00h for a VAR, 01h for an ARRAY, and for a RECORD member 00h, which the caller replaces by the
    /// member's place ([`Row::sub`]); `None` when `shapes` has no such shape.
    #[inline(always)]
    pub fn unpack(self, shapes: &[Shape]) -> Option<Row> {
        let s = shapes.get(usize::from(self.shape))?;
        let (sub, n) = match s.n {
            Shape::VAR => (0, 1),
            n => (u8::from(n != 0), n),
        };
        Some(Row { field: self.field, data_type: s.data_type, flags: s.flags, sub, n })
    }
}

/// Whether any of `shapes` has [`Row::CHECKS`] ([`OdData::CHECKED`](super::OdData::CHECKED), computed at compile
/// time): without, the limits and hooks of a write compile away.
///
/// ```
/// use canopen_core::od::{data::{any_checks, Row, Shape}, Access, DataType, PdoMapping};
/// let plain = Row::var(0, DataType::Unsigned8, Access::Rw, PdoMapping::No);
/// assert!(!any_checks(&[Shape::of(plain)]));
/// assert!(any_checks(&[Shape::of(plain), Shape::of(plain.with(Row::CHECKS))]));
/// ```
pub const fn any_checks(shapes: &[Shape]) -> bool {
    let mut i = 0;
    while i < shapes.len() {
        if shapes[i].flags & Row::CHECKS != 0 {
            return true;
        }
        i += 1;
    }
    false
}
