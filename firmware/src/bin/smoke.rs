//! Smoke run: every scheme × post-step stabilizer, and Baumgarte on every Runge–Kutta scheme, on four f32
//! scenes fed through the input models (Hold, Linear, TwiceRate, History), and the fixed-point propagator on
//! the constant and coning scenes as counts, results logged with defmt as bit patterns. `firmware/check-boards` compares the decoded output with `firmware/expected/smoke.txt`
//! (`smoke-soft.txt` on the soft-float boards, which run fewer steps), which the host test
//! `tests/firmware_snapshot.rs` writes and checks: host and every board must agree bit for bit.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use quatprop_firmware::exit::exit;
use quatprop_firmware::scenes::{bits, run, run_fixed, Config, Scene};

/// Steps per run: fewer where every float operation is emulated in software (Cortex-M3, M0).
#[cfg(target_abi = "eabihf")]
const STEPS: u32 = quatprop_firmware::scenes::STEPS;
#[cfg(not(target_abi = "eabihf"))]
const STEPS: u32 = quatprop_firmware::scenes::STEPS_SOFT;

#[entry]
fn main() -> ! {
    let mut refused_total = 0;
    defmt::println!("smoke steps={=u32}", STEPS);
    for scene in Scene::ALL {
        for c in Config::all() {
            let o = run(scene, c, STEPS);
            refused_total += o.refused;
            defmt::println!(
                "{=str} {=str} {=str} {=u32:08x} {=u32:08x} {=u32:08x} {=u32:08x} steps={=u64} corrections={=u64} refused={=u32}",
                scene.name(),
                c.scheme_name(),
                c.stabilizer_name(),
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
    for scene in [Scene::Constant, Scene::ConingHistory] {
        match run_fixed(scene, STEPS) {
            Some((q, n)) => defmt::println!(
                "fixed {=str} Q30Propagator {=u32:08x} {=u32:08x} {=u32:08x} {=u32:08x} steps={=u64}",
                scene.name(),
                q[0] as u32,
                q[1] as u32,
                q[2] as u32,
                q[3] as u32,
                n
            ),
            None => refused_total += 1,
        }
    }
    defmt::println!("smoke done");
    exit(refused_total == 0)
}
