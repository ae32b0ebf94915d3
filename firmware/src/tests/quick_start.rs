//! The README's quick start is the firmware's `quickstart` program, verbatim: the code between the
//! markers of `firmware/quickstart/src/lib.rs` must appear in the repository's README.md as one block, so what
//! runs on the Cortex-M4F under QEMU (and what the snapshot test compares with the host) is what users paste.

use crate::quickstart;

#[test]
fn readme_quick_start_is_the_firmware_quickstart_module() {
    let module = include_str!("../../quickstart/src/lib.rs");
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md"))
        .expect("the repository's README.md");
    let begin = module
        .find("// quick start: begin\n")
        .expect("begin marker")
        + "// quick start: begin\n".len();
    let end = module.find("// quick start: end").expect("end marker");
    let code = &module[begin..end];
    assert!(code.contains("Propagator::"), "markers enclose the code");
    assert!(
        readme.contains(code),
        "README.md does not show firmware/quickstart/src/lib.rs verbatim:\n{code}"
    );
}

/// The quick start drops nothing: a FIFO read longer than its stack batch gives bit for bit the
/// attitude of the same samples in reads of at most one batch.
#[test]
fn quick_start_takes_a_fifo_read_of_any_length() {
    let counts: Vec<[i16; 3]> = (0..1000i32)
        .map(|i| {
            let c = |f: f64, a: f64| (a * (f * f64::from(i)).sin()) as i16;
            [
                12 + c(0.0131, 900.0),
                -3 + c(0.0077, 1500.0),
                7 + c(0.0029, 2500.0),
            ]
        })
        .collect();
    let mut long = quickstart::Attitude::new().unwrap();
    long.on_fifo(&counts);
    let mut short = quickstart::Attitude::new().unwrap();
    for read in counts.chunks(7) {
        short.on_fifo(read);
    }
    let bits = |a: &quickstart::Attitude| {
        let (q, refused) = a.attitude();
        ([q.w, q.x, q.y, q.z].map(f32::to_bits), refused)
    };
    assert_eq!(bits(&long), bits(&short));
    // 1000 samples at 1 kHz of a rotation of up to 2500 counts (150 °/s): the attitude moved.
    let (q, _) = long.attitude();
    assert!(q.w < 0.999, "{q:?}");
}
