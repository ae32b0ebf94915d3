//! The Rust side of the C state: safe code only. `lib.rs` turns C pointers into references and calls these.
//!
//! The input model and the accumulator are type parameters of [`Propagator`]; C picks them at run time, so
//! [`Prop`] holds one propagator per input model × accumulator, each with the core's run-time
//! [`SchemeKind`], [`StabilizerKind`] (and [`ConingKind`] for delta angles). A burst matches on the variant
//! once and then runs a loop monomorphized for it; the scheme and stabilizer are matched per step, as in the
//! core's own run-time dispatch.

use quatprop::accumulate::{Kahan, Plain};
use quatprop::frontend::{
    Alignment, AxisRemap, BiasEstimator, CountScale, FixedBias, FixedPeriod, TickClock,
};
use quatprop::input::coning::ConingKind;
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::scheme::SchemeKind;
use quatprop::stabilize::StabilizerKind;
use quatprop::{DeltaAngle, Error, GyroSample, Propagator, Quat, Vec3};

/// One propagator configuration with the run-time scheme and stabilizer.
pub type P<I, A> = Propagator<f32, SchemeKind, I, StabilizerKind, A>;

/// The rate input models (one `GyroSample` per push).
#[derive(Clone, Copy)]
pub enum Prop {
    HoldPlain(P<Hold, Plain>),
    HoldKahan(P<Hold, Kahan<f32>>),
    LinearPlain(P<Linear<f32>, Plain>),
    LinearKahan(P<Linear<f32>, Kahan<f32>>),
    HistoryPlain(P<History<f32>, Plain>),
    HistoryKahan(P<History<f32>, Kahan<f32>>),
    TwiceRatePlain(P<TwiceRate<f32>, Plain>),
    TwiceRateKahan(P<TwiceRate<f32>, Kahan<f32>>),
    GaussPointsPlain(P<GaussPoints<f32>, Plain>),
    GaussPointsKahan(P<GaussPoints<f32>, Kahan<f32>>),
    DeltaPlain(P<DeltaAngles<f32, ConingKind>, Plain>),
    DeltaKahan(P<DeltaAngles<f32, ConingKind>, Kahan<f32>>),
}

/// `dispatch!(prop, rate p => e1, delta d => e2)`: `e1` for the rate models, `e2` for delta angles.
macro_rules! dispatch {
    ($prop:expr, rate $p:ident => $r:expr, delta $d:ident => $e:expr) => {
        match $prop {
            Prop::HoldPlain($p) => $r,
            Prop::HoldKahan($p) => $r,
            Prop::LinearPlain($p) => $r,
            Prop::LinearKahan($p) => $r,
            Prop::HistoryPlain($p) => $r,
            Prop::HistoryKahan($p) => $r,
            Prop::TwiceRatePlain($p) => $r,
            Prop::TwiceRateKahan($p) => $r,
            Prop::GaussPointsPlain($p) => $r,
            Prop::GaussPointsKahan($p) => $r,
            Prop::DeltaPlain($d) => $e,
            Prop::DeltaKahan($d) => $e,
        }
    };
    ($prop:expr, any $p:ident => $r:expr) => {
        dispatch!($prop, rate $p => $r, delta $p => $r)
    };
}

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
#[derive(Clone, Copy)]
pub enum Bias {
    None,
    Fixed(FixedBias<f32>),
    Estimator(BiasEstimator<f32>),
}

impl Bias {
    #[inline(always)]
    fn apply(&mut self, s: GyroSample<f32>) -> Result<GyroSample<f32>, Error> {
        match self {
            Bias::None => Ok(s),
            Bias::Fixed(b) => Ok(b.apply(s)),
            Bias::Estimator(e) => e.update(s),
        }
    }
}

/// The sensor front end: counts → rad/s, sensor → body axes, bias removed; the time bases of the bursts.
#[derive(Clone, Copy)]
pub struct FrontEnd {
    pub scale: Option<CountScale<f32>>,
    pub alignment: Option<Alignment<f32>>,
    pub bias: Bias,
    pub period: Option<FixedPeriod<f32>>,
    pub clock: Option<TickClock<f32>>,
}

impl FrontEnd {
    const NONE: Self = Self {
        scale: None,
        alignment: None,
        bias: Bias::None,
        period: None,
        clock: None,
    };

    #[inline(always)]
    fn align(&self, s: GyroSample<f32>) -> GyroSample<f32> {
        match &self.alignment {
            Some(a) => a.apply(s),
            None => s,
        }
    }
}

/// Everything a `quatprop_t` holds.
#[derive(Clone, Copy)]
pub struct Inner {
    pub prop: Prop,
    pub front: FrontEnd,
}

