//! Target `burst`: `push_burst` (fixed period) and `push_burst_timed` (sensor timestamps with wraparound,
//! duplicates, backwards steps, gaps and raw values; 16-bit, 32-bit and any counter width) against the same
//! samples pushed one at a time, on every input model, f32 and f64, Plain and Kahan.
//!
//! Invariants after every burst call:
//! - the result is `Ok(len)`, or `Err(Refused { index, error })` with the index and error of the first
//!   sample that one-at-a-time pushing refuses;
//! - the propagator equals the one-at-a-time propagator bit for bit (`==`, attitude bits, `Debug` text);
//! - fixed period: the period equals one that gave each refused sample's `dt` back (`carry_over`);
//!   timestamps: the clock equals one committed only with accepted samples (`TickClock::advance`);
//! - a stream's first timestamp starts the clock and its sample starts the input model: the model is then
//!   `InputModel::start(sample)` of the model before, attitude and steps unchanged, a saturated sample
//!   counted; a non-finite first sample is refused with the propagator and clock unchanged.
//!
//! The burst is resumed after each refusal with the samples after the refused one, as documented.

use super::frontend::{clock_config, period_config};
use super::model::Model;
use super::push::{assert_unchanged, stabilizer};
use super::{assert_same_text, quat_bits, Bytes, Fz, ANGLE, RATE};
use quatprop::accumulate::{Accumulator, Kahan};
use quatprop::frontend::{FixedPeriod, TickClock};
use quatprop::input::coning::ConingKind;
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::scheme::SchemeKind;
use quatprop::stabilize::StabilizerKind;
use quatprop::Sample as _;
use quatprop::{Propagator, Quat, Refused};
use std::fmt::Debug;

/// Decodes and checks one input.
pub fn run(data: &[u8]) {
    crate::by_precision(data, config::<f32>, config::<f64>)
}

fn config<T: Fz>(b: &mut Bytes<'_>) {
    let s = SchemeKind::ALL[b.below(8)];
    let z = stabilizer(b);
    let kahan = b.bool();
    match b.below(11) {
        0 => with_model::<T, _>(b, s, Hold, z, kahan),
        1 => with_model::<T, _>(b, s, Linear::new(), z, kahan),
        2 => with_model::<T, _>(b, s, History::new(), z, kahan),
        3 => with_model::<T, _>(b, s, TwiceRate::new(), z, kahan),
        4 => with_model::<T, _>(b, s, GaussPoints::new(), z, kahan),
        n => with_model::<T, _>(
            b,
            s,
            DeltaAngles::new(ConingKind::ALL[(n - 5) % 6]),
            z,
            kahan,
        ),
    }
}

fn with_model<T: Fz, I: Model<T>>(
    b: &mut Bytes<'_>,
    s: SchemeKind,
    i: I,
    z: StabilizerKind,
    kahan: bool,
) {
    let Ok(p) = Propagator::new(Quat::<T>::IDENTITY, s, i, z) else {
        return;
    };
    let timed = b.bool();
    match (kahan, timed) {
        (false, false) => fixed(b, p),
        (false, true) => timed_bursts(b, p),
        (true, false) => fixed(b, p.with_accumulator(Kahan::new())),
        (true, true) => timed_bursts(b, p.with_accumulator(Kahan::new())),
    }
}

type P<T, I, A> = Propagator<T, SchemeKind, I, StabilizerKind, A>;

fn sample<T: Fz, I: Model<T>>(b: &mut Bytes<'_>, delta: bool) -> I::Sample {
    let v = b.vec::<T>(if delta { ANGLE } else { RATE });
    I::sample(v, b.u8() < 16)
}

fn is_delta<T: Fz, I: Model<T>>(i: &I) -> bool {
    matches!(i.schedule().kind(), super::model::Kind::Delta(_))
}

fn assert_same<T: Fz, I: Model<T>, A: Accumulator<T> + Debug + PartialEq>(
    a: &P<T, I, A>,
    b: &P<T, I, A>,
) {
    assert_unchanged(b, a, &"burst vs one at a time");
    assert_eq!(quat_bits(a.attitude()), quat_bits(b.attitude()));
}

