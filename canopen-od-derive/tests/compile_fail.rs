//! Mistakes in a dictionary definition are compile errors with a clear span; the `.stderr` files pin the
//! messages. The limits of what a definition may hold build and run (`tests/pass`).

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
    t.pass("tests/pass/*.rs");
}