/// What C chose in `quatprop_config_t`, validated.
pub struct Choice {
    pub q0: Quat<f32>,
    pub scheme: u32,
    pub stabilizer: u32,
    pub every: u32,
    pub input: u32,
    pub coning: u32,
    pub accumulator: u32,
}

fn scheme_of(v: u32) -> Result<SchemeKind, Fail> {
    SchemeKind::ALL
        .get(v as usize)
        .copied()
        .ok_or(Fail::BadEnum)
}

fn stabilizer_of(v: u32, every: u32) -> Result<StabilizerKind, Fail> {
    match v {
        0 => Ok(StabilizerKind::Off),
        1 => Ok(StabilizerKind::Normalize),
        2 => Ok(StabilizerKind::FirstOrder),
        3 => Ok(StabilizerKind::Every(every)),
        _ => Err(Fail::BadEnum),
    }
}

/// The axis remap with C value `v` (the order of [`AxisRemap::ALL`]).
pub fn remap_of(v: u32) -> Result<AxisRemap, Fail> {
    AxisRemap::ALL.get(v as usize).copied().ok_or(Fail::BadEnum)
}

fn build<I: InputModel<f32>>(
    c: &Choice,
    input: I,
    plain: fn(P<I, Plain>) -> Prop,
    kahan: fn(P<I, Kahan<f32>>) -> Prop,
) -> Result<Prop, Fail> {
    let scheme = scheme_of(c.scheme)?;
    let stabilizer = stabilizer_of(c.stabilizer, c.every)?;
    let p = Propagator::new(c.q0, scheme, input, stabilizer)?;
    match c.accumulator {
        0 => Ok(plain(p)),
        1 => Ok(kahan(p.with_accumulator(Kahan::new()))),
        _ => Err(Fail::BadEnum),
    }
}

impl Inner {
    /// A propagator as chosen, with an empty front end (no scale, identity alignment, no bias, no time base).
    pub fn new(c: &Choice) -> Result<Self, Fail> {
        let prop = match c.input {
            0 => build(c, Hold, Prop::HoldPlain, Prop::HoldKahan),
            1 => build(c, Linear::new(), Prop::LinearPlain, Prop::LinearKahan),
            2 => build(c, History::new(), Prop::HistoryPlain, Prop::HistoryKahan),
            3 => build(
                c,
                TwiceRate::new(),
                Prop::TwiceRatePlain,
                Prop::TwiceRateKahan,
            ),
            4 => build(
                c,
                GaussPoints::new(),
                Prop::GaussPointsPlain,
                Prop::GaussPointsKahan,
            ),
            5 => {
                let coning = ConingKind::ALL
                    .get(c.coning as usize)
                    .copied()
                    .ok_or(Fail::BadEnum)?;
                build(
                    c,
                    DeltaAngles::new(coning),
                    Prop::DeltaPlain,
                    Prop::DeltaKahan,
                )
            }
            _ => Err(Fail::BadEnum),
        }?;
        Ok(Self {
            prop,
            front: FrontEnd::NONE,
        })
    }

    pub fn attitude(&self) -> Quat<f32> {
        dispatch!(&self.prop, any p => p.attitude())
    }

    pub fn norm_error(&self) -> f32 {
        dispatch!(&self.prop, any p => p.norm_error())
    }

    /// Steps, corrections, saturated samples.
    pub fn counters(&self) -> (u64, u64, u64) {
        dispatch!(&self.prop, any p => (p.steps(), p.corrections(), p.saturated_samples()))
    }

    pub fn set_attitude(&mut self, q: Quat<f32>) -> Result<(), Fail> {
        dispatch!(&mut self.prop, any p => p.set_attitude(q).map_err(Fail::Core))
    }

    pub fn restart_input(&mut self) {
        dispatch!(&mut self.prop, any p => p.restart_input())
    }

    /// One rate sample (rad/s, sensor axes) through alignment and bias, `dt` after the previous one.
    /// All or nothing: on error nothing changes.
    pub fn push_rate(&mut self, s: GyroSample<f32>, dt: f32) -> Result<(), Fail> {
        let front = &mut self.front;
        dispatch!(&mut self.prop,
            rate p => {
                let mut bias = front.bias;
                let s = bias.apply(front.align(s))?;
                p.push(s, dt)?;
                front.bias = bias;
                Ok(())
            },
            delta _d => Err(Fail::WrongInputKind))
    }

    /// One delta-angle sample (rad, sensor axes) through the alignment. All or nothing.
    pub fn push_delta(&mut self, d: DeltaAngle<f32>, dt: f32) -> Result<(), Fail> {
        let d = align_delta(&self.front, d);
        dispatch!(&mut self.prop,
            rate _p => Err(Fail::WrongInputKind),
            delta p => p.push(d, dt).map_err(Fail::Core))
    }

