use canopen_core::od::VisibleString;
use canopen_od_derive::ObjectDictionary;

// A capacity given by a constant is checked at compile time: a mapped string must fit a PDO's 8 bytes.
const LEN: usize = 9;

#[derive(ObjectDictionary)]
struct App {
    #[od(index = 0x2001, pdo = "tpdo")]
    name: VisibleString<LEN>,
}

fn main() {}
