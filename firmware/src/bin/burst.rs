//! FIFO bursts on the Cortex-M4F, counted with SysTick under QEMU `-icount shift=10` like `bench` (a program
//! of its own, so the grid's figures keep `bench`'s code layout): `Propagator::push_burst` with a
//! `FixedPeriod` (ExpMap + History + FirstOrder, Plain, f32) over bursts of 1, 8 and 32 samples against one
//! `push` per sample; the same bursts through the run-time configuration (`config::Configured` built from
//! `Config::RECOMMENDED`), and Rk4 + Linear + Normalize + Kahan both ways; and the README quick start's
//! `Attitude::on_fifo` fed FIFO reads of 1, 8 and 32.
//!
//! Each figure is (instructions of the loop over 256 samples − instructions of the same timed call over
//! none) / 256: what a caller runs per sample, loop, `dt` and error check included. Every burst length must
//! end on the attitude of the single pushes bit for bit (and every read length on the same quick-start
//! attitude), or the program exits 1.
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use quatprop::accumulate::{Accumulator, Kahan};
use quatprop::config::{AccumulatorKind, Config, Configured, InputKind};
use quatprop::frontend::FixedPeriod;
use quatprop::input::{History, InputModel, Linear};
use quatprop::scheme::{ExpMap, Rk4, Scheme, SchemeKind};
use quatprop::stabilize::{FirstOrder, Normalize, Stabilizer, StabilizerKind};
use quatprop::{GyroSample, Propagator, Quat};
use quatprop_firmware::bench_input::{fifo_counts, rates};
use quatprop_firmware::exit::exit;
use quatprop_firmware::icount::{per_x100, Counter};
use quatprop_firmware::quickstart::Attitude;

/// Samples in each burst measurement (a multiple of every burst length).
const BURST_SAMPLES: usize = 256;
/// Burst lengths measured.
const BURST_LENGTHS: [usize; 3] = [1, 8, 32];

type Recommended = Propagator<f32, ExpMap, History<f32>, FirstOrder>;

/// The burst samples: 32 opaque body rates (the bench's 8, repeated).
fn burst_samples() -> [GyroSample<f32>; 32] {
    let w = rates();
    let mut s = [GyroSample::default(); 32];
    for (i, x) in s.iter_mut().enumerate() {
        *x = GyroSample::new(w[i & 7]);
    }
    black_box(s)
}

