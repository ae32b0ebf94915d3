//! Instructions per step on the Cortex-M4F, counted with SysTick under QEMU `-icount shift=10`, for every
//! input model (Hold, Linear, History, TwiceRate, GaussPoints, DeltaAngles with TwoSample) × scheme (ExpMap,
//! Magnus4, Cf4, Rk4) × stabilizer (FirstOrder, Normalize) × accumulator (Plain, Kahan, FloatFloat) in f32, and the
//! README quick start's `Attitude::on_fifo` per sample (raw counts in, a FIFO burst of 32).
//!
//! On a core without an FPU (thumbv7m: the Cortex-M3 on mps2-an385; thumbv6m: the Cortex-M0 on the
//! microbit) f32 is soft-float, and the grid is the recommended configuration (History + ExpMap +
//! FirstOrder) and ExpMap + Hold with FirstOrder and with Normalize, plus the quick start.
//!
//! On every core: the fixed-point propagator (`fixed::Q30Propagator`, the recommended step on raw counts in
//! integer arithmetic), counted the same way.
//!
//! Each figure is (instructions of a loop of pushes − instructions of the same loop without the push) per
//! step of 1 ms: 64 steps, i.e. 64 pushes for one-sample-per-step models and 128 for TwiceRate, GaussPoints
//! and DeltaAngles(TwoSample), after the model's warm-up (History is full). Samples come from an opaque array
//! (`black_box`), so nothing is constant-folded; the zero-sized scheme and stabilizer types are measured as a
//! firmware that names them gets them; the count includes the input checks, the input model, the step and
//! the commit. Step angles are small (|ω| ≈ 1.2 rad/s at 1 kHz): the exponential maps take their Taylor
//! branch, as in normal flight.
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use quatprop::accumulate::{Accumulator, Plain};
#[cfg(fpu)]
use quatprop::accumulate::{FloatFloat, Kahan};
use quatprop::fixed::Q30Propagator;
#[cfg(fpu)]
use quatprop::input::coning::TwoSample;
#[cfg(fpu)]
use quatprop::input::{DeltaAngles, GaussPoints, Linear, TwiceRate};
use quatprop::input::{History, Hold};
#[cfg(fpu)]
use quatprop::scheme::{Cf4, Magnus4, Rk4};
use quatprop::scheme::{ExpMap, Scheme};
use quatprop::stabilize::{FirstOrder, Normalize, Stabilizer};
use quatprop::{Propagator, Quat};
use quatprop_firmware::bench_input::{fifo_counts, rates};
use quatprop_firmware::configs::Input;
use quatprop_firmware::exit::exit;
use quatprop_firmware::icount::{per_x100, Counter};
use quatprop_firmware::quickstart::Attitude;

/// Steps per measured loop (fewer in soft-float, whose steps are 20 to 30 times longer: a loop must stay
/// inside one wrap of SysTick, see `icount`).
const STEPS: u32 = if cfg!(fpu) { 64 } else { 16 };
/// Step (s).
const H: f32 = 1.0e-3;

