use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary)]
struct App {
    #[od(index = 0x1017, access = "rw")]
    heartbeat: u16,
}

fn main() {}
