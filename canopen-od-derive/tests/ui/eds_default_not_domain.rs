use canopen_od_derive::ObjectDictionary;

// `eds_default` is the EDS text of a DOMAIN's default; any other entry takes `default`, which the node applies.
#[derive(ObjectDictionary)]
struct App {
    #[od(index = 0x2001, eds_default = "5")]
    speed: u16,
}

fn main() {}
