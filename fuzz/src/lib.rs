//! Invariant checks shared by the fuzz targets (fuzz_targets/*.rs) and the regression tests
//! (tests/fuzz_regressions.rs includes `checks` by path): each `checks::<target>::run(bytes)` decodes the
//! bytes into calls on quatprop's public API and panics if an invariant fails.
pub mod checks;
