//! Panic-freedom proven by the linker: every step entry point of the library (hold, linear, mid, Gauss,
//! sample history, delta angles with every coning correction, gyro samples), for every scheme × stabilizer,
//! plus construction and `set_attitude`, is called with opaque inputs. The panic handler calls a function
//! that does not exist, so if any panic path is still reachable after optimization, the link fails with
//! "undefined symbol: quatprop_step_path_can_panic". Built (not run) by CI:
//! `cargo build --manifest-path firmware/Cargo.toml --release --target thumbv7em-none-eabihf --bin nopanic`.
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use quatprop::coning::{self, ConingCorrection};
use quatprop::scheme::{Cf4, Euler, ExpMap, Magnus4, Rk2, Rk3, Rk4, Rk5, Scheme};
use quatprop::stabilize::{Baumgarte, Every, FirstOrder, Normalize, Off, Policy, Stabilizer};
use quatprop::{GyroSample, Propagator, Quat, SampleHistory, Vec3};

fn v() -> Vec3<f32> {
    black_box(Vec3::new(0.1, -0.2, 0.3))
}

#[inline(never)]
fn exercise<S: Scheme, Z: Stabilizer<f32>>(s: S, z: Z) {
    let dt = black_box(1e-3_f32);
    let q0 = black_box(Quat::new(1.0_f32, 0.0, 0.0, 0.0));
    let Ok(mut p) = Propagator::new(q0, s, z) else {
        return;
    };
    let _ = black_box(p.step_hold(v(), dt));
    let _ = black_box(p.step_linear(v(), v(), dt));
    let _ = black_box(p.step_mid(v(), v(), v(), dt));
    let _ = black_box(p.step_gauss(v(), v(), dt));
    let mut h = black_box(SampleHistory::new());
    let _ = black_box(p.step_history(&mut h, v(), dt));
    let sample = black_box(GyroSample {
        rate: v(),
        saturated: true,
    });
    let _ = black_box(p.step_hold_sample(sample, dt));
    let _ = black_box(p.step_linear_samples(sample, sample, dt));
    let incs = black_box([v(), v(), v(), v(), v()]);
    let n = black_box(3usize);
    // Any slice length, with the runtime enum and with each zero-sized correction.
    let slice = incs.get(..n).unwrap_or(&incs);
    for m in coning::Method::ALL {
        let _ = black_box(p.step_delta(m, slice, dt));
    }
    delta(&mut p, coning::Uncorrected, slice, dt);
    delta(&mut p, coning::OnePlusPrevious, slice, dt);
    delta(&mut p, coning::TwoSample, slice, dt);
    delta(&mut p, coning::ThreeSample, slice, dt);
    delta(&mut p, coning::FourSample, slice, dt);
    delta(&mut p, coning::FiveSample, slice, dt);
    let _ = black_box(p.set_attitude(black_box(q0)));
    black_box(p.attitude());
    black_box(p.norm_error());
    // The compensated state.
    if let Ok(mut c) = Propagator::new_compensated(q0, s, z) {
        let _ = black_box(c.step_linear(v(), v(), dt));
    }
}

fn delta<S: Scheme, Z: Stabilizer<f32>, C: ConingCorrection>(
    p: &mut Propagator<f32, S, Z>,
    c: C,
    incs: &[Vec3<f32>],
    dt: f32,
) {
    let _ = black_box(p.step_delta(c, incs, dt));
}

macro_rules! every_stabilizer {
    ($s:expr) => {{
        exercise($s, Off);
        exercise($s, Normalize);
        exercise($s, FirstOrder);
        exercise($s, Every(black_box(16)));
        exercise(
            $s,
            Baumgarte {
                k: black_box(0.5_f32),
            },
        );
        exercise($s, black_box(Policy::<f32>::FirstOrder));
    }};
}

#[entry]
fn main() -> ! {
    every_stabilizer!(Euler);
    every_stabilizer!(Rk2);
    every_stabilizer!(Rk3);
    every_stabilizer!(Rk4);
    every_stabilizer!(Rk5);
    every_stabilizer!(ExpMap);
    every_stabilizer!(Magnus4);
    every_stabilizer!(Cf4);
    every_stabilizer!(black_box(quatprop::scheme::Method::Rk4));
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    extern "C" {
        // Deliberately never defined: referencing it from a reachable panic path fails the link.
        fn quatprop_step_path_can_panic() -> !;
    }
    // SAFETY: never executes; the call only exists if a panic path survived optimization, and then the
    // image does not link at all.
    unsafe { quatprop_step_path_can_panic() }
}
