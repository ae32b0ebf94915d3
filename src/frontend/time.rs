//! Time bases: the `dt` of each sample, exact over any number of samples.
//!
//! In f32 a period such as 1 ms is not representable: `f32(0.001) = 0.001 + 4.75e-11`, a relative error of
//! 4.75e-8 that a propagator fed the same rounded `dt` every step turns into 4.75e-3 rad after 10⁸ steps at
//! 1 rad/s, whatever its arithmetic. Both time bases here keep the period as a pair `hi + lo` (`hi` the
//! rounded period, `lo` its rounding error, both in `T`) and carry the part of the exact time that each
//! rounded `dt` leaves out into the next one: the `dt`s handed out sum to the exact elapsed time within half
//! an ulp of one `dt` plus the rounding of `lo` itself, about 2⁻⁴⁸ of the period per sample in f32 (the lab
//! measures Σdt − k·0.001 = 1.16e-10 s after 10⁸ samples of 1 ms: one ulp of `dt`).

use crate::exact::{two_product, two_sum};
use crate::{Error, Real};

fn split_period<T: Real>(period: f64) -> Result<(T, T), Error> {
    if !period.is_finite() {
        return Err(Error::NonFiniteStep);
    }
    if !(period > 0.0) {
        return Err(Error::NonPositiveStep);
    }
    let hi = T::from_f64(period);
    let lo = T::from_f64(period - hi.to_f64());
    if !(hi > T::ZERO && hi <= T::MAX) {
        // The period underflows or overflows T.
        return Err(Error::NonPositiveStep);
    }
    Ok((hi, lo))
}

/// A fixed sample period, given once (in `f64`) and kept exactly: each [`FixedPeriod::next_dt`] is the
/// rounded period plus the carried remainder, so `Σ dt` after k samples equals `k·period` within half an
/// ulp of `dt` (not `k` roundings of it).
///
/// ```
/// use quatprop::frontend::FixedPeriod;
/// let mut p = FixedPeriod::<f32>::new(1.0e-3)?;
/// let (mut exact, mut naive) = (0.0_f64, 0.0_f64);
/// for _ in 0..1_000_000 {
///     exact += p.next_dt() as f64; // the dt handed out, summed without further rounding
///     naive += 1.0e-3_f32 as f64;
/// }
/// assert!((exact - 1000.0).abs() < 1e-10); // 1000 s to within half an ulp of 1 ms
/// assert!((naive - 1000.0).abs() > 4e-5); // f32(0.001) is 4.75e-8 relative off
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FixedPeriod<T> {
    hi: T,
    lo: T,
    /// The sub-ulp remainder of the time handed out so far (normally below half an ulp of `hi`).
    carry: T,
    /// Intervals given back by [`FixedPeriod::carry_over`] and not yet handed out (normally zero).
    owed: T,
}

impl<T: Real> FixedPeriod<T> {
    /// The sample period (s).
    ///
    /// # Errors
    /// [`Error::NonFiniteStep`] for a NaN or infinite period, [`Error::NonPositiveStep`] for a zero or
    /// negative one (or one that underflows `T`).
    pub fn new(period: f64) -> Result<Self, Error> {
        let (hi, lo) = split_period(period)?;
        Ok(Self {
            hi,
            lo,
            carry: T::ZERO,
            owed: T::ZERO,
        })
    }

    /// The period rounded to `T` (s).
    #[must_use]
    pub fn period(&self) -> T {
        self.hi
    }

    /// Gives back a `dt` this time base handed out for a sample that was refused: the interval goes into
    /// the next [`FixedPeriod::next_dt`], so no time is lost, however long the run of refused samples (the
    /// interval is kept as an exact sum, not rounded into the carry).
    ///
    /// ```
    /// use quatprop::frontend::FixedPeriod;
    /// let mut p = FixedPeriod::<f64>::new(0.25)?;
    /// let dt = p.next_dt();
    /// p.carry_over(dt); // that sample was refused
    /// assert_eq!(p.next_dt(), 0.5); // the next one covers both periods
    /// # Ok::<(), quatprop::Error>(())
    /// ```
    #[inline]
    pub fn carry_over(&mut self, dt: T) {
        let (owed, rounding) = two_sum(self.owed, dt);
        self.owed = owed;
        self.carry += rounding;
    }

