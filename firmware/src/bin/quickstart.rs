//! The README's quick start on the board: `firmware/quickstart/src/lib.rs` (the README's code, verbatim) fed the
//! deterministic raw-count FIFO stream of `scenes::quickstart_fifo` (400 bursts of 25 samples at 1 kHz: 2 s
//! still with a bias, then coning). Prints the attitude's bits and the refused count;
//! `firmware/expected/quickstart.txt` holds what the host computes from the same code and stream.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use quatprop_firmware::exit::{exit, fail};
use quatprop_firmware::quickstart::Attitude;
use quatprop_firmware::scenes::{bits, quickstart_fifo, QUICKSTART_BURST, QUICKSTART_BURSTS};

#[entry]
fn main() -> ! {
    let Ok(mut attitude) = Attitude::new() else {
        fail("quick start refused to start")
    };
    for burst in quickstart_fifo() {
        attitude.on_fifo(&burst);
    }
    let (q, refused) = attitude.attitude();
    defmt::println!(
        "quickstart samples={=u32} {=u32:08x} {=u32:08x} {=u32:08x} {=u32:08x} refused={=u32}",
        QUICKSTART_BURSTS * QUICKSTART_BURST as u32,
        bits(q.w),
        bits(q.x),
        bits(q.y),
        bits(q.z),
        refused
    );
    defmt::println!("quickstart done");
    exit(refused == 0)
}
