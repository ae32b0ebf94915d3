//! The propagator: an attitude, a scheme, an input model, a stabilizer and an accumulator, advanced one
//! sensor sample at a time. Data flows one way: sample → input model → scheme → accumulator → stabilizer.

use crate::accumulate::{Accumulator, Plain};
use crate::frontend::{FixedPeriod, TickClock};
use crate::input::{History, InputModel};
use crate::sample::Sample;
use crate::scheme::{ExpMap, Scheme};
use crate::stabilize::{FirstOrder, Stabilizer};
use crate::{Error, Quat, Real, Vec3};

/// Propagates a body-to-reference attitude quaternion from body-frame gyro samples.
///
/// `T` is the working precision (`f32` or `f64`), `S` the [scheme](crate::scheme), `I` the
/// [input model](crate::input) (which keeps every sample it needs between steps), `Z` the
/// [stabilizer](crate::stabilize) and `A` how increments are added ([`Plain`], or
/// [`Kahan`](crate::accumulate::Kahan) via [`Propagator::with_accumulator`]). Small and `Copy`; no
/// allocation, no trait objects, no panic on the step path.
///
/// [`Propagator::push`] validates first, computes the new state into locals and commits only on success:
/// on any `Err` the propagator is bit for bit what it was before the call.
///
/// ```
/// use quatprop::{input::History, scheme::ExpMap, stabilize::FirstOrder, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)?;
/// for _ in 0..=1000 {
///     p.push(GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f32)), 1.0e-3)?; // 1 rad/s yaw, 1 kHz
/// }
/// let q = p.attitude(); // 1 rad of yaw after 1000 steps: (cos ½, 0, 0, sin ½)
/// assert!((q.w - 0.5_f32.cos()).abs() < 1e-6 && (q.z - 0.5_f32.sin()).abs() < 1e-6);
/// assert_eq!((p.steps(), p.corrections()), (1000, 1000));
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Propagator<T, S, I, Z, A = Plain> {
    q: Quat<T>,
    scheme: S,
    input: I,
    stabilizer: Z,
    accumulator: A,
    counters: Counters,
}

/// What a propagator counts, apart from its parts (shared with [`crate::config::Configured`], which keeps
/// the parts as run-time values and rebuilds a static propagator around them for each call).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Counters {
    steps: u64,
    /// Steps the stabilizer left uncorrected (`corrections = steps − uncorrected`): a stabilizer that
    /// corrects every step then costs no counter update.
    uncorrected: u64,
    saturated: u64,
    pending: u32,
}

impl Counters {
    #[inline(always)]
    pub(crate) fn steps(&self) -> u64 {
        self.steps
    }
    #[inline(always)]
    pub(crate) fn corrections(&self) -> u64 {
        self.steps.wrapping_sub(self.uncorrected)
    }
    #[inline(always)]
    pub(crate) fn saturated(&self) -> u64 {
        self.saturated
    }
    /// The attitude was replaced: no step is pending a correction.
    #[inline(always)]
    pub(crate) fn attitude_replaced(&mut self) {
        self.pending = 0;
    }
}

impl<T: Real, S: Scheme<T>, I: InputModel<T>, Z: Stabilizer> Propagator<T, S, I, Z, Plain> {
    /// Starts from attitude `q0` (normalized here; any finite non-zero quaternion is accepted) with the
    /// given scheme, input model and stabilizer, adding increments plainly.
    ///
    /// # Errors
    /// [`Error::NonFiniteQuaternion`], [`Error::ZeroQuaternion`], or [`Error::InvalidStabilizer`].
    pub fn new(q0: Quat<T>, scheme: S, input: I, stabilizer: Z) -> Result<Self, Error> {
        stabilizer.validate()?;
        Ok(Self {
            q: checked_unit(q0)?,
            scheme,
            input,
            stabilizer,
            accumulator: Plain,
            counters: Counters::default(),
        })
    }
}

