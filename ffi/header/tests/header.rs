//! The committed header is the one cbindgen generates from the C API's source (QUATPROP_BLESS=1 writes it).

use std::path::PathBuf;

/// Regenerates the header in memory and compares it with `include/quatprop.h` (QUATPROP_BLESS=1 writes it).
#[test]
fn header_is_current() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    // cbindgen emits no string constant: QUATPROP_VERSION is written here, from the C API crate's manifest
    // (the version `quatprop_version()` returns; ffi/c/host_test.c compares the two at run time).
    let version =
        package_version(&std::fs::read_to_string(dir.join("Cargo.toml")).expect("Cargo.toml"));
    let define = format!(
        "\n/* The version of quatprop this header belongs to; quatprop_version() returns the library's. */\n\
         #define QUATPROP_VERSION \"{version}\""
    );
    let bindings = cbindgen::Builder::new()
        .with_crate(&dir)
        .with_config(config)
        .with_after_include(define)
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

/// The `version` of a manifest's `[package]` section.
fn package_version(manifest: &str) -> String {
    let mut in_package = false;
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            in_package = line == "[package]";
        } else if let Some(rest) = line.strip_prefix("version").filter(|_| in_package) {
            if let Some(v) = rest.trim_start().strip_prefix('=') {
                return v.trim().trim_matches('"').to_string();
            }
        }
    }
    panic!("no [package] version in ffi/Cargo.toml")
}
