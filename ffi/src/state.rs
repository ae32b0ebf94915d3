//! The Rust side of the C state: safe code only. `lib.rs` turns C pointers into references and calls these.
//!
//! The propagator is the core's run-time configuration ([`Configured`], built from a [`Config`]): each call
//! matches the configuration once and runs a loop compiled for it. The C layer adds its front end (count
//! scale, alignment, bias) per sample inside that loop, through [`Visit`]: one rate loop ([`RateLoop`]) and
//! one delta-angle loop ([`DeltaLoop`]) serve every call, single samples and bursts alike.
//!
//! By default the loops are compiled per input model × accumulator, with the scheme and the stabilizer
//! matched per step ([`Configured::visit_compact`]: small flash); with the feature `monomorphized`, per
//! scheme × input model × accumulator ([`Configured::visit`]: fewer instructions, far more flash).
//! docs/c-api.md measures both.

use crate::{quatprop_config_t, quatprop_sample_t};
use quatprop::accumulate::Accumulator;
use quatprop::config::{
    AccumulatorKind, Config, Configured, DeltaModel, InputKind, RateModel, Visit, Visited,
};
use quatprop::frontend::{
    Alignment, Aux, AxisRemap, BiasEstimator, Calibration, CountScale, FixedBias, FixedPeriod,
    TickClock,
};
use quatprop::input::coning::ConingKind;
use quatprop::input::InputModel;
use quatprop::scheme::{Scheme, SchemeKind};
use quatprop::stabilize::StabilizerKind;
use quatprop::{DeltaAngle, Error, GyroSample, Propagator, Quat, Vec3};

/// Why a call failed: a core error, or one of the C boundary's own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fail {
    Core(Error),
    /// An enum value out of range.
    BadEnum,
    /// A numeric argument out of range (a front-end parameter the core does not validate itself).
    BadArgument,
    /// A rate call on the delta-angle model, or a delta-angle call on a rate model.
    WrongInputKind,
    /// The call needs a front-end part that was not set (count scale, fixed period or tick clock).
    NotConfigured,
}

impl From<Error> for Fail {
    fn from(e: Error) -> Self {
        Fail::Core(e)
    }
}

/// A refused burst sample: its index (= samples integrated before it) and why.
pub type Refusal = (usize, Fail);

/// The bias stage of the front end.
// The estimator is most of the variant's size; boxing it is not an option here (no heap), and the state is
// one block of fixed size whichever variant it holds.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, serde::Serialize, serde::Deserialize)]
pub enum Bias {
    None,
    Fixed(FixedBias<f32>),
    Estimator(BiasEstimator<f32>),
}

impl Bias {
    /// The sample with the bias subtracted, nothing learned yet.
    #[inline(always)]
    fn correct(&self, s: GyroSample<f32>) -> Result<GyroSample<f32>, Error> {
        match self {
            Bias::None => Ok(s),
            Bias::Fixed(b) => Ok(b.apply(s)),
            Bias::Estimator(e) => e.correct(s, Aux::NONE),
        }
    }

    /// Learns from a corrected sample the propagator accepted (so a refused one changes nothing and the
    /// stage needs no copy per sample).
    #[inline(always)]
    fn learn(&mut self, corrected: GyroSample<f32>) {
        if let Bias::Estimator(e) = self {
            e.learn(corrected, Aux::NONE);
        }
    }
}

/// The sensor front end: counts → rad/s, the gyro's calibration, sensor → body axes, bias removed; the
/// time bases of the bursts.
#[derive(Clone, Copy, serde::Serialize, serde::Deserialize)]
pub struct FrontEnd {
    pub scale: Option<CountScale<f32>>,
    pub calibration: Option<Calibration<f32>>,
    pub alignment: Option<Alignment<f32>>,
    pub bias: Bias,
    pub period: Option<FixedPeriod<f32>>,
    pub clock: Option<TickClock<f32>>,
}

impl FrontEnd {
    const NONE: Self = Self {
        scale: None,
        calibration: None,
        alignment: None,
        bias: Bias::None,
        period: None,
        clock: None,
    };

