//! Instructions per step for every scheme × stabilizer × input model in f32 (and Rk4 in f64, to show the
//! soft-float cost on a single-precision FPU), counted with SysTick under QEMU `-icount shift=10`.
//!
//! Each figure is (instructions of a loop of N steps − instructions of the same loop without the step) / N,
//! with inputs passed through `black_box` so nothing is constant-folded. The zero-sized scheme and stabilizer
//! types are measured, exactly as a firmware that names them gets them; the count includes the propagator's
//! input validation and the commit. Step angles are small (|ω| ≈ 1.2 rad/s at 1 kHz), so the exponential
//! map takes its Taylor branch, as it does in normal flight.
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};
use defmt_semihosting as _;
use quatprop::accumulate::{Accumulator, Kahan, Plain};
use quatprop::scheme::{Cf4, Euler, ExpMap, Magnus4, Rk2, Rk3, Rk4, Rk5, Scheme};
use quatprop::stabilize::{Baumgarte, Every, FirstOrder, Normalize, Off, Stabilizer};
use quatprop::{Propagator, Quat, Real, Vec3};
use quatprop_firmware::icount::Counter;

const HOLD: u8 = 0;
const LINEAR: u8 = 1;
const MID: u8 = 2;

fn rates<T: Real>() -> [Vec3<T>; 8] {
    let mut r = [Vec3::ZERO; 8];
    for (i, w) in r.iter_mut().enumerate() {
        let a = i as f64 * 0.7;
        *w = Vec3::new(
            T::from_f64(0.3 + 0.1 * a),
            T::from_f64(-0.2 + 0.05 * a),
            T::from_f64(1.0 - 0.03 * a),
        );
    }
    r
}

