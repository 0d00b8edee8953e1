// The dictionaries `layouts_agree.rs` and the fuzz target `od_layouts` (fuzz/) compare in their three
// layouts (issue 41): each struct is declared once by a macro and derived as match arms (`Code...`),
// `#[od(compact)]` tables (`Compact...`) and `#[od(compact, zerocopy)]` tables reached by offset
// (`Offset...`). Included by path (`include!`), so both compare the same definitions; the includer brings
// `AbortCode` and the derive into scope.

/// One dictionary with every shape the tables describe: VARs of 1 to 8 bytes, signed and REAL32 limits, an
/// ARRAY, a RECORD with a gap in its sub-indices, ro/wo/const entries and a field with both hooks. Fields
/// are ordered by alignment so that the zerocopy layout has no padding.
macro_rules! dictionary {
    ($name:ident $(, $attr:meta)*) => {
        #[derive(ObjectDictionary, Default, Debug, PartialEq)]
        $(#[$attr])*
        struct $name {
            #[od(index = 0x2008, access = "rw", pdo = "both", min = -5000000000, max = 5000000000, default = -3)]
            wide: i64,
            #[od(index = 0x2000, access = "rw", pdo = "both", default = 0x0102_0304)]
            speed: u32,
            #[od(index = 0x2005, sub = 3, access = "rw", default = 9)]
            rec_c: u32,
            #[od(index = 0x2006, access = "rw", pdo = "rpdo", min = -1.5, max = 2.5, default = 0.5)]
            gain: f32,
            #[od(index = 0x2007, access = "ro", pdo = "tpdo", default = 77)]
            actual: u32,
            #[od(index = 0x2004, sub = 1..=4, access = "rw", pdo = "both", default = 0x1122)]
            table: [u16; 4],
            #[od(index = 0x2005, sub = 1, record = "Mixed", access = "rw", count_access = "ro", default = 2)]
            rec_a: u16,
            #[od(index = 0x2001, access = "rww", pdo = "both", min = -100, max = 100, check = "not_13", on_write = "count")]
            offset: i16,
            #[od(index = 0x2002, access = "wo", pdo = "rpdo")]
            command: u16,
            #[od(index = 0x2003, access = "const", default = 5)]
            version: u8,
            /// Not in the dictionary: how often `offset` was written (its `on_write`).
            writes: u8,
        }

        impl Writes for $name {
            fn writes(&self) -> u8 {
                self.writes
            }
        }

        impl $name {
            fn not_13(&self, _sub: u8, v: &i16) -> Result<(), AbortCode> {
                if *v == 13 { Err(AbortCode::InvalidValue) } else { Ok(()) }
            }
            fn count(&mut self, _sub: u8) {
                self.writes = self.writes.wrapping_add(1);
            }
        }
    };
}
dictionary!(Code);
dictionary!(Compact, od(compact));
dictionary!(
    Offsets,
    od(compact, zerocopy),
    derive(zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable),
    repr(C)
);

/// A dictionary of RECORDs with more than two members on average: the derive gives it a key per object and
/// `FIRST_ROWS` (where each object's rows start) instead of a key per row. Gaps in the sub-indices, a
/// `ro` count, a hook on a member, and a VAR and an ARRAY between the RECORDs.
macro_rules! records {
    ($name:ident $(, $attr:meta)*) => {
        #[derive(ObjectDictionary, Default, Debug, PartialEq)]
        $(#[$attr])*
        struct $name {
            #[od(index = 0x2000, access = "rw", pdo = "both", default = 0x0102_0304)]
            speed: u32,
            #[od(index = 0x2002, sub = 1, record = "Axis", access = "rw", pdo = "both", default = 7)]
            axis_a: u32,
            #[od(index = 0x2002, sub = 2, access = "ro", pdo = "tpdo", default = 8)]
            axis_b: u32,
            #[od(index = 0x2002, sub = 5, access = "wo", pdo = "rpdo")]
            axis_e: u32,
            #[od(index = 0x2004, sub = 1, record = "Limits", access = "rw", count_access = "ro", min = -10, max = 10, on_write = "count")]
            lim_a: i32,
            #[od(index = 0x2004, sub = 2, access = "rw", default = -3)]
            lim_b: i32,
            #[od(index = 0x2004, sub = 3, access = "const", default = 1)]
            lim_c: u32,
            #[od(index = 0x2003, sub = 1..=3, access = "rw", pdo = "both", default = 0x1122)]
            table: [u16; 3],
            #[od(index = 0x2006, sub = 2, record = "Pair", access = "rw", default = 5)]
            pair_b: u16,
            #[od(index = 0x2006, sub = 4, access = "rw", default = 6)]
            pair_d: u16,
            #[od(index = 0x2006, sub = 6, access = "rw")]
            pair_f: u16,
            #[od(index = 0x2006, sub = 1, access = "ro", default = 4)]
            pair_a: u8,
            /// Not in the dictionary: how often `lim_a` was written (its `on_write`).
            writes: u8,
            /// Not in the dictionary: the tail a `repr(C)` struct would pad.
            spare: [u8; 2],
        }

        impl Writes for $name {
            fn writes(&self) -> u8 {
                self.writes
            }
        }

        impl $name {
            fn count(&mut self, _sub: u8) {
                self.writes = self.writes.wrapping_add(1);
            }
        }
    };
}
records!(CodeRecords);
records!(CompactRecords, od(compact));
records!(
    OffsetRecords,
    od(compact, zerocopy),
    derive(zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable),
    repr(C)
);

/// Regularly numbered dictionaries (a VAR at sub 00h, ARRAYs from 01h, RECORD members 01h, 02h... in
/// order): the derive stores no sub-index (`SUBS` is empty) and the tables infer it from a row's shape and
/// place. Here a key per row (one RECORD of two members), in `regular_records!` a key per object; an ARRAY
/// of one element beside a VAR, a hooked and limited member, and PDO-mappable members reached through
/// their handles.
macro_rules! regular {
    ($name:ident $(, $attr:meta)*) => {
        #[derive(ObjectDictionary, Default, Debug, PartialEq)]
        $(#[$attr])*
        struct $name {
            #[od(index = 0x2000, access = "rw", pdo = "both", default = 0x0102_0304)]
            speed: u32,
            #[od(index = 0x2001, sub = 1..=1, access = "rw", pdo = "both", default = 3)]
            single: [u32; 1],
            #[od(index = 0x2002, sub = 1, record = "Axis", access = "rw", pdo = "both", min = -10, max = 10, on_write = "count")]
            axis_a: i32,
            #[od(index = 0x2002, sub = 2, access = "ro", pdo = "tpdo", default = 8)]
            axis_b: u32,
            #[od(index = 0x2003, sub = 1..=3, access = "rw", pdo = "both", default = 0x1122)]
            table: [u16; 3],
            #[od(index = 0x2008, access = "wo", pdo = "rpdo")]
            command: u16,
            /// Not in the dictionary: how often `axis_a` was written (its `on_write`).
            writes: u8,
            /// Not in the dictionary: the tail a `repr(C)` struct would pad.
            spare: [u8; 3],
        }

        impl Writes for $name {
            fn writes(&self) -> u8 {
                self.writes
            }
        }

        impl $name {
            fn count(&mut self, _sub: u8) {
                self.writes = self.writes.wrapping_add(1);
            }
        }
    };
}
/// [`regular!`] with the RECORDs that give it a key per object (written out: the code the derive writes
/// for a field must see the struct's own tokens, so fields cannot be handed from one macro to another).
macro_rules! regular_records {
    ($name:ident $(, $attr:meta)*) => {
        #[derive(ObjectDictionary, Default, Debug, PartialEq)]
        $(#[$attr])*
        struct $name {
            #[od(index = 0x2000, access = "rw", pdo = "both", default = 0x0102_0304)]
            speed: u32,
            #[od(index = 0x2001, sub = 1..=1, access = "rw", pdo = "both", default = 3)]
            single: [u32; 1],
            #[od(index = 0x2002, sub = 1, record = "Axis", access = "rw", pdo = "both", min = -10, max = 10, on_write = "count")]
            axis_a: i32,
            #[od(index = 0x2002, sub = 2, access = "ro", pdo = "tpdo", default = 8)]
            axis_b: u32,
            #[od(index = 0x2004, sub = 1, record = "Limits", access = "rw", pdo = "both", min = -10, max = 10)]
            lim_a: i32,
            #[od(index = 0x2004, sub = 2, access = "rw", pdo = "both", min = -3, max = 3, default = -3)]
            lim_b: i32,
            #[od(index = 0x2004, sub = 3, access = "const", default = 1)]
            lim_c: u32,
            #[od(index = 0x2006, sub = 1, record = "Seven", access = "ro", count_access = "ro", pdo = "tpdo", default = 4)]
            seven_a: u32,
            #[od(index = 0x2006, sub = 2, access = "wo", pdo = "rpdo")]
            seven_b: u32,
            #[od(index = 0x2006, sub = 3, access = "rw", default = 6)]
            seven_c: u32,
            #[od(index = 0x2006, sub = 4, access = "rw", pdo = "both", default = 9)]
            seven_d: u32,
            #[od(index = 0x2006, sub = 5, access = "rw", pdo = "both")]
            seven_e: u32,
            #[od(index = 0x2006, sub = 6, access = "ro", default = 12)]
            seven_f: u32,
            #[od(index = 0x2006, sub = 7, access = "rw", min = -3, max = 3, default = 2)]
            seven_g: i32,
            #[od(index = 0x2003, sub = 1..=3, access = "rw", pdo = "both", default = 0x1122)]
            table: [u16; 3],
            #[od(index = 0x2008, access = "wo", pdo = "rpdo")]
            command: u16,
            /// Not in the dictionary: how often `axis_a` was written (its `on_write`).
            writes: u8,
            /// Not in the dictionary: the tail a `repr(C)` struct would pad.
            spare: [u8; 3],
        }

        impl Writes for $name {
            fn writes(&self) -> u8 {
                self.writes
            }
        }

        impl $name {
            fn count(&mut self, _sub: u8) {
                self.writes = self.writes.wrapping_add(1);
            }
        }
    };
}
regular!(CodeRegular);
regular!(CompactRegular, od(compact));
regular!(
    OffsetRegular,
    od(compact, zerocopy),
    derive(zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable),
    repr(C)
);
regular_records!(CodeRegularRecords);
regular_records!(CompactRegularRecords, od(compact));
regular_records!(
    OffsetRegularRecords,
    od(compact, zerocopy),
    derive(zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable),
    repr(C)
);

/// What a dictionary's `on_write` hook counted.
trait Writes {
    fn writes(&self) -> u8;
}

/// Values at and beside the dictionaries' limits and the hook's refusal (random bytes seldom hit them), in
/// each limited field's encoding: INTEGER16 -100..100 and not 13, INTEGER32 -10..10 and -3..3, INTEGER64
/// -5,000,000,000..5,000,000,000, REAL32 -1.5..2.5 (with -0, NaN and infinity).
fn edges() -> Vec<Vec<u8>> {
    let mut edges: Vec<Vec<u8>> = Vec::new();
    for v in [-101i16, -100, -99, 12, 13, 14, 99, 100, 101] {
        edges.push(v.to_le_bytes().to_vec());
    }
    for v in [-11i32, -10, -4, -3, 3, 4, 10, 11] {
        edges.push(v.to_le_bytes().to_vec());
    }
    for v in [-5_000_000_001i64, -5_000_000_000, -4_999_999_999, 4_999_999_999, 5_000_000_000, 5_000_000_001] {
        edges.push(v.to_le_bytes().to_vec());
    }
    let up = |x: f32| f32::from_bits(x.to_bits() + 1);
    for v in [-1.5f32, up(-1.5), -1.4999999, 2.5, up(2.5), 2.4999998, -0.0, f32::NAN, f32::INFINITY] {
        edges.push(v.to_le_bytes().to_vec());
    }
    edges
}
