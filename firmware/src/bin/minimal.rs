//! The flash floor of a real use: one scheme + `FirstOrder`, `step_linear` in f32, no defmt, no formatting.
//! The scheme is Rk4 unless a `scheme-*` feature picks another (for the per-scheme size table).
//! Exits 0 if a 1 rad/s yaw over 1000 steps of 1 ms lands at 1 rad (quaternion components within 1e-4).
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};
use quatprop::stabilize::FirstOrder;
use quatprop::{scheme, Propagator, Quat, Vec3};

#[cfg(feature = "scheme-euler")]
type S = scheme::Euler;
#[cfg(feature = "scheme-rk2")]
type S = scheme::Rk2;
#[cfg(feature = "scheme-rk3")]
type S = scheme::Rk3;
#[cfg(feature = "scheme-rk5")]
type S = scheme::Rk5;
#[cfg(feature = "scheme-expmap")]
type S = scheme::ExpMap;
#[cfg(not(any(
    feature = "scheme-euler",
    feature = "scheme-rk2",
    feature = "scheme-rk3",
    feature = "scheme-rk5",
    feature = "scheme-expmap"
)))]
type S = scheme::Rk4;

#[entry]
fn main() -> ! {
    let ok = match Propagator::new(Quat::<f32>::IDENTITY, S::default(), FirstOrder) {
        Ok(mut p) => {
            let mut refused = false;
            let mut prev = Vec3::new(0.0, 0.0, 1.0);
            for _ in 0..1000 {
                // black_box: the inputs are data, as from a sensor.
                let w = black_box(Vec3::new(0.0_f32, 0.0, 1.0));
                refused |= p.step_linear(prev, w, black_box(1.0e-3)).is_err();
                prev = w;
            }
            // 1 rad of yaw: q = (cos ½, 0, 0, sin ½).
            let q = p.attitude();
            !refused && (q.w - 0.877_582_6).abs() < 1e-4 && (q.z - 0.479_425_55).abs() < 1e-4
        }
        Err(_) => false,
    };
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
