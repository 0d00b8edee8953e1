use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary)]
struct App {
    #[od(index = 0x2001, min = -1000, max = 1000, default = 2000)]
    setpoint: i16,
}

fn main() {}
