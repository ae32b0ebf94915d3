//! Picks the board's memory map from the target triple (one QEMU board family per triple, files in
//! `memory/`) and adds the linker scripts: `link.x` for every program, `defmt.x` when defmt logging is on.
use std::{env, fs, path::PathBuf};

fn main() {
    let target = env::var("TARGET").unwrap_or_default();
    let map = match target.as_str() {
        "thumbv8m.main-none-eabihf" => "memory/mps2-an505.x",
        "thumbv6m-none-eabi" => "memory/microbit.x",
        // mps2-an386 / an500 (thumbv7em-none-eabihf) and mps2-an385 (thumbv7m-none-eabi).
        _ => "memory/mps2.x",
    };
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed={map}");
    // `fpu`: a hard-float target (an FPU on every board of the triple); `microbit`: the nRF51 board, whose
    // SysTick runs at 16 MHz (25 MHz on the mps2 boards).
    println!("cargo:rustc-check-cfg=cfg(fpu)");
    println!("cargo:rustc-check-cfg=cfg(microbit)");
    if target.ends_with("eabihf") {
        println!("cargo:rustc-cfg=fpu");
    }
    if target == "thumbv6m-none-eabi" {
        println!("cargo:rustc-cfg=microbit");
    }
    if !target.starts_with("thumb") {
        return;
    }
    // cortex-m-rt's link.x includes `memory.x`: put the board's map under that name in OUT_DIR.
    let out = PathBuf::from(env::var("OUT_DIR").unwrap());
    fs::copy(map, out.join("memory.x")).expect("memory map");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    if env::var_os("CARGO_FEATURE_LOG").is_some() {
        println!("cargo:rustc-link-arg-bins=-Tdefmt.x");
    }
}
