use canopen_core::od::{OctetString, VisibleString};
use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary)]
struct App {
    // An OCTET_STRING default may be any bytes...
    #[od(index = 0x2001, default = b"\xAB\xCD")]
    raw: OctetString<4>,
    // ...a VISIBLE_STRING's is text.
    #[od(index = 0x2002, default = b"\xAB\xCD")]
    name: VisibleString<4>,
}

fn main() {}
