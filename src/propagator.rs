//! The propagator: an attitude, a scheme, a stabilizer and counters, advanced one gyro step at a time.

use crate::accumulate::{Accumulator, Kahan, Plain};
use crate::coning::ConingCorrection;
use crate::rates::{GaussPair, Hold, Linear, Quadratic, RateModel, RotationVector};
use crate::scheme::Scheme;
use crate::stabilize::Stabilizer;
use crate::{Error, GyroSample, Quat, Real, SampleHistory, Vec3};

/// Propagates a body-to-reference attitude quaternion from body-frame gyro rates.
///
/// `T` is the working precision (`f32` or `f64`), `S` the [scheme](crate::scheme), `Z` the
/// [stabilizer](crate::stabilize), `A` how increments are added ([`Plain`], or [`Kahan`] for a compensated
/// f32 state, see [`Propagator::new_compensated`]). Small and `Copy`; no allocation, no trait objects, no
/// panics on the step path.
///
/// Every `step_*` call validates its inputs first, computes the new attitude into locals and commits only
/// on success: on any `Err` the propagator is bit-for-bit what it was before the call.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Propagator<T, S, Z, A = Plain> {
    q: Quat<T>,
    scheme: S,
    stabilizer: Z,
    accumulator: A,
    steps: u64,
    corrections: u64,
    saturated: u64,
    pending: u32,
    previous_increment: Option<Vec3<T>>,
}

impl<T: Real, S: Scheme, Z: Stabilizer<T>> Propagator<T, S, Z, Plain> {
    /// Starts from attitude `q0` (normalized here; any finite non-zero quaternion is accepted).
    ///
    /// # Errors
    /// [`Error::NonFiniteQuaternion`], [`Error::ZeroQuaternion`], or [`Error::InvalidStabilizer`].
    pub fn new(q0: Quat<T>, scheme: S, stabilizer: Z) -> Result<Self, Error> {
        Self::with_accumulator(q0, scheme, stabilizer, Plain)
    }
}

impl<T: Real, S: Scheme, Z: Stabilizer<T>> Propagator<T, S, Z, Kahan<T>> {
    /// Like [`Propagator::new`], with the attitude kept by Kahan-compensated summation of the step
    /// increments ([`Kahan`]): an f32 state that tracks an f64 one over millions of steps.
    ///
    /// # Errors
    /// As [`Propagator::new`].
    pub fn new_compensated(q0: Quat<T>, scheme: S, stabilizer: Z) -> Result<Self, Error> {
        Self::with_accumulator(q0, scheme, stabilizer, Kahan::new())
    }
}

impl<T: Real, S: Scheme, Z: Stabilizer<T>, A: Accumulator<T>> Propagator<T, S, Z, A> {
    /// Starts from attitude `q0` (normalized) with an explicit [`Accumulator`].
    ///
    /// # Errors
    /// As [`Propagator::new`].
    pub fn with_accumulator(
        q0: Quat<T>,
        scheme: S,
        stabilizer: Z,
        accumulator: A,
    ) -> Result<Self, Error> {
        stabilizer.validate()?;
        let q = Self::checked_unit(q0)?;
        Ok(Self {
            q,
            scheme,
            stabilizer,
            accumulator,
            steps: 0,
            corrections: 0,
            saturated: 0,
            pending: 0,
            previous_increment: None,
        })
    }

    fn checked_unit(q0: Quat<T>) -> Result<Quat<T>, Error> {
        if !q0.is_finite() {
            return Err(Error::NonFiniteQuaternion);
        }
        q0.normalized().ok_or(Error::ZeroQuaternion)
    }

    /// Replaces the attitude (normalized), keeping the counters. On error nothing changes.
    ///
    /// # Errors
    /// [`Error::NonFiniteQuaternion`] or [`Error::ZeroQuaternion`].
    pub fn set_attitude(&mut self, q: Quat<T>) -> Result<(), Error> {
        self.q = Self::checked_unit(q)?;
        self.accumulator.reset();
        self.pending = 0;
        Ok(())
    }

    /// One step of `dt` (s) with the body rate `w` (rad/s) held constant over it (the seed's assumption V1).
    ///
    /// # Errors
    /// See [`Propagator::step_with`].
    #[inline]
    pub fn step_hold(&mut self, w: Vec3<T>, dt: T) -> Result<(), Error> {
        self.step_with(&Hold::new(w), dt)
    }

