//! The input models: each owns the samples it keeps between steps.

use super::coning::ConingCorrection;
use super::segment::{
    GaussRates, HeldRate, HistoryRate, LinearRate, QuadraticRate, RotationVector,
};
use super::{Accepted, InputModel};
use crate::vec3::all_finite;
use crate::{DeltaAngle, Error, GyroSample, Real, Vec3};

/// `w − delta`, refused if it overflows (a bias correction of a kept sample).
#[inline]
fn lowered<T: Real>(w: Vec3<T>, delta: Vec3<T>) -> Result<Vec3<T>, Error> {
    let v = w - delta;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::NonFiniteRate)
    }
}

#[inline(always)]
fn finite_rate<T: Real>(s: &GyroSample<T>) -> Result<Vec3<T>, Error> {
    if s.rate.is_finite() {
        Ok(s.rate)
    } else {
        Err(Error::NonFiniteRate)
    }
}

/// Each sample's rate held over the `dt` that ends at it (the seed's assumption V1). Exact for a constant
/// rate, first order on a varying one; keeps no state.
///
/// ```
/// use quatprop::{input::Hold, scheme::ExpMap, stabilize::Off, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, Hold::new(), Off)?;
/// p.push(GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f64)), 0.5)?; // 1 rad/s about z for 0.5 s
/// assert!((p.attitude().z - 0.25_f64.sin()).abs() < 1e-15);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Hold;

impl Hold {
    /// The model (it keeps no state; the same as the unit value `Hold`), constructed as every input
    /// model is.
    #[must_use]
    pub const fn new() -> Self {
        Hold
    }
}

// Each model below is a struct, its `new` and its `InputModel` impl: the impls share the trait's
// signatures (and `finite_rate`, the one check they all make first); their bodies are each model's own.
impl<T: Real> InputModel<T> for Hold {
    type Sample = GyroSample<T>;
    type Segment = HeldRate<T>;
    #[inline(always)]
    fn accept(&self, sample: &GyroSample<T>, dt: T) -> Accepted<Self, HeldRate<T>, T> {
        Ok((Hold, Some((HeldRate(finite_rate(sample)?), dt))))
    }
    #[inline(always)]
    fn start(&self, sample: &GyroSample<T>) -> Result<Self, Error> {
        finite_rate(sample).map(|_| Hold)
    }
    #[inline(always)]
    fn restart(&mut self) {}
    /// Nothing kept: nothing to correct.
    #[inline(always)]
    fn correct_bias(&self, _delta: Vec3<T>) -> Result<Self, Error> {
        Ok(Self)
    }
}

/// The rate linear between the previous sample and this one: second order (the trapezoid rule's error in
/// `∫ω`), whatever the scheme's order. The first sample only starts the model.
///
/// ```
/// use quatprop::{input::Linear, scheme::ExpMap, stabilize::Off, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, Linear::new(), Off)?;
/// p.push(GyroSample::new(Vec3::new(0.0, 0.0, 0.0_f64)), 0.5)?; // starts: no step
/// p.push(GyroSample::new(Vec3::new(0.0, 0.0, 2.0_f64)), 0.5)?; // ramp 0 → 2 rad/s: 0.5 rad
/// assert_eq!(p.steps(), 1);
/// assert!((p.attitude().z - 0.25_f64.sin()).abs() < 1e-15);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Linear<T> {
    previous: Option<Vec3<T>>,
}

impl<T: Real> Linear<T> {
    /// A model that has seen no sample yet.
    #[must_use]
    pub const fn new() -> Self {
        Self { previous: None }
    }
}