/// `n` single pushes with a constant `dt`, errors ignored (the grid's loop).
#[inline(never)]
fn singles_const(
    c: &Counter,
    p: &mut Recommended,
    s: &[GyroSample<f32>; 32],
    dt: f32,
    n: usize,
) -> u32 {
    let t0 = c.now();
    for i in 0..n {
        let _ = black_box(p.push(s[i & 31], dt));
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// `n` single pushes doing what `push_burst` does per sample: `dt` from the period, and on a refusal the
/// interval carried over and the refusal counted.
#[inline(never)]
fn singles_period(
    c: &Counter,
    p: &mut Recommended,
    s: &[GyroSample<f32>; 32],
    period: &mut FixedPeriod<f32>,
    n: usize,
) -> (u32, u32) {
    let mut refused = 0;
    let t0 = c.now();
    for i in 0..n {
        let dt = period.next_dt();
        if p.push(s[i & 31], dt).is_err() {
            period.carry_over(dt);
            refused += 1;
        }
    }
    (Counter::instructions(Counter::ticks(t0, c.now())), refused)
}

/// `push_burst` for the static types and for the run-time configuration alike.
trait Bursts {
    fn burst(
        &mut self,
        s: &[GyroSample<f32>],
        period: &mut FixedPeriod<f32>,
    ) -> Result<usize, quatprop::Refused>;
    fn state(&self) -> (Quat<f32>, u64);
}

/// [`Bursts`] by the inherent methods of the same names, which the static types and `Configured` both have
/// (no library trait names them).
macro_rules! bursts_by_inherent_methods {
    ($([$($generics:tt)*] $ty:ty;)*) => {$(
        impl<$($generics)*> Bursts for $ty {
            #[inline(always)]
            fn burst(
                &mut self,
                s: &[GyroSample<f32>],
                period: &mut FixedPeriod<f32>,
            ) -> Result<usize, quatprop::Refused> {
                self.push_burst(s, period)
            }
            fn state(&self) -> (Quat<f32>, u64) {
                (self.attitude(), self.steps())
            }
        }
    )*};
}

bursts_by_inherent_methods! {
    [
        S: Scheme<f32>,
        I: InputModel<f32, Sample = GyroSample<f32>>,
        Z: Stabilizer,
        A: Accumulator<f32>,
    ] Propagator<f32, S, I, Z, A>;
    [] Configured<f32>;
}

/// `bursts` calls of `push_burst` with `len` samples each (the same sample sequence as above).
#[inline(never)]
fn bursts<P: Bursts>(
    c: &Counter,
    p: &mut P,
    s: &[GyroSample<f32>; 32],
    period: &mut FixedPeriod<f32>,
    len: usize,
    bursts: usize,
) -> (u32, u32) {
    let mut refused = 0;
    let t0 = c.now();
    for k in 0..bursts {
        let at = (k * len) & 31;
        let burst = s.get(at..at + len).unwrap_or(&[]);
        if p.burst(burst, period).is_err() {
            refused += 1;
        }
    }
    (Counter::instructions(Counter::ticks(t0, c.now())), refused)
}

/// A warmed-up propagator and period (History full, one step taken).
fn warmed(s: &[GyroSample<f32>; 32]) -> Option<(Recommended, FixedPeriod<f32>)> {
    warm(
        Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder).ok()?,
        s,
    )
}

/// `p` and a period after the first four samples.
fn warm<P: Bursts>(mut p: P, s: &[GyroSample<f32>; 32]) -> Option<(P, FixedPeriod<f32>)> {
    let mut period = FixedPeriod::new(1.0e-3).ok()?;
    p.burst(s.get(..4)?, &mut period).ok()?;
    Some((p, period))
}

/// Bursts of 32 through `static_p` and through `configured` (the same configuration, chosen at run time):
/// per-sample figures of both; false if anything was refused or the bits differ.
fn static_vs_configured<P: Bursts>(
    c: &Counter,
    name: &str,
    static_p: P,
    configured: Configured<f32>,
    s: &[GyroSample<f32>; 32],
) -> bool {
    let (Some((mut a, mut pa)), Some((mut b, mut pb))) = (warm(static_p, s), warm(configured, s))
    else {
        return false;
    };
    let len = 32;
    let (empty, _) = bursts(c, &mut a, s, &mut pa, len, 0);
    let (total, ra) = bursts(c, &mut a, s, &mut pa, len, BURST_SAMPLES / len);
    let static_cost = per_sample_x100(total, empty);
    let (empty, _) = bursts(c, &mut b, s, &mut pb, len, 0);
    let (total, rb) = bursts(c, &mut b, s, &mut pb, len, BURST_SAMPLES / len);
    let same = a.state() == b.state();
    defmt::println!(
        "bench config {=str} len={=usize} static={=u32}.{=u32:02} configured={=u32}.{=u32:02} identical={=bool}",
        name,
        len,
        static_cost / 100,
        static_cost % 100,
        per_sample_x100(total, empty) / 100,
        per_sample_x100(total, empty) % 100,
        same
    );
    ra == 0 && rb == 0 && same
}

/// The run-time configuration against the static types.
fn config_figures(c: &Counter) -> bool {
    let s = burst_samples();
    let rk4 = Config {
        scheme: SchemeKind::Rk4,
        input: InputKind::Linear,
        stabilizer: StabilizerKind::Normalize,
        accumulator: AccumulatorKind::Kahan,
        ..Config::RECOMMENDED
    };
    let (Ok(rec_static), Ok(rec_config), Ok(rk4_static), Ok(rk4_config)) = (
        Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder),
        black_box(Config::RECOMMENDED).build(Quat::IDENTITY),
        Propagator::new(Quat::IDENTITY, Rk4, Linear::new(), Normalize),
        black_box(rk4).build(Quat::IDENTITY),
    ) else {
        return false;
    };
    let rk4_static = rk4_static.with_accumulator(Kahan::new());
    static_vs_configured(c, "recommended", rec_static, rec_config, &s)
        & static_vs_configured(c, "rk4-linear-normalize-kahan", rk4_static, rk4_config, &s)
}

