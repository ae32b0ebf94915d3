//! One run-time configuration: a plain [`Config`] value that builds one propagator type, [`Configured`].
//!
//! A firmware names its scheme, input model, stabilizer and accumulator as types
//! ([`Propagator`]) and links only them. Whoever chooses at run time — a C caller, Python, the host lab, a
//! configuration byte read at boot — fills a [`Config`] instead: `no_std`, no allocation, no trait object.
//! [`Config::build`] validates it (typed errors) and returns a [`Configured`] propagator. Each call on it
//! matches the configuration once and then runs the code of the static types it stands for: a burst
//! ([`Configured::push_burst`]) is one `match` and then the same monomorphized loop as
//! [`Propagator::push_burst`]. The cost is flash, not time: every configuration the `match` can reach is
//! linked (see docs/c-api.md for the figures).
//!
//! The precision is the type parameter of [`Config::build`] (`f32` or `f64`); everything else is a value.
//!
//! ```
//! use quatprop::config::{AccumulatorKind, Config, InputKind};
//! use quatprop::frontend::FixedPeriod;
//! use quatprop::{scheme::SchemeKind, stabilize::StabilizerKind, GyroSample, Quat, Vec3};
//!
//! let config = Config {
//!     scheme: SchemeKind::Rk4,
//!     input: InputKind::Linear,
//!     stabilizer: StabilizerKind::Normalize,
//!     accumulator: AccumulatorKind::Kahan,
//!     ..Config::RECOMMENDED
//! };
//! let mut p = config.build::<f32>(Quat::IDENTITY)?;
//! let mut period = FixedPeriod::new(1.0e-3)?; // 1 kHz
//! let burst = [GyroSample::new(Vec3::new(0.0, 0.0, 1.0)); 32]; // 1 rad/s yaw
//! assert_eq!(p.push_burst(&burst, &mut period), Ok(32));
//! assert_eq!(p.steps(), 31); // Linear: the first sample only starts the model
//! let yaw = 2.0 * p.attitude().z.atan2(p.attitude().w);
//! assert!((yaw - 31.0e-3).abs() < 1e-7);
//! # Ok::<(), quatprop::Error>(())
//! ```
//!
//! A binding that needs its own loop (a front end per sample, a time base of its own) implements [`Visit`]:
//! [`Configured::visit`] hands it the static propagator, so its loop is monomorphized too.

use crate::accumulate::{Accumulator, FloatFloat, Kahan, Plain};
use crate::frontend::{FixedPeriod, TickClock};
use crate::input::coning::ConingKind;
use crate::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use crate::propagator::{checked_unit, corrected, Counters, Frame};
use crate::scheme::{
    Baumgarte, Cf4, Euler, ExpMap, Magnus4, Rk2, Rk3, Rk4, Rk5, Scheme, SchemeKind,
};
use crate::stabilize::{Stabilizer, StabilizerKind};
use crate::{DeltaAngle, Error, GyroSample, Propagator, Quat, Real, Refused, Vec3};

/// The input model of a [`Config`] ([`crate::input`]): what is known of ω inside a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum InputKind {
    /// [`Hold`]: each rate held over its interval.
    Hold,
    /// [`Linear`]: the rate linear between two samples.
    Linear,
    /// [`History`]: the cubic through the last four samples (the recommended input for a rate gyro).
    History,
    /// [`TwiceRate`]: one step per two samples, the quadratic through three.
    TwiceRate,
    /// [`GaussPoints`]: samples taken at the two Gauss points of each step.
    GaussPoints,
    /// [`DeltaAngles`] with the given coning correction: angle increments ([`DeltaAngle`]) instead of rates.
    DeltaAngles(ConingKind),
}

/// How a [`Config`]'s increments are added ([`crate::accumulate`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum AccumulatorKind {
    /// [`Plain`]: `q + Δ`.
    Plain,
    /// [`Kahan`]: compensated addition.
    Kahan,
    /// [`FloatFloat`]: a float-float attitude advanced by exact products.
    FloatFloat,
}

/// Everything that chooses how a propagator works, as one plain value: scheme (with Baumgarte's term for
/// a Runge–Kutta scheme), input model (with its coning correction), stabilizer and accumulator.
/// [`Config::build`] validates it and builds a [`Configured`] propagator in the precision asked for.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Config {
    /// The integration scheme ([`crate::scheme`]).
    pub scheme: SchemeKind,
    /// `Some(k)`: Baumgarte's term with gain `k` (1/s, finite, ≥ 0) in every stage of a Runge–Kutta
    /// scheme ([`Baumgarte`], the seed's method; use a post-step stabilizer instead unless you study it).
    pub baumgarte_gain: Option<f64>,
    /// The input model ([`crate::input`]).
    pub input: InputKind,
    /// The post-step stabilizer ([`crate::stabilize`]).
    pub stabilizer: StabilizerKind,
    /// How increments are added ([`crate::accumulate`]).
    pub accumulator: AccumulatorKind,
}