impl<T: Real> InputModel<T> for Linear<T> {
    type Sample = GyroSample<T>;
    type Segment = LinearRate<T>;
    #[inline(always)]
    fn accept(&self, sample: &GyroSample<T>, dt: T) -> Accepted<Self, LinearRate<T>, T> {
        let w = finite_rate(sample)?;
        let next = Self { previous: Some(w) };
        Ok((next, self.previous.map(|w0| (LinearRate::new(w0, w), dt))))
    }
    #[inline(always)]
    fn start(&self, sample: &GyroSample<T>) -> Result<Self, Error> {
        Ok(Self {
            previous: Some(finite_rate(sample)?),
        })
    }
    #[inline(always)]
    fn restart(&mut self) {
        self.previous = None;
    }
    #[inline]
    fn correct_bias(&self, delta: Vec3<T>) -> Result<Self, Error> {
        Ok(Self {
            previous: self.previous.map(|w| lowered(w, delta)).transpose()?,
        })
    }
}

/// The sample history: the cubic through the last four samples ω_{k−2}, ω_{k−1}, ω_k, ω_{k+1}, integrated
/// over the last interval — fourth order from one gyro sample per step, with no latency (the step ends at
/// the newest sample). The recommended input for a rate gyro.
///
/// Start-up: the first sample only starts the history, the second gives a linear step, the third a
/// quadratic one that also corrects the linear step before it (the trapezoid's O(h³) error, known once
/// three samples give ω''; see [`HistoryRate`](super::segment::HistoryRate)). From the third sample on the
/// attitude is fourth order over any horizon, from a cold start as from a primed history. Equally spaced
/// samples (each spacing within 2⁻²⁰ (relative) of the next) use constant weights; jittered ones the cubic
/// through the samples at their true times (each `dt` as given), still fourth order — a refused or dropped
/// sample too: its interval (twice the others) goes into the next `dt` and the cubic spans it. A gap — a
/// `dt` more than [`History::GAP_RATIO`] times the previous one, or less than its inverse (two or more
/// samples missing, a restarted sensor) — restarts the history at the last sample: that interval is
/// integrated linearly over its true length (nothing is known of ω inside it) and the history starts again
/// as from cold, fourth order from the next two samples on.
///
/// ```
/// use quatprop::{input::History, scheme::ExpMap, stabilize::Off, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), Off)?;
/// for k in 0..5 {
///     let t = 0.1 * k as f64; // ω_z = t³ from t = 0.1: the history's linear, quadratic and cubic steps
///     p.push(GyroSample::new(Vec3::new(0.0, 0.0, (t + 0.1).powi(3))), 0.1)?;
/// }
/// assert_eq!((p.steps(), p.input().len()), (4, 3));
/// // Exact: ∫ t³ over [0.1, 0.5]. The linear step over [0.1, 0.2] errs by h³ω''(0.15)/12 = 7.5e-5 rad;
/// // the quadratic step takes that back (the two make Simpson's rule, exact for t³), the cubic steps are
/// // exact.
/// let exact = (0.5_f64.powi(4) - 0.1_f64.powi(4)) / 4.0;
/// let angle = 2.0 * p.attitude().z.atan2(p.attitude().w);
/// assert!((angle - exact).abs() < 1e-15, "{}", angle - exact);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct History<T> {
    /// The newest sample ω_k (valid when `count ≥ 1`).
    w: Vec3<T>,
    /// The differences of the kept samples, `[ω_{k−1} − ω_{k−2}, ω_k − ω_{k−1}]` (the last `count − 1`
    /// are valid). Kept rather than the samples themselves: each is computed once, when its later
    /// sample arrives, and reused by the next two steps (bit for bit the difference they would form).
    d: [Vec3<T>; 2],
    count: u8,
    /// Three samples are kept and their two spacings are within 2⁻²⁰ (relative) of each
    /// other: a next `dt` within it of the later one makes a step with the constant weights (one test
    /// in the steady state instead of two).
    uniform: bool,
    /// The spacings (s) of the kept samples: `[t_{k−1} − t_{k−2}, t_k − t_{k−1}]` (the first is zero
    /// unless all three are kept).
    dt: [T; 2],
}