/// (instructions of the loop over `BURST_SAMPLES` samples − instructions of the same timed call over none)
/// per sample, ×100: the loop, the `dt` and the error check count, as a caller pays them.
fn per_sample_x100(total: u32, empty: u32) -> u32 {
    per_x100(total, empty, BURST_SAMPLES as u32)
}

fn report_burst(what: &str, len: usize, v: u32, identical: bool) {
    defmt::println!(
        "bench burst {=str} len={=usize} {=u32}.{=u32:02} identical={=bool}",
        what,
        len,
        v / 100,
        v % 100,
        identical
    );
}

/// Burst vs single pushes (ExpMap + History + FirstOrder, Plain); false if anything was refused or the bits
/// differ.
fn burst_figures(c: &Counter) -> bool {
    let s = burst_samples();
    let Some((mut p, _)) = warmed(&s) else {
        return false;
    };
    let dt = black_box(1.0e-3_f32);
    let empty = singles_const(c, &mut p, &s, dt, 0);
    let v = per_sample_x100(singles_const(c, &mut p, &s, dt, BURST_SAMPLES), empty);
    report_burst("push-const-dt", 1, v, true);
    let Some((mut single, mut single_period)) = warmed(&s) else {
        return false;
    };
    let (empty, _) = singles_period(c, &mut single, &s, &mut single_period, 0);
    let (total, mut refused) =
        singles_period(c, &mut single, &s, &mut single_period, BURST_SAMPLES);
    report_burst("push-period", 1, per_sample_x100(total, empty), true);
    for len in BURST_LENGTHS {
        let Some((mut b, mut period)) = warmed(&s) else {
            return false;
        };
        let (empty, _) = bursts(c, &mut b, &s, &mut period, len, 0);
        let (total, r) = bursts(c, &mut b, &s, &mut period, len, BURST_SAMPLES / len);
        refused += r;
        // Bit for bit the attitude of the same samples pushed one at a time with the same period.
        let same = b.attitude() == single.attitude() && b.steps() == single.steps();
        report_burst("push_burst", len, per_sample_x100(total, empty), same);
        refused += u32::from(!same);
    }
    refused == 0
}

/// The quick start fed `BURST_SAMPLES` raw samples in FIFO reads of 1, 8 and 32; false if a sample was
/// refused or the attitudes differ.
fn quickstart_bursts(c: &Counter, fifo: &[[i16; 3]; 32]) -> bool {
    let mut ok = true;
    let mut first = None;
    for len in BURST_LENGTHS {
        let Ok(mut attitude) = Attitude::new() else {
            return false;
        };
        let t0 = c.now();
        for k in 0..BURST_SAMPLES / len {
            let at = (k * len) & 31;
            attitude.on_fifo(black_box(fifo.get(at..at + len).unwrap_or(&[])));
        }
        let total = Counter::instructions(Counter::ticks(t0, c.now()));
        let t0 = c.now();
        let empty = Counter::instructions(Counter::ticks(t0, c.now()));
        let (q, refused) = attitude.attitude();
        // Any read length gives the same bits.
        let same = q == *first.get_or_insert(q);
        ok &= refused == 0 && same;
        report_burst("quickstart", len, per_sample_x100(total, empty), same);
    }
    ok
}

#[entry]
fn main() -> ! {
    let c = Counter::take();
    let mut ok = burst_figures(&c);
    ok &= config_figures(&c);
    let fifo = fifo_counts();
    ok &= quickstart_bursts(&c, &fifo);
    defmt::println!("bench burst done");
    exit(ok)
}