/// What the burst calls run on: a fixed period (`push_burst`) or a sensor clock (`push_burst_timed`).
trait TimeBase<T: Fz, I: Model<T>>: Debug {
    /// One element of a burst: a sample, or a sample and its timestamp.
    type Item;
    /// What an assertion on the two time bases says.
    const WHAT: &'static str;
    /// The library's burst call.
    fn burst<A: Accumulator<T>>(
        &mut self,
        p: &mut P<T, I, A>,
        items: &[Self::Item],
    ) -> Result<usize, Refused>;
    /// What the burst call is documented to do, one sample at a time.
    fn one_at_a_time<A: Accumulator<T> + Debug + PartialEq>(
        &mut self,
        p: &mut P<T, I, A>,
        items: &[Self::Item],
    ) -> Result<usize, Refused>;
}

impl<T: Fz, I: Model<T>> TimeBase<T, I> for FixedPeriod<T> {
    type Item = I::Sample;
    const WHAT: &'static str = "fixed period: burst vs one at a time";
    fn burst<A: Accumulator<T>>(
        &mut self,
        p: &mut P<T, I, A>,
        items: &[I::Sample],
    ) -> Result<usize, Refused> {
        p.push_burst(items, self)
    }
    /// Each sample's `dt` from the period; a refused sample's interval carried over.
    fn one_at_a_time<A: Accumulator<T> + Debug + PartialEq>(
        &mut self,
        p: &mut P<T, I, A>,
        items: &[I::Sample],
    ) -> Result<usize, Refused> {
        for (index, s) in items.iter().enumerate() {
            let dt = self.next_dt();
            if let Err(error) = p.push(*s, dt) {
                self.carry_over(dt);
                return Err(Refused { index, error });
            }
        }
        Ok(items.len())
    }
}

impl<T: Fz, I: Model<T>> TimeBase<T, I> for TickClock<T> {
    type Item = (I::Sample, u32);
    const WHAT: &'static str = "tick clock: burst vs one at a time";
    fn burst<A: Accumulator<T>>(
        &mut self,
        p: &mut P<T, I, A>,
        items: &[(I::Sample, u32)],
    ) -> Result<usize, Refused> {
        p.push_burst_timed(items, self)
    }
    fn one_at_a_time<A: Accumulator<T> + Debug + PartialEq>(
        &mut self,
        p: &mut P<T, I, A>,
        items: &[(I::Sample, u32)],
    ) -> Result<usize, Refused> {
        one_at_a_time(p, self, items)
    }
}

/// `chunk` through the burst call on `burst` and one sample at a time on `one` (each a propagator and its
/// time base), both resumed after a refusal with the samples after the refused one, until the burst takes
/// the rest. After each call the results, the propagators and the time bases must agree.
fn burst_vs_one_at_a_time<T, I, A, B>(
    (a, base_a): (&mut P<T, I, A>, &mut B),
    (one, base_one): (&mut P<T, I, A>, &mut B),
    chunk: &[B::Item],
) where
    T: Fz,
    I: Model<T>,
    A: Accumulator<T> + Debug + PartialEq,
    B: TimeBase<T, I>,
{
    let mut rest = chunk;
    loop {
        let ra = base_a.burst(a, rest);
        let rb = base_one.one_at_a_time(one, rest);
        // Ok(n) against Ok(m) is decided by n == m; a refusal by its Debug text (its payload may be NaN:
        // a step angle of 0·∞).
        if !matches!((&ra, &rb), (Ok(n), Ok(m)) if n == m) {
            assert_same_text(&ra, &rb, &"burst result: burst vs one at a time");
        }
        assert_same(a, one);
        // Debug text: a time base whose arithmetic overflowed (a period near T::MAX) carries NaN.
        assert_same_text(base_a, base_one, &B::WHAT);
        match ra {
            Ok(n) => {
                assert_eq!(n, rest.len());
                break;
            }
            Err(r) => rest = &rest[r.index + 1..],
        }
    }
}

