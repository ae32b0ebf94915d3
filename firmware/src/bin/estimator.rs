//! The example estimator (`examples/estimator/filter.rs`: an error-state Kalman filter on quatprop's
//! predict step, gyroscope and accelerometer) on the board, fed 7 s of a real recording (BROAD trial 07,
//! `firmware/data/`). Prints its attitude, bias and inclination σ as bit patterns every 500 samples and at
//! the end; `firmware/expected/estimator.txt` holds what the host computes from the same code and data.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use quatprop_firmware::estimator_run::{len, line, run};
use quatprop_firmware::exit::{exit, fail};

#[entry]
fn main() -> ! {
    defmt::println!("estimator samples={=usize}", len());
    let mut last = (0, 0);
    let ran = run(|s| {
        let b = line(s);
        defmt::println!(
            "estimator {=usize} {=u32:08x} {=u32:08x} {=u32:08x} {=u32:08x} bias {=u32:08x} {=u32:08x} {=u32:08x} sigma {=u32:08x} updates={=u64} rejected={=u64}",
            s.samples, b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], s.updates, s.rejected
        );
        last = (s.samples, s.updates);
    });
    if ran.is_err() {
        fail("the estimator refused a sample");
    }
    defmt::println!("estimator done");
    exit(last.0 == len() && last.1 > 0)
}
