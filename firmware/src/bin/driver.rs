//! The embedded-hal path end to end on the board: the `icm426xx` driver (blocking SPI) initializes a
//! scripted ICM-42688-P (`device_model`: 4000 samples at 1 kHz in FIFO bursts of 1 to 40, a bias, coning at
//! incommensurate frequencies, one sample at the rail), reads its FIFO bursts, and the raw counts go into the
//! README's quick start. Prints the attitude's bits; `firmware/expected/driver.txt` holds what the host
//! computes from the same code, over the same model and over `embedded-hal-mock` (tests/firmware_snapshot.rs).
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use quatprop_firmware::device_model::{Icm42688Model, SAMPLES};
use quatprop_firmware::driver_demo::run;
use quatprop_firmware::exit::{exit, fail};
use quatprop_firmware::scenes::bits;

#[entry]
fn main() -> ! {
    let Ok((o, model)) = run(Icm42688Model::new(), 10_000) else {
        fail("driver run")
    };
    let (_, over) = model.served();
    // The host test (`driver_output` in src/tests/snapshot.rs) writes the same line with `format!`: defmt
    // formats only here, on the board, so each side lists the fields.
    defmt::println!(
        "driver icm426xx samples={=u32} bursts={=u32} rails={=u32} ticks={=u32} {=u32:08x} {=u32:08x} {=u32:08x} {=u32:08x} refused={=u32}",
        o.samples,
        o.bursts,
        o.rails,
        o.ticks,
        bits(o.q.w),
        bits(o.q.x),
        bits(o.q.y),
        bits(o.q.z),
        o.refused
    );
    defmt::println!("driver spi-transactions={=u32}", model.transactions());
    defmt::println!("driver done");
    exit(over && o.refused == 0 && o.samples == SAMPLES as u32)
}
