//! What the derive emits for the SDO, PDO and Reset Application paths: the dictionary as data
//! (`canopen_core::od::data`). Per object only table rows and defaults; per field one arm in the
//! accessor of its type (`&self` and `&mut self`); per string or DOMAIN and per hook a few arms more.
//! The `ObjectDictionary` impl is a forwarder to the core's generic functions.

use proc_macro2::{Literal, Span, TokenStream as Ts};
use quote::{format_ident, quote, quote_spanned};
use syn::{Ident, Type};

use crate::ConstLit;

/// How a field's value is reached.
pub(crate) enum Kind {
    /// A fixed-size value (its element type): through the accessors of its data type.
    Fixed(Type),
    /// A string (its type): per-field arms.
    Text(Type),
    /// A DOMAIN: per-field arms calling its `Domain` implementation.
    Domain,
}

/// One row of the data table: a VAR, an ARRAY or a RECORD member (see `canopen_core::od::data::Row`).
pub(crate) struct DataField {
    pub index: u16,
    /// VAR: 0; ARRAY: first element's sub-index; RECORD member: its sub-index.
    pub sub: u8,
    /// ARRAY: number of elements; VAR: 1; RECORD member: 0.
    pub n: u8,
    pub dt: &'static str,
    pub kind: Kind,
    pub access: Ts,
    pub pdo: Ts,
    pub writable: bool,
    pub mapped: bool,
    pub count_ro: bool,
    pub check: Option<Ident>,
    pub on_write: Option<Ident>,
    pub min: Option<ConstLit>,
    pub max: Option<ConstLit>,
    pub default: Option<ConstLit>,
    pub default_ts: Ts,
    pub member: Ident,
}

impl DataField {
    fn is_array(&self) -> bool {
        self.sub != 0 && self.n != 0
    }

    /// Whether it has a `min` or `max` (strings cannot: the attribute check refuses them).
    fn has_limits(&self) -> bool {
        self.min.is_some() || self.max.is_some()
    }
}

/// The accessor name stem of a data type: `Unsigned32` → `unsigned32`, `TimeOfDay` → `time_of_day`.
fn stem(dt: &str) -> String {
    crate::spec_name(dt).to_ascii_lowercase()
}