    /// Rate sample `i` of `rates` through the calibration, the alignment and the bias (subtracted; the
    /// estimator learns from it only once the propagator has accepted it). Not generic: one copy for every
    /// configuration.
    // Out of line when every scheme has its loops (flash); inlined into the compact build's few loops.
    #[cfg_attr(feature = "monomorphized", inline(never))]
    #[cfg_attr(not(feature = "monomorphized"), inline(always))]
    fn sample(&self, rates: &Rates<'_>, i: usize) -> Result<GyroSample<f32>, Error> {
        self.bias.correct(self.calibrate_and_align(rates.get(i)))
    }

    #[inline(always)]
    fn align(&self, s: GyroSample<f32>) -> GyroSample<f32> {
        match &self.alignment {
            Some(a) => a.apply(s),
            None => s,
        }
    }

    /// The calibration (sensor axes), then the alignment: a rate sample's way to body axes.
    #[inline(always)]
    fn calibrate_and_align(&self, s: GyroSample<f32>) -> GyroSample<f32> {
        match &self.calibration {
            Some(c) => self.align(c.apply(s)),
            None => self.align(s),
        }
    }
}

/// Everything a `quatprop_t` holds (encoded: see `lib.rs`).
#[derive(Clone, Copy, serde::Serialize, serde::Deserialize)]
pub struct Inner {
    pub prop: Configured<f32>,
    pub front: FrontEnd,
}

/// `ALL[v]`, or `BadEnum`.
fn nth<K: Copy>(all: &[K], v: u32) -> Result<K, Fail> {
    all.get(v as usize).copied().ok_or(Fail::BadEnum)
}

/// The core's configuration of what C chose, the C values in the order of the header's constants.
fn config(c: &quatprop_config_t) -> Result<Config, Fail> {
    Ok(Config {
        scheme: nth(&SchemeKind::ALL, c.scheme)?,
        baumgarte_gain: None,
        input: match c.input {
            0 => InputKind::Hold,
            1 => InputKind::Linear,
            2 => InputKind::History,
            3 => InputKind::TwiceRate,
            4 => InputKind::GaussPoints,
            5 => InputKind::DeltaAngles(nth(&ConingKind::ALL, c.coning)?),
            _ => return Err(Fail::BadEnum),
        },
        stabilizer: match c.stabilizer {
            0 => StabilizerKind::Off,
            1 => StabilizerKind::Normalize,
            2 => StabilizerKind::FirstOrder,
            3 => StabilizerKind::Every(c.every),
            _ => return Err(Fail::BadEnum),
        },
        accumulator: nth(
            &[
                AccumulatorKind::Plain,
                AccumulatorKind::Kahan,
                AccumulatorKind::FloatFloat,
            ],
            c.accumulator,
        )?,
    })
}

/// The axis remap with C value `v` (the order of [`AxisRemap::ALL`]).
pub fn remap_of(v: u32) -> Result<AxisRemap, Fail> {
    nth(&AxisRemap::ALL, v)
}

/// Where a rate loop's samples come from.
#[derive(Clone, Copy)]
pub enum Rates<'a> {
    /// One sample (rad/s, sensor axes).
    One(GyroSample<f32>),
    /// Raw counts, scaled by the front end's count scale.
    Counts(&'a [[i16; 3]], CountScale<f32>),
    /// C samples (rad/s, sensor axes).
    Samples(&'a [quatprop_sample_t]),
}

impl Rates<'_> {
    fn len(&self) -> usize {
        match self {
            Rates::One(_) => 1,
            Rates::Counts(c, _) => c.len(),
            Rates::Samples(s) => s.len(),
        }
    }
    #[inline(always)]
    fn get(&self, i: usize) -> GyroSample<f32> {
        match self {
            Rates::One(s) => *s,
            Rates::Counts(c, scale) => scale.sample(c.get(i).copied().unwrap_or_default()),
            Rates::Samples(s) => s
                .get(i)
                .map_or(GyroSample::default(), quatprop_sample_t::rate),
        }
    }
}