#[inline(never)]
fn baseline<I: Input>(c: &Counter, s: &[I::Sample; 8], dt: f32, n: u32) -> u32 {
    let t0 = c.now();
    for i in 0..n as usize {
        black_box((s[i & 7], dt));
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

#[inline(never)]
fn pushes<S: Scheme<f32>, I: Input, Z: Stabilizer, A: Accumulator<f32>>(
    c: &Counter,
    p: &mut Propagator<f32, S, I, Z, A>,
    s: &[I::Sample; 8],
    dt: f32,
    n: u32,
) -> u32 {
    let t0 = c.now();
    for i in 0..n as usize {
        let _ = black_box(p.push(s[i & 7], dt));
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// Instructions per step ×100, or u32::MAX if a sample was refused.
fn measure<S: Scheme<f32>, I: Input, Z: Stabilizer, A: Accumulator<f32>>(
    c: &Counter,
    scheme: S,
    input: I,
    stabilizer: Z,
    accumulator: A,
) -> u32 {
    let Ok(p) = Propagator::new(Quat::IDENTITY, scheme, input, stabilizer) else {
        return u32::MAX;
    };
    let mut p = p.with_accumulator(accumulator);
    let dt = black_box(H / input.per_step() as f32);
    let w = rates();
    let s = black_box(w.map(|w| input.sample(w, dt)));
    // Warm-up: the samples that only start the model, then one full step.
    pushes(c, &mut p, &s, dt, input.warm_up() + input.per_step());
    let before = p.steps();
    let n = STEPS * input.per_step();
    let total = pushes(c, &mut p, &s, dt, n);
    let base = baseline::<I>(c, &s, dt, n);
    if p.steps() - before != u64::from(STEPS) {
        return u32::MAX;
    }
    per_x100(total, base, STEPS)
}

fn report(ok: &mut bool, what: [&str; 4], v: u32) {
    *ok &= v != u32::MAX;
    defmt::println!(
        "bench {=str} {=str} {=str} {=str} {=u32}.{=u32:02}",
        what[0],
        what[1],
        what[2],
        what[3],
        v / 100,
        v % 100
    );
}

#[cfg(fpu)]
fn accumulators<S: Scheme<f32>, I: Input, Z: Stabilizer>(
    c: &Counter,
    ok: &mut bool,
    s: S,
    i: I,
    z: Z,
    names: [&str; 2],
) {
    let what = |a| [i.name(), names[0], names[1], a];
    report(ok, what("Plain"), measure(c, s, i, z, Plain));
    report(ok, what("Kahan"), measure(c, s, i, z, Kahan::new()));
    report(
        ok,
        what("FloatFloat"),
        measure(c, s, i, z, FloatFloat::new()),
    );
}

#[cfg(fpu)]
fn stabilizers<S: Scheme<f32>, I: Input>(c: &Counter, ok: &mut bool, s: S, i: I, name: &str) {
    accumulators(c, ok, s, i, FirstOrder, [name, "FirstOrder"]);
    accumulators(c, ok, s, i, Normalize, [name, "Normalize"]);
}

#[cfg(fpu)]
fn schemes<I: Input>(c: &Counter, ok: &mut bool, i: I) {
    stabilizers(c, ok, ExpMap, i, "ExpMap");
    stabilizers(c, ok, Magnus4, i, "Magnus4");
    stabilizers(c, ok, Cf4, i, "Cf4");
    stabilizers(c, ok, Rk4, i, "Rk4");
}

/// Every input model × scheme × stabilizer × accumulator.
#[cfg(fpu)]
fn grid(c: &Counter, ok: &mut bool) {
    schemes(c, ok, Hold);
    schemes(c, ok, Linear::new());
    schemes(c, ok, History::new());
    schemes(c, ok, TwiceRate::new());
    schemes(c, ok, GaussPoints::new());
    schemes(c, ok, DeltaAngles::new(TwoSample));
}

/// Soft-float f32: the recommended configuration and the cheapest exponential-map ones.
#[cfg(not(fpu))]
fn grid(c: &Counter, ok: &mut bool) {
    let h = History::new();
    let what = |i, z| [i, "ExpMap", z, "Plain"];
    let v = measure(c, ExpMap, h, FirstOrder, Plain);
    report(ok, what(h.name(), "FirstOrder"), v);
    let v = measure(c, ExpMap, Hold, FirstOrder, Plain);
    report(ok, what(Hold.name(), "FirstOrder"), v);
    let v = measure(c, ExpMap, Hold, Normalize, Plain);
    report(ok, what(Hold.name(), "Normalize"), v);
}

/// Instructions of `n` pushes of raw counts into the fixed-point propagator.
#[inline(never)]
fn fixed_pushes(c: &Counter, p: &mut Q30Propagator, s: &[[i16; 3]; 8], n: u32) -> u32 {
    let t0 = c.now();
    for i in 0..n as usize {
        let _ = black_box(p.push(s[i & 7]));
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// Instructions of the same loop without the push.
#[inline(never)]
fn fixed_baseline(c: &Counter, s: &[[i16; 3]; 8], n: u32) -> u32 {
    let t0 = c.now();
    for i in 0..n as usize {
        black_box(s[i & 7]);
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// The fixed-point step ×100 (±2000 °/s counts at 1 kHz, the same rates as the grid), or u32::MAX if a
/// sample was refused.
fn fixed_point(c: &Counter) -> u32 {
    let rad_per_count = 2000.0_f32.to_radians() / 32768.0;
    let Ok(mut p) = Q30Propagator::new(Quat::<f32>::IDENTITY, rad_per_count, H) else {
        return u32::MAX;
    };
    let s = black_box(rates().map(|w| [w.x, w.y, w.z].map(|v| (v / rad_per_count) as i16)));
    fixed_pushes(c, &mut p, &s, 4);
    let before = p.steps();
    let total = fixed_pushes(c, &mut p, &s, STEPS);
    let base = fixed_baseline(c, &s, STEPS);
    if p.steps() - before != u64::from(STEPS) {
        return u32::MAX;
    }
    per_x100(total, base, STEPS)
}

/// Samples in the quick-start measurement: 8 FIFO bursts of 32 (one in soft-float).
const QS_SAMPLES: usize = if cfg!(fpu) { 256 } else { 32 };

/// Instructions of `bursts` calls of the quick start's `on_fifo` with 32 raw samples each.
#[inline(never)]
fn quickstart(c: &Counter, fifo: &[[i16; 3]; 32], bursts: usize) -> (u32, bool) {
    let Ok(mut attitude) = Attitude::new() else {
        return (0, false);
    };
    let t0 = c.now();
    for _ in 0..bursts {
        attitude.on_fifo(black_box(fifo));
    }
    let n = Counter::instructions(Counter::ticks(t0, c.now()));
    (n, black_box(attitude.attitude()).1 == 0)
}

#[entry]
fn main() -> ! {
    let c = Counter::take();
    let mut ok = true;
    grid(&c, &mut ok);
    let v = fixed_point(&c);
    ok &= v != u32::MAX;
    defmt::println!(
        "bench fixed Q30Propagator {=u32}.{=u32:02}",
        v / 100,
        v % 100
    );

    // The quick start: (its cost on QS_SAMPLES samples − its cost on none) per sample.
    let fifo = fifo_counts();
    let (full, accepted) = quickstart(&c, &fifo, QS_SAMPLES / 32);
    let (empty, _) = quickstart(&c, &fifo, 0);
    ok &= accepted;
    let per = per_x100(full, empty, QS_SAMPLES as u32);
    defmt::println!(
        "bench quickstart on_fifo per-sample {=u32}.{=u32:02} (samples={=usize}, fixed={=u32})",
        per / 100,
        per % 100,
        QS_SAMPLES,
        empty
    );
    defmt::println!("bench done");
    exit(ok)
}
