//! Instructions per step on the Cortex-M4F, counted with SysTick under QEMU `-icount shift=10`, for every
//! input model (Hold, Linear, History, TwiceRate, GaussPoints, DeltaAngles with TwoSample) × scheme (ExpMap,
//! Magnus4, Cf4, Rk4) × stabilizer (FirstOrder, Normalize) × accumulator (Plain, Kahan, FloatFloat) in f32, and the
//! README quick start's `Attitude::on_fifo` per sample (raw counts in, a FIFO burst of 32).
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
use quatprop::accumulate::{Accumulator, FloatFloat, Kahan, Plain};
use quatprop::input::coning::TwoSample;
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, Linear, TwiceRate};
use quatprop::scheme::{Cf4, ExpMap, Magnus4, Rk4, Scheme};
use quatprop::stabilize::{FirstOrder, Normalize, Stabilizer};
use quatprop::{Propagator, Quat, Vec3};
use quatprop_firmware::configs::Input;
use quatprop_firmware::exit::{exit, fail};
use quatprop_firmware::icount::Counter;
use quatprop_firmware::quickstart::Attitude;

/// Steps per measured loop.
const STEPS: u32 = 64;
/// Step (s).
const H: f32 = 1.0e-3;

fn rates() -> [Vec3<f32>; 8] {
    let mut r = [Vec3::ZERO; 8];
    for (i, w) in r.iter_mut().enumerate() {
        let a = i as f32 * 0.7;
        *w = Vec3::new(0.3 + 0.1 * a, -0.2 + 0.05 * a, 1.0 - 0.03 * a);
    }
    r
}

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
    ((u64::from(total.saturating_sub(base)) * 100) / u64::from(STEPS)) as u32
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

fn stabilizers<S: Scheme<f32>, I: Input>(c: &Counter, ok: &mut bool, s: S, i: I, name: &str) {
    accumulators(c, ok, s, i, FirstOrder, [name, "FirstOrder"]);
    accumulators(c, ok, s, i, Normalize, [name, "Normalize"]);
}

fn schemes<I: Input>(c: &Counter, ok: &mut bool, i: I) {
    stabilizers(c, ok, ExpMap, i, "ExpMap");
    stabilizers(c, ok, Magnus4, i, "Magnus4");
    stabilizers(c, ok, Cf4, i, "Cf4");
    stabilizers(c, ok, Rk4, i, "Rk4");
}

/// Samples in the quick-start measurement: 8 FIFO bursts of 32.
const QS_SAMPLES: usize = 256;

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
    let Some(cp) = cortex_m::Peripherals::take() else {
        fail("peripherals")
    };
    let c = Counter::new(cp.SYST);
    let mut ok = true;
    schemes(&c, &mut ok, Hold);
    schemes(&c, &mut ok, Linear::new());
    schemes(&c, &mut ok, History::new());
    schemes(&c, &mut ok, TwiceRate::new());
    schemes(&c, &mut ok, GaussPoints::new());
    schemes(&c, &mut ok, DeltaAngles::new(TwoSample));

    // The quick start: (its cost on QS_SAMPLES samples − its cost on none) per sample.
    let w = rates();
    let mut fifo = [[0i16; 3]; 32];
    for (i, s) in fifo.iter_mut().enumerate() {
        let r = w[i & 7];
        *s = [r.x, r.y, r.z].map(|v| (v * 938.734_6) as i16); // counts at ±2000 °/s
    }
    let (full, accepted) = quickstart(&c, &fifo, QS_SAMPLES / 32);
    let (empty, _) = quickstart(&c, &fifo, 0);
    ok &= accepted;
    let per = (u64::from(full.saturating_sub(empty)) * 100 / QS_SAMPLES as u64) as u32;
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