impl Default for Config {
    /// [`Config::RECOMMENDED`].
    fn default() -> Self {
        Self::RECOMMENDED
    }
}

impl Config {
    /// The recommended configuration, as [`crate::Recommended`] names it in types: [`ExpMap`] +
    /// [`History`] + [`FirstOrder`](crate::stabilize::FirstOrder), plain addition, no Baumgarte term.
    pub const RECOMMENDED: Config = Config {
        scheme: SchemeKind::ExpMap,
        baumgarte_gain: None,
        input: InputKind::History,
        stabilizer: StabilizerKind::FirstOrder,
        accumulator: AccumulatorKind::Plain,
    };

    /// Checks the configuration.
    ///
    /// # Errors
    /// [`Error::InvalidStabilizer`] for `Every(0)`; [`Error::InvalidGain`] for a negative or non-finite
    /// Baumgarte gain; [`Error::BaumgarteNeedsRungeKutta`] for a gain with an exponential-map scheme.
    pub fn validate(&self) -> Result<(), Error> {
        self.stabilizer.validate()?;
        if let Some(k) = self.baumgarte_gain {
            if !(k.is_finite() && k >= 0.0) {
                return Err(Error::InvalidGain);
            }
            if !is_runge_kutta(self.scheme) {
                return Err(Error::BaumgarteNeedsRungeKutta);
            }
        }
        Ok(())
    }

    /// The propagator this configuration describes, in precision `T`, starting from attitude `q0`
    /// (normalized here; any finite non-zero quaternion).
    ///
    /// # Errors
    /// Those of [`Config::validate`]; [`Error::NonFiniteQuaternion`] or [`Error::ZeroQuaternion`] for
    /// `q0`; [`Error::InvalidGain`] if the gain is not finite in `T`.
    pub fn build<T: Real>(&self, q0: Quat<T>) -> Result<Configured<T>, Error> {
        self.validate()?;
        let gain = match self.baumgarte_gain {
            Some(k) => {
                let k = T::from_f64(k);
                if !k.is_finite() {
                    return Err(Error::InvalidGain);
                }
                Some(k)
            }
            None => None,
        };
        Ok(Configured {
            q: checked_unit(q0)?,
            counters: Counters::default(),
            input: match self.input {
                InputKind::Hold => InputState::Hold(Hold::new()),
                InputKind::Linear => InputState::Linear(Linear::new()),
                InputKind::History => InputState::History(History::new()),
                InputKind::TwiceRate => InputState::TwiceRate(TwiceRate::new()),
                InputKind::GaussPoints => InputState::GaussPoints(GaussPoints::new()),
                InputKind::DeltaAngles(c) => InputState::DeltaAngles(DeltaAngles::new(c)),
            },
            accumulator: match self.accumulator {
                AccumulatorKind::Plain => AccumulatorState::Plain(Plain),
                AccumulatorKind::Kahan => AccumulatorState::Kahan(Kahan::new()),
                AccumulatorKind::FloatFloat => AccumulatorState::FloatFloat(FloatFloat::new()),
            },
            scheme: self.scheme,
            gain,
            stabilizer: self.stabilizer,
        })
    }

    /// `true` if the input model takes angle increments ([`DeltaAngle`]) rather than rates.
    #[must_use]
    pub fn takes_delta_angles(&self) -> bool {
        matches!(self.input, InputKind::DeltaAngles(_))
    }
}

fn is_runge_kutta(s: SchemeKind) -> bool {
    matches!(
        s,
        SchemeKind::Euler | SchemeKind::Rk2 | SchemeKind::Rk3 | SchemeKind::Rk4 | SchemeKind::Rk5
    )
}

/// Baumgarte's term on the Runge–Kutta scheme `kind`, matched at every use
/// ([`Configured::visit_compact`]).
#[derive(Clone, Copy, Debug)]
struct BaumgarteKind<T> {
    kind: SchemeKind,
    k: T,
}

