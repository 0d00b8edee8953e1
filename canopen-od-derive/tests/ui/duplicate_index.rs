use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary)]
struct App {
    #[od(index = 0x2001)]
    a: u16,
    #[od(index = 0x2001)]
    b: u32,
}

fn main() {}