impl<T: Real> History<T> {
    /// The relative difference of two consecutive spacings (2⁻²⁰, relative to the later one) within which
    /// samples count as equally spaced and the constant weights are used. An exact time base
    /// ([`crate::frontend::FixedPeriod`]) varies an f32 `dt` by one ulp (2⁻²³ relative), inside it;
    /// treating the step's three spacings as equal when they differ by δ (at most about twice the
    /// tolerance) errs by about `δ·h²·|ω'|` per step, below f32 rounding at this tolerance.
    pub(crate) const SPACING_TOLERANCE: f64 = 1.0 / 1_048_576.0;

    /// A `dt` more than this times the previous one (or less than its inverse) is a gap: the history
    /// restarts. One missing sample (twice the spacing, with jitter) stays below it and is spanned by the
    /// cubic; two missing samples (three times) are a gap.
    pub const GAP_RATIO: f64 = 2.5;

    /// An empty history.
    #[must_use]
    pub fn new() -> Self {
        Self {
            w: Vec3::ZERO,
            d: [Vec3::ZERO; 2],
            count: 0,
            uniform: false,
            dt: [T::ZERO; 2],
        }
    }

    /// Samples kept (0 to 3).
    #[must_use]
    pub fn len(&self) -> usize {
        self.count as usize
    }

    /// `true` before the first sample (and after a restart).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }
}

/// `true` if `a` and `b` differ by at most `tolerance·b`.
#[inline(always)]
fn close<T: Real>(a: T, b: T, tolerance: f64) -> bool {
    (a - b).abs() <= b * T::from_f64(tolerance)
}

impl<T: Real> InputModel<T> for History<T> {
    type Sample = GyroSample<T>;
    type Segment = HistoryRate<T>;
    #[inline(always)]
    fn accept(&self, sample: &GyroSample<T>, dt: T) -> Accepted<Self, HistoryRate<T>, T> {
        let w = finite_rate(sample)?;
        let [f, e] = self.dt;
        let c = self.w;
        let [d1, d2] = self.d;
        let d3 = w - c;
        // Whatever the step, the history moves on by one sample (the count below says how many are
        // valid).
        let shifted = |count, uniform, dt| Self {
            w,
            d: [d2, d3],
            count,
            uniform,
            dt,
        };
        let close_to_last = close(e, dt, Self::SPACING_TOLERANCE);
        // The steady state first: a full, equally spaced history and a `dt` equal to its spacing (which
        // is no gap).
        if self.uniform && close_to_last {
            let segment = HistoryRate::Uniform {
                ends: [c, w],
                d: [d1, d2],
                count: 4,
            };
            return Ok((shifted(3, true, [e, dt]), Some((segment, dt))));
        }
        let gap = T::from_f64(Self::GAP_RATIO);
        // A gap: keep only the last sample (the step becomes linear over its true length).
        let kept = if self.count > 1 && (dt > e * gap || dt * gap < e) {
            1
        } else {
            self.count
        };
        let z = Vec3::ZERO;
        let segment = match kept {
            0 => None,
            1 => Some(HistoryRate::Uniform {
                ends: [c, w],
                d: [z, z],
                count: 2,
            }),
            2 => Some(if close_to_last {
                HistoryRate::Uniform {
                    ends: [c, w],
                    d: [z, d2],
                    count: 3,
                }
            } else {
                HistoryRate::newton([c, w], [z, d2], 3, e / dt, T::ONE)
            }),
            // Three samples whose spacings are not all equal (equal ones took the steady state).
            _ => Some({
                let inv = T::ONE / dt;
                HistoryRate::newton([c, w], [d1, d2], 4, e * inv, f * inv)
            }),
        };
        let next = if kept < 2 {
            shifted(kept + 1, false, [T::ZERO, dt])
        } else {
            shifted(3, close_to_last, [e, dt])
        };
        Ok((next, segment.map(|s| (s, dt))))
    }
    #[inline(always)]
    fn start(&self, sample: &GyroSample<T>) -> Result<Self, Error> {
        let w = finite_rate(sample)?;
        Ok(Self {
            w,
            d: [Vec3::ZERO; 2],
            count: 1,
            uniform: false,
            dt: [T::ZERO; 2],
        })
    }
    #[inline(always)]
    fn restart(&mut self) {
        self.count = 0;
        self.uniform = false;
        self.dt[0] = T::ZERO;
    }
    /// The newest sample moves; the differences the history keeps do not (every kept sample moves by
    /// the same `delta`).
    #[inline]
    fn correct_bias(&self, delta: Vec3<T>) -> Result<Self, Error> {
        let mut next = *self;
        if self.count > 0 {
            next.w = lowered(self.w, delta)?;
        }
        Ok(next)
    }
}

