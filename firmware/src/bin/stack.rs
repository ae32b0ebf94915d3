//! Worst-case stack use of one step, for every scheme × stabilizer in f32 on the Cortex-M4F, measured by
//! painting: the free stack below SP is filled with a pattern, a propagator is built and stepped once with
//! `step_mid` (the input model with the most live values), and the deepest overwritten word gives the depth.
//! The figure includes the propagator value itself and the call into the step. The exponential-map family is
//! also measured with a large step (the trigonometric branch, which calls libm). Fails (exit 1) if any depth
//! exceeds `BOUND`. Run: `cargo run --manifest-path firmware/Cargo.toml --release --target
//! thumbv7em-none-eabihf --bin stack`.
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};
use defmt_semihosting as _;
use quatprop::scheme::{Cf4, Euler, ExpMap, Magnus4, Rk2, Rk3, Rk4, Rk5, Scheme};
use quatprop::stabilize::{Baumgarte, Every, FirstOrder, Normalize, Off, Stabilizer};
use quatprop::{Propagator, Quat, Vec3};

/// Bound for steps on the polynomial / Taylor path (bytes): measured 144–224 (Rk5 deepest) with rustc 1.95;
/// the bound leaves room for compiler drift and is what README promises for stack sizing.
const BOUND_SMALL: usize = 256;
/// Bound when the exponential map takes its trigonometric branch (steps above 0.2 rad in f32): libm's
/// `sinf`/`cosf` argument reduction keeps arrays on the stack; measured 1064 bytes.
const BOUND_LARGE: usize = 1280;
const PAINT: u32 = 0xA5A5_A5A5;
/// Painted depth below the measuring frame (bytes).
const DEPTH: usize = 4096;
/// Margin left unpainted under the measuring function's own frame (bytes).
const MARGIN: usize = 64;

#[inline(never)]
fn measure(f: &dyn Fn()) -> usize {
    let sp = cortex_m::register::msp::read() as usize;
    let top = sp - MARGIN;
    let bottom = sp - DEPTH;
    let mut a = bottom;
    while a < top {
        // SAFETY: [bottom, top) is free stack below the current frame (4 KB of the 4 MB RAM), no interrupt
        // is enabled, and it is only written here and read back below.
        unsafe { core::ptr::write_volatile(a as *mut u32, PAINT) };
        a += 4;
    }
    f();
    let mut lowest = top;
    let mut a = bottom;
    while a < top {
        // SAFETY: as above.
        if unsafe { core::ptr::read_volatile(a as *const u32) } != PAINT {
            lowest = a;
            break;
        }
        a += 4;
    }
    sp - lowest
}

#[inline(never)]
fn one_step<S: Scheme, Z: Stabilizer<f32>>(s: S, z: Z, angle: f32) {
    let dt = black_box(1e-3_f32);
    let w = black_box(Vec3::new(angle, -0.2, 0.3));
    if let Ok(mut p) = Propagator::new(black_box(Quat::<f32>::IDENTITY), s, z) {
        let _ = black_box(p.step_mid(w, w, w, dt));
        black_box(p);
    }
}

macro_rules! rows {
    ($worst:ident, $bound:expr, $ok:ident, $s:expr, $angle:expr, $label:expr) => {{
        for (name, d) in [
            ("Off", measure(&|| one_step($s, Off, $angle))),
            ("Normalize", measure(&|| one_step($s, Normalize, $angle))),
            ("FirstOrder", measure(&|| one_step($s, FirstOrder, $angle))),
            ("Every(16)", measure(&|| one_step($s, Every(16), $angle))),
            (
                "Baumgarte",
                measure(&|| one_step($s, Baumgarte { k: 0.5_f32 }, $angle)),
            ),
        ] {
            $worst = $worst.max(d);
            $ok &= d > 0 && d <= $bound;
            defmt::println!(
                "stack {=str} {=str} {=str} {=usize}",
                $s.name(),
                name,
                $label,
                d
            );
        }
    }};
}

#[entry]
fn main() -> ! {
    let mut ok = true;
    let mut small = 0usize;
    rows!(small, BOUND_SMALL, ok, Euler, 0.1, "small");
    rows!(small, BOUND_SMALL, ok, Rk2, 0.1, "small");
    rows!(small, BOUND_SMALL, ok, Rk3, 0.1, "small");
    rows!(small, BOUND_SMALL, ok, Rk4, 0.1, "small");
    rows!(small, BOUND_SMALL, ok, Rk5, 0.1, "small");
    rows!(small, BOUND_SMALL, ok, ExpMap, 0.1, "small");
    rows!(small, BOUND_SMALL, ok, Magnus4, 0.1, "small");
    rows!(small, BOUND_SMALL, ok, Cf4, 0.1, "small");
    // 300 rad/s at 1 ms: 0.3 rad per step, the exponential map's trigonometric branch.
    let mut large = 0usize;
    rows!(large, BOUND_LARGE, ok, ExpMap, 300.0, "large");
    rows!(large, BOUND_LARGE, ok, Magnus4, 300.0, "large");
    rows!(large, BOUND_LARGE, ok, Cf4, 300.0, "large");
    defmt::println!(
        "stack worst small-step {=usize} (bound {=usize}), large-step {=usize} (bound {=usize})",
        small,
        BOUND_SMALL,
        large,
        BOUND_LARGE
    );
    debug::exit(if ok { EXIT_SUCCESS } else { EXIT_FAILURE });
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    debug::exit(EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
