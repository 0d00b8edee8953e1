use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary)]
struct App {
    #[od(index = 0x2100, sub = 1, record = "PID")]
    kp: f32,
    #[od(index = 0x2100, sub = 1)]
    ki: f32,
}

fn main() {}