/// A gyro sampled at twice the step rate: each step takes the sample that ended the previous step, a
/// middle one and an end one, and integrates the quadratic through them (fourth order with
/// [`crate::scheme::ExpMap`], [`crate::scheme::Magnus4`], [`crate::scheme::Rk4`]). Pass each sample with its
/// own `dt` (half the step); the middle sample is taken to sit at the middle of the step.
///
/// ```
/// use quatprop::{input::TwiceRate, scheme::Rk4, stabilize::Off, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, Rk4, TwiceRate::new(), Off)?;
/// let w = GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f64));
/// for _ in 0..5 {
///     p.push(w, 0.01)?; // start, then middle, end, middle, end
/// }
/// assert_eq!(p.steps(), 2); // two steps of 0.02 s: 0.04 rad
/// // RK4's phase error is x⁵/120 per step at x = h|ω|/2 = 0.01: 1.7e-12 after two steps.
/// assert!((p.attitude().z - 0.02_f64.sin()).abs() < 2e-12);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TwiceRate<T> {
    start: Option<Vec3<T>>,
    middle: Option<(Vec3<T>, T)>,
}

impl<T: Real> TwiceRate<T> {
    /// A model that has seen no sample yet.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            start: None,
            middle: None,
        }
    }
}

impl<T: Real> InputModel<T> for TwiceRate<T> {
    type Sample = GyroSample<T>;
    type Segment = QuadraticRate<T>;
    #[inline(always)]
    fn accept(&self, sample: &GyroSample<T>, dt: T) -> Accepted<Self, QuadraticRate<T>, T> {
        let w = finite_rate(sample)?;
        Ok(match (self.start, self.middle) {
            (None, _) => (
                Self {
                    start: Some(w),
                    middle: None,
                },
                None,
            ),
            (Some(s), None) => (
                Self {
                    start: Some(s),
                    middle: Some((w, dt)),
                },
                None,
            ),
            (Some(w0), Some((wm, dt_m))) => (
                Self {
                    start: Some(w),
                    middle: None,
                },
                Some((QuadraticRate { w0, wm, w1: w }, dt_m + dt)),
            ),
        })
    }
    #[inline(always)]
    fn start(&self, sample: &GyroSample<T>) -> Result<Self, Error> {
        Ok(Self {
            start: Some(finite_rate(sample)?),
            middle: None,
        })
    }
    #[inline(always)]
    fn restart(&mut self) {
        *self = Self::new();
    }
    #[inline]
    fn correct_bias(&self, delta: Vec3<T>) -> Result<Self, Error> {
        Ok(Self {
            start: self.start.map(|w| lowered(w, delta)).transpose()?,
            middle: self
                .middle
                .map(|(w, dt)| lowered(w, delta).map(|w| (w, dt)))
                .transpose()?,
        })
    }
}

/// Rates sampled at the two Gauss–Legendre points `t + (½ ∓ √3/6)h` of each step (a gyro sampled at twice
/// the step rate with that phase, or rates reconstructed there): fourth order with
/// [`crate::scheme::Magnus4`], [`crate::scheme::Cf4`] or [`crate::scheme::ExpMap`]. Push the two samples of a
/// step in order, each with `dt = h/2` (the Gauss weight of each node); the second closes the step.
///
/// ```
/// use quatprop::{input::GaussPoints, scheme::Magnus4, stabilize::Off, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, Magnus4, GaussPoints::new(), Off)?;
/// p.push(GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f64)), 0.05)?; // pending
/// p.push(GyroSample::new(Vec3::new(0.0, 0.0, 3.0_f64)), 0.05)?; // a step of 0.1 s: 0.2 rad
/// assert!((p.attitude().z - 0.1_f64.sin()).abs() < 1e-15);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GaussPoints<T> {
    first: Option<(Vec3<T>, T)>,
}

