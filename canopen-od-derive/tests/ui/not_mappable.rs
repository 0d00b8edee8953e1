use canopen_core::od::VisibleString;
use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary)]
struct App {
    #[od(index = 0x2001, pdo = "tpdo")]
    name: VisibleString<16>,
}

fn main() {}
