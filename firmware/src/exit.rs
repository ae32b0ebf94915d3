//! How every program ends: the verdict becomes QEMU's exit status through semihosting (0 success,
//! 1 failure). The panic handler lives here too, so no program carries its own: a panic exits 1 (and, with
//! defmt logging, says so first).
//!
//! With the feature `panic-never` (the `nopanic` program), the `panic-never` crate provides the handler
//! instead: it references a symbol that does not exist, so the image only links if no panic path survived
//! optimization.

use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};

#[cfg(feature = "log")]
use defmt_semihosting as _;
#[cfg(feature = "panic-never")]
use panic_never as _;

/// Ends the program: QEMU exits with 0 if `ok`, else 1.
pub fn exit(ok: bool) -> ! {
    debug::exit(if ok { EXIT_SUCCESS } else { EXIT_FAILURE });
    loop {
        cortex_m::asm::wfi();
    }
}

/// Logs why the program cannot go on (with defmt) and exits 1.
pub fn fail(what: &str) -> ! {
    #[cfg(feature = "log")]
    defmt::println!("failed: {=str}", what);
    #[cfg(not(feature = "log"))]
    let _ = what;
    exit(false)
}

#[cfg(not(feature = "panic-never"))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    fail("panic")
}