macro_rules! baumgarte_kind {
    ($self:ident, $s:ident => $e:expr) => {
        match $self.kind {
            SchemeKind::Euler => {
                let $s = Baumgarte::validated(Euler, $self.k);
                $e
            }
            SchemeKind::Rk2 => {
                let $s = Baumgarte::validated(Rk2, $self.k);
                $e
            }
            SchemeKind::Rk3 => {
                let $s = Baumgarte::validated(Rk3, $self.k);
                $e
            }
            SchemeKind::Rk4 => {
                let $s = Baumgarte::validated(Rk4, $self.k);
                $e
            }
            SchemeKind::Rk5 => {
                let $s = Baumgarte::validated(Rk5, $self.k);
                $e
            }
            // A gain with an exponential map is refused by `Config::validate`.
            kind => {
                let $s = kind;
                $e
            }
        }
    };
}

impl<T: Real> Scheme<T> for BaumgarteKind<T> {
    #[inline]
    fn information(&self) -> crate::scheme::Information {
        self.kind.information()
    }
    #[inline]
    fn check<G: crate::input::Segment<T>>(&self, segment: &G, h: T) -> Result<(), Error> {
        baumgarte_kind!(self, s => s.check(segment, h))
    }
    #[inline]
    fn increment<G: crate::input::Segment<T>>(&self, q: Quat<T>, segment: &G, h: T) -> Quat<T> {
        baumgarte_kind!(self, s => s.increment(q, segment, h))
    }
    #[inline]
    fn right_factor<G: crate::input::Segment<T>>(&self, segment: &G, h: T) -> (Quat<T>, Quat<T>) {
        baumgarte_kind!(self, s => s.right_factor(segment, h))
    }
}

/// The input model's state, one variant per [`InputKind`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum InputState<T> {
    Hold(Hold),
    Linear(Linear<T>),
    History(History<T>),
    TwiceRate(TwiceRate<T>),
    GaussPoints(GaussPoints<T>),
    DeltaAngles(DeltaAngles<T, ConingKind>),
}

/// The accumulator's state, one variant per [`AccumulatorKind`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum AccumulatorState<T> {
    Plain(Plain),
    Kahan(Kahan<T>),
    FloatFloat(FloatFloat<T>),
}

impl<T: Real> AccumulatorState<T> {
    /// [`Accumulator::reset`] of the accumulator held.
    fn reset(&mut self) {
        match self {
            AccumulatorState::Plain(a) => Accumulator::<T>::reset(a),
            AccumulatorState::Kahan(a) => a.reset(),
            AccumulatorState::FloatFloat(a) => a.reset(),
        }
    }

    /// [`Accumulator::add`] of the accumulator held.
    fn add(&mut self, q: Quat<T>, d: Quat<T>) -> Quat<T> {
        match self {
            AccumulatorState::Plain(a) => a.add(q, d),
            AccumulatorState::Kahan(a) => a.add(q, d),
            AccumulatorState::FloatFloat(a) => a.add(q, d),
        }
    }
}

/// The propagator a [`Config`] builds: the attitude, the counters, and the input model's and
/// accumulator's state as run-time values. Small and `Copy`; no allocation, no trait objects, no panic.
///
/// Every call matches the configuration once, rebuilds the static [`Propagator`] it stands for around
/// the state, runs it and keeps its new state: results are bit for bit those of the static types, and the
/// all-or-nothing rule holds (on any error nothing changes, or for a burst, nothing after the last
/// accepted sample).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Configured<T> {
    q: Quat<T>,
    counters: Counters,
    input: InputState<T>,
    accumulator: AccumulatorState<T>,
    scheme: SchemeKind,
    gain: Option<T>,
    stabilizer: StabilizerKind,
}

/// A loop of a binding's own over the static propagator a [`Configured`] stands for
/// ([`Configured::visit`]): `rates` is called for the rate input models, `deltas` for [`DeltaAngles`].
/// The stabilizer is the run-time [`StabilizerKind`]; scheme, input model and accumulator are the types.
///
/// A loop over many samples can run faster on a copy of the propagator, written back after
/// (`let mut local = *p; … *p = local;`): behind the reference the state goes through memory at every
/// step (the Python binding's loop over whole arrays ran 1.5x as long per sample on an x86-64 host
/// without it). The copy costs about one step on a Cortex-M4F, so a burst of a few samples does better
/// without it (the C API's loops and the core's bursts have none).
pub trait Visit<T: Real> {
    /// What the loop returns.
    type Output;
    /// The loop, for an input model that takes [`GyroSample`]s.
    fn rates<S: Scheme<T>, I: RateModel<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output;
    /// The loop, for an input model that takes [`DeltaAngle`]s.
    fn deltas<S: Scheme<T>, I: DeltaModel<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output;
}