/// The Rust type the core's accessor of `dt` returns.
fn core_type(core: &Ts, dt: &str) -> Ts {
    match dt {
        "Boolean" => quote!(bool),
        "Integer8" => quote!(i8),
        "Integer16" => quote!(i16),
        "Integer32" => quote!(i32),
        "Integer64" => quote!(i64),
        "Unsigned8" => quote!(u8),
        "Unsigned16" => quote!(u16),
        "Unsigned32" => quote!(u32),
        "Unsigned64" => quote!(u64),
        "Real32" => quote!(f32),
        "Real64" => quote!(f64),
        "Integer24" => quote!(#core::od::I24),
        "Integer40" => quote!(#core::od::I40),
        "Integer48" => quote!(#core::od::I48),
        "Integer56" => quote!(#core::od::I56),
        "Unsigned24" => quote!(#core::od::U24),
        "Unsigned40" => quote!(#core::od::U40),
        "Unsigned48" => quote!(#core::od::U48),
        "Unsigned56" => quote!(#core::od::U56),
        "TimeOfDay" => quote!(#core::od::TimeOfDay),
        _ => quote!(#core::od::TimeDifference),
    }
}

/// The encoded size and DT-17 code of a fixed-size data type.
fn size_and_code(dt: &str) -> (usize, usize) {
    match dt {
        "Boolean" => (1, 0x01),
        "Integer8" => (1, 0x02),
        "Integer16" => (2, 0x03),
        "Integer32" => (4, 0x04),
        "Unsigned8" => (1, 0x05),
        "Unsigned16" => (2, 0x06),
        "Unsigned32" => (4, 0x07),
        "Real32" => (4, 0x08),
        "TimeOfDay" => (6, 0x0C),
        "TimeDifference" => (6, 0x0D),
        "Integer24" => (3, 0x10),
        "Real64" => (8, 0x11),
        "Integer40" => (5, 0x12),
        "Integer48" => (6, 0x13),
        "Integer56" => (7, 0x14),
        "Integer64" => (8, 0x15),
        "Unsigned24" => (3, 0x16),
        "Unsigned40" => (5, 0x18),
        "Unsigned48" => (6, 0x19),
        "Unsigned56" => (7, 0x1A),
        _ => (8, 0x1B),
    }
}

/// A default's little-endian bytes in its type's size (zeros without one): what `restore_defaults` decodes.
fn default_bytes(dt: &str, size: usize, lit: Option<&ConstLit>) -> Vec<u8> {
    let wide: [u8; 16] = match (dt, lit) {
        (_, None) => [0; 16],
        ("Real32", Some(l)) => u128::from((l.as_f64().unwrap_or(0.0) as f32).to_bits()).to_le_bytes(),
        ("Real64", Some(l)) => u128::from(l.as_f64().unwrap_or(0.0).to_bits()).to_le_bytes(),
        (_, Some(ConstLit::Bool(b))) => u128::from(*b).to_le_bytes(),
        ("Boolean", Some(ConstLit::Int(i))) => u128::from(*i != 0).to_le_bytes(),
        (_, Some(ConstLit::Int(i))) => i.to_le_bytes(),
        _ => [0; 16],
    };
    wide[..size].to_vec()
}

/// A default's bytes in `OdData::DEFAULTS` (the core's `od::data::restore_defaults` reads them): LEB128 of
/// its little-endian bytes `le` read as a number, a signed integer zigzag-encoded first (sign-extended from
/// its width), so a small default takes one byte whatever the type (a REAL or TIME value: its bits).
fn encode_default(dt: &str, le: &[u8]) -> Vec<u8> {
    let mut raw = [0u8; 8];
    raw[..le.len()].copy_from_slice(le);
    let mut v = u64::from_le_bytes(raw);
    if dt.starts_with("Integer") {
        let shift = 64 - 8 * le.len() as u32;
        let s = ((v << shift) as i64) >> shift;
        v = ((s << 1) ^ (s >> 63)) as u64;
    }
    let mut out = Vec::new();
    loop {
        let b = (v & 0x7F) as u8;
        v >>= 7;
        if v == 0 {
            out.push(b);
            return out;
        }
        out.push(b | 0x80);
    }
}

/// The lowest (`high` false) or highest value of a fixed-size data type: the limit of a side without one.
fn extreme(dt: &str, high: bool) -> ConstLit {
    let bits = size_and_code(dt).0 as u32 * 8;
    match dt {
        "Real32" | "Real64" => ConstLit::Float(if high { f64::INFINITY } else { f64::NEG_INFINITY }),
        "Boolean" => ConstLit::Bool(high),
        _ if dt.starts_with("Integer") => {
            ConstLit::Int(if high { (1i128 << (bits - 1)) - 1 } else { -(1i128 << (bits - 1)) })
        }
        _ => ConstLit::Int(if high { (1i128 << bits) - 1 } else { 0 }),
    }
}

/// `Some(&self.m)` for a VAR or record member, `self.m.get(e)` for an element of an ARRAY of strings.
fn place(f: &DataField, mutable: bool) -> Ts {
    let m = &f.member;
    match (f.is_array(), mutable) {
        (false, false) => quote!(::core::option::Option::Some(&self.#m)),
        (false, true) => quote!(::core::option::Option::Some(&mut self.#m)),
        (true, false) => quote!(self.#m.get(usize::from(elem))),
        (true, true) => quote!(self.#m.get_mut(usize::from(elem))),
    }
}

/// `impl OdData` and the forwarding `impl ObjectDictionary`.
///
/// `by_offset` (`#[od(compact, zerocopy)]`): a fixed-size row's `field` is the member's `offset_of!` and
/// no accessor is emitted; the struct's byte view (zerocopy) reaches every fixed-size value.
pub(crate) fn data_impl(
    core: &Ts,
    ident: &Ident,
    mut fields: Vec<DataField>,
    write_events: bool,
    by_offset: bool,
) -> Ts {
    fields.sort_by_key(|f| (f.index, f.sub));
    // Sub 00h of a RECORD is `ro` when any member says so; the row the search lands on is the first.
    let ro_records: Vec<u16> = fields.iter().filter(|f| f.n == 0 && f.count_ro).map(|f| f.index).collect();
    for f in fields.iter_mut().filter(|f| f.n == 0 && ro_records.contains(&f.index)) {
        f.count_ro = true;
    }

    // Field numbers: per fixed data type its VARs and record members first, then its ARRAYs, each in
    // row order, so every accessor's `match` is a dense jump table; strings and DOMAINs in row order.
    let mut dts: Vec<&'static str> = Vec::new();
    for f in fields.iter().filter(|f| matches!(f.kind, Kind::Fixed(_))) {
        if !dts.contains(&f.dt) {
            dts.push(f.dt);
        }
    }
    dts.sort_by_key(|dt| size_and_code(dt).1);
    let mut number = vec![0u16; fields.len()];
    let mut accessors = Vec::new();
    for dt in dts.iter().filter(|_| !by_offset) {
        let of_type = |array: bool| {
            fields.iter().enumerate().filter(move |(_, f)| f.dt == *dt && f.is_array() == array).map(|(i, _)| i)
        };
        let order: Vec<usize> = of_type(false).chain(of_type(true)).collect();
        let (mut var, mut var_mut, mut arr, mut arr_mut) = (vec![], vec![], vec![], vec![]);
        for (k, &i) in order.iter().enumerate() {
            let f = &fields[i];
            number[i] = k as u16;
            let (m, k) = (&f.member, k as u16);
            if f.is_array() {
                arr.push(quote!(#k => ::core::option::Option::Some(&self.#m[..]),));
                arr_mut.push(quote!(#k => ::core::option::Option::Some(&mut self.#m[..]),));
            } else {
                var.push(quote!(#k => ::core::option::Option::Some(&self.#m),));
                var_mut.push(quote!(#k => ::core::option::Option::Some(&mut self.#m),));
            }
        }
        let t = core_type(core, dt);
        let s = stem(dt);
        let (v, vm, a, am) = (
            format_ident!("var_{s}"),
            format_ident!("var_{s}_mut"),
            format_ident!("array_{s}"),
            format_ident!("array_{s}_mut"),
        );
        if !var.is_empty() {
            accessors.push(quote! {
                #[inline]
                fn #v(&self, field: u16) -> ::core::option::Option<&#t> {
                    match field { #(#var)* _ => ::core::option::Option::None }
                }
                #[inline]
                fn #vm(&mut self, field: u16) -> ::core::option::Option<&mut #t> {
                    match field { #(#var_mut)* _ => ::core::option::Option::None }
                }
            });
        }
        if !arr.is_empty() {
            accessors.push(quote! {
                #[inline]
                fn #a(&self, field: u16) -> ::core::option::Option<&[#t]> {
                    match field { #(#arr)* _ => ::core::option::Option::None }
                }
                #[inline]
                fn #am(&mut self, field: u16) -> ::core::option::Option<&mut [#t]> {
                    match field { #(#arr_mut)* _ => ::core::option::Option::None }
                }
            });
        }
    }
    let mut special = 0u16;
    for (i, f) in fields.iter().enumerate() {
        if !matches!(f.kind, Kind::Fixed(_)) {
            number[i] = special;
            special += 1;
        }
    }

    // The defaults of the fixed-size rows, in row order (Reset Application walks the rows).
    let mut defaults: Vec<u8> = Vec::new();
    let mut defaulted = vec![0u8; fields.len().div_ceil(8)];
    for (pos, f) in fields.iter().enumerate().filter(|(_, f)| matches!(f.kind, Kind::Fixed(_))) {
        let size = size_and_code(f.dt).0;
        let bytes = default_bytes(f.dt, size, f.default.as_ref());
        if bytes.iter().any(|&b| b != 0) {
            defaults.extend(encode_default(f.dt, &bytes));
            defaulted[pos / 8] |= 1 << (pos % 8);
        }
    }

    // A key per row, or a key per object and where its rows start: one byte per object (and one), the rows
    // before it beyond one per object modulo 256, and the objects where that passes a multiple of 256
    // (`canopen_core::od::data::search::rows_of`). Whichever is smaller, so only RECORDs of more than
    // two members on average pay for the second table.
    let mut keys: Vec<u16> = Vec::new();
    let mut first_rows: Vec<u8> = Vec::new();
    let mut wraps: Vec<u16> = Vec::new();
    let mut start = |k: usize, pos: usize, first_rows: &mut Vec<u8>| {
        let extra = pos - k;
        while wraps.len() < extra / 256 {
            wraps.push(k as u16);
        }
        first_rows.push((extra % 256) as u8);
    };
    for (pos, f) in fields.iter().enumerate() {
        if keys.last() != Some(&f.index) {
            start(keys.len(), pos, &mut first_rows);
            keys.push(f.index);
        }
    }
    start(keys.len(), fields.len(), &mut first_rows);
    if 2 * keys.len() + first_rows.len() + 2 * wraps.len() >= 2 * fields.len() {
        keys = fields.iter().map(|f| f.index).collect();
        first_rows.clear();
        wraps.clear();
    }
    // The sub-indices: none when the numbering is regular (what `PackedRow::unpack` and `find_member`
    // infer: a VAR at 0, an ARRAY from 1, a RECORD's members 1, 2, 3... in order),
    // else one per row.
    let regular = fields.iter().enumerate().all(|(pos, f)| {
        let place = fields[..pos].iter().rev().take_while(|g| g.index == f.index).count();
        match (f.sub, f.n) {
            (_, 0) => usize::from(f.sub) == place + 1,
            (0, _) => true,
            (first, _) => first == 1,
        }
    });
    let subs: Vec<u8> = if regular { Vec::new() } else { fields.iter().map(|f| f.sub).collect() };
    // Each row's shape (data type, flags, count and, for a fixed-size value with limits, its limit values),
    // listed once in SHAPES: first the shapes with limits, then the others, each in the order first met; a
    // row names its shape by position, and LIMITS says where each limited shape's values start.
    struct ShapeOf {
        key: String,
        shape: Ts,
        limits: Option<Vec<u8>>,
    }
    let mut found: Vec<ShapeOf> = Vec::new();
    let mut row_shape: Vec<usize> = Vec::new();
    for f in &fields {
        let dt = Ident::new(f.dt, Span::call_site());
        let (access, pdo) = (&f.access, &f.pdo);
        // Shape::n: a VAR is FFh (no ARRAY has 255 elements), so its shape tells it from an ARRAY of one.
        let n = if f.sub == 0 && f.n == 1 { 0xFF } else { f.n };
        let mut extra = Vec::new();
        if f.count_ro {
            extra.push(quote!(#core::od::data::Row::COUNT_RO));
        }
        if matches!(f.kind, Kind::Fixed(_)) && (f.has_limits() || f.check.is_some() || f.on_write.is_some()) {
            extra.push(quote!(#core::od::data::Row::CHECKS));
        }
        let limits = (f.has_limits() && matches!(f.kind, Kind::Fixed(_))).then(|| {
            let size = size_and_code(f.dt).0;
            let mut v = default_bytes(f.dt, size, Some(f.min.as_ref().unwrap_or(&extreme(f.dt, false))));
            v.extend(default_bytes(f.dt, size, Some(f.max.as_ref().unwrap_or(&extreme(f.dt, true)))));
            v
        });
        let flags = quote!(#core::od::data::Row::flags(#access, #pdo) #(| #extra)*);
        let key = format!("{} {} {} {:?}", f.dt, flags, n, limits);
        let i = found.iter().position(|s| s.key == key).unwrap_or_else(|| {
            let shape = quote!(#core::od::data::Shape { data_type: #core::od::DataType::#dt, flags: #flags, n: #n });
            found.push(ShapeOf { key, shape, limits });
            found.len() - 1
        });
        row_shape.push(i);
    }
    let mut order: Vec<usize> = (0..found.len()).collect();
    order.sort_by_key(|&i| found[i].limits.is_none()); // stable: first met within each group
    let mut place = vec![0usize; found.len()];
    for (to, &from) in order.iter().enumerate() {
        place[from] = to;
    }
    let shapes: Vec<&Ts> = order.iter().map(|&i| &found[i].shape).collect();
    let mut limit_values: Vec<u8> = Vec::new();
    let mut limits: Vec<u16> = Vec::new();
    // Shapes that differ only in access or flags often share their limit values: such values are stored
    // once (any run of bytes already there that equals them will do).
    for v in order.iter().filter_map(|&i| found[i].limits.as_ref()) {
        match limit_values.windows(v.len()).position(|w| w == v.as_slice()) {
            Some(at) => limits.push(at as u16),
            None => {
                limits.push(limit_values.len() as u16);
                limit_values.extend(v);
            }
        }
    }
    if shapes.len() > 256 {
        return quote!(::core::compile_error!(
            "#[od(compact)]: more than 256 shapes of entries (data type, access, PDO mapping, count, limits); use the default layout"
        ););
    }
    let mut rows: Vec<Ts> = Vec::new();
    for ((f, &num), &shape) in fields.iter().zip(&number).zip(&row_shape) {
        let member = &f.member;
        let num = match f.kind {
            Kind::Fixed(_) if by_offset => quote!(::core::mem::offset_of!(#ident, #member) as u16),
            _ => quote!(#num),
        };
        let shape = place[shape] as u8;
        rows.push(quote!(#core::od::data::PackedRow { field: #num, shape: #shape }));
    }
    let defaults = defaults.iter().map(|b| Literal::u8_unsuffixed(*b));
    let defaulted = defaulted.iter().map(|b| Literal::u8_unsuffixed(*b));
    let limit_values = limit_values.iter().map(|b| Literal::u8_unsuffixed(*b));

    // The byte view: zerocopy's traits on the struct (the user derives them) prove it sound, and offsets
    // must fit a row's u16.
    let by_offset_items = by_offset.then(|| {
        quote! {
            const BY_OFFSET: bool = true;
            #[inline(always)]
            fn bytes(&self) -> &[u8] {
                #core::od::data::as_bytes(self)
            }
            #[inline(always)]
            fn bytes_mut(&mut self) -> &mut [u8] {
                #core::od::data::as_bytes_mut(self)
            }
        }
    });
    let offset_assert = by_offset.then(|| {
        quote! {
            const _: () = assert!(
                ::core::mem::size_of::<#ident>() <= u16::MAX as usize,
                "#[od(compact, zerocopy)]: a dictionary struct of more than 65,535 bytes"
            );
            // A PDO handle's row slot is the row's position with bit 15 set, and 7FFFh is what the
            // slot of no row (FFFFh) leaves: every position must stay below it.
            const _: () = assert!(
                <#ident as #core::od::data::OdData>::ROWS.len() < 0x7FFF,
                "#[od(compact, zerocopy)]: more than 32,766 rows (VARs, ARRAYs and RECORD members)"
            );
        }
    });
    let hooks = hook_fns(core, &fields);
    let specials = special_fns(core, &fields, &number);

    quote! {
        #[automatically_derived]
        impl #core::od::data::OdData for #ident {
            const KEYS: &'static [u16] = &[#(#keys),*];
            const ROWS: &'static [#core::od::data::PackedRow] = &[#(#rows),*];
            const SHAPES: &'static [#core::od::data::Shape] = &[#(#shapes),*];
            const FIRST_ROWS: &'static [u8] = &[#(#first_rows),*];
            const FIRST_ROW_WRAPS: &'static [u16] = &[#(#wraps),*];
            const SUBS: &'static [u8] = &[#(#subs),*];
            const DEFAULTS: &'static [u8] = &[#(#defaults),*];
            const DEFAULTED: &'static [u8] = &[#(#defaulted),*];
            #by_offset_items
            const LIMITS: &'static [u16] = &[#(#limits),*];
            const LIMIT_VALUES: &'static [u8] = &[#(#limit_values),*];
            #hooks
            #specials
            #(#accessors)*
        }

        const _: () = assert!({
            let d = <#ident as #core::od::data::OdData>::FIRST_ROWS.len();
            d == 0 || d == <#ident as #core::od::data::OdData>::KEYS.len() + 1
        });
        const _: () = assert!({
            let s = <#ident as #core::od::data::OdData>::SUBS.len();
            s == 0 || s == <#ident as #core::od::data::OdData>::ROWS.len()
        });
        // Row positions are u16 (FIRST_ROWS, the positions `find` and PDO handles carry).
        const _: () = assert!(
            <#ident as #core::od::data::OdData>::ROWS.len() <= u16::MAX as usize,
            "#[od(compact)]: more than 65,535 rows (VARs, ARRAYs and RECORD members)"
        );
        #offset_assert

        #[automatically_derived]
        impl #core::od::ObjectDictionary for #ident {
            /// Whether a writable string or DOMAIN takes streamed writes.
            const STREAMS: bool = #core::od::data::streams(<Self as #core::od::data::OdData>::SHAPES);
            /// Whether a readable entry's type has no fixed size of 1..=4 bytes (a string, a DOMAIN, a
            /// 64-bit value), so that an upload of it is segmented.
            const SEGMENTED_UPLOADS: bool =
                #core::od::data::segmented_uploads(<Self as #core::od::data::OdData>::SHAPES);

            #[inline]
            fn info(&self, index: u16, sub: u8) -> ::core::result::Result<#core::od::SubInfo, __AbortCode> {
                #core::od::data::info(self, index, sub)
            }
            #[inline]
            fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> ::core::result::Result<usize, __AbortCode> {
                #core::od::data::read(self, index, sub, offset, buf)
            }
            #[inline]
            fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                #core::od::data::write(self, index, sub, data)
            }
            #[inline]
            fn begin_write(&mut self, index: u16, sub: u8, size: ::core::option::Option<usize>) -> ::core::result::Result<(), __AbortCode> {
                #core::od::data::begin_write(self, index, sub, size)
            }
            #[inline]
            fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                #core::od::data::write_chunk(self, index, sub, offset, data)
            }
            #[inline]
            fn end_write(&mut self, index: u16, sub: u8, total: usize) -> ::core::result::Result<(), __AbortCode> {
                #core::od::data::end_write(self, index, sub, total)
            }
            #[inline]
            fn abort_write(&mut self, index: u16, sub: u8) {
                #core::od::data::abort_write(self, index, sub)
            }
            /// NMT-04 Reset Application: every entry gets its `default` (or the type's default when none
            /// is given); DOMAIN fields and fields without `#[od]` are left alone.
            fn restore_defaults(&mut self) {
                #core::od::data::restore_defaults(self)
            }
            #[inline]
            fn write_events(&self) -> bool {
                #write_events
            }
            #[inline]
            fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> ::core::result::Result<(usize, usize), __AbortCode> {
                #core::od::data::read_expedited(self, index, sub, buf)
            }
            #[inline]
            fn write_expedited(&mut self, index: u16, sub: u8, data: &[u8; 4], len: ::core::option::Option<usize>) -> ::core::result::Result<(), __AbortCode> {
                #core::od::data::write_expedited(self, index, sub, data, len)
            }
            #[inline]
            fn slot(&self, index: u16, sub: u8) -> u16 {
                #core::od::data::slot(self, index, sub)
            }
            #[inline]
            fn read_slot(&self, index: u16, sub: u8, slot: u16, offset: usize, buf: &mut [u8]) -> ::core::result::Result<(), __AbortCode> {
                #core::od::data::read_slot(self, index, sub, slot, offset, buf)
            }
            #[inline]
            fn pdo_resolve(&self, index: u16, sub: u8, dir: #core::od::PdoDir) -> ::core::result::Result<#core::od::PdoHandle, __AbortCode> {
                #core::od::data::pdo_resolve(self, index, sub, dir)
            }
            #[inline(always)]
            fn pdo_read(&self, handle: &#core::od::PdoHandle, buf: &mut [u8]) -> ::core::result::Result<usize, __AbortCode> {
                #core::od::data::pdo_read(self, handle, buf)
            }
            #[inline]
            fn pdo_write(&mut self, handle: &#core::od::PdoHandle, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                #core::od::data::pdo_write(self, handle, data)
            }
        }
    }
}

/// `OdData::check`/`on_write`: an arm per fixed-size row with a hook (strings call theirs in their own
/// arms). None at all without hooks: the trait's defaults answer.
fn hook_fns(core: &Ts, fields: &[DataField]) -> Ts {
    let mut checks = Vec::new();
    let mut writes = Vec::new();
    for (pos, f) in fields.iter().enumerate() {
        let Kind::Fixed(ty) = &f.kind else { continue };
        let pos = pos as u16;
        if let Some(c) = &f.check {
            checks.push(quote_spanned! {c.span()=>
                #pos => {
                    let v = <#ty as #core::od::OdValue>::decode(data)?;
                    self.#c(sub, &v)
                }
            });
        }
        if let Some(c) = &f.on_write {
            writes.push(quote_spanned!(c.span()=> #pos => self.#c(sub),));
        }
    }
    let check = (!checks.is_empty()).then(|| {
        quote! {
            fn check(&self, row: u16, sub: u8, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                match row { #(#checks)* _ => ::core::result::Result::Ok(()) }
            }
        }
    });
    let on_write = (!writes.is_empty()).then(|| {
        quote! {
            fn on_write(&mut self, row: u16, sub: u8) {
                match row { #(#writes)* _ => {} }
            }
        }
    });
    quote!(#check #on_write)
}

/// `OdData::special_*`: the arms of the strings and DOMAINs (variable size, streamed by SDO).
fn special_fns(core: &Ts, fields: &[DataField], number: &[u16]) -> Ts {
    let (mut size, mut map, mut read, mut write) = (vec![], vec![], vec![], vec![]);
    let (mut begin, mut chunk, mut end, mut abort, mut restore) = (vec![], vec![], vec![], vec![], vec![]);
    let none = quote!(::core::option::Option::None);
    let no_sub = quote!(return ::core::result::Result::Err(__AbortCode::SubIndexDoesNotExist));
    for (f, &k) in fields.iter().zip(number) {
        let (r, w) = (place(f, false), place(f, true));
        match &f.kind {
            Kind::Fixed(_) => continue,
            Kind::Text(ty) => {
                let value = quote!(#core::od::OdValue);
                size.push(quote!(#k => match #r { ::core::option::Option::Some(v) => #value::size(v), #none => 0 },));
                if f.mapped {
                    map.push(quote!(#k => <#ty as #value>::MAX_SIZE,));
                }
                read.push(quote! {
                    #k => match #r { ::core::option::Option::Some(v) => ::core::result::Result::Ok(#value::read_bytes(v, offset, buf)), #none => #no_sub },
                });
                let m = &f.member;
                let default = &f.default_ts;
                let restored = quote!((#default).as_ref().and_then(<#ty as #value>::from_value).unwrap_or_default());
                restore.push(if f.is_array() {
                    quote!(for v in self.#m.iter_mut() { *v = #restored; })
                } else {
                    quote!(self.#m = #restored;)
                });
                if !f.writable {
                    continue;
                }
                let check_call = f.check.as_ref().map(|c| quote_spanned!(c.span()=> self.#c(sub, &v)?;));
                let on_write_call = f.on_write.as_ref().map(|c| quote_spanned!(c.span()=> self.#c(sub);));
                let store = quote! {
                    #check_call
                    match #w { ::core::option::Option::Some(p) => *p = v, #none => #no_sub }
                    #on_write_call
                    ::core::result::Result::Ok(())
                };
                write.push(quote!(#k => { let v = <#ty as #value>::decode(data)?; #store }));
                begin.push(quote!(#k => match #w { ::core::option::Option::Some(p) => #value::begin_stream(p, size), #none => #no_sub },));
                chunk.push(quote!(#k => match #w { ::core::option::Option::Some(p) => #value::stream_chunk(p, offset, data), #none => #no_sub },));
                end.push(quote! {
                    #k => {
                        let v = match #r { ::core::option::Option::Some(p) => #value::end_stream(p, total)?, #none => #no_sub };
                        #store
                    }
                });
            }
            Kind::Domain => {
                let domain = quote!(#core::od::Domain);
                let m = &f.member;
                size.push(quote!(#k => #domain::size(&self.#m).unwrap_or(0),));
                if f.mapped {
                    map.push(quote!(#k => #domain::size(&self.#m).unwrap_or(0),));
                }
                read.push(quote!(#k => #domain::read(&self.#m, offset, buf),));
                if !f.writable {
                    continue;
                }
                write.push(quote! {
                    #k => {
                        #domain::begin_write(&mut self.#m, ::core::option::Option::Some(data.len()))?;
                        if let ::core::result::Result::Err(e) = #domain::write_chunk(&mut self.#m, 0, data) {
                            #domain::abort_write(&mut self.#m);
                            return ::core::result::Result::Err(e);
                        }
                        #domain::end_write(&mut self.#m, data.len())
                    }
                });
                begin.push(quote!(#k => #domain::begin_write(&mut self.#m, size),));
                chunk.push(quote!(#k => #domain::write_chunk(&mut self.#m, offset, data),));
                end.push(quote!(#k => #domain::end_write(&mut self.#m, total),));
                abort.push(quote!(#k => #domain::abort_write(&mut self.#m),));
            }
        }
    }
    let refuse = quote!(_ => ::core::result::Result::Err(__AbortCode::UnsupportedAccess));
    let mut out = Ts::new();
    if !size.is_empty() {
        out.extend(quote! {
            #[allow(unused_variables)]
            fn special_size(&self, field: u16, elem: u8) -> usize {
                match field { #(#size)* _ => 0 }
            }
            #[allow(unused_variables)]
            fn special_read(&self, field: u16, elem: u8, offset: usize, buf: &mut [u8]) -> ::core::result::Result<usize, __AbortCode> {
                match field { #(#read)* _ => ::core::result::Result::Err(__AbortCode::ObjectDoesNotExist) }
            }
        });
    }
    if !map.is_empty() {
        out.extend(quote! {
            #[allow(unused_variables)]
            fn special_map_size(&self, field: u16, elem: u8) -> usize {
                match field { #(#map)* _ => 0 }
            }
        });
    }
    if !write.is_empty() {
        out.extend(quote! {
            #[allow(unused_variables)]
            fn special_write(&mut self, field: u16, elem: u8, sub: u8, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                match field { #(#write)* #refuse }
            }
            #[allow(unused_variables)]
            fn special_begin(&mut self, field: u16, elem: u8, size: ::core::option::Option<usize>) -> ::core::result::Result<(), __AbortCode> {
                match field { #(#begin)* #refuse }
            }
            #[allow(unused_variables)]
            fn special_chunk(&mut self, field: u16, elem: u8, offset: usize, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                match field { #(#chunk)* #refuse }
            }
            #[allow(unused_variables)]
            fn special_end(&mut self, field: u16, elem: u8, sub: u8, total: usize) -> ::core::result::Result<(), __AbortCode> {
                match field { #(#end)* #refuse }
            }
        });
    }
    if !abort.is_empty() {
        out.extend(quote! {
            #[allow(unused_variables)]
            fn special_abort(&mut self, field: u16, elem: u8) {
                match field { #(#abort)* _ => {} }
            }
        });
    }
    if !restore.is_empty() {
        out.extend(quote! {
            fn special_restore(&mut self) {
                #(#restore)*
            }
        });
    }
    out
}
