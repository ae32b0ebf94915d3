//! Smoke run: every scheme × stabilizer on three fixed f32 scenes (10⁵ steps each), results logged with
//! defmt as bit patterns. CI compares the decoded output with `firmware/expected/smoke.txt`, which the host
//! test `tests/firmware_snapshot.rs` also checks: host and every board must agree bit for bit.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};
use defmt_semihosting as _;
use quatprop::scheme::{Method, Scheme};
use quatprop_firmware::scenes::{bits, policy_name, run, Scene, POLICIES, STEPS};

#[entry]
fn main() -> ! {
    let mut refused_total = 0;
    for scene in Scene::ALL {
        for m in Method::ALL {
            for p in POLICIES {
                let o = run(scene, m, p, STEPS);
                refused_total += o.refused;
                defmt::println!(
                    "{=str} {=str} {=str} {=u32:08x} {=u32:08x} {=u32:08x} {=u32:08x} steps={=u64} corrections={=u64} refused={=u32}",
                    scene.name(),
                    m.name(),
                    policy_name(p),
                    bits(o.q.w),
                    bits(o.q.x),
                    bits(o.q.y),
                    bits(o.q.z),
                    o.steps,
                    o.corrections,
                    o.refused
                );
            }
        }
    }
    defmt::println!("smoke done");
    debug::exit(if refused_total == 0 {
        EXIT_SUCCESS
    } else {
        EXIT_FAILURE
    });
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