#[inline(never)]
fn baseline<T: Real, const INPUT: u8>(c: &Counter, w: &[Vec3<T>; 8], n: usize) -> u32 {
    let t0 = c.now();
    for i in 0..n {
        match INPUT {
            HOLD => {
                black_box(w[i & 7]);
            }
            LINEAR => {
                black_box((w[i & 7], w[(i + 1) & 7]));
            }
            _ => {
                black_box((w[i & 7], w[(i + 3) & 7], w[(i + 1) & 7]));
            }
        }
        black_box(());
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

#[inline(never)]
fn steps<T: Real, S: Scheme, Z: Stabilizer<T>, A: Accumulator<T>, const INPUT: u8>(
    c: &Counter,
    p: &mut Propagator<T, S, Z, A>,
    w: &[Vec3<T>; 8],
    dt: T,
    n: usize,
) -> u32 {
    let t0 = c.now();
    for i in 0..n {
        let r = match INPUT {
            HOLD => p.step_hold(w[i & 7], dt),
            LINEAR => p.step_linear(w[i & 7], w[(i + 1) & 7], dt),
            _ => p.step_mid(w[i & 7], w[(i + 3) & 7], w[(i + 1) & 7], dt),
        };
        let _ = black_box(r);
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// Instructions per step ×100 (two decimals), or u32::MAX if a step was refused.
fn measure<T: Real, S: Scheme, Z: Stabilizer<T>, const INPUT: u8>(
    c: &Counter,
    s: S,
    z: Z,
    n: usize,
) -> u32 {
    let Ok(p) = Propagator::new(Quat::<T>::IDENTITY, s, z) else {
        return u32::MAX;
    };
    measure_propagator::<T, S, Z, Plain, INPUT>(c, p, n)
}

/// The same with the Kahan-compensated accumulator.
fn measure_kahan<T: Real, S: Scheme, Z: Stabilizer<T>, const INPUT: u8>(
    c: &Counter,
    s: S,
    z: Z,
    n: usize,
) -> u32 {
    let Ok(p) = Propagator::new_compensated(Quat::<T>::IDENTITY, s, z) else {
        return u32::MAX;
    };
    measure_propagator::<T, S, Z, Kahan<T>, INPUT>(c, p, n)
}

fn measure_propagator<T: Real, S: Scheme, Z: Stabilizer<T>, A: Accumulator<T>, const INPUT: u8>(
    c: &Counter,
    mut p: Propagator<T, S, Z, A>,
    n: usize,
) -> u32 {
    let w = black_box(rates::<T>());
    let dt = black_box(T::from_f64(1e-3));
    // Warm-up (nothing is cached on this core, but keep the first call out of the figure anyway).
    steps::<T, S, Z, A, INPUT>(c, &mut p, &w, dt, 1);
    let total = steps::<T, S, Z, A, INPUT>(c, &mut p, &w, dt, n);
    let base = baseline::<T, INPUT>(c, &w, n);
    if p.steps() != n as u64 + 1 {
        return u32::MAX;
    }
    ((total.saturating_sub(base) as u64 * 100) / n as u64) as u32
}

fn input_name(i: u8) -> &'static str {
    match i {
        HOLD => "hold",
        LINEAR => "linear",
        _ => "mid",
    }
}

macro_rules! row {
    ($c:expr, $ok:ident, $t:ty, $tname:expr, $n:expr, $s:expr, $z:expr, $zname:expr) => {{
        for input in [HOLD, LINEAR, MID] {
            let v = match input {
                HOLD => measure::<$t, _, _, HOLD>($c, $s, $z, $n),
                LINEAR => measure::<$t, _, _, LINEAR>($c, $s, $z, $n),
                _ => measure::<$t, _, _, MID>($c, $s, $z, $n),
            };
            $ok &= v != u32::MAX;
            defmt::println!(
                "bench {=str} {=str} {=str} {=str} {=u32}.{=u32:02}",
                $tname,
                $s.name(),
                $zname,
                input_name(input),
                v / 100,
                v % 100
            );
        }
    }};
}

macro_rules! scheme_rows {
    ($c:expr, $ok:ident, $s:expr) => {{
        row!($c, $ok, f32, "f32", 64, $s, Off, "Off");
        row!($c, $ok, f32, "f32", 64, $s, Normalize, "Normalize");
        row!($c, $ok, f32, "f32", 64, $s, FirstOrder, "FirstOrder");
        row!($c, $ok, f32, "f32", 64, $s, Every(16), "Every(16)");
        row!(
            $c,
            $ok,
            f32,
            "f32",
            64,
            $s,
            Baumgarte { k: 0.5_f32 },
            "Baumgarte"
        );
    }};
}

#[entry]
fn main() -> ! {
    let Some(cp) = cortex_m::Peripherals::take() else {
        debug::exit(EXIT_FAILURE);
        loop {
            cortex_m::asm::wfi();
        }
    };
    let c = Counter::new(cp.SYST);
    let mut ok = true;
    scheme_rows!(&c, ok, Euler);
    scheme_rows!(&c, ok, Rk2);
    scheme_rows!(&c, ok, Rk3);
    scheme_rows!(&c, ok, Rk4);
    scheme_rows!(&c, ok, Rk5);
    scheme_rows!(&c, ok, ExpMap);
    scheme_rows!(&c, ok, Magnus4);
    scheme_rows!(&c, ok, Cf4);
    // The compensated (Kahan) accumulator, for the cost ratio against the plain rows above.
    for (label, v) in [
        (
            "ExpMap FirstOrder hold",
            measure_kahan::<f32, _, _, HOLD>(&c, ExpMap, FirstOrder, 64),
        ),
        (
            "ExpMap FirstOrder linear",
            measure_kahan::<f32, _, _, LINEAR>(&c, ExpMap, FirstOrder, 64),
        ),
        (
            "Rk4 FirstOrder linear",
            measure_kahan::<f32, _, _, LINEAR>(&c, Rk4, FirstOrder, 64),
        ),
        (
            "ExpMap Off hold",
            measure_kahan::<f32, _, _, HOLD>(&c, ExpMap, Off, 64),
        ),
    ] {
        ok &= v != u32::MAX;
        defmt::println!("kahan f32 {=str} {=u32}.{=u32:02}", label, v / 100, v % 100);
    }
    // Soft-float f64 on the single-precision FPU (16 steps keep the count below SysTick's wrap).
    row!(&c, ok, f64, "f64", 16, Rk4, FirstOrder, "FirstOrder");
    row!(&c, ok, f64, "f64", 16, ExpMap, FirstOrder, "FirstOrder");
    defmt::println!("bench done");
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