impl<T: Real> GaussPoints<T> {
    /// A model waiting for the first Gauss sample of a step.
    #[must_use]
    pub const fn new() -> Self {
        Self { first: None }
    }
}

impl<T: Real> InputModel<T> for GaussPoints<T> {
    type Sample = GyroSample<T>;
    type Segment = GaussRates<T>;
    #[inline(always)]
    fn accept(&self, sample: &GyroSample<T>, dt: T) -> Accepted<Self, GaussRates<T>, T> {
        let w = finite_rate(sample)?;
        Ok(match self.first {
            None => (
                Self {
                    first: Some((w, dt)),
                },
                None,
            ),
            Some((w1, dt1)) => (Self::new(), Some((GaussRates::new(w1, w), dt1 + dt))),
        })
    }
    #[inline(always)]
    fn start(&self, sample: &GyroSample<T>) -> Result<Self, Error> {
        finite_rate(sample).map(|_| Self::new())
    }
    #[inline(always)]
    fn restart(&mut self) {
        self.first = None;
    }
    #[inline]
    fn correct_bias(&self, delta: Vec3<T>) -> Result<Self, Error> {
        Ok(Self {
            first: self
                .first
                .map(|(w, dt)| lowered(w, delta).map(|w| (w, dt)))
                .transpose()?,
        })
    }
}

/// Delta angles (integrated-rate sensors): the increments `Δθᵢ` of the sensor's sample intervals are
/// combined by a [coning correction](super::coning) into the update's rotation vector φ, then
/// `q ← q ⊗ exp_q(φ)` with an exponential-map scheme (Runge–Kutta schemes see the constant rate `φ/h`).
/// The update closes when the correction has its increments; `h` is the sum of their `dt`.
///
/// A refused increment is not integrated: its rotation is lost (a refused rate sample loses no time, its
/// interval going into the next one; an increment *is* the rotation). An increment that arrives while
/// the update is still open is checked on its own against the scheme's step-angle bound
/// ([`InputModel::pending_step`]): kept, one beyond the bound would refuse the update and every later one.
///
/// ```
/// use quatprop::input::{coning::TwoSample, DeltaAngles};
/// use quatprop::{scheme::ExpMap, stabilize::Off, DeltaAngle, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, DeltaAngles::new(TwoSample), Off)?;
/// let d = DeltaAngle::new(Vec3::new(0.0, 0.0, 0.1_f64));
/// p.push(d, 0.01)?; // pending
/// p.push(d, 0.01)?; // update: φ = 0.2 rad about z
/// assert_eq!(p.steps(), 1);
/// assert!((p.attitude().z - 0.1_f64.sin()).abs() < 1e-15);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DeltaAngles<T, C> {
    correction: C,
    pending: [Vec3<T>; 4],
    count: u8,
    time: T,
    previous: Option<Vec3<T>>,
}

impl<T: Real, C: ConingCorrection> DeltaAngles<T, C> {
    /// A model with the coning correction `correction` and no increment yet.
    #[must_use]
    pub fn new(correction: C) -> Self {
        Self {
            correction,
            pending: [Vec3::ZERO; 4],
            count: 0,
            time: T::ZERO,
            previous: None,
        }
    }

    /// The coning correction.
    #[must_use]
    pub fn correction(&self) -> C {
        self.correction
    }
}