/// Where a loop's `dt`s come from.
#[derive(Clone, Copy)]
pub enum Time<'a> {
    /// One given `dt` (s): single samples.
    Dt(f32),
    /// The front end's fixed period.
    Period,
    /// The front end's tick clock, one timestamp per sample.
    Ticks(&'a [u32]),
}

/// A [`Time`] with the front end's period or clock taken out for the loop (and put back after it).
#[derive(Clone, Copy)]
enum Timing<'a> {
    Dt(f32),
    Period(FixedPeriod<f32>),
    Ticks(TickClock<f32>, &'a [u32]),
}

impl<'a> Timing<'a> {
    /// The timing `time` asks for, or `NotConfigured` before any sample.
    fn of(time: Time<'a>, front: &FrontEnd) -> Result<Self, Refusal> {
        let missing = (0, Fail::NotConfigured);
        Ok(match time {
            Time::Dt(dt) => Timing::Dt(dt),
            Time::Period => Timing::Period(front.period.ok_or(missing)?),
            Time::Ticks(t) => Timing::Ticks(front.clock.ok_or(missing)?, t),
        })
    }

    /// Puts the period or clock back into the front end.
    fn restore(self, front: &mut FrontEnd) {
        match self {
            Timing::Dt(_) => {}
            Timing::Period(p) => front.period = Some(p),
            Timing::Ticks(c, _) => front.clock = Some(c),
        }
    }

    /// Sample `i`'s interval: `Some(dt)`, or `None` for the first timestamp of a clock (it starts the
    /// stream). Not generic: one copy for every configuration.
    // Out of line when every scheme has its loops (flash); inlined into the compact build's few loops.
    #[cfg_attr(feature = "monomorphized", inline(never))]
    #[cfg_attr(not(feature = "monomorphized"), inline(always))]
    fn interval(&mut self, i: usize) -> Result<Option<f32>, Error> {
        match self {
            Timing::Dt(dt) => Ok(Some(*dt)),
            Timing::Period(period) => Ok(Some(period.next_dt())),
            Timing::Ticks(clock, t) => {
                let (next, dt) = clock.advance(t.get(i).copied().unwrap_or(0))?;
                // Committed by `accepted`, dropped by `refused`.
                *clock = next;
                Ok(dt)
            }
        }
    }

    /// Sample `i` was refused after `interval` gave `dt`: a period keeps the interval (the next sample's
    /// `dt` covers it), a clock goes back to `before`.
    #[cold]
    #[inline(never)]
    fn refused(&mut self, dt: Option<f32>, before: Self) {
        match self {
            Timing::Dt(_) => {}
            Timing::Period(period) => {
                if let Some(dt) = dt {
                    period.carry_over(dt);
                }
            }
            Timing::Ticks(..) => *self = before,
        }
    }

    /// Pushes sample `i`, made by `sample` (the front end), with its interval from the time base. The time
    /// base goes first, as in the core's bursts; on a refusal (of the time, the front end or the
    /// propagator) a period keeps the interval and a clock stays where it was. One push site per
    /// configuration.
    #[inline(always)]
    fn push<S, I, A>(
        &mut self,
        p: &mut Propagator<f32, S, I, StabilizerKind, A>,
        i: usize,
        sample: impl FnOnce() -> Result<I::Sample, Error>,
    ) -> Result<(), Error>
    where
        S: Scheme<f32>,
        I: InputModel<f32>,
        A: Accumulator<f32>,
    {
        let before = *self;
        let dt = self.interval(i)?;
        let pushed = sample().and_then(|s| match dt {
            Some(dt) => p.push(s, dt),
            None => p.start(s),
        });
        if pushed.is_err() {
            self.refused(dt, before);
        }
        pushed
    }
}

/// The rate loop: per sample, the calibration, the alignment and the bias, its `dt`, the push, then the
/// estimator learns from the accepted sample; on a refusal it
/// stops, the time base and the bias stage as after the last accepted sample (a period keeps the refused
/// interval, as the core's `push_burst` does).
pub struct RateLoop<'a> {
    rates: Rates<'a>,
    time: Timing<'a>,
    front: &'a mut FrontEnd,
}