    /// A burst of rate samples produced by `sample(i)`, `i < n`, timed by the fixed period.
    #[inline(always)]
    pub fn rate_burst<F: Fn(usize) -> GyroSample<f32>>(
        &mut self,
        n: usize,
        sample: F,
    ) -> Result<usize, Refusal> {
        let Some(mut period) = self.front.period else {
            return Err((0, Fail::NotConfigured));
        };
        let front = &mut self.front;
        let r = dispatch!(&mut self.prop,
            rate p => rate_loop(p, front, &mut period, n, sample),
            delta _d => Err((0, Fail::WrongInputKind)));
        front.period = Some(period);
        r
    }

    /// A burst of rate samples with the sensor's timestamps (ticks of the tick clock).
    #[inline(always)]
    pub fn rate_burst_timed<F: Fn(usize) -> (GyroSample<f32>, u32)>(
        &mut self,
        n: usize,
        sample: F,
    ) -> Result<usize, Refusal> {
        let Some(mut clock) = self.front.clock else {
            return Err((0, Fail::NotConfigured));
        };
        let front = &mut self.front;
        let r = dispatch!(&mut self.prop,
            rate p => timed_loop(p, front, &mut clock, n, sample),
            delta _d => Err((0, Fail::WrongInputKind)));
        front.clock = Some(clock);
        r
    }

    /// A burst of delta angles timed by the fixed period.
    pub fn delta_burst(&mut self, samples: &[DeltaAngle<f32>]) -> Result<usize, Refusal> {
        let Some(mut period) = self.front.period else {
            return Err((0, Fail::NotConfigured));
        };
        let front = self.front;
        let r = dispatch!(&mut self.prop,
        rate _p => Err((0, Fail::WrongInputKind)),
        delta p => {
            let mut r = Ok(samples.len());
            for (i, d) in samples.iter().enumerate() {
                let dt = period.next_dt();
                if let Err(e) = p.push(align_delta(&front, *d), dt) {
                    period.carry_over(dt);
                    r = Err((i, Fail::Core(e)));
                    break;
                }
            }
            r
        });
        self.front.period = Some(period);
        r
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

/// The burst loop, monomorphized per input model × accumulator. Per sample: the next period, the front end
/// (bias on a copy), the push; on a refusal the interval is carried over and the bias stage stays as it was
/// after the last accepted sample (the core's `push_burst` semantics).
#[inline(always)]
fn rate_loop<I, A, F>(
    p: &mut P<I, A>,
    front: &mut FrontEnd,
    period: &mut FixedPeriod<f32>,
    n: usize,
    sample: F,
) -> Result<usize, Refusal>
where
    I: InputModel<f32, Sample = GyroSample<f32>>,
    A: quatprop::accumulate::Accumulator<f32>,
    F: Fn(usize) -> GyroSample<f32>,
{
    for i in 0..n {
        let dt = period.next_dt();
        let mut bias = front.bias;
        let pushed = bias
            .apply(front.align(sample(i)))
            .and_then(|s| p.push(s, dt));
        if let Err(e) = pushed {
            period.carry_over(dt);
            return Err((i, Fail::Core(e)));
        }
        front.bias = bias;
    }
    Ok(n)
}

/// The timed burst loop: the clock's first timestamp starts the input model (the core's
/// `push_burst_timed` semantics); on a refusal the clock and the bias stay as after the last accepted sample.
#[inline(always)]
fn timed_loop<I, A, F>(
    p: &mut P<I, A>,
    front: &mut FrontEnd,
    clock: &mut TickClock<f32>,
    n: usize,
    sample: F,
) -> Result<usize, Refusal>
where
    I: InputModel<f32, Sample = GyroSample<f32>>,
    A: quatprop::accumulate::Accumulator<f32>,
    F: Fn(usize) -> (GyroSample<f32>, u32),
{
    for i in 0..n {
        let (raw, timestamp) = sample(i);
        let mut bias = front.bias;
        let step = |bias: &mut Bias, p: &mut P<I, A>| -> Result<TickClock<f32>, Error> {
            let (next, dt) = clock.advance(timestamp)?;
            let s = bias.apply(front.align(raw))?;
            match dt {
                Some(dt) => p.push(s, dt)?,
                None => p.start(s)?,
            }
            Ok(next)
        };
        match step(&mut bias, p) {
            Ok(next) => {
                *clock = next;
                front.bias = bias;
            }
            Err(e) => return Err((i, Fail::Core(e))),
        }
    }
    Ok(n)
}

/// Counts to rad/s with the front end's scale (checked by the caller).
#[inline(always)]
pub fn counts_sample(scale: &CountScale<f32>, c: [i16; 3]) -> GyroSample<f32> {
    scale.sample(c)
}

/// A `Vec3` from C's three floats.
pub fn vec3(v: [f32; 3]) -> Vec3<f32> {
    Vec3::new(v[0], v[1], v[2])
}