impl<T: Real, C: ConingCorrection> DeltaAngles<T, C> {
    /// [`InputModel::accept`] (`SPLIT` false) and [`InputModel::accept_split`] (`SPLIT` true: the rotation
    /// vector's rounding kept in the segment's low part).
    #[inline(always)]
    fn accept_with<const SPLIT: bool>(
        &self,
        sample: &DeltaAngle<T>,
        dt: T,
    ) -> Accepted<Self, RotationVector<T>, T> {
        let d = sample.angle;
        if !all_finite(&[d]) {
            return Err(Error::NonFiniteRate);
        }
        let n = self.correction.samples().clamp(1, 5);
        let k = self.count as usize;
        let time = self.time + dt;
        let mut next = *self;
        if k + 1 < n {
            if let Some(slot) = next.pending.get_mut(k) {
                *slot = d;
            }
            next.count += 1;
            next.time = time;
            return Ok((next, None));
        }
        let increments = gather(&self.pending, k, d);
        let increments = increments.get(..k + 1).unwrap_or(&[]);
        let (phi, low) = if SPLIT {
            self.correction
                .rotation_vector_split(self.previous, increments)
        } else {
            (
                self.correction.rotation_vector(self.previous, increments),
                Vec3::ZERO,
            )
        };
        next.count = 0;
        next.time = T::ZERO;
        next.previous = Some(d);
        Ok((next, Some((RotationVector { phi, low, h: time }, time))))
    }
}

impl<T: Real, C: ConingCorrection> InputModel<T> for DeltaAngles<T, C> {
    type Sample = DeltaAngle<T>;
    type Segment = RotationVector<T>;
    #[inline(always)]
    fn accept(&self, sample: &DeltaAngle<T>, dt: T) -> Accepted<Self, RotationVector<T>, T> {
        self.accept_with::<false>(sample, dt)
    }
    #[inline(always)]
    fn accept_split(&self, sample: &DeltaAngle<T>, dt: T) -> Accepted<Self, RotationVector<T>, T> {
        self.accept_with::<true>(sample, dt)
    }
    /// A kept increment's own rotation: any update holding an increment beyond the scheme's bound
    /// would be refused, and so would every later one while it stays kept.
    #[inline(always)]
    fn pending_step(&self, sample: &DeltaAngle<T>, dt: T) -> Option<(RotationVector<T>, T)> {
        Some((
            RotationVector {
                phi: sample.angle,
                low: Vec3::ZERO,
                h: dt,
            },
            dt,
        ))
    }
    #[inline(always)]
    fn start(&self, sample: &DeltaAngle<T>) -> Result<Self, Error> {
        if !all_finite(&[sample.angle]) {
            return Err(Error::NonFiniteRate);
        }
        let mut next = *self;
        next.restart();
        Ok(next)
    }
    #[inline(always)]
    fn restart(&mut self) {
        self.count = 0;
        self.time = T::ZERO;
        self.previous = None;
    }
    /// The pending increments of the open update are lowered by `delta` times their mean interval (the
    /// update's time so far over their count: exact at a fixed sample period, which is how integrating
    /// IMUs deliver them). The previous update's last increment, which only the coning correction's cross
    /// term reads, is lowered by the same interval if the update is open, and left as it was if not (its
    /// interval is not kept; it enters only that cross term, as a product with the next increments).
    #[inline]
    fn correct_bias(&self, delta: Vec3<T>) -> Result<Self, Error> {
        let k = usize::from(self.count);
        let mut next = *self;
        if k == 0 {
            return Ok(next);
        }
        let d = delta * (self.time / T::from_f64(f64::from(self.count)));
        for p in next.pending.iter_mut().take(k) {
            *p = lowered(*p, d)?;
        }
        next.previous = self.previous.map(|w| lowered(w, d)).transpose()?;
        Ok(next)
    }
}

