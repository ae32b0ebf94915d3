//! Input models: what is known of the body rate ω(t) inside a step, and every piece of state that carries
//! from one step to the next (the previous sample, the sample history, a pending Gauss sample, the previous
//! angle increment).
//!
//! The propagator holds one input model and feeds it one sensor sample per
//! [`push`](crate::Propagator::push). The model decides when a sample closes a step and hands the scheme a
//! [`Segment`]: the rate function of that step. It knows nothing of how the scheme integrates.
//!
//! `dt` passed with a sample is always the time (s) from the previous sample to this one.
//!
//! | model | sample | a step per | order on a smooth ω (ExpMap) | first sample |
//! |---|---|---|---|---|
//! | [`Hold`] | [`GyroSample`] | sample | 1 (exact for a constant rate) | steps |
//! | [`Linear`] | [`GyroSample`] | sample | 2 | only starts |
//! | [`History`] | [`GyroSample`] | sample | 4, no latency (cubic through the last four samples) | only starts |
//! | [`TwiceRate`] | [`GyroSample`] | 2 samples (start shared, middle, end) | 4 | only starts |
//! | [`GaussPoints`] | [`GyroSample`] | 2 samples at the Gauss points | 4 | pending |
//! | [`DeltaAngles`] | [`DeltaAngle`] | as many increments as its [coning correction](coning) takes | see [`coning`] | steps or pending |
//!
//! A custom model implements [`InputModel`] (`accept` and `restart`; `start` has a default) and returns
//! its own [`Segment`] (the rate function `rate_at`, its integral `half_angle`, and the bound
//! `max_step_angle_squared` the stability check reads; the rest are optional shortcuts). For instance the
//! mean of the two samples around each step, held over it:
//!
//! ```
//! use quatprop::input::{InputModel, Segment};
//! use quatprop::{scheme::ExpMap, stabilize::Off, Error, GyroSample, Propagator, Quat, Vec3};
//!
//! /// The mean of the previous and the newest sample, held over the step between them.
//! #[derive(Clone, Copy, Default)]
//! struct MeanOfTwo {
//!     previous: Option<Vec3<f64>>,
//! }
//!
//! /// A rate held over the step (rad/s).
//! #[derive(Clone, Copy)]
//! struct Held(Vec3<f64>);
//!
//! impl Segment<f64> for Held {
//!     fn rate_at(&self, _c: f64) -> Vec3<f64> {
//!         self.0
//!     }
//!     fn half_angle(&self, hh: f64) -> Vec3<f64> {
//!         self.0 * hh
//!     }
//!     fn max_step_angle_squared(&self, h: f64) -> f64 {
//!         (self.0 * h).norm_squared()
//!     }
//! }
//!
//! impl InputModel<f64> for MeanOfTwo {
//!     type Sample = GyroSample<f64>;
//!     type Segment = Held;
//!     fn accept(&self, s: &GyroSample<f64>, dt: f64) -> Result<(Self, Option<(Held, f64)>), Error> {
//!         if !s.rate.is_finite() {
//!             return Err(Error::NonFiniteRate);
//!         }
//!         let step = self.previous.map(|w0| (Held((w0 + s.rate) * 0.5), dt));
//!         Ok((MeanOfTwo { previous: Some(s.rate) }, step))
//!     }
//!     fn restart(&mut self) {
//!         self.previous = None;
//!     }
//! }
//!
//! let mut p = Propagator::new(Quat::IDENTITY, ExpMap, MeanOfTwo::default(), Off)?;
//! p.push(GyroSample::new(Vec3::new(0.0, 0.0, 0.0)), 0.5)?; // starts: no step
//! p.push(GyroSample::new(Vec3::new(0.0, 0.0, 2.0)), 0.5)?; // mean 1 rad/s for 0.5 s
//! assert!((p.attitude().z - 0.25_f64.sin()).abs() < 1e-15);
//! # Ok::<(), Error>(())
//! ```

pub mod coning;
mod models;
pub mod segment;

pub use models::{DeltaAngles, GaussPoints, History, Hold, Linear, TwiceRate};

use crate::sample::Sample;
#[cfg(doc)]
use crate::{DeltaAngle, GyroSample};
use crate::{Error, Real, Vec3};

/// The rate function of one step `[t, t + h]`, as a scheme reads it. Rates are body-frame rad/s.
pub trait Segment<T: Real> {
    /// ω(t + c·h) (rad/s) at the fraction `c ∈ [0, 1]` of the step (Runge–Kutta stages, Gauss nodes).
    /// A segment returns its samples exactly at their own nodes.
    fn rate_at(&self, c: f64) -> Vec3<T>;