/// The recommended configuration, by name: [`ExpMap`] + [`History`] + [`FirstOrder`], adding increments
/// plainly. The most accurate per Cortex-M4F instruction in the project's measurements (docs/firmware.md,
/// docs/report): fourth order with one sample per step and no latency, unit norm to a few ε for one
/// multiply-add of correction.
pub type Recommended<T> = Propagator<T, ExpMap, History<T>, FirstOrder>;

impl<T: Real> Recommended<T> {
    /// The recommended configuration ([`Recommended`]) from attitude `q0` (normalized here).
    ///
    /// ```
    /// use quatprop::{GyroSample, Propagator, Quat, Vec3};
    /// let mut p = Propagator::recommended(Quat::IDENTITY)?;
    /// p.push(GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f32)), 1.0e-3)?;
    /// # Ok::<(), quatprop::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFiniteQuaternion`] or [`Error::ZeroQuaternion`].
    pub fn recommended(q0: Quat<T>) -> Result<Self, Error> {
        Propagator::new(q0, ExpMap, History::new(), FirstOrder)
    }
}

/// The sample of a burst that was refused, and why ([`Propagator::push_burst`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Refused {
    /// Index of the refused sample in the burst (= the number of samples integrated before it).
    pub index: usize,
    /// Why it was refused.
    pub error: Error,
}

impl core::fmt::Display for Refused {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "sample {} of the burst refused: {}",
            self.index, self.error
        )
    }
}