/// The static propagator a [`Configured`] stands for, as a [`Visit`] sees it: the scheme `S`, input model
/// `I` and accumulator `A` as types, the stabilizer the run-time [`StabilizerKind`].
pub type Visited<T, S, I, A> = Propagator<T, S, I, StabilizerKind, A>;

/// An input model that takes [`GyroSample`]s (every model but [`DeltaAngles`]): the models
/// [`Visit::rates`] is called with.
pub trait RateModel<T: Real>: InputModel<T, Sample = GyroSample<T>> {}
impl<T: Real, I: InputModel<T, Sample = GyroSample<T>>> RateModel<T> for I {}

/// An input model that takes [`DeltaAngle`]s ([`DeltaAngles`]): the models [`Visit::deltas`] is called
/// with.
pub trait DeltaModel<T: Real>: InputModel<T, Sample = DeltaAngle<T>> {}
impl<T: Real, I: InputModel<T, Sample = DeltaAngle<T>>> DeltaModel<T> for I {}

/// Which of [`Visit`]'s loops an input model takes (by its sample type).
trait Route<T: Real, I: InputModel<T>> {
    fn call<V: Visit<T>, S: Scheme<T>, A: Accumulator<T>>(
        v: V,
        p: &mut Visited<T, S, I, A>,
    ) -> V::Output;
}

struct Rates;
struct Deltas;

impl<T: Real, I: RateModel<T>> Route<T, I> for Rates {
    #[inline(always)]
    fn call<V: Visit<T>, S: Scheme<T>, A: Accumulator<T>>(
        v: V,
        p: &mut Visited<T, S, I, A>,
    ) -> V::Output {
        v.rates(p)
    }
}

impl<T: Real, I: DeltaModel<T>> Route<T, I> for Deltas {
    #[inline(always)]
    fn call<V: Visit<T>, S: Scheme<T>, A: Accumulator<T>>(
        v: V,
        p: &mut Visited<T, S, I, A>,
    ) -> V::Output {
        v.deltas(p)
    }
}

/// A sample a [`Configured`] propagator takes: [`GyroSample`] or [`DeltaAngle`] (sealed). A sample of
/// the kind the input model does not take is refused with [`Error::WrongSampleKind`].
pub trait ConfiguredSample<T>: crate::Sample + sealed::Sealed {
    /// The samples as rates, if they are.
    #[doc(hidden)]
    fn as_rates(samples: &[Self]) -> Option<&[GyroSample<T>]>;
    /// The samples as angle increments, if they are.
    #[doc(hidden)]
    fn as_deltas(samples: &[Self]) -> Option<&[DeltaAngle<T>]>;
    /// Timestamped samples as rates, if they are.
    #[doc(hidden)]
    fn as_timed_rates(samples: &[(Self, u32)]) -> Option<&[(GyroSample<T>, u32)]>;
    /// Timestamped samples as angle increments, if they are.
    #[doc(hidden)]
    fn as_timed_deltas(samples: &[(Self, u32)]) -> Option<&[(DeltaAngle<T>, u32)]>;
}

mod sealed {
    pub trait Sealed {}
    impl<T> Sealed for crate::GyroSample<T> {}
    impl<T> Sealed for crate::DeltaAngle<T> {}
}

impl<T: Copy> ConfiguredSample<T> for GyroSample<T> {
    #[inline(always)]
    fn as_rates(samples: &[Self]) -> Option<&[GyroSample<T>]> {
        Some(samples)
    }
    #[inline(always)]
    fn as_deltas(_: &[Self]) -> Option<&[DeltaAngle<T>]> {
        None
    }
    #[inline(always)]
    fn as_timed_rates(samples: &[(Self, u32)]) -> Option<&[(GyroSample<T>, u32)]> {
        Some(samples)
    }
    #[inline(always)]
    fn as_timed_deltas(_: &[(Self, u32)]) -> Option<&[(DeltaAngle<T>, u32)]> {
        None
    }
}

impl<T: Copy> ConfiguredSample<T> for DeltaAngle<T> {
    #[inline(always)]
    fn as_rates(_: &[Self]) -> Option<&[GyroSample<T>]> {
        None
    }
    #[inline(always)]
    fn as_deltas(samples: &[Self]) -> Option<&[DeltaAngle<T>]> {
        Some(samples)
    }
    #[inline(always)]
    fn as_timed_rates(_: &[(Self, u32)]) -> Option<&[(GyroSample<T>, u32)]> {
        None
    }
    #[inline(always)]
    fn as_timed_deltas(samples: &[(Self, u32)]) -> Option<&[(DeltaAngle<T>, u32)]> {
        Some(samples)
    }
}