    /// `Some(ω)` if ω is constant over the step (the seed's assumption V1): a Runge–Kutta step then
    /// reduces to one quaternion product.
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        None
    }

    /// Half the angle integral of the step, `½∫ω dt` (rad), from the half step `hh = h/2` (s): the
    /// quadrature of this segment's own rate function (exact for it).
    fn half_angle(&self, hh: T) -> Vec3<T>;

    /// [`Segment::half_angle`] as an unevaluated sum `hi + lo`, `lo` holding the rounding of its final
    /// sum and product (TwoSum, TwoProduct): what [`crate::accumulate::FloatFloat`] carries. By default no
    /// low part. `hi` need not equal `half_angle` bit for bit.
    #[doc(hidden)]
    #[inline(always)]
    fn half_angle_split(&self, hh: T) -> (Vec3<T>, Vec3<T>) {
        (self.half_angle(hh), Vec3::ZERO)
    }

    /// `ω × dω/dc` at mid-step (rad²/s², `dω/dc` per unit fraction of the step), accurate to O(h³), or
    /// `None` if ω keeps its direction over the step. The second Magnus term of the exponential-map
    /// schemes is built from it.
    #[inline(always)]
    fn rate_commutator(&self) -> Option<Vec3<T>> {
        None
    }

    /// `max |ω·h|²` over the samples (rad²), scaled before squaring so that a tiny rate over a huge step
    /// cannot underflow to zero; infinite on overflow (which the stability check refuses).
    fn max_step_angle_squared(&self, h: T) -> T;
}

/// What [`InputModel::accept`] returns: the model's next state `M` and, if the sample closes a step, the
/// step's segment `G` and length `h` (s); or why the sample was refused.
pub type Accepted<M, G, T> = Result<(M, Option<(G, T)>), Error>;

/// What the propagator knows of ω between samples, and the state that carries across steps.
///
/// Implementations are small and `Copy`. [`InputModel::accept`] does not change the model: it returns the
/// next state, which the propagator commits only when the whole step succeeds, so a refused sample leaves
/// everything as it was.
pub trait InputModel<T: Real>: Copy {
    /// What one push carries ([`GyroSample`] for rates, [`DeltaAngle`] for angle increments).
    type Sample: Sample;
    /// The rate function of a step this model closes.
    type Segment: Segment<T>;

    /// Takes `sample`, which arrives `dt` seconds after the previous one (`dt` finite and positive: the
    /// propagator checks it first). Returns the next state and, if this sample closes a step, the step's
    /// segment and length `h` (s).
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if the sample has a NaN or infinite component.
    fn accept(&self, sample: &Self::Sample, dt: T) -> Accepted<Self, Self::Segment, T>;

    /// [`InputModel::accept`] for an accumulator that carries low parts
    /// ([`crate::accumulate::Accumulator::CARRIES_LOW_PARTS`]): a model whose segment keeps a rounding that
    /// the plain path drops computes it here (`DeltaAngles`: the rounding of the rotation vector's sum,
    /// [`coning::ConingCorrection::rotation_vector_split`]), so the plain path does not pay for it. By
    /// default `accept`.
    ///
    /// # Errors
    /// As [`InputModel::accept`].
    #[doc(hidden)]
    #[inline(always)]
    fn accept_split(&self, sample: &Self::Sample, dt: T) -> Accepted<Self, Self::Segment, T> {
        self.accept(sample, dt)
    }

    /// The step `sample` would make on its own, when [`InputModel::accept`] keeps it for a later step:
    /// the propagator checks it against the scheme's stability bound when it arrives, so a sample beyond
    /// the bound is refused at once instead of being kept and refusing every step after it. `None` (the
    /// default): nothing to check before the step closes.
    #[allow(clippy::type_complexity)]
    #[inline(always)]
    fn pending_step(&self, sample: &Self::Sample, dt: T) -> Option<(Self::Segment, T)> {
        let _ = (sample, dt);
        None
    }

    /// Takes the first sample of a stream, which sets its time origin (there is no `dt` before it): a
    /// restarted model that keeps the sample as the start of its next step where it can (`Linear`,
    /// `History`, `TwiceRate`); models that need the sample's interval (`Hold`, `GaussPoints`,
    /// `DeltaAngles`) only restart.
    ///
    /// The default restarts and keeps nothing (the sample is not used).
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if the sample has a NaN or infinite component (the built-in models).
    fn start(&self, sample: &Self::Sample) -> Result<Self, Error> {
        let _ = sample;
        let mut next = *self;
        next.restart();
        Ok(next)
    }

    /// Forgets every sample kept between steps: the next sample starts the model afresh (after a gap).
    fn restart(&mut self);

    /// The bias subtracted from the samples grew by `delta` (rad/s, body axes; finite: the propagator
    /// checks it first): an estimator's bias correction. The samples kept for later steps were corrected
    /// with the old bias, so the returned model has each lowered by `delta` (an angle increment by `delta`
    /// times its interval), and the next step joins them to samples corrected with the new bias as if every
    /// sample had been: no jump in the rate for the model to integrate.
    /// [`crate::Propagator::correct_bias`] calls it.
    ///
    /// The default restarts the model (a model of the caller's own that does not say how forgets its
    /// samples, which is never wrong, only less accurate for a step or two).
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] if a kept sample would overflow (the built-in models).
    fn correct_bias(&self, delta: Vec3<T>) -> Result<Self, Error> {
        let _ = delta;
        let mut next = *self;
        next.restart();
        Ok(next)
    }
}