// Each loop implements both of `Visit`'s methods, the trait's signatures as they stand (one per sample
// type, each with its bounds); the one a loop does not take refuses the input kind.
impl Visit<f32> for RateLoop<'_> {
    type Output = Result<usize, Refusal>;
    #[inline(always)]
    fn rates<S: Scheme<f32>, I: RateModel<f32>, A: Accumulator<f32>>(
        mut self,
        p: &mut Visited<f32, S, I, A>,
    ) -> Self::Output {
        let n = self.rates.len();
        let mut result = Ok(n);
        for i in 0..n {
            let front = &*self.front;
            let rates = &self.rates;
            let mut corrected = None;
            let pushed = self.time.push(p, i, || {
                let s = front.sample(rates, i)?;
                corrected = Some(s);
                Ok(s)
            });
            if let Err(e) = pushed {
                result = Err((i, Fail::Core(e)));
                break;
            }
            if let Some(s) = corrected {
                self.front.bias.learn(s);
            }
        }
        self.time.restore(self.front);
        result
    }
    fn deltas<S: Scheme<f32>, I: DeltaModel<f32>, A: Accumulator<f32>>(
        self,
        _: &mut Visited<f32, S, I, A>,
    ) -> Self::Output {
        Err((0, Fail::WrongInputKind))
    }
}

/// Where a delta-angle loop's samples come from.
#[derive(Clone, Copy)]
pub enum Deltas<'a> {
    /// One increment (rad, sensor axes).
    One(DeltaAngle<f32>),
    /// C samples (rad, sensor axes).
    Samples(&'a [quatprop_sample_t]),
}

/// The delta-angle loop: the alignment per sample (the bias does not apply: it is a rate), then its `dt`
/// and the push, as the rate loop.
pub struct DeltaLoop<'a> {
    deltas: Deltas<'a>,
    time: Timing<'a>,
    front: &'a mut FrontEnd,
}

impl Visit<f32> for DeltaLoop<'_> {
    type Output = Result<usize, Refusal>;
    fn rates<S: Scheme<f32>, I: RateModel<f32>, A: Accumulator<f32>>(
        self,
        _: &mut Visited<f32, S, I, A>,
    ) -> Self::Output {
        Err((0, Fail::WrongInputKind))
    }
    #[inline(always)]
    fn deltas<S: Scheme<f32>, I: DeltaModel<f32>, A: Accumulator<f32>>(
        mut self,
        p: &mut Visited<f32, S, I, A>,
    ) -> Self::Output {
        let n = match self.deltas {
            Deltas::One(_) => 1,
            Deltas::Samples(s) => s.len(),
        };
        let mut result = Ok(n);
        for i in 0..n {
            let d = match self.deltas {
                Deltas::One(d) => d,
                Deltas::Samples(s) => s
                    .get(i)
                    .map_or(DeltaAngle::default(), quatprop_sample_t::delta),
            };
            let front = &*self.front;
            if let Err(e) = self.time.push(p, i, || Ok(align_delta(front, d))) {
                result = Err((i, Fail::Core(e)));
                break;
            }
        }
        self.time.restore(self.front);
        result
    }
}

/// Runs `v` on the propagator, compiled as the crate's features choose (see the module's documentation).
#[inline(always)]
fn visit<V: Visit<f32>>(prop: &mut Configured<f32>, v: V) -> V::Output {
    #[cfg(feature = "monomorphized")]
    {
        prop.visit(v)
    }
    #[cfg(not(feature = "monomorphized"))]
    {
        prop.visit_compact(v)
    }
}

impl Inner {
    /// A propagator as chosen, with an empty front end (no scale, identity alignment, no bias, no time base).
    pub fn new(c: &quatprop_config_t) -> Result<Self, Fail> {
        Ok(Self {
            prop: config(c)?.build(c.q0.into())?,
            front: FrontEnd::NONE,
        })
    }

    pub fn attitude(&self) -> Quat<f32> {
        self.prop.attitude()
    }

    pub fn norm_error(&self) -> f32 {
        self.prop.norm_error()
    }

