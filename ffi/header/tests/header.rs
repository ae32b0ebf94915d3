//! The committed header is the one cbindgen generates from the C API's source (QUATPROP_BLESS=1 writes it).

use std::path::PathBuf;

/// Regenerates the header in memory and compares it with `include/quatprop.h` (QUATPROP_BLESS=1 writes it).
#[test]
fn header_is_current() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let bindings = cbindgen::Builder::new()
        .with_crate(&dir)
        .with_config(config)
        .generate()
        .expect("cbindgen");
    let mut fresh = Vec::new();
    bindings.write(&mut fresh);
    let path = dir.join("include/quatprop.h");
    if std::env::var_os("QUATPROP_BLESS").is_some() {
        std::fs::write(&path, &fresh).expect("write header");
    }
    let committed = std::fs::read(&path).unwrap_or_default();
    assert!(
        committed == fresh,
        "ffi/include/quatprop.h is stale: run `QUATPROP_BLESS=1 cargo test -p quatprop-ffi-header` in ffi/ and commit it"
    );
}
