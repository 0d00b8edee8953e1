use canopen_core::od::{UnicodeString, VisibleString};
use canopen_od_derive::ObjectDictionary;

// A mapped string moves its whole capacity, which must fit a PDO's 8 bytes (PDO-31, PDO-32).
#[derive(ObjectDictionary)]
struct App {
    #[od(index = 0x2001, pdo = "tpdo")]
    name: VisibleString<16>,
    #[od(index = 0x2002, pdo = "rpdo")]
    units: UnicodeString<5>,
    #[od(index = 0x2003, pdo = "both")]
    fits: VisibleString<8>,
}

fn main() {}