/// `[pending[0..k], d, …]`: the update's increments in order, in a fixed array (panic-free).
#[inline(always)]
fn gather<T: Real>(pending: &[Vec3<T>; 4], k: usize, d: Vec3<T>) -> [Vec3<T>; 5] {
    let [a, b, c, e] = *pending;
    match k {
        0 => [d, a, b, c, e],
        1 => [a, d, b, c, e],
        2 => [a, b, d, c, e],
        3 => [a, b, c, d, e],
        _ => [a, b, c, e, d],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::Segment;

    /// The step segment for samples of ω at times `t` (the last interval is the step).
    fn history_segment(t: &[f64], omega: impl Fn(f64) -> f64) -> (HistoryRate<f64>, f64) {
        let mut h = History::<f64>::new();
        let mut last = None;
        for (k, &tk) in t.iter().enumerate() {
            let s = GyroSample::new(Vec3::new(0.0, 0.0, omega(tk)));
            let dt = if k == 0 { 1.0 } else { tk - t[k - 1] };
            let (next, seg) = h.accept(&s, dt).unwrap();
            h = next;
            last = seg;
        }
        last.unwrap()
    }

    #[test]
    fn jittered_history_integrates_a_cubic_exactly() {
        let omega = |t: f64| 0.3 - 2.0 * t + 5.0 * t * t - 7.0 * t * t * t;
        let integral = |a: f64, b: f64| {
            let f = |t: f64| 0.3 * t - t * t + 5.0 / 3.0 * t.powi(3) - 7.0 / 4.0 * t.powi(4);
            f(b) - f(a)
        };
        // ±20 % jitter: inside the gap ratio, outside the spacing tolerance.
        let t = [0.0, 0.011, 0.0195, 0.0302];
        let (seg, h) = history_segment(&t, omega);
        assert!(matches!(seg, HistoryRate::Newton { .. }));
        let got = 2.0 * seg.half_angle(0.5 * h).z;
        assert!((got - integral(t[2], t[3])).abs() < 1e-16, "{got:e}");
        // The interpolant reproduces ω inside the step (RK stages read it).
        for c in [0.0, 0.25, 0.5, 0.8, 1.0] {
            let w = seg.rate_at(c).z;
            assert!((w - omega(t[2] + c * h)).abs() < 1e-15, "c = {c}: {w}");
        }
    }

    #[test]
    fn equal_spacing_takes_the_constant_weights_and_a_gap_restarts() {
        let omega = |t: f64| (3.0 * t).sin();
        let (seg, _) = history_segment(&[0.0, 0.01, 0.02, 0.03], omega);
        assert!(matches!(seg, HistoryRate::Uniform { count: 4, .. }));
        // The Newton form at equal spacing agrees with the constant weights to rounding.
        let w = [0.0, 0.01, 0.02, 0.03].map(|t| Vec3::new(0.0, 0.0, omega(t)));
        let newton = HistoryRate::newton([w[2], w[3]], [w[1] - w[0], w[2] - w[1]], 4, 1.0, 1.0);
        let d = newton.half_angle(0.005).z - seg.half_angle(0.005).z;
        assert!(d.abs() < 1e-18, "{d:e}");
        // dt doubled (a dropped sample): the cubic through the samples at their true times.
        let (seg, _) = history_segment(&[0.0, 0.01, 0.02, 0.04], omega);
        assert!(matches!(seg, HistoryRate::Newton { .. }));
        // dt tripled (two dropped samples): a gap, linear over the true interval.
        let (seg, _) = history_segment(&[0.0, 0.01, 0.02, 0.05], omega);
        assert!(matches!(seg, HistoryRate::Uniform { count: 2, .. }));
    }

    #[test]
    fn a_constant_rate_integrates_exactly_in_f32() {
        // The difference form: no rounded weight multiplies the constant part.
        let w = Vec3::new(0.36_f32, -0.48, 0.8);
        let mut h = History::<f32>::new();
        let mut seg = None;
        for _ in 0..4 {
            let (next, s) = h.accept(&GyroSample::new(w), 1e-3).unwrap();
            h = next;
            seg = s;
        }
        let (seg, dt) = seg.unwrap();
        assert_eq!(seg.half_angle(0.5 * dt), w * (0.5 * dt));
    }
}
