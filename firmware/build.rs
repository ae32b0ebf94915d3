//! Chooses the memory map from the target triple (one QEMU board family per triple) and adds the
//! linker scripts: `link.x` for every binary, `defmt.x` for those that log with defmt.
use std::{env, fs, path::PathBuf};

fn main() {
    let target = env::var("TARGET").unwrap_or_default();
    let memory = match target.as_str() {
        // mps2-an505 (Cortex-M33): secure alias; code at 0x0 locks up.
        "thumbv8m.main-none-eabihf" => {
            "MEMORY\n{\n  FLASH : ORIGIN = 0x10000000, LENGTH = 4M\n  RAM : ORIGIN = 0x38000000, LENGTH = 4M\n}\n"
                .to_string()
        }
        // micro:bit (Cortex-M0, nRF51).
        "thumbv6m-none-eabi" => {
            "MEMORY\n{\n  FLASH : ORIGIN = 0x00000000, LENGTH = 256K\n  RAM : ORIGIN = 0x20000000, LENGTH = 16K\n}\n"
                .to_string()
        }
        // mps2-an386 / an500 / an385: the top-level memory.x.
        _ => fs::read_to_string("../memory.x").expect("top-level memory.x"),
    };
    let out = PathBuf::from(env::var("OUT_DIR").unwrap());
    fs::write(out.join("memory.x"), memory).unwrap();
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=../memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    if target.starts_with("thumb") {
        println!("cargo:rustc-link-arg-bins=-Tlink.x");
        for bin in ["smoke", "isr", "bench", "stack"] {
            println!("cargo:rustc-link-arg-bin={bin}=-Tdefmt.x");
        }
    }
}
