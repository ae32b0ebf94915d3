//! The README's quick start on the board: `firmware/src/quickstart.rs` (the README's code, verbatim) fed the
//! deterministic coning stream of `scenes::quickstart_samples` (10⁴ samples at 1 kHz, one NaN in the middle,
//! so the refused-sample path runs). Prints the attitude's bits and the refused count;
//! `firmware/expected/quickstart.txt` holds what the host computes from the same code and stream.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use quatprop_firmware::exit::{exit, fail};
use quatprop_firmware::quickstart::attitude_from;
use quatprop_firmware::scenes::{bits, quickstart_samples, QUICKSTART_SAMPLES};

#[entry]
fn main() -> ! {
    let Ok((q, refused)) = attitude_from(quickstart_samples()) else {
        fail("quick start refused to start")
    };
    defmt::println!(
        "quickstart samples={=u32} {=u32:08x} {=u32:08x} {=u32:08x} {=u32:08x} refused={=u32}",
        QUICKSTART_SAMPLES,
        bits(q.w),
        bits(q.x),
        bits(q.y),
        bits(q.z),
        refused
    );
    defmt::println!("quickstart done");
    exit(refused == 1)
}