/// The sample kind a propagator's input model takes ([`GyroSample`] or [`DeltaAngle`]): a
/// [`ConfiguredSample`]'s samples as this kind, if they are.
trait Kind<T>: Sized {
    fn of<X: ConfiguredSample<T>>(samples: &[X]) -> Option<&[Self]>;
    fn of_timed<X: ConfiguredSample<T>>(samples: &[(X, u32)]) -> Option<&[(Self, u32)]>;
}

impl<T: Copy> Kind<T> for GyroSample<T> {
    #[inline(always)]
    fn of<X: ConfiguredSample<T>>(samples: &[X]) -> Option<&[Self]> {
        X::as_rates(samples)
    }
    #[inline(always)]
    fn of_timed<X: ConfiguredSample<T>>(samples: &[(X, u32)]) -> Option<&[(Self, u32)]> {
        X::as_timed_rates(samples)
    }
}

impl<T: Copy> Kind<T> for DeltaAngle<T> {
    #[inline(always)]
    fn of<X: ConfiguredSample<T>>(samples: &[X]) -> Option<&[Self]> {
        X::as_deltas(samples)
    }
    #[inline(always)]
    fn of_timed<X: ConfiguredSample<T>>(samples: &[(X, u32)]) -> Option<&[(Self, u32)]> {
        X::as_timed_deltas(samples)
    }
}

/// An input model that takes one of the two sample kinds.
trait Model<T: Real>: InputModel<T, Sample: Kind<T>> {}
impl<T: Real, I: InputModel<T, Sample: Kind<T>>> Model<T> for I {}

/// A burst's samples as the input model's kind, pushed by `push`; a non-empty burst of the other kind is
/// refused at index 0.
#[inline(always)]
fn of_kind<Y>(
    samples: Option<Y>,
    empty: bool,
    push: impl FnOnce(Y) -> Result<usize, Refused>,
) -> Result<usize, Refused> {
    match samples {
        Some(s) => push(s),
        None if empty => Ok(0),
        None => Err(Refused {
            index: 0,
            error: Error::WrongSampleKind,
        }),
    }
}

/// What [`Configured`]'s own calls do on the static propagator, written once for both sample kinds
/// (a [`Visit`] through [`Either`]). Each call is a struct and an impl of this trait (a closure cannot be
/// generic over the propagator's types), so the impls below repeat its signature's shape.
trait Op<T: Real> {
    type Output;
    fn run<S: Scheme<T>, I: Model<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output;
}

/// An [`Op`] as a [`Visit`]: the same for the rate input models and for [`DeltaAngles`].
struct Either<O>(O);

impl<T: Real, O: Op<T>> Visit<T> for Either<O> {
    type Output = O::Output;
    #[inline(always)]
    fn rates<S: Scheme<T>, I: RateModel<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        self.0.run(p)
    }
    #[inline(always)]
    fn deltas<S: Scheme<T>, I: DeltaModel<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        self.0.run(p)
    }
}

/// One sample with its `dt` ([`Configured::push`]).
struct Push<'a, X, T> {
    sample: &'a X,
    dt: T,
}

impl<T: Real, X: ConfiguredSample<T>> Op<T> for Push<'_, X, T> {
    type Output = Result<(), Error>;
    #[inline(always)]
    fn run<S: Scheme<T>, I: Model<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        match I::Sample::of(core::slice::from_ref(self.sample)) {
            Some([s]) => p.push(*s, self.dt),
            _ => Err(Error::WrongSampleKind),
        }
    }
}

/// The first sample of a stream ([`Configured::start`]).
struct Start<'a, X>(&'a X);

impl<T: Real, X: ConfiguredSample<T>> Op<T> for Start<'_, X> {
    type Output = Result<(), Error>;
    #[inline(always)]
    fn run<S: Scheme<T>, I: Model<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        match I::Sample::of(core::slice::from_ref(self.0)) {
            Some([s]) => p.start(*s),
            _ => Err(Error::WrongSampleKind),
        }
    }
}

/// A burst at a fixed period ([`Configured::push_burst`]).
struct Burst<'a, X, T> {
    samples: &'a [X],
    period: &'a mut FixedPeriod<T>,
}

