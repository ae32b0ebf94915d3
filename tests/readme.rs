//! The README is a front door (at most 10 KiB). Its quick start runs as the crate-level doctest, and
//! `firmware/check-host` checks that the firmware's `quickstart` program is that code verbatim.

#[test]
fn readme_is_a_front_door() {
    let size = include_str!("../README.md").len();
    assert!(
        size <= 10 * 1024,
        "README.md is {size} bytes (at most 10 KiB)"
    );
}