    /// The `dt` (s) of the next sample: the period (plus any interval given back by
    /// [`FixedPeriod::carry_over`]), rounded so that the `dt`s sum to the exact elapsed time.
    ///
    /// Every `dt` is positive: after a `dt` covering a very long run of refused samples, its rounding (half
    /// an ulp of that `dt`: 1 ms after 2²⁴ refused samples of 1 ms in f32) can exceed a period; a remainder
    /// beyond an eighth of the period is then paid an eighth of a period per sample.
    #[inline]
    pub fn next_dt(&mut self) -> T {
        let e = self.carry + self.lo;
        // Steady state: nothing owed and the remainder a fraction of an ulp of the period.
        if self.owed == T::ZERO && e.abs() * T::from_f64(8.0) <= self.hi {
            let dt = self.hi + e;
            // Fast2Sum (|hi| ≥ |e|): dt − hi is exact, and so is e − (dt − hi).
            self.carry = e - (dt - self.hi);
            return dt;
        }
        self.next_dt_carrying()
    }

    /// [`FixedPeriod::next_dt`] with an interval owed or a remainder beyond an eighth of the period: the
    /// period, the interval owed and the remainder summed exactly (2Sum); a negative remainder beyond an
    /// eighth of that sum is left for the next samples.
    #[inline(never)]
    fn next_dt_carrying(&mut self) -> T {
        let (a, rounding) = two_sum(self.hi, self.owed);
        let e = (self.carry + self.lo) + rounding;
        let floor = -a * T::from_f64(0.125);
        let paid = if e < floor { floor } else { e };
        let (dt, rest) = two_sum(a, paid);
        self.carry = (e - paid) + rest;
        self.owed = T::ZERO;
        dt
    }
}

/// The sensor's own clock: per-sample timestamps in integer ticks of a clock of known frequency, wrapping
/// at 2³² (a 32-bit counter; a narrower counter's timestamps are its value, wrapping at its own width:
/// give that width). `dt` is the tick count since the previous timestamp times the tick period, exact in
/// the same carried sense as [`FixedPeriod`]: the `dt`s handed out since the last [`TickClock::restart`]
/// sum to the elapsed ticks times the period within half an ulp of the longest of them (plus about 2⁻⁴⁸ of
/// each `dt` in f32 for the rounding of the carry and of the period's low part).
///
/// The carried remainder goes into the next `dt` only up to an eighth of that `dt`'s interval; the rest
/// stays carried and is paid over the following samples. After a long interval the remainder (up to half an
/// ulp of its `dt`: 2.4 µs after a 40 s gap in f32) can be longer than a short next interval (1 µs, one tick
/// at 1 MHz); given whole, it would make that `dt` negative. So every `dt` is positive and within an eighth
/// of its own interval (`n` ticks give `dt` in `[⅞, 9⁄8]·n·period` to rounding), and a carry only shrinks
/// while it is spread. In steady operation the remainder is far below that limit (half an ulp of a `dt`
/// like the next one) and goes whole into the next `dt`.
///
/// A timestamp that does not advance (a duplicate) or goes backwards (a wrapped difference beyond half the
/// counter's range) is refused with a typed error and leaves the clock unchanged. A jump of more than
/// 1.5 times the previous interval is counted as a gap ([`TickClock::gaps`]) and integrated honestly over
/// its true length. A `History` input model spans one missing sample and restarts by itself beyond
/// [`History::GAP_RATIO`](crate::input::History::GAP_RATIO) times the previous interval (two or more
/// missing).
///
/// ```
/// use quatprop::frontend::TickClock;
/// use quatprop::Error;
/// let mut clock = TickClock::<f32>::new(1.0e6, 32)?; // 1 MHz ticks, 32-bit counter
/// assert_eq!(clock.dt(u32::MAX - 499)?, None); // the first timestamp only starts the clock
/// let dt = clock.dt(500)?.unwrap(); // wrapped: 1000 ticks later
/// assert!((dt - 1.0e-3).abs() < 1e-10);
/// assert_eq!(clock.dt(500), Err(Error::TimestampNotIncreasing)); // duplicate
/// assert_eq!(clock.dt(400), Err(Error::TimestampNotIncreasing)); // backwards
/// assert!(clock.dt(3500)?.is_some()); // 3 ms: a gap
/// assert_eq!(clock.gaps(), 1);
/// # Ok::<(), Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TickClock<T> {
    hi: T,
    lo: T,
    carry: T,
    mask: u32,
    last: Option<u32>,
    previous_ticks: u32,
    gaps: u32,
}