    /// [`Propagator::step_hold`] with a sensor sample: integrated even if saturated, and counted then
    /// ([`Propagator::saturated_samples`]). A refused step counts nothing.
    ///
    /// # Errors
    /// See [`Propagator::step_with`].
    #[inline]
    pub fn step_hold_sample(&mut self, s: GyroSample<T>, dt: T) -> Result<(), Error> {
        self.step_hold(s.rate, dt)?;
        self.saturated += s.saturated as u64;
        Ok(())
    }

    /// [`Propagator::step_linear`] between the previous and the current sensor sample. The current
    /// sample's saturation is counted (each sample once, as it arrives); a refused step counts nothing.
    ///
    /// # Errors
    /// See [`Propagator::step_with`].
    #[inline]
    pub fn step_linear_samples(
        &mut self,
        previous: GyroSample<T>,
        current: GyroSample<T>,
        dt: T,
    ) -> Result<(), Error> {
        self.step_linear(previous.rate, current.rate, dt)?;
        self.saturated += current.saturated as u64;
        Ok(())
    }

    /// One step of `dt` (s) with the rate linear from `w_start` to `w_end` (rad/s, samples at the step's ends).
    ///
    /// # Errors
    /// See [`Propagator::step_with`].
    #[inline]
    pub fn step_linear(&mut self, w_start: Vec3<T>, w_end: Vec3<T>, dt: T) -> Result<(), Error> {
        self.step_with(&Linear::new(w_start, w_end), dt)
    }

    /// One step of `dt` (s) with samples at the start, middle and end of the step (rad/s): a gyro sampled
    /// at twice the step rate. The rate is the quadratic through the three samples.
    ///
    /// # Errors
    /// See [`Propagator::step_with`].
    #[inline]
    pub fn step_mid(
        &mut self,
        w_start: Vec3<T>,
        w_middle: Vec3<T>,
        w_end: Vec3<T>,
        dt: T,
    ) -> Result<(), Error> {
        self.step_with(&Quadratic::new(w_start, w_middle, w_end), dt)
    }

    /// One update from delta angles: the angle increments `Δθᵢ = ∫ω dt` (rad, body frame) of the gyro
    /// samples covering this update of `dt` (s), combined by the coning correction `coning`
    /// (see [`crate::coning`]) into the update's rotation vector φ, then `q ← q ⊗ exp_q(φ)` with an
    /// exponential-map scheme (Runge–Kutta schemes see the equivalent constant rate φ/dt). The last
    /// increment is kept for [`crate::coning::OnePlusPrevious`] on the next update.
    ///
    /// # Errors
    /// [`Error::SampleCount`] if the correction takes another number of increments;
    /// [`Error::NonFiniteRate`] for a non-finite increment; otherwise as [`Propagator::step_with`].
    pub fn step_delta<C: ConingCorrection>(
        &mut self,
        coning: C,
        increments: &[Vec3<T>],
        dt: T,
    ) -> Result<(), Error> {
        let n = increments.len();
        let want = coning.samples().unwrap_or(n.max(1));
        if n != want {
            return Err(Error::SampleCount {
                expected: want as u32,
                got: n as u32,
            });
        }
        if !increments.iter().all(|d| d.is_finite()) {
            return Err(Error::NonFiniteRate);
        }
        let phi = coning.rotation_vector(self.previous_increment, increments);
        self.step_with(&RotationVector::new(phi, dt), dt)?;
        self.previous_increment = increments.last().copied();
        Ok(())
    }

    /// One step from the previous gyro sample to `w` (rad/s) over `dt` (s), using up to three earlier samples
    /// kept in `history` (see [`SampleHistory`]): fourth order with one sample per step and no latency.
    /// The first sample of a history only starts it (no step, `Ok`). `history` is updated only on success.
    ///
    /// # Errors
    /// As [`Propagator::step_with`].
    pub fn step_history(
        &mut self,
        history: &mut SampleHistory<T>,
        w: Vec3<T>,
        dt: T,
    ) -> Result<(), Error> {
        match history.model(w) {
            Some(model) => self.step_with(&model, dt)?,
            None => {
                if !w.is_finite() {
                    return Err(Error::NonFiniteRate);
                }
            }
        }
        history.push(w);
        Ok(())
    }