impl<T: Real, X: ConfiguredSample<T>> Op<T> for Burst<'_, X, T> {
    type Output = Result<usize, Refused>;
    #[inline(always)]
    fn run<S: Scheme<T>, I: Model<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        of_kind(I::Sample::of(self.samples), self.samples.is_empty(), |s| {
            p.push_burst(s, self.period)
        })
    }
}

/// A burst with the sensor's timestamps ([`Configured::push_burst_timed`]).
struct TimedBurst<'a, X, T> {
    samples: &'a [(X, u32)],
    clock: &'a mut TickClock<T>,
}

impl<T: Real, X: ConfiguredSample<T>> Op<T> for TimedBurst<'_, X, T> {
    type Output = Result<usize, Refused>;
    #[inline(always)]
    fn run<S: Scheme<T>, I: Model<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        of_kind(
            I::Sample::of_timed(self.samples),
            self.samples.is_empty(),
            |s| p.push_burst_timed(s, self.clock),
        )
    }
}

// The methods below mirror `Propagator`'s one for one (the run-time API is the static one, documented
// there): each forwards to the static propagator through `visit`, or to code written once in
// propagator.rs (`corrected`, `checked_unit`); the repeated lines are the mirror's signatures and docs.
impl<T: Real> Configured<T> {
    /// Runs `visitor` on the static propagator this one stands for, then keeps its new state. One `match`
    /// on the configuration per call.
    pub fn visit<V: Visit<T>>(&mut self, visitor: V) -> V::Output {
        let gain = self.gain;
        macro_rules! runge_kutta {
            ($s:expr) => {
                match gain {
                    Some(k) => self.with_scheme(Baumgarte::validated($s, k), visitor),
                    None => self.with_scheme($s, visitor),
                }
            };
        }
        match self.scheme {
            SchemeKind::Euler => runge_kutta!(Euler),
            SchemeKind::Rk2 => runge_kutta!(Rk2),
            SchemeKind::Rk3 => runge_kutta!(Rk3),
            SchemeKind::Rk4 => runge_kutta!(Rk4),
            SchemeKind::Rk5 => runge_kutta!(Rk5),
            // A gain with an exponential map is refused by `Config::validate`.
            SchemeKind::ExpMap => self.with_scheme(ExpMap, visitor),
            SchemeKind::Magnus4 => self.with_scheme(Magnus4, visitor),
            SchemeKind::Cf4 => self.with_scheme(Cf4, visitor),
        }
    }

    /// [`Configured::visit`] with the scheme, like the stabilizer, matched inside every step
    /// ([`SchemeKind`]; Baumgarte's term on a Runge–Kutta scheme likewise): one loop per input model ×
    /// accumulator (twice: with and without the term) instead of one per scheme × input model ×
    /// accumulator, for a fraction of the flash and more instructions per step. docs/c-api.md measures
    /// both; the C API uses this one unless built with its `monomorphized` feature.
    pub fn visit_compact<V: Visit<T>>(&mut self, visitor: V) -> V::Output {
        match self.gain {
            None => self.with_scheme(self.scheme, visitor),
            Some(k) => self.with_scheme(
                BaumgarteKind {
                    kind: self.scheme,
                    k,
                },
                visitor,
            ),
        }
    }

    #[inline(always)]
    fn with_scheme<S: Scheme<T>, V: Visit<T>>(&mut self, s: S, v: V) -> V::Output {
        match self.input {
            InputState::Hold(i) => self.with_input::<S, _, Rates, V, _>(s, i, v, InputState::Hold),
            InputState::Linear(i) => {
                self.with_input::<S, _, Rates, V, _>(s, i, v, InputState::Linear)
            }
            InputState::History(i) => {
                self.with_input::<S, _, Rates, V, _>(s, i, v, InputState::History)
            }
            InputState::TwiceRate(i) => {
                self.with_input::<S, _, Rates, V, _>(s, i, v, InputState::TwiceRate)
            }
            InputState::GaussPoints(i) => {
                self.with_input::<S, _, Rates, V, _>(s, i, v, InputState::GaussPoints)
            }
            InputState::DeltaAngles(i) => {
                self.with_input::<S, _, Deltas, V, _>(s, i, v, InputState::DeltaAngles)
            }
        }
    }