impl<T: Real> TickClock<T> {
    /// A clock of `frequency` ticks per second whose counter is `bits` wide (1 to 32).
    ///
    /// # Errors
    /// [`Error::NonFiniteStep`] / [`Error::NonPositiveStep`] for a frequency that is not finite and positive
    /// (or so low that a tick exceeds `T::MAX / 2²⁷` s); [`Error::InvalidClock`] for a width outside 1–32.
    pub fn new(frequency: f64, bits: u32) -> Result<Self, Error> {
        if !(1..=32).contains(&bits) {
            return Err(Error::InvalidClock);
        }
        if !frequency.is_finite() {
            return Err(Error::NonFiniteStep);
        }
        if !(frequency > 0.0) {
            return Err(Error::NonPositiveStep);
        }
        let (hi, lo): (T, T) = split_period(1.0 / frequency)?;
        // The exact product splits the period with a factor 2^⌈p/2⌉ + 1 (134217729 for f64): it must stay
        // finite. Ticks longer than T::MAX / 2^27 s (8.3e34 s in f32) are refused.
        if !(hi.to_f64() * 134_217_729.0 <= <T as Real>::MAX.to_f64()) {
            return Err(Error::NonFiniteStep);
        }
        Ok(Self {
            hi,
            lo,
            carry: T::ZERO,
            mask: if bits == 32 {
                u32::MAX
            } else {
                (1u32 << bits) - 1
            },
            last: None,
            previous_ticks: 0,
            gaps: 0,
        })
    }

    /// Gaps seen so far: intervals longer than 1.5 times the previous one.
    #[must_use]
    pub fn gaps(&self) -> u32 {
        self.gaps
    }

    /// Forgets the last timestamp (after the sensor was reset): the next one only starts the clock.
    pub fn restart(&mut self) {
        self.last = None;
        self.previous_ticks = 0;
        self.carry = T::ZERO;
    }

    /// The `dt` (s) from the previous timestamp to `timestamp` (ticks), or `None` for the first one.
    ///
    /// # Errors
    /// [`Error::TimestampNotIncreasing`] for a duplicate or a timestamp behind the previous one; the clock is
    /// then unchanged.
    pub fn dt(&mut self, timestamp: u32) -> Result<Option<T>, Error> {
        let (next, dt) = self.advance(timestamp)?;
        *self = next;
        Ok(dt)
    }

    /// [`TickClock::dt`] without changing the clock: the clock after `timestamp`, and the `dt`. Commit the
    /// returned clock only when the sample is accepted, so that a refused sample's interval carries into
    /// the next one ([`crate::Propagator::push_burst_timed`] does).
    ///
    /// # Errors
    /// As [`TickClock::dt`].
    pub fn advance(&self, timestamp: u32) -> Result<(Self, Option<T>), Error> {
        let timestamp = timestamp & self.mask;
        let mut next = *self;
        next.last = Some(timestamp);
        let Some(last) = self.last else {
            return Ok((next, None));
        };
        let ticks = timestamp.wrapping_sub(last) & self.mask;
        if ticks == 0 || ticks > self.mask / 2 {
            return Err(Error::TimestampNotIncreasing);
        }
        // n·(hi + lo) + carry, with n·hi split exactly. n rounds in f32 beyond 2²⁴ ticks: its rounding
        // error (an integer below 2⁸, exact in T) is added back. It is taken in f64, where both are exact:
        // near 2³¹ ticks f32 rounds n up to 2³¹, which `as i32` would saturate to 2³¹ − 1.
        let count = ticks.min(i32::MAX as u32) as i32;
        let n = T::from_i32(count);
        let n_err = T::from_f64(f64::from(count) - n.to_f64());
        let (p, p_err) = two_product(n, self.hi);
        // The carry goes into this dt up to an eighth of the interval; the rest stays carried. After a long
        // interval the carry (up to half an ulp of its dt) can exceed a short interval's whole length.
        let limit = p * T::from_f64(0.125);
        let (given, rest) = if self.carry.abs() <= limit {
            (self.carry, None)
        } else {
            let target = if self.carry > T::ZERO { limit } else { -limit };
            // given + rest = carry exactly: if |target| ≤ |carry|/2 then rest ≥ carry/2 (same sign) and
            // carry − rest is exact (Sterbenz); otherwise carry − target is exact and given = target.
            let rest = self.carry - target;
            (self.carry - rest, Some(rest))
        };
        let (dt, s_err) = two_sum(p, p_err + n_err * self.hi + n * self.lo + given);
        // |s_err + rest| < |carry| − interval/8 + ½ ulp(dt): a spread carry only shrinks.
        next.carry = match rest {
            Some(rest) => s_err + rest,
            None => s_err,
        };
        if self.previous_ticks != 0 && u64::from(ticks) * 2 > u64::from(self.previous_ticks) * 3 {
            next.gaps = self.gaps.saturating_add(1);
        }
        next.previous_ticks = ticks;
        Ok((next, Some(dt)))
    }
}
