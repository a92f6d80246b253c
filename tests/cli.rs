//! Command-line tests: each `tests/cmd/*.toml` runs `awl` and compares exit code and output.

#[test]
fn cli() {
    trycmd::TestCases::new().case("tests/cmd/*.toml");
}
