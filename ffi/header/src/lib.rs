//! Nothing: this crate only has the header test (`tests/header.rs`).