    /// One step of `dt` (s) with the rates `w1`, `w2` (rad/s) at the two Gauss points `t + (½ ∓ √3/6)dt`:
    /// fourth order with [`crate::scheme::Magnus4`], [`crate::scheme::Cf4`] or [`crate::scheme::ExpMap`].
    ///
    /// # Errors
    /// As [`Propagator::step_with`].
    #[inline]
    pub fn step_gauss(&mut self, w1: Vec3<T>, w2: Vec3<T>, dt: T) -> Result<(), Error> {
        self.step_with(&GaussPair::new(w1, w2), dt)
    }

    /// One step of `dt` (s) with any [`RateModel`].
    ///
    /// # Errors
    /// - [`Error::NonFiniteStep`] / [`Error::NonPositiveStep`]: `dt` is NaN, ±∞, zero or negative.
    /// - [`Error::NonFiniteRate`]: a rate component is NaN or ±∞.
    /// - [`Error::StepAngleBeyondStability`]: `dt · max|ω|` exceeds [`Scheme::step_angle_limit`].
    /// - [`Error::GainBeyondStability`]: Baumgarte's `4k·dt` exceeds [`Scheme::gain_step_limit`].
    /// - [`Error::NonFiniteResult`]: the arithmetic overflowed.
    ///
    /// In every case the state is unchanged.
    #[inline]
    pub fn step_with<R: RateModel<T>>(&mut self, rates: &R, dt: T) -> Result<(), Error> {
        // One compare pair for the common case; the cold path tells the errors apart.
        if !(dt > T::ZERO && dt <= T::MAX) {
            return Err(if dt.is_finite() {
                Error::NonPositiveStep
            } else {
                Error::NonFiniteStep
            });
        }
        if !rates.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        let limit = self.scheme.step_angle_limit();
        if limit.is_finite() {
            let angle_sq = rates.max_step_angle_squared(dt);
            let l = T::from_f64(limit);
            if !(angle_sq <= l * l) {
                return Err(Error::StepAngleBeyondStability {
                    step_angle: angle_sq.sqrt().to_f64(),
                    limit,
                });
            }
        }
        if self.stabilizer.has_rhs_term() {
            let gain_step = self.stabilizer.norm_stiffness() * dt;
            let limit = self.scheme.gain_step_limit();
            if !(gain_step <= T::from_f64(limit)) {
                return Err(Error::GainBeyondStability {
                    gain_step: gain_step.to_f64(),
                    limit,
                });
            }
        }
        // Compute into locals (the accumulator is Copy), commit only on success.
        let mut acc = self.accumulator;
        let d = self.scheme.increment(self.q, rates, dt, &self.stabilizer);
        let advanced = acc.add(self.q, d);
        let pending = self.pending.saturating_add(1);
        let (q, corrected) = match self.stabilizer.correction(advanced, pending) {
            Some(c) => (acc.add(advanced, c), true),
            None => (advanced, false),
        };
        if !q.is_finite() {
            return Err(Error::NonFiniteResult);
        }
        self.q = q;
        self.accumulator = acc;
        self.steps = self.steps.wrapping_add(1);
        if corrected {
            self.corrections = self.corrections.wrapping_add(1);
            self.pending = 0;
        } else {
            self.pending = pending;
        }
        Ok(())
    }

    /// The attitude `q` (body to reference; Hamilton, scalar first). Unit up to the stabilizer's bound.
    #[inline]
    #[must_use]
    pub fn attitude(&self) -> Quat<T> {
        self.q
    }

    /// The seed's normalization error `N = |q|² − 1` (eq. (2)), evaluated with error far below ε.
    #[inline]
    #[must_use]
    pub fn norm_error(&self) -> T {
        self.q.norm_error()
    }

    /// Steps taken successfully.
    #[inline]
    #[must_use]
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Post-step corrections applied (normalizations).
    #[inline]
    #[must_use]
    pub fn corrections(&self) -> u64 {
        self.corrections
    }

    /// Saturated sensor samples integrated so far (via the `*_sample(s)` steps).
    #[inline]
    #[must_use]
    pub fn saturated_samples(&self) -> u64 {
        self.saturated
    }

    /// The scheme.
    #[inline]
    #[must_use]
    pub fn scheme(&self) -> S {
        self.scheme
    }

    /// The stabilizer.
    #[inline]
    #[must_use]
    pub fn stabilizer(&self) -> Z {
        self.stabilizer
    }
}
