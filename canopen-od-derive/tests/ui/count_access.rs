use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary)]
struct App {
    // Sub-index 0 holds the fixed count: ro or const only...
    #[od(index = 0x2001, count_access = "rw")]
    gains: [u16; 2],
    // ...and only an ARRAY or RECORD has one.
    #[od(index = 0x2002, count_access = "ro")]
    speed: u16,
}

fn main() {}
