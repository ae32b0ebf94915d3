//! The README's quick start is the firmware's `quickstart` program, verbatim: the code between the
//! markers of `firmware/src/quickstart.rs` must appear in README.md as one block, so what runs on the
//! Cortex-M4F under QEMU (and what the snapshot test compares with the host) is what users paste.

#[test]
fn readme_quick_start_is_the_firmware_quickstart_module() {
    let module = include_str!("../firmware/src/quickstart.rs");
    let readme = include_str!("../README.md");
    let begin = module
        .find("// quick start: begin\n")
        .expect("begin marker")
        + "// quick start: begin\n".len();
    let end = module.find("// quick start: end").expect("end marker");
    let code = &module[begin..end];
    assert!(code.contains("Propagator::new"), "markers enclose the code");
    assert!(
        readme.contains(code),
        "README.md does not show firmware/src/quickstart.rs verbatim:\n{code}"
    );
}

#[test]
fn readme_is_a_front_door() {
    let size = include_str!("../README.md").len();
    assert!(
        size <= 10 * 1024,
        "README.md is {size} bytes (at most 10 KiB)"
    );
}