impl core::error::Error for Refused {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// The frame a correction's rotation is given in.
#[derive(Clone, Copy)]
pub(crate) enum Frame {
    /// `q ← q ⊗ exp_q(dtheta)`.
    Body,
    /// `q ← exp_q(dtheta) ⊗ q`.
    Reference,
}

/// The attitude `q` corrected by the rotation vector `dtheta` (rad) in `frame`, its increment added
/// through `add` (an accumulator's `add`) on a copy of `accumulator`: the new attitude and accumulator,
/// which the caller keeps only with this result (an error leaves it unchanged). Written once for the
/// static and the run-time propagator.
pub(crate) fn corrected<T: Real, A: Copy>(
    q: Quat<T>,
    mut accumulator: A,
    dtheta: Vec3<T>,
    frame: Frame,
    add: impl FnOnce(&mut A, Quat<T>, Quat<T>) -> Quat<T>,
) -> Result<(Quat<T>, A), Error> {
    if !dtheta.is_finite() {
        return Err(Error::NonFiniteRate);
    }
    let e = Quat::rotation_increment(dtheta);
    if !e.is_finite() {
        // f32 beyond the step path's sine; its square root: no f64 arithmetic linked for a refusal.
        return Err(Error::StepAngleBeyondStability {
            step_angle: dtheta.norm_squared().sqrt_step().to_f64(),
            limit: Quat::<T>::INCREMENT_ANGLE_LIMIT,
        });
    }
    let d = match frame {
        Frame::Body => q * e,
        Frame::Reference => e * q,
    };
    let next = add(&mut accumulator, q, d);
    if next.is_finite() {
        Ok((next, accumulator))
    } else {
        Err(Error::NonFiniteResult)
    }
}

pub(crate) fn checked_unit<T: Real>(q0: Quat<T>) -> Result<Quat<T>, Error> {
    if !q0.is_finite() {
        return Err(Error::NonFiniteQuaternion);
    }
    q0.normalized().ok_or(Error::ZeroQuaternion)
}

/// The body of [`Propagator::push`], written once for `push` itself and for the loops of the bursts, which
/// must inline it whatever the compiler decides for `push` (see `push_burst`). `$p` is the propagator
/// (`self`, or the burst's local copy); the expansion returns `Err` from the enclosing function, committing
/// nothing, or commits and evaluates to `Ok(())`.
macro_rules! push_body {
    ($p:ident, $sample:ident, $dt:ident) => {{
        let (sample, dt) = ($sample, $dt);
        // One compare pair for the common case; the cold path tells the errors apart.
        if !(dt > T::ZERO && dt <= T::MAX) {
            return Err(if dt.is_finite() {
                Error::NonPositiveStep
            } else {
                Error::NonFiniteStep
            });
        }
        let (input, step) = if A::CARRIES_LOW_PARTS {
            $p.input.accept_split(&sample, dt)?
        } else {
            $p.input.accept(&sample, dt)?
        };
        if let Some((segment, h)) = step {
            $p.scheme.check(&segment, h)?;
            // Compute into locals (the accumulator is Copy), commit only on success.
            let mut acc = $p.accumulator;
            let advanced = acc.advance($p.q, &$p.scheme, &segment, h);
            let pending = $p.counters.pending.saturating_add(1);
            let (q, corrected) = match $p.stabilizer.correction(advanced, pending) {
                Some(c) => (acc.add(advanced, c), true),
                None => (advanced, false),
            };
            if !q.is_finite() {
                return Err(Error::NonFiniteResult);
            }
            $p.q = q;
            $p.accumulator = acc;
            $p.counters.steps = $p.counters.steps.wrapping_add(1);
            if corrected {
                $p.counters.pending = 0;
            } else {
                $p.counters.uncorrected = $p.counters.uncorrected.wrapping_add(1);
                $p.counters.pending = pending;
            }
        } else if let Some((segment, h)) = $p.input.pending_step(&sample, dt) {
            // Kept for a later step: beyond the bound on its own, it would refuse every later step.
            $p.scheme.check(&segment, h)?;
        }
        $p.input = input;
        $p.count_saturated(&sample);
        Ok(())
    }};
}

impl<T: Real, S: Scheme<T>, I: InputModel<T>, Z: Stabilizer, A: Accumulator<T>>
    Propagator<T, S, I, Z, A>
{
    /// The same propagator adding increments with `accumulator` instead (e.g.
    /// [`Kahan`](crate::accumulate::Kahan): an f32 state that tracks an f64 one over millions of steps).
    ///
    /// ```
    /// use quatprop::{accumulate::Kahan, input::History, scheme::ExpMap, stabilize::FirstOrder};
    /// use quatprop::{Propagator, Quat};
    /// let p = Propagator::new(Quat::<f32>::IDENTITY, ExpMap, History::new(), FirstOrder)?
    ///     .with_accumulator(Kahan::new());
    /// assert_eq!(p.attitude(), Quat::IDENTITY);
    /// # Ok::<(), quatprop::Error>(())
    /// ```
    #[must_use]
    pub fn with_accumulator<B: Accumulator<T>>(self, accumulator: B) -> Propagator<T, S, I, Z, B> {
        Propagator {
            q: self.q,
            scheme: self.scheme,
            input: self.input,
            stabilizer: self.stabilizer,
            accumulator,
            counters: self.counters,
        }
    }

    /// A propagator from its parts, as [`Propagator::into_parts`] returns them (no validation: the parts
    /// come from a propagator or from a validated [`crate::config::Config`]). Its parameters are the
    /// struct's fields, in their order.
    #[inline(always)]
    pub(crate) fn from_parts(
        q: Quat<T>,
        scheme: S,
        input: I,
        stabilizer: Z,
        accumulator: A,
        counters: Counters,
    ) -> Self {
        Self {
            q,
            scheme,
            input,
            stabilizer,
            accumulator,
            counters,
        }
    }

    /// The parts that change as samples arrive: attitude, input model, accumulator and counters.
    #[inline(always)]
    pub(crate) fn into_parts(self) -> (Quat<T>, I, A, Counters) {
        (self.q, self.input, self.accumulator, self.counters)
    }

    /// Takes one sensor sample that arrives `dt` seconds after the previous one. The input model decides
    /// whether it closes a step (see [`crate::input`]); if it does, the scheme advances the attitude over
    /// it and the stabilizer corrects it. A saturated sample is integrated and counted
    /// ([`Propagator::saturated_samples`]).
    ///
    /// After a refused sample, pass the next one with the time since the last *accepted* sample, so no
    /// interval is lost (the README's quick start shows how).
    ///
    /// # Errors
    /// - [`Error::NonFiniteStep`] / [`Error::NonPositiveStep`]: `dt` is NaN, ±∞, zero or negative.
    /// - [`Error::NonFiniteRate`]: a sample component is NaN or ±∞.
    /// - [`Error::StepAngleBeyondStability`]: the step angle exceeds the scheme's bound
    ///   ([`crate::scheme::Information::step_angle_limit`]); [`Error::GainBeyondStability`] for
    ///   [`crate::scheme::Baumgarte`].
    /// - [`Error::NonFiniteResult`]: the arithmetic overflowed.
    ///
    /// In every case the propagator, its input model included, is unchanged.
    ///
    /// A loop runs fastest with one call site of `push` per propagator type: the compiler then inlines
    /// it and can keep the state in registers (out of line, each call loads and stores the state:
    /// about 1.5 times as long on an x86-64 host, docs/push-cost.md). It is not forced inline: a firmware
    /// that pushes from many places would hold a copy of the step at each (the firmware's `stack` program
    /// then overflows the M4F's flash). [`Propagator::push_burst`] and
    /// [`Propagator::push_burst_timed`] always inline the step into their loop.
    #[inline]
    pub fn push(&mut self, sample: I::Sample, dt: T) -> Result<(), Error> {
        push_body!(self, sample, dt)
    }

    /// Takes the first sample of a stream, which sets its time origin: there is no `dt` before it. The
    /// input model keeps it as the start of its next step where it can ([`InputModel::start`]); a saturated
    /// sample is counted. For `Linear` and `History` this equals `push` with any `dt`.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] for a NaN or infinite sample; the propagator is then unchanged.
    ///
    /// ```
    /// use quatprop::{input::History, scheme::ExpMap, stabilize::FirstOrder};
    /// use quatprop::{GyroSample, Propagator, Quat, Vec3};
    /// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)?;
    /// p.start(GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f64)))?;
    /// p.push(GyroSample::new(Vec3::new(0.0, 0.0, 1.0)), 0.5)?;
    /// assert_eq!((p.steps(), p.input().len()), (1, 2));
    /// # Ok::<(), quatprop::Error>(())
    /// ```
    pub fn start(&mut self, sample: I::Sample) -> Result<(), Error> {
        self.input = self.input.start(&sample)?;
        self.count_saturated(&sample);
        Ok(())
    }

    /// Pushes a FIFO burst of samples taken at a fixed period: each sample's `dt` is
    /// [`FixedPeriod::next_dt`], so time is exact over any number of bursts. Bit for bit the same as
    /// `push(sample, period.next_dt())` one sample at a time; allocates nothing. Returns how many were
    /// integrated (all of them).
    ///
    /// # Errors
    /// At the first refused sample it stops and returns its index and error ([`Refused`]). The propagator is
    /// then what it was after the last accepted sample, and the refused sample's interval has been given
    /// back to `period` ([`FixedPeriod::carry_over`]): push `samples[index + 1..]` next and it is covered.
    ///
    /// ```
    /// use quatprop::{frontend::FixedPeriod, input::History, scheme::ExpMap, stabilize::FirstOrder};
    /// use quatprop::{Error, GyroSample, Propagator, Quat, Refused, Vec3};
    /// let w = GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f32));
    /// let mut burst = [w; 32];
    /// burst[5].rate.y = f32::INFINITY;
    /// let mut period = FixedPeriod::new(1.0e-3)?;
    /// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)?;
    /// let r = p.push_burst(&burst, &mut period);
    /// assert_eq!(r, Err(Refused { index: 5, error: Error::NonFiniteRate }));
    /// assert_eq!(p.push_burst(&burst[6..], &mut period), Ok(26));
    /// let yaw = 2.0 * p.attitude().z.atan2(p.attitude().w);
    /// assert!((yaw - 31.0e-3).abs() < 1e-8, "{yaw}"); // 31 intervals after the first sample
    /// # Ok::<(), Error>(())
    /// ```
    pub fn push_burst(
        &mut self,
        samples: &[I::Sample],
        period: &mut FixedPeriod<T>,
    ) -> Result<usize, Refused> {
        // The state in locals for the whole burst, written back once (also after a refusal: the samples
        // before it were taken), and the step inlined: through `push`, out of line where a binary pushes
        // one type from several places, every sample would load and store the whole state (53 ns per
        // sample on an x86-64 host against 34 for an inlined `push`).
        let mut p = *self;
        for (index, sample) in samples.iter().enumerate() {
            let dt = period.next_dt();
            let pushed = (|| {
                let sample = *sample;
                push_body!(p, sample, dt)
            })();
            if let Err(error) = pushed {
                period.carry_over(dt);
                *self = p;
                return Err(Refused { index, error });
            }
        }
        *self = p;
        Ok(samples.len())
    }

    /// Pushes a FIFO burst of samples with the sensor's own timestamps (ticks of `clock`, see
    /// [`TickClock`]): each sample's `dt` is the exact time since the last *accepted* sample. The very
    /// first timestamp of a stream starts the clock, and its sample starts the input model
    /// ([`InputModel::start`]). Bit for bit the same as pushing the samples one at a time with those `dt`s.
    ///
    /// # Errors
    /// At the first refused sample (a bad sample, or a timestamp that does not advance:
    /// [`Error::TimestampNotIncreasing`]) it stops and returns its index and error; the propagator and the
    /// clock are then what they were after the last accepted sample, so the next sample's `dt` covers the
    /// refused interval too.
    ///
    /// ```
    /// use quatprop::{frontend::TickClock, input::History, scheme::ExpMap, stabilize::FirstOrder};
    /// use quatprop::{Error, GyroSample, Propagator, Quat, Refused, Vec3};
    /// let mut clock = TickClock::<f32>::new(1.0e6, 32)?; // 1 µs ticks
    /// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)?;
    /// let w = GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f32));
    /// let fifo = [(w, 0_u32), (w, 1000), (w, 2000), (w, 2000), (w, 4000)];
    /// let r = p.push_burst_timed(&fifo, &mut clock);
    /// assert_eq!(r, Err(Refused { index: 3, error: Error::TimestampNotIncreasing }));
    /// assert_eq!(p.push_burst_timed(&fifo[4..], &mut clock), Ok(1)); // covers 2000 → 4000
    /// let yaw = 2.0 * p.attitude().z.atan2(p.attitude().w); // 4 ms at 1 rad/s
    /// assert!((yaw - 4.0e-3).abs() < 4.0 * f32::EPSILON * 4.0e-3, "{yaw}");
    /// # Ok::<(), Error>(())
    /// ```
    pub fn push_burst_timed(
        &mut self,
        samples: &[(I::Sample, u32)],
        clock: &mut TickClock<T>,
    ) -> Result<usize, Refused> {
        // As `push_burst`: the state in locals, the step inlined, written back once.
        let mut p = *self;
        for (index, (sample, timestamp)) in samples.iter().enumerate() {
            let taken = clock.advance(*timestamp).and_then(|(next, dt)| {
                let sample = *sample;
                match dt {
                    Some(dt) => (|| push_body!(p, sample, dt))()?,
                    None => p.start(sample)?,
                }
                Ok(next)
            });
            match taken {
                Ok(next) => *clock = next,
                Err(error) => {
                    *self = p;
                    return Err(Refused { index, error });
                }
            }
        }
        *self = p;
        Ok(samples.len())
    }

    /// Counts an accepted sample if it is saturated (a branch, not an add: most samples are not).
    #[inline(always)]
    fn count_saturated(&mut self, sample: &I::Sample) {
        if sample.is_saturated() {
            self.counters.saturated = self.counters.saturated.wrapping_add(1);
        }
    }

    /// Forgets the samples the input model keeps between steps (after a gap in the data: the next sample
    /// starts the model afresh). The attitude and counters stay.
    pub fn restart_input(&mut self) {
        self.input.restart();
    }

    /// Replaces the attitude (normalized), keeping the counters and the input model's samples. On error
    /// nothing changes.
    ///
    /// ```
    /// use quatprop::{input::Hold, scheme::Rk4, stabilize::Off, Error, Propagator, Quat};
    /// let mut p = Propagator::new(Quat::IDENTITY, Rk4, Hold, Off)?;
    /// p.set_attitude(Quat::new(0.0, 2.0_f64, 0.0, 0.0))?;
    /// assert_eq!(p.attitude(), Quat::new(0.0, 1.0, 0.0, 0.0));
    /// assert_eq!(p.set_attitude(Quat::new(0.0, 0.0, 0.0, 0.0)), Err(Error::ZeroQuaternion));
    /// # Ok::<(), Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFiniteQuaternion`] or [`Error::ZeroQuaternion`].
    pub fn set_attitude(&mut self, q: Quat<T>) -> Result<(), Error> {
        self.q = checked_unit(q)?;
        self.accumulator.reset();
        self.counters.attitude_replaced();
        Ok(())
    }

    /// Rotates the attitude by the small rotation `dtheta` (rotation vector, rad) given in the **body**
    /// frame: `q ← q ⊗ exp_q(dtheta)`. An error-state filter's update with the attitude error defined as
    /// `q_true = q ⊗ exp_q(δθ)` (the convention of [`crate::error_state`]) applies its estimate this way.
    ///
    /// Nothing else changes: the input model keeps its samples (they are body rates, which a change of
    /// attitude does not move), the counters stay, and the accumulator keeps what it carries. The rotation
    /// is added through the accumulator as a step's increment is (`q + q ⊗ (exp_q(dtheta) − 1)`), so a
    /// [`Kahan`](crate::accumulate::Kahan) or [`FloatFloat`](crate::accumulate::FloatFloat) low part
    /// stays in the sum; that low part is not itself rotated (it is below an ulp of `q`, and its rotation
    /// by `dtheta` changes it by less than `|dtheta|` times that). The norm is left to the next step's
    /// stabilizer, as after a step (the rotation is unit to within rounding).
    ///
    /// ```
    /// use quatprop::{Propagator, Quat, Vec3};
    /// let tilted = Quat::from_rotation_vector(Vec3::new(0.1, 0.0, 0.0_f64)); // rolled 0.1 rad
    /// let mut p = Propagator::recommended(tilted)?;
    /// p.rotate_body(Vec3::new(0.0, 0.0, 0.2))?; // yaw about the body's own z
    /// let expected = tilted * Quat::from_rotation_vector(Vec3::new(0.0, 0.0, 0.2));
    /// assert!(p.attitude().angle_to(expected) < 1e-15);
    /// # Ok::<(), quatprop::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] for a NaN or infinite component; [`Error::StepAngleBeyondStability`] in
    /// f32 for a rotation beyond 16384 rad (the step path's sine; no libm sine is linked);
    /// [`Error::NonFiniteResult`] if the result is not finite. The propagator is then unchanged.
    pub fn rotate_body(&mut self, dtheta: Vec3<T>) -> Result<(), Error> {
        self.correct(dtheta, Frame::Body)
    }

    /// Rotates the attitude by the small rotation `dtheta` (rotation vector, rad) given in the
    /// **reference** frame: `q ← exp_q(dtheta) ⊗ q`. For a filter whose attitude error is defined in the
    /// reference frame (`q_true = exp_q(δθ) ⊗ q`, as in PX4's EKF2). Otherwise as
    /// [`Propagator::rotate_body`].
    ///
    /// ```
    /// use quatprop::{Propagator, Quat, Vec3};
    /// let tilted = Quat::from_rotation_vector(Vec3::new(0.1, 0.0, 0.0_f64));
    /// let mut p = Propagator::recommended(tilted)?;
    /// p.rotate_reference(Vec3::new(0.0, 0.0, 0.2))?; // yaw about the reference z (heading)
    /// let expected = Quat::from_rotation_vector(Vec3::new(0.0, 0.0, 0.2)) * tilted;
    /// assert!(p.attitude().angle_to(expected) < 1e-15);
    /// # Ok::<(), quatprop::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Propagator::rotate_body`].
    pub fn rotate_reference(&mut self, dtheta: Vec3<T>) -> Result<(), Error> {
        self.correct(dtheta, Frame::Reference)
    }

    /// A correction through the accumulator; commits only a finite result.
    fn correct(&mut self, dtheta: Vec3<T>, frame: Frame) -> Result<(), Error> {
        (self.q, self.accumulator) = corrected(self.q, self.accumulator, dtheta, frame, A::add)?;
        Ok(())
    }

    /// The bias subtracted from the samples grew by `delta` (rad/s, body axes): an estimator's bias
    /// correction, given here so that the samples the input model keeps for its next steps (corrected with
    /// the old bias) are lowered by `delta` too ([`InputModel::correct_bias`]). Subtract the same `delta`
    /// from the samples from now on (e.g.
    /// [`FixedBias::correct_bias`](crate::frontend::FixedBias::correct_bias) or
    /// [`BiasEstimator::correct_bias`](crate::frontend::BiasEstimator::correct_bias)): the next step then
    /// integrates rates that all carry the new bias, where a model left alone would see a jump of
    /// `delta` between its kept samples and the new ones (a cubic through a step, for [`History`]). The
    /// attitude, accumulator and counters stay.
    ///
    /// ```
    /// use quatprop::{frontend::FixedBias, GyroSample, Propagator, Quat, Vec3};
    /// let mut p = Propagator::recommended(Quat::IDENTITY)?;
    /// let mut bias = FixedBias::new(Vec3::ZERO)?;
    /// let raw = GyroSample::new(Vec3::new(0.0, 0.0, 1.01_f64)); // 1 rad/s and a 0.01 rad/s bias
    /// for _ in 0..10 {
    ///     p.push(bias.apply(raw), 1.0e-3)?;
    /// }
    /// let delta = Vec3::new(0.0, 0.0, 0.01); // an estimator's update finds the bias
    /// bias.correct_bias(delta)?;
    /// p.correct_bias(delta)?;
    /// let before = p.attitude();
    /// p.push(bias.apply(raw), 1.0e-3)?; // 1 rad/s exactly, history included: 1 mrad
    /// assert!((before.angle_to(p.attitude()) - 1.0e-3).abs() < 1e-15);
    /// # Ok::<(), quatprop::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] for a NaN or infinite component, or one that makes a kept sample so; the
    /// propagator is then unchanged.
    pub fn correct_bias(&mut self, delta: Vec3<T>) -> Result<(), Error> {
        if !delta.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        self.input = self.input.correct_bias(delta)?;
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

    /// Steps taken (samples that closed a step and were accepted).
    #[inline]
    #[must_use]
    pub fn steps(&self) -> u64 {
        self.counters.steps
    }

    /// Post-step corrections applied by the stabilizer.
    #[inline]
    #[must_use]
    pub fn corrections(&self) -> u64 {
        self.counters.corrections()
    }

    /// Saturated samples accepted so far (on every input path).
    #[inline]
    #[must_use]
    pub fn saturated_samples(&self) -> u64 {
        self.counters.saturated
    }

    /// The scheme.
    #[inline]
    #[must_use]
    pub fn scheme(&self) -> S {
        self.scheme
    }

    /// The input model, with the samples it keeps.
    #[inline]
    #[must_use]
    pub fn input(&self) -> I {
        self.input
    }

    /// The stabilizer.
    #[inline]
    #[must_use]
    pub fn stabilizer(&self) -> Z {
        self.stabilizer
    }

    /// The accumulator, with what it carries beside the attitude (e.g. [`FloatFloat::low`]: the
    /// attitude is then `attitude() + accumulator().low()`).
    ///
    /// [`FloatFloat::low`]: crate::accumulate::FloatFloat::low
    #[inline]
    #[must_use]
    pub fn accumulator(&self) -> A {
        self.accumulator
    }
}