    /// Steps, corrections, saturated samples.
    pub fn counters(&self) -> (u64, u64, u64) {
        let p = &self.prop;
        (p.steps(), p.corrections(), p.saturated_samples())
    }

    pub fn set_attitude(&mut self, q: Quat<f32>) -> Result<(), Fail> {
        Ok(self.prop.set_attitude(q)?)
    }

    pub fn restart_input(&mut self) {
        self.prop.restart_input();
    }

    /// An estimator's correction, `q ← q ⊗ exp(dtheta)` (body frame) or `exp(dtheta) ⊗ q` (reference).
    pub fn rotate(&mut self, dtheta: Vec3<f32>, body: bool) -> Result<(), Fail> {
        if body {
            Ok(self.prop.rotate_body(dtheta)?)
        } else {
            Ok(self.prop.rotate_reference(dtheta)?)
        }
    }

    /// The bias moved by `delta`: the front end's bias stage (a fixed bias of `delta` where there was
    /// none) and the samples the input model keeps, both or neither.
    pub fn correct_bias(&mut self, delta: Vec3<f32>) -> Result<(), Fail> {
        let bias = match self.front.bias {
            Bias::None => Bias::Fixed(FixedBias::new(delta)?),
            Bias::Fixed(mut b) => {
                b.correct_bias(delta)?;
                Bias::Fixed(b)
            }
            Bias::Estimator(mut e) => {
                e.correct_bias(delta)?;
                Bias::Estimator(e)
            }
        };
        let mut prop = self.prop;
        prop.correct_bias(delta)?;
        self.front.bias = bias;
        self.prop = prop;
        Ok(())
    }

    /// Rate samples through the front end, timed by `time`: stops at the first refusal (its index and why).
    /// A burst that needs a time base the front end lacks is refused before any sample.
    pub fn rates(&mut self, rates: Rates<'_>, time: Time<'_>) -> Result<usize, Refusal> {
        let time = Timing::of(time, &self.front)?;
        visit(
            &mut self.prop,
            RateLoop {
                rates,
                time,
                front: &mut self.front,
            },
        )
    }

    /// Raw counts through the count scale, then as [`Inner::rates`]; `NotConfigured` before any sample
    /// without a count scale. Inlined into the bursts: as the code they had before it (the same instructions).
    #[inline(always)]
    pub fn counts(&mut self, fifo: &[[i16; 3]], time: Time<'_>) -> Result<usize, Refusal> {
        let scale = self.front.scale.ok_or((0, Fail::NotConfigured))?;
        self.rates(Rates::Counts(fifo, scale), time)
    }

    /// Delta angles through the alignment, timed by `time` (a given `dt` or the fixed period).
    pub fn deltas(&mut self, deltas: Deltas<'_>, time: Time<'_>) -> Result<usize, Refusal> {
        let time = Timing::of(time, &self.front)?;
        visit(
            &mut self.prop,
            DeltaLoop {
                deltas,
                time,
                front: &mut self.front,
            },
        )
    }
}

fn align_delta(front: &FrontEnd, d: DeltaAngle<f32>) -> DeltaAngle<f32> {
    // The alignment is linear: it turns an angle increment as it turns a rate.
    let g = front.align(GyroSample {
        rate: d.angle,
        saturated: d.saturated,
    });
    DeltaAngle {
        angle: g.rate,
        saturated: g.saturated,
    }
}

impl quatprop_sample_t {
    /// The sample as a rate (rad/s).
    pub fn rate(&self) -> GyroSample<f32> {
        GyroSample {
            rate: vec3([self.x, self.y, self.z]),
            saturated: self.saturated != 0,
        }
    }

    /// The sample as a delta angle (rad).
    pub fn delta(&self) -> DeltaAngle<f32> {
        DeltaAngle {
            angle: vec3([self.x, self.y, self.z]),
            saturated: self.saturated != 0,
        }
    }
}

/// A `Vec3` from C's three floats.
pub fn vec3(v: [f32; 3]) -> Vec3<f32> {
    Vec3::new(v[0], v[1], v[2])
}