fn fixed<T: Fz, I: Model<T>, A: Accumulator<T> + Debug + PartialEq>(
    b: &mut Bytes<'_>,
    p: P<T, I, A>,
) {
    let Some((period, _)) = period_config::<T>(b) else {
        return;
    };
    let delta = is_delta(&p.input());
    let (mut a, mut one) = (p, p);
    let (mut pa, mut pb): (FixedPeriod<T>, FixedPeriod<T>) = (period, period);
    for _ in 0..32 {
        if b.is_empty() {
            break;
        }
        let len = b.below(17);
        let chunk: Vec<I::Sample> = (0..len).map(|_| sample::<T, I>(b, delta)).collect();
        burst_vs_one_at_a_time((&mut a, &mut pa), (&mut one, &mut pb), &chunk);
    }
}

fn timed_bursts<T: Fz, I: Model<T>, A: Accumulator<T> + Debug + PartialEq>(
    b: &mut Bytes<'_>,
    p: P<T, I, A>,
) {
    let Some((clock, _, _)) = clock_config::<T>(b) else {
        return;
    };
    let delta = is_delta(&p.input());
    let (mut a, mut one) = (p, p);
    let (mut ca, mut cb): (TickClock<T>, TickClock<T>) = (clock, clock);
    let period_ticks = u32::from(b.u16()).max(1);
    let mut t = b.u32();
    for _ in 0..32 {
        if b.is_empty() {
            break;
        }
        if b.u8() < 16 {
            // The sensor was reset: both clocks forget the last timestamp, both models their samples.
            ca.restart();
            cb.restart();
            a.restart_input();
            one.restart_input();
        }
        let len = b.below(17);
        let mut chunk = Vec::with_capacity(len);
        for _ in 0..len {
            t = match b.below(16) {
                0..=9 => t.wrapping_add(period_ticks),
                10 => t,
                11 => t.wrapping_sub(u32::from(b.u8())),
                12 | 13 => t.wrapping_add(period_ticks.wrapping_mul(2 + b.below(8) as u32)),
                14 => t.wrapping_add(b.u32()),
                _ => b.u32(),
            };
            chunk.push((sample::<T, I>(b, delta), t));
        }
        burst_vs_one_at_a_time((&mut a, &mut ca), (&mut one, &mut cb), &chunk);
    }
}

/// The documented behaviour of `push_burst_timed`, one sample at a time: the clock commits only with an
/// accepted sample; the stream's first timestamp starts the clock and its sample starts the model.
fn one_at_a_time<T: Fz, I: Model<T>, A: Accumulator<T> + Debug + PartialEq>(
    p: &mut P<T, I, A>,
    clock: &mut TickClock<T>,
    samples: &[(I::Sample, u32)],
) -> Result<usize, Refused> {
    for (index, (s, t)) in samples.iter().enumerate() {
        let (next, dt) = clock
            .advance(*t)
            .map_err(|error| Refused { index, error })?;
        match dt {
            Some(dt) => {
                p.push(*s, dt).map_err(|error| Refused { index, error })?;
                *clock = next;
            }
            None => {
                // Only the library can start a propagator's model: check that it did exactly that.
                let before = *p;
                let clock_before = *clock;
                let r = p.push_burst_timed(&[(*s, *t)], clock);
                match InputModel::start(&before.input(), s) {
                    Ok(started) => {
                        assert_eq!(r, Ok(1), "first sample refused");
                        assert!(p.input() == started, "first sample did not start the model");
                        assert_eq!(quat_bits(p.attitude()), quat_bits(before.attitude()));
                        assert_eq!(
                            (p.steps(), p.corrections()),
                            (before.steps(), before.corrections())
                        );
                        assert_eq!(
                            p.saturated_samples(),
                            before.saturated_samples() + u64::from(s.is_saturated())
                        );
                        assert!(
                            *clock == next,
                            "the first timestamp did not start the clock"
                        );
                    }
                    Err(error) => {
                        assert_eq!(r, Err(Refused { index: 0, error }));
                        assert_unchanged(&before, p, &error);
                        assert!(*clock == clock_before);
                        return Err(Refused { index, error });
                    }
                }
            }
        }
    }
    Ok(samples.len())
}