    #[inline(always)]
    fn with_input<S, I, R, V, P>(&mut self, s: S, i: I, v: V, put: P) -> V::Output
    where
        S: Scheme<T>,
        I: InputModel<T>,
        R: Route<T, I>,
        V: Visit<T>,
        P: FnOnce(I) -> InputState<T>,
    {
        match self.accumulator {
            AccumulatorState::Plain(a) => {
                self.run::<S, I, _, R, V, _, _>(s, i, a, v, put, AccumulatorState::Plain)
            }
            AccumulatorState::Kahan(a) => {
                self.run::<S, I, _, R, V, _, _>(s, i, a, v, put, AccumulatorState::Kahan)
            }
            AccumulatorState::FloatFloat(a) => {
                self.run::<S, I, _, R, V, _, _>(s, i, a, v, put, AccumulatorState::FloatFloat)
            }
        }
    }

    /// The static propagator around the state, the visitor's loop, the state back. Not inlined: one
    /// function per configuration and visitor, which the `match` above calls.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn run<S, I, A, R, V, PI, PA>(
        &mut self,
        s: S,
        i: I,
        a: A,
        v: V,
        put_input: PI,
        put_accumulator: PA,
    ) -> V::Output
    where
        S: Scheme<T>,
        I: InputModel<T>,
        A: Accumulator<T>,
        R: Route<T, I>,
        V: Visit<T>,
        PI: FnOnce(I) -> InputState<T>,
        PA: FnOnce(A) -> AccumulatorState<T>,
    {
        let mut p = Propagator::from_parts(self.q, s, i, self.stabilizer, a, self.counters);
        let out = R::call(v, &mut p);
        let (q, input, accumulator, counters) = p.into_parts();
        self.q = q;
        self.input = put_input(input);
        self.accumulator = put_accumulator(accumulator);
        self.counters = counters;
        out
    }

    /// [`Propagator::push`]: one sample ([`GyroSample`], or [`DeltaAngle`] for the delta-angle input)
    /// `dt` seconds after the previous one.
    ///
    /// # Errors
    /// Those of [`Propagator::push`]; [`Error::WrongSampleKind`] for a sample of the other kind. The
    /// propagator is then unchanged.
    #[inline]
    pub fn push<X: ConfiguredSample<T>>(&mut self, sample: X, dt: T) -> Result<(), Error> {
        self.visit(Either(Push {
            sample: &sample,
            dt,
        }))
    }

    /// [`Propagator::start`]: the first sample of a stream, which sets its time origin.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`]; [`Error::WrongSampleKind`]. The propagator is then unchanged.
    pub fn start<X: ConfiguredSample<T>>(&mut self, sample: X) -> Result<(), Error> {
        self.visit(Either(Start(&sample)))
    }

    /// [`Propagator::push_burst`]: a FIFO burst at a fixed period, bit for bit the same as one sample
    /// at a time; one `match` per burst.
    ///
    /// # Errors
    /// As [`Propagator::push_burst`]; a non-empty burst of the other sample kind is refused at index 0
    /// with [`Error::WrongSampleKind`] (and `period` is left as it was).
    pub fn push_burst<X: ConfiguredSample<T>>(
        &mut self,
        samples: &[X],
        period: &mut FixedPeriod<T>,
    ) -> Result<usize, Refused> {
        self.visit(Either(Burst { samples, period }))
    }

    /// [`Propagator::push_burst_timed`]: a FIFO burst with the sensor's timestamps.
    ///
    /// # Errors
    /// As [`Propagator::push_burst_timed`]; a non-empty burst of the other sample kind is refused at
    /// index 0 with [`Error::WrongSampleKind`] (and `clock` is left as it was).
    pub fn push_burst_timed<X: ConfiguredSample<T>>(
        &mut self,
        samples: &[(X, u32)],
        clock: &mut TickClock<T>,
    ) -> Result<usize, Refused> {
        self.visit(Either(TimedBurst { samples, clock }))
    }

    /// [`Propagator::restart_input`]: forgets the samples the input model keeps (after a gap).
    pub fn restart_input(&mut self) {
        match &mut self.input {
            InputState::Hold(i) => InputModel::<T>::restart(i),
            InputState::Linear(i) => i.restart(),
            InputState::History(i) => i.restart(),
            InputState::TwiceRate(i) => i.restart(),
            InputState::GaussPoints(i) => i.restart(),
            InputState::DeltaAngles(i) => i.restart(),
        }
    }

    /// [`Propagator::set_attitude`]: replaces the attitude (normalized); on error nothing changes.
    ///
    /// # Errors
    /// [`Error::NonFiniteQuaternion`] or [`Error::ZeroQuaternion`].
    pub fn set_attitude(&mut self, q: Quat<T>) -> Result<(), Error> {
        self.q = checked_unit(q)?;
        self.accumulator.reset();
        self.counters.attitude_replaced();
        Ok(())
    }

    /// A correction through the accumulator, as [`Propagator::rotate_body`] makes it.
    fn correct(&mut self, dtheta: Vec3<T>, frame: Frame) -> Result<(), Error> {
        (self.q, self.accumulator) = corrected(
            self.q,
            self.accumulator,
            dtheta,
            frame,
            AccumulatorState::add,
        )?;
        Ok(())
    }

    /// [`Propagator::rotate_body`]: `q ← q ⊗ exp_q(dtheta)`, a correction in the body frame (rad).
    ///
    /// # Errors
    /// As [`Propagator::rotate_body`]; the propagator is then unchanged.
    pub fn rotate_body(&mut self, dtheta: Vec3<T>) -> Result<(), Error> {
        self.correct(dtheta, Frame::Body)
    }

    /// [`Propagator::rotate_reference`]: `q ← exp_q(dtheta) ⊗ q`, in the reference frame (rad).
    ///
    /// # Errors
    /// As [`Propagator::rotate_body`]; the propagator is then unchanged.
    pub fn rotate_reference(&mut self, dtheta: Vec3<T>) -> Result<(), Error> {
        self.correct(dtheta, Frame::Reference)
    }

    /// [`Propagator::correct_bias`]: the samples the input model keeps lowered by `delta` (rad/s), the
    /// bias correction an estimator also subtracts from the samples from now on.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`]; the propagator is then unchanged.
    pub fn correct_bias(&mut self, delta: Vec3<T>) -> Result<(), Error> {
        if !delta.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        self.input = match &self.input {
            InputState::Hold(i) => InputState::Hold(InputModel::<T>::correct_bias(i, delta)?),
            InputState::Linear(i) => InputState::Linear(i.correct_bias(delta)?),
            InputState::History(i) => InputState::History(i.correct_bias(delta)?),
            InputState::TwiceRate(i) => InputState::TwiceRate(i.correct_bias(delta)?),
            InputState::GaussPoints(i) => InputState::GaussPoints(i.correct_bias(delta)?),
            InputState::DeltaAngles(i) => InputState::DeltaAngles(i.correct_bias(delta)?),
        };
        Ok(())
    }

    /// The configuration this propagator was built from.
    #[must_use]
    pub fn config(&self) -> Config {
        Config {
            scheme: self.scheme,
            baumgarte_gain: self.gain.map(Real::to_f64),
            input: match self.input {
                InputState::Hold(_) => InputKind::Hold,
                InputState::Linear(_) => InputKind::Linear,
                InputState::History(_) => InputKind::History,
                InputState::TwiceRate(_) => InputKind::TwiceRate,
                InputState::GaussPoints(_) => InputKind::GaussPoints,
                InputState::DeltaAngles(d) => InputKind::DeltaAngles(d.correction()),
            },
            stabilizer: self.stabilizer,
            accumulator: match self.accumulator {
                AccumulatorState::Plain(_) => AccumulatorKind::Plain,
                AccumulatorState::Kahan(_) => AccumulatorKind::Kahan,
                AccumulatorState::FloatFloat(_) => AccumulatorKind::FloatFloat,
            },
        }
    }

    /// The attitude `q` (body to reference; Hamilton, scalar first).
    #[inline]
    #[must_use]
    pub fn attitude(&self) -> Quat<T> {
        self.q
    }

    /// The attitude's low part with [`AccumulatorKind::FloatFloat`] (the attitude is then
    /// `attitude() + attitude_low()`); zero otherwise.
    #[must_use]
    pub fn attitude_low(&self) -> Quat<T> {
        match self.accumulator {
            AccumulatorState::FloatFloat(a) => a.low(),
            _ => Quat::ZERO,
        }
    }

    /// The seed's normalization error `N = |q|² − 1`.
    #[inline]
    #[must_use]
    pub fn norm_error(&self) -> T {
        self.q.norm_error()
    }

    /// Steps taken.
    #[inline]
    #[must_use]
    pub fn steps(&self) -> u64 {
        self.counters.steps()
    }

    /// Post-step corrections applied by the stabilizer.
    #[inline]
    #[must_use]
    pub fn corrections(&self) -> u64 {
        self.counters.corrections()
    }

    /// Saturated samples accepted so far.
    #[inline]
    #[must_use]
    pub fn saturated_samples(&self) -> u64 {
        self.counters.saturated()
    }
}
