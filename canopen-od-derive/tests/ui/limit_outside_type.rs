use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary)]
struct App {
    #[od(index = 0x2001, min = -1)]
    count: u8,
}

fn main() {}
