//! Mistakes in a dictionary definition are compile errors with a clear span; the `.stderr` files pin the
//! messages.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
}
