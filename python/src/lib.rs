//! `quatprop._native`: the extension behind the `quatprop` Python package.
//!
//! The Python layer (`pysrc/quatprop/__init__.py`) validates and converts the arguments; this module runs
//! the core library's own loop over the whole buffer with the GIL released. The configuration is the
//! core's run-time [`Config`]; the loop ([`Run`]) is a [`Visit`] of the [`Configured`] propagator it
//! builds, so it is compiled for each scheme × input model × accumulator, and for each precision and time
//! base: the inner loop is the code a Rust user writes with those types (the stabilizer and the coning
//! correction are the core's run-time enums, [`StabilizerKind`] and [`ConingKind`]).
//!
//! A stream's methods take either precision and run one generic body on its session (`with_session!`);
//! the module's functions come in pairs, one per precision (`calibrate_f32` / `calibrate_f64`, …): pyo3
//! exports concrete signatures only, so a macro writes each pair from one body.

// As in the core: `!(t > last)` is written so that a NaN lands in the error branch.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use std::time::Instant;

use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::IntoPyObjectExt;
use quatprop::accumulate::Accumulator;
use quatprop::config::{
    AccumulatorKind, Config, Configured, DeltaModel, InputKind, RateModel, Visit, Visited,
};
use quatprop::frontend::{
    Alignment, Aux, AxisRemap, BiasEstimator, Calibration, CalibrationEstimator, CountScale,
    FixedBias, FixedPeriod, MotionBias, SampleTiming, TickClock,
};
use quatprop::input::coning::ConingKind;
use quatprop::input::{History, InputModel};
use quatprop::noise::{AllanVariance, GyroNoise, NoiseFit, Term};
use quatprop::scheme::{ExpMap, Scheme, SchemeKind};
use quatprop::stabilize::{FirstOrder, Stabilizer, StabilizerKind};
use quatprop::{
    DeltaAngle, Error, EulerZxz, EulerZyx, GyroSample, Propagator, Quat, Real, Refused, Vec3,
};

/// A sample type built from one row `[x, y, z]` of the input buffer.
trait FromRow<T>: Copy {
    /// The sample of a row (clipped or not) pushed with `dt` (`None`: the first timestamp, which starts
    /// the stream).
    fn from_row(r: [T; 3], saturated: bool, dt: Option<T>, timing: &SampleTiming<T>) -> Self;
    /// The rotation the sample carries (rad), if it is an increment.
    fn angle(&self) -> Option<Vec3<T>>;
}

impl<T: Real> FromRow<T> for GyroSample<T> {
    #[inline(always)]
    fn from_row(r: [T; 3], saturated: bool, _: Option<T>, _: &SampleTiming<T>) -> Self {
        GyroSample {
            rate: Vec3::new(r[0], r[1], r[2]),
            saturated,
        }
    }
    fn angle(&self) -> Option<Vec3<T>> {
        None
    }
}

impl<T: Real> FromRow<T> for DeltaAngle<T> {
    /// An increment (rad), or an interval-mean rate (rad/s) times its interval.
    #[inline(always)]
    fn from_row(r: [T; 3], saturated: bool, dt: Option<T>, timing: &SampleTiming<T>) -> Self {
        let v = Vec3::new(r[0], r[1], r[2]);
        if timing.is_interval_mean() {
            let s = GyroSample { rate: v, saturated };
            timing.increment(s, dt.unwrap_or(T::ZERO))
        } else {
            DeltaAngle {
                angle: v,
                saturated,
            }
        }
    }
    fn angle(&self) -> Option<Vec3<T>> {
        Some(self.angle)
    }
}

/// The time base's state between calls: where each sample's `dt` comes from.
#[derive(Clone, Copy)]
enum Clock<T> {
    /// A fixed period: the core's [`FixedPeriod`], exactly as [`Propagator::push_burst`] uses it.
    Fixed(FixedPeriod<T>),
    /// Timestamps in seconds (f64). The first accepted sample starts the stream (`Propagator::start`);
    /// each later one is pushed with `dt = T(t_k − t_last + carry)`, where `t_last` is the last
    /// *accepted* timestamp and `carry` (f64) the part of the previous intervals that rounding to `T`
    /// left out. So the `dt`s sum to `t_last − t_first` within half an ulp of one `dt` (in f64 the carry
    /// stays zero and `dt = t_k − t_last` as computed in f64, exact by Sterbenz whenever
    /// `t_last ≥ t_k / 2`).
    Seconds { last: Option<f64>, carry: f64 },
    /// Integer timestamps: the core's [`TickClock`], exactly as [`Propagator::push_burst_timed`] uses it.
    Ticks(TickClock<T>),
}

/// A [`Clock`] with one call's timestamps. One value per call, matched per sample, so that each
/// propagator type has one call site of `push` and the compiler inlines it into the loop (with one loop
/// per time base it did not, and `integrate` took 1.3x to 1.6x the same Rust loop).
struct Time<'a, T> {
    clock: Clock<T>,
    seconds: &'a [f64],
    ticks: &'a [u32],
    /// What a row means in time; the rate of the last accepted row (for the group delay).
    timing: SampleTiming<T>,
    last_rate: Vec3<T>,
    /// The rotation the refused increments carried (rad; finite ones only).
    lost: [f64; 3],
}

impl<T: Real> Time<'_, T> {
    /// Sample `i`'s interval, the clock advanced past it: `Some(dt)`, or `None` for the first timestamp
    /// of a stream (its sample starts the stream). On error nothing changed.
    #[inline(always)]
    fn advance(&mut self, i: usize) -> Result<Option<T>, Error> {
        match &mut self.clock {
            Clock::Fixed(period) => Ok(Some(period.next_dt())),
            Clock::Seconds { last, carry } => {
                let t = self.seconds.get(i).copied().unwrap_or(f64::NAN);
                if !t.is_finite() {
                    return Err(Error::NonFiniteStep);
                }
                match *last {
                    None => {
                        *last = Some(t);
                        Ok(None)
                    }
                    Some(before) => {
                        if !(t > before) {
                            return Err(Error::TimestampNotIncreasing);
                        }
                        let exact = (t - before) + *carry;
                        let dt = T::from_f64(exact);
                        *last = Some(t);
                        *carry = exact - dt.to_f64();
                        Ok(Some(dt))
                    }
                }
            }
            Clock::Ticks(clock) => {
                let tick = self.ticks.get(i).copied().unwrap_or(0);
                let (next, dt) = clock.advance(tick)?;
                *clock = next;
                Ok(dt)
            }
        }
    }

    /// After a refused sample (`before`: the clock before it): the next interval covers the refused
    /// one. A period gives the interval back ([`FixedPeriod::carry_over`]); timestamps count from the
    /// last accepted one.
    #[inline(always)]
    fn refused(&mut self, dt: Option<T>, before: Clock<T>) {
        match &mut self.clock {
            Clock::Fixed(period) => {
                if let Some(dt) = dt {
                    period.carry_over(dt);
                }
            }
            _ => self.clock = before,
        }
    }
}

/// The loop: every sample into the propagator, its attitude after every sample into `out`. A refused
/// sample either stops the loop (`mask` is `None`) or is flagged and skipped, the state as after the last
/// accepted sample and its interval carried into the next one. It runs on a copy of the propagator in
/// this frame, written back at the end: behind the `&mut` the state would go through memory at every
/// step (see [`Visit`]).
#[inline(always)]
fn run<T, S, I, Z, A>(
    prop: &mut Propagator<T, S, I, Z, A>,
    time: &mut Time<'_, T>,
    rows: &[[T; 3]],
    saturated: &[bool],
    out: &mut [[T; 4]],
    mut mask: Option<&mut [bool]>,
) -> Result<(), Refused>
where
    T: Real,
    S: Scheme<T>,
    I: InputModel<T>,
    I::Sample: FromRow<T>,
    Z: Stabilizer,
    A: Accumulator<T>,
{
    let mut local = *prop;
    let p = &mut local;
    let mut result = Ok(());
    for (index, (row, o)) in rows.iter().zip(out.iter_mut()).enumerate() {
        let before = time.clock;
        let clipped = saturated.get(index).copied().unwrap_or(false);
        let mut interval = None;
        let pushed = time.advance(index).and_then(|dt| {
            interval = dt;
            let sample = I::Sample::from_row(*row, clipped, dt, &time.timing);
            match dt {
                Some(dt) => p.push(sample, dt),
                None => p.start(sample),
            }
            .inspect_err(|_| time.refused(dt, before))
        });
        if let Err(error) = pushed {
            // The rotation a refused increment took with it (an interval mean's needs its interval).
            let refused = I::Sample::from_row(*row, clipped, interval, &time.timing);
            if let Some(a) = refused.angle().filter(|a| a.is_finite()) {
                for (l, e) in time.lost.iter_mut().zip([a.x, a.y, a.z]) {
                    *l += e.to_f64();
                }
            }
            match mask.as_deref_mut().and_then(|m| m.get_mut(index)) {
                Some(m) => *m = true,
                None => {
                    result = Err(Refused { index, error });
                    break;
                }
            }
        } else {
            time.last_rate = Vec3::new(row[0], row[1], row[2]);
        }
        *o = quat_row(time.timing.ahead(p.attitude(), time.last_rate));
    }
    *prop = local;
    result
}

/// [`run`] as a [`Visit`] of the configured propagator: compiled for each scheme × input model ×
/// accumulator and precision.
struct Run<'a, 'b, T> {
    time: &'a mut Time<'b, T>,
    rows: &'a [[T; 3]],
    /// Per row, clipped at a rail (empty: none is).
    saturated: &'a [bool],
    out: &'a mut [[T; 4]],
    mask: Option<&'a mut [bool]>,
}

// Both of `Visit`'s methods, the same loop: the trait has one per sample type, each with its own bounds.
impl<T: Real> Visit<T> for Run<'_, '_, T> {
    type Output = Result<(), Refused>;
    fn rates<S: Scheme<T>, I: RateModel<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        run(p, self.time, self.rows, self.saturated, self.out, self.mask)
    }
    fn deltas<S: Scheme<T>, I: DeltaModel<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        run(p, self.time, self.rows, self.saturated, self.out, self.mask)
    }
}

/// What the IMU gave beside the rates, per row (validated finite by `update`): accelerations and
/// temperatures for the bias estimator; empty slices when not given.
struct Companions<'a, T> {
    accel: &'a [[T; 3]],
    temperature: &'a [T],
}

impl<T: Real> Companions<'_, T> {
    fn at(&self, k: usize) -> Aux<T> {
        Aux {
            accel: self.accel.get(k).map(|a| Vec3::new(a[0], a[1], a[2])),
            temperature: self.temperature.get(k).copied(),
        }
    }
}

/// Everything a stream keeps between calls: the configured propagator, its clock, the front end
/// (the gyro's calibration, the alignment to body axes, then a fixed bias or the bias estimator) and the
/// count of refused samples.
/// `integrate` is one call on a new one; `Stream` keeps one, so any chunking of a stream gives the same
/// bits as one call over the whole of it.
#[derive(Clone, Copy)]
struct Session<T: Real> {
    p: Configured<T>,
    clock: Clock<T>,
    scale: Option<CountScale<T>>,
    calibration: Option<Calibration<T>>,
    alignment: Option<Alignment<T>>,
    fixed: Option<FixedBias<T>>,
    estimator: Option<BiasEstimator<T>>,
    /// What is learned in motion from the accelerometer, after the estimator.
    motion: Option<Motion<T>>,
    refused: u64,
    /// The sum of the refused delta angles (rad, body axes; finite ones only): rotation not integrated.
    lost: [f64; 3],
    /// What a row means in time, and the rate of the last accepted row.
    timing: SampleTiming<T>,
    last_rate: Vec3<T>,
}

/// What a stream learns in motion from the accelerometer, after the rest estimator.
#[derive(Clone, Copy)]
enum Motion<T> {
    /// The residual bias (VQF's motion bias estimation).
    Bias(MotionBias<T>),
    /// The gain (scale and misalignment) and the residual bias.
    Calibration(CalibrationEstimator<T>),
}

impl<T: Real> Motion<T> {
    fn at_rest(&mut self) {
        match self {
            Motion::Bias(m) => m.at_rest(),
            Motion::Calibration(c) => c.at_rest(),
        }
    }

    /// The rate with what has been learned taken out.
    fn correct(&self, s: GyroSample<T>) -> GyroSample<T> {
        match self {
            Motion::Bias(m) => GyroSample {
                rate: s.rate - m.bias(),
                ..s
            },
            Motion::Calibration(c) => c.correct(s),
        }
    }

    fn update(&mut self, rate: Vec3<T>, accel: Vec3<T>, dt: T) -> Result<(), Error> {
        match self {
            Motion::Bias(m) => m.update(rate, accel, dt),
            Motion::Calibration(c) => c.update(rate, accel, dt),
        }
    }

    fn bias(&self) -> Vec3<T> {
        match self {
            Motion::Bias(m) => m.bias(),
            Motion::Calibration(c) => c.bias(),
        }
    }
}

impl<T: Real> Session<T> {
    fn new(args: &StreamArgs) -> PyResult<Self> {
        let config = Config {
            scheme: parse_scheme(&args.scheme)?,
            baumgarte_gain: None,
            input: parse_input(&args.input, &args.coning)?,
            stabilizer: parse_stabilizer(&args.stabilizer, args.every)?,
            accumulator: if args.kahan {
                AccumulatorKind::Kahan
            } else {
                AccumulatorKind::Plain
            },
        };
        let clock = match (args.period, args.timestamps, args.tick_hz) {
            (Some(p), false, None) => Clock::Fixed(FixedPeriod::new(p).map_err(config_error)?),
            (None, true, None) => Clock::Seconds {
                last: None,
                carry: 0.0,
            },
            (None, false, Some(hz)) => {
                Clock::Ticks(TickClock::new(hz, args.tick_bits).map_err(config_error)?)
            }
            _ => {
                return Err(PyValueError::new_err(
                    "give exactly one time base: a period, timestamps (s) or a tick frequency",
                ))
            }
        };
        let calibration = match args.calibration {
            Some(c) => Some(calibration(c).map_err(config_error)?),
            None => None,
        };
        let alignment = match (&args.remap, args.matrix) {
            (Some(r), None) => Some(Alignment::from(axis_remap(r)?)),
            (None, Some(m)) => Some(
                Alignment::from_matrix(m.map(|row| row.map(T::from_f64))).map_err(config_error)?,
            ),
            (None, None) => None,
            _ => {
                return Err(PyValueError::new_err(
                    "give alignment as a remap name or a matrix, not both",
                ))
            }
        };
        let (fixed, estimator) = match (args.bias, args.estimator) {
            (None, None) => (None, None),
            (Some(b), None) => (Some(FixedBias::new(vec3(b)).map_err(config_error)?), None),
            (None, Some(e)) => {
                // The estimator's sample period: its own, else the stream's fixed period (a tick clock's
                // frequency is its counter's, not the sample rate: give the period then).
                let period = e.period.or(args.period).ok_or_else(|| {
                    PyValueError::new_err(
                        "BiasEstimator needs a sample period: give the stream dt= or BiasEstimator(period=...)",
                    )
                })?;
                let mut est = BiasEstimator::new(e.window, period, T::from_f64(e.gate))
                    .map_err(config_error)?;
                if let Some(d) = e.drift {
                    est = est.with_drift(T::from_f64(d)).map_err(config_error)?;
                }
                if let Some(d) = e.rest_drift {
                    est = est.with_rest_drift(T::from_f64(d)).map_err(config_error)?;
                }
                if let Some(n) = e.noise {
                    let noise = GyroNoise::new(T::from_f64(n), T::ZERO).map_err(config_error)?;
                    est = est.with_noise(&noise).map_err(config_error)?;
                }
                if let Some(g) = e.accel_gate {
                    est = est.with_accel_gate(T::from_f64(g)).map_err(config_error)?;
                }
                if let Some(s) = e.span {
                    est = est
                        .with_temperature_model(T::from_f64(s))
                        .map_err(config_error)?;
                }
                if let Some((b, sigma)) = e.initial {
                    est = est
                        .with_initial(vec3(b), T::from_f64(sigma))
                        .map_err(config_error)?;
                }
                (None, Some(est))
            }
            _ => {
                return Err(PyValueError::new_err(
                    "give a fixed bias or an estimator, not both",
                ))
            }
        };
        let timing = if args.interval_mean {
            SampleTiming::interval_mean()
        } else {
            SampleTiming::instant()
        };
        let timing = timing
            .with_group_delay(T::from_f64(args.group_delay))
            .map_err(config_error)?;
        let motion = match (&args.estimator, &clock) {
            (Some(e), Clock::Fixed(_)) if e.motion => {
                let period = args.period.unwrap_or(f64::NAN);
                Some(match e.calibrate {
                    None => Motion::Bias(MotionBias::new(period).map_err(config_error)?),
                    Some((sensitivity, misalignment, noise)) => Motion::Calibration(
                        CalibrationEstimator::with_motion_noise(
                            period,
                            sensitivity,
                            misalignment,
                            noise.unwrap_or(CalibrationEstimator::<T>::DEFAULT_MOTION_NOISE),
                        )
                        .map_err(config_error)?,
                    ),
                })
            }
            (Some(e), _) if e.motion => {
                return Err(PyValueError::new_err(
                    "the motion bias estimator needs a fixed period (dt=)",
                ))
            }
            _ => None,
        };
        let scale = match args.count_scale {
            Some((true, fs)) => Some(CountScale::full_scale_dps(fs).map_err(config_error)?),
            Some((false, sensitivity)) => {
                Some(CountScale::sensitivity(sensitivity).map_err(config_error)?)
            }
            None => None,
        };
        Ok(Self {
            p: config.build(quat(args.q0)).map_err(config_error)?,
            clock,
            scale,
            calibration,
            alignment,
            fixed,
            estimator,
            motion,
            refused: 0,
            lost: [0.0; 3],
            timing,
            last_rate: Vec3::ZERO,
        })
    }

    /// The bias subtracted now (`NativeStream::bias`).
    fn bias(&self) -> Option<[f64; 3]> {
        let b = match (self.estimator, self.fixed) {
            (Some(e), _) => e.bias() + self.motion.map_or(Vec3::ZERO, |m| m.bias()),
            (None, Some(f)) => f.bias(),
            (None, None) => return None,
        };
        Some(f64x3(b))
    }

    /// What the calibration estimator has learned (`NativeStream::learned_calibration`).
    #[allow(clippy::type_complexity)]
    fn learned_calibration(&self) -> Option<(CalibrationArgs, [[f64; 3]; 3], [[f64; 3]; 3])> {
        let Some(Motion::Calibration(c)) = self.motion else {
            return None;
        };
        let m = |m: [[T; 3]; 3]| m.map(|r| r.map(|x| x.to_f64()));
        let cal = c.calibration();
        Some((
            (
                f64x3(cal.offset()),
                f64x3(cal.sensitivity()),
                m(cal.misalignment()),
            ),
            m(c.gain()),
            m(c.gain_std_dev()),
        ))
    }

    /// The bias estimator's variance per axis (`NativeStream::bias_variance`).
    fn bias_variance(&self) -> Option<[f64; 3]> {
        let v = self.estimator?.variance();
        let f = |x: T| if x == T::MAX { f64::MAX } else { x.to_f64() };
        Some([f(v.x), f(v.y), f(v.z)])
    }

    /// An estimator's bias correction (`NativeStream::correct_bias`): both or neither.
    fn correct_bias(&mut self, v: Vec3<T>) -> Result<(), Error> {
        let mut next = *self;
        match (&mut next.estimator, &mut next.fixed) {
            (Some(e), _) => e.correct_bias(v)?,
            (None, Some(f)) => f.correct_bias(v)?,
            (None, None) => next.fixed = Some(FixedBias::new(v)?),
        }
        next.p.correct_bias(v)?;
        *self = next;
        Ok(())
    }

    /// Whether samples pass a front end (else they go to the propagator as they are).
    fn has_front_end(&self) -> bool {
        self.calibration.is_some()
            || self.alignment.is_some()
            || self.fixed.is_some()
            || self.estimator.is_some()
    }

    /// Sample `k` of the input through the front end: the count scale (counts only), the gyro's
    /// calibration (sensor axes), the alignment (sensor to body axes), then the bias (body axes), as the
    /// README's quick start composes them. A sample the bias estimator refuses (NaN) is passed on
    /// unchanged, so the propagator refuses it too.
    fn front_sample(
        &mut self,
        input: &Input<'_, T>,
        k: usize,
        aux: &Companions<'_, T>,
    ) -> GyroSample<T> {
        let mut s = match input {
            Input::Counts(c, scale) => scale.sample(c[k]),
            Input::Rows(r) => GyroSample::new(Vec3::new(r[k][0], r[k][1], r[k][2])),
        };
        if let Some(c) = &self.calibration {
            s = c.apply(s);
        }
        if let Some(a) = &self.alignment {
            s = a.apply(s);
        }
        if let Some(b) = &self.fixed {
            s = b.apply(s);
        }
        let mut aux = aux.at(k);
        if let (Some(a), Some(acc)) = (&self.alignment, aux.accel) {
            aux.accel = Some(a.apply(GyroSample::new(acc)).rate); // the same axes as the rates
        }
        if let Some(e) = self.estimator.as_mut() {
            let rest = e.bias();
            s = e.update_with(s, aux).unwrap_or(s);
            if let Some(m) = self.motion.as_mut() {
                if e.bias() != rest {
                    m.at_rest(); // a window learned: the rest estimate holds, the residual restarts
                }
                let corrected = m.correct(s);
                if let (Some(acc), Clock::Fixed(p)) = (aux.accel, &self.clock) {
                    // A refused sample (NaN) leaves it unchanged; the propagator refuses the sample too.
                    let _ = m.update(s.rate, acc, p.period());
                }
                s = corrected;
            }
        }
        s
    }

    /// The first `n` samples of the input through the front end: rows and their clipped flags (empty
    /// when nothing can clip: no count scale).
    fn front_end(
        &mut self,
        input: &Input<'_, T>,
        n: usize,
        aux: &Companions<'_, T>,
    ) -> (Vec<[T; 3]>, Vec<bool>) {
        let mut rows = Vec::with_capacity(n);
        let mut clipped = Vec::new();
        for k in 0..n {
            let s = self.front_sample(input, k, aux);
            rows.push([s.rate.x, s.rate.y, s.rate.z]);
            if matches!(input, Input::Counts(..)) {
                clipped.push(s.saturated);
            }
        }
        (rows, clipped)
    }

    /// The input (and its timestamps, for a timed clock: as many as rows) through the front end and the
    /// propagator, the attitude after each row into `out`. With `mask` a refused sample is flagged and
    /// skipped; without, the first one stops the call with the propagator and clock as after the last
    /// accepted sample and the front end as after the refused one (it sees every sample given), so the
    /// rows after it can be given next.
    fn update(
        &mut self,
        input: &Input<'_, T>,
        aux: &Companions<'_, T>,
        seconds: &[f64],
        ticks: &[u32],
        out: &mut [[T; 4]],
        mut mask: Option<&mut [bool]>,
    ) -> Result<(), Refused> {
        let n = out.len();
        let (estimator, motion) = (self.estimator, self.motion);
        let processed;
        let (rows, clipped): (&[[T; 3]], &[bool]) = match input {
            Input::Rows(r) if !self.has_front_end() => (r, &[]),
            _ => {
                processed = self.front_end(input, n, aux);
                (&processed.0, &processed.1)
            }
        };
        let mut time = Time {
            clock: self.clock,
            seconds,
            ticks,
            timing: self.timing,
            last_rate: self.last_rate,
            lost: [0.0; 3],
        };
        let result = self.p.visit(Run {
            time: &mut time,
            rows,
            saturated: clipped,
            out,
            mask: mask.as_deref_mut(),
        });
        self.clock = time.clock;
        self.last_rate = time.last_rate;
        for (l, e) in self.lost.iter_mut().zip(time.lost) {
            *l += e;
        }
        match &result {
            Ok(()) => {
                let flags = mask.as_deref().unwrap_or(&[]);
                self.refused += flags.iter().filter(|&&f| f).count() as u64;
            }
            Err(r) => {
                self.refused += 1;
                // The estimator has seen the whole call: back to where the refused sample left it.
                if estimator.is_some() {
                    (self.estimator, self.motion) = (estimator, motion);
                    self.front_end(input, r.index + 1, aux);
                }
            }
        }
        result
    }
}

/// One call's samples: rows of rates (rad/s) or increments (rad), or raw counts with the stream's scale.
enum Input<'a, T> {
    Rows(&'a [[T; 3]]),
    Counts(&'a [[i16; 3]], CountScale<T>),
}

/// The arguments of a stream as the Python layer passes them, a dict by field name (validated there;
/// checked again here).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
struct StreamArgs {
    period: Option<f64>,
    timestamps: bool,
    tick_hz: Option<f64>,
    tick_bits: u32,
    scheme: String,
    stabilizer: String,
    every: u32,
    input: String,
    coning: String,
    kahan: bool,
    q0: [f64; 4],
    remap: Option<String>,
    matrix: Option<[[f64; 3]; 3]>,
    bias: Option<[f64; 3]>,
    estimator: Option<EstimatorArgs>,
    calibration: Option<CalibrationArgs>,
    interval_mean: bool,
    group_delay: f64,
    /// `(true, full scale °/s)` or `(false, counts per °/s)`.
    count_scale: Option<(bool, f64)>,
}

/// A bias estimator as Python passes it (`quatprop.BiasEstimator`): the window (s), the gate (rad/s), the
/// sample period (s; None: the stream's), the drift and the rest drift (rad/s/√s; None: the core's
/// defaults), the white noise
/// density (rad/√s; None: the scatter at rest is learned), an initial bias (rad/s) with its standard
/// deviation, an acceleration gate, a temperature span, and whether the residual bias is also learned in
/// motion from the accelerometer (`MotionBias`).
#[derive(Clone, Copy, Debug, FromPyObject)]
struct EstimatorArgs {
    window: f64,
    gate: f64,
    period: Option<f64>,
    drift: Option<f64>,
    rest_drift: Option<f64>,
    noise: Option<f64>,
    initial: Option<([f64; 3], f64)>,
    accel_gate: Option<f64>,
    span: Option<f64>,
    motion: bool,
    /// With `motion`: learn the gain too (`CalibrationEstimator`): the sensitivity's and the
    /// misalignment's prior sigmas and the measurement noise (rad/s; None: the core's default).
    calibrate: Option<(f64, f64, Option<f64>)>,
}

/// A calibration as Python passes it: offset (rad/s), sensitivity, misalignment (rows).
type CalibrationArgs = ([f64; 3], [f64; 3], [[f64; 3]; 3]);

fn calibration<T: Real>(
    (offset, sensitivity, m): CalibrationArgs,
) -> Result<Calibration<T>, Error> {
    Calibration::new(
        vec3(offset),
        vec3(sensitivity),
        m.map(|row| row.map(T::from_f64)),
    )
}

/// `$body` with `$s` bound to the session in `$sessions` (a `Sessions`, by reference), whichever its
/// precision: one body, compiled for each (a closure cannot be generic over the precision).
macro_rules! with_session {
    ($sessions:expr, $s:ident => $body:expr) => {
        match $sessions {
            Sessions::F32($s) => $body,
            Sessions::F64($s) => $body,
        }
    };
}

/// A session in the precision the stream was made with.
// One per Python object, on the heap: the f32 variant's unused bytes cost nothing worth a box.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy)]
enum Sessions {
    F32(Session<f32>),
    F64(Session<f64>),
}

/// The state behind `quatprop.Stream`: the session now and as it was made (for `reset`).
#[pyclass(module = "quatprop._native")]
struct NativeStream {
    now: Sessions,
    made: Sessions,
    mask: bool,
}

/// The refused sample, if any: `(index, kind, reason)`.
type RefusedInfo = Option<(usize, String, String)>;

/// One call's result: the attitudes, the refused flags (with `mask`), the refused sample (without).
type Updated<'py, T> = (
    Bound<'py, PyArray2<T>>,
    Option<Bound<'py, PyArray1<bool>>>,
    RefusedInfo,
);

/// One call's arrays as Python passes them, a dict by field name: rates (in the stream's precision, or
/// raw counts), timestamps (seconds or ticks), accelerations and temperatures.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
struct Arrays<'py, T: numpy::Element> {
    gyr: PyReadonlyArray2<'py, T>,
    counts: Option<PyReadonlyArray2<'py, i16>>,
    t: Option<PyReadonlyArray1<'py, f64>>,
    ticks: Option<PyReadonlyArray1<'py, u32>>,
    acc: Option<PyReadonlyArray2<'py, T>>,
    temperature: Option<PyReadonlyArray1<'py, T>>,
}

fn update<'py, T: Real + numpy::Element>(
    py: Python<'py>,
    session: &mut Session<T>,
    mask: bool,
    arrays: Arrays<'py, T>,
) -> PyResult<Updated<'py, T>> {
    let Arrays {
        gyr,
        counts,
        t,
        ticks,
        acc,
        temperature,
    } = arrays;
    let (rows, rest) = gyr.as_slice()?.as_chunks::<3>();
    if !rest.is_empty() {
        return Err(PyValueError::new_err("gyr must have shape (N, 3)"));
    }
    let input = match (&counts, session.scale) {
        (None, None) => Input::Rows(rows),
        (Some(c), Some(scale)) if rows.is_empty() => {
            let (c, rest) = c.as_slice()?.as_chunks::<3>();
            if !rest.is_empty() {
                return Err(PyValueError::new_err("counts must have shape (N, 3)"));
            }
            Input::Counts(c, scale)
        }
        (Some(_), None) => {
            return Err(PyValueError::new_err(
                "counts need a stream made with count_scale",
            ))
        }
        _ => {
            return Err(PyValueError::new_err(
                "a stream made with count_scale takes int16 counts",
            ))
        }
    };
    let n = match &input {
        Input::Rows(r) => r.len(),
        Input::Counts(c, _) => c.len(),
    };
    let accel = match &acc {
        Some(a) => {
            let (r, rest) = a.as_slice()?.as_chunks::<3>();
            if !rest.is_empty() || r.len() != n {
                return Err(PyValueError::new_err(
                    "acc must have shape (N, 3), N as gyr",
                ));
            }
            r
        }
        None => &[],
    };
    let temps = match &temperature {
        Some(a) => a.as_slice()?,
        None => &[],
    };
    if temperature.is_some() && temps.len() != n {
        return Err(PyValueError::new_err(
            "temperature must have shape (N,), N as gyr",
        ));
    }
    if (acc.is_some() || temperature.is_some()) && session.estimator.is_none() {
        return Err(PyValueError::new_err(
            "acc and temperature feed the bias estimator: make the stream with bias=BiasEstimator(...)",
        ));
    }
    if !(accel.iter().flatten().all(|e| e.is_finite()) && temps.iter().all(|e| e.is_finite())) {
        return Err(config_error(Error::NonFiniteAux));
    }
    let aux = Companions {
        accel,
        temperature: temps,
    };
    let seconds = match &t {
        Some(a) => a.as_slice()?,
        None => &[],
    };
    let tick_slice = match &ticks {
        Some(a) => a.as_slice()?,
        None => &[],
    };
    let given = match session.clock {
        Clock::Fixed(_) => t.is_none() && ticks.is_none(),
        Clock::Seconds { .. } => seconds.len() == n && ticks.is_none(),
        Clock::Ticks(_) => tick_slice.len() == n && t.is_none(),
    };
    if !given {
        return Err(PyValueError::new_err(
            "the timestamps do not match the stream's time base (none for a period, t[N] for seconds, ticks[N] for a tick clock)",
        ));
    }
    let (out, flags, result) = py.detach(|| {
        let mut out = vec![[T::ZERO; 4]; n];
        let mut flags = if mask { vec![false; n] } else { Vec::new() };
        let m = if mask { Some(&mut flags[..]) } else { None };
        let result = session.update(&input, &aux, seconds, tick_slice, &mut out, m);
        (out, flags, result)
    });
    let refused = result
        .err()
        .map(|r| (r.index, error_kind(&r.error), r.error.to_string()));
    let q = out.into_flattened().into_pyarray(py).reshape([n, 4])?;
    let flags = if mask {
        Some(flags.into_pyarray(py))
    } else {
        None
    };
    Ok((q, flags, refused))
}

fn quat4<T: Real>(q: Quat<T>) -> [f64; 4] {
    [q.w.to_f64(), q.x.to_f64(), q.y.to_f64(), q.z.to_f64()]
}

#[pymethods]
impl NativeStream {
    /// See `quatprop.Stream`: a stream in `precision` ("f32" or "f64") that flags refused samples
    /// (`mask`) or raises on the first; `args` already validated by the Python layer.
    #[new]
    fn new(precision: &str, mask: bool, args: StreamArgs) -> PyResult<Self> {
        let made = match precision {
            "f32" => Sessions::F32(Session::new(&args)?),
            "f64" => Sessions::F64(Session::new(&args)?),
            _ => {
                return Err(PyValueError::new_err(format!(
                    "unknown precision {precision:?}"
                )))
            }
        };
        Ok(Self {
            now: made,
            made,
            mask,
        })
    }

    /// Rows of samples into the stream: `arrays` as [`Arrays`] names them, in the stream's precision; the
    /// result as [`Updated`].
    fn update<'py>(
        &mut self,
        py: Python<'py>,
        arrays: Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        with_session!(&mut self.now, s => {
            update(py, s, self.mask, arrays.extract()?)?.into_bound_py_any(py)
        })
    }

    /// The attitude `[w, x, y, z]` after the last accepted sample.
    fn attitude(&self) -> [f64; 4] {
        with_session!(&self.now, s => quat4(s.p.attitude()))
    }

    /// The bias subtracted now (rad/s, body axes): the estimator's estimate (with the residual learned
    /// in motion, when it runs: both are subtracted) or the fixed bias.
    fn bias(&self) -> Option<[f64; 3]> {
        with_session!(&self.now, s => s.bias())
    }

    /// What `CalibrationEstimator` has learned: the correction as a calibration (offset rad/s,
    /// sensitivity, misalignment rows), the gain `I − G` (rows) and each of its terms' standard deviation;
    /// None without one.
    #[allow(clippy::type_complexity)]
    fn learned_calibration(&self) -> Option<(CalibrationArgs, [[f64; 3]; 3], [[f64; 3]; 3])> {
        with_session!(&self.now, s => s.learned_calibration())
    }

    /// The bias estimator's variance per axis ((rad/s)², `BiasEstimator::variance`: the last update's,
    /// grown by the drift since; `f64::MAX` before its first still window), or None without one.
    fn bias_variance(&self) -> Option<[f64; 3]> {
        with_session!(&self.now, s => s.bias_variance())
    }

    /// Steps taken, samples refused (skipped or raised), saturated samples counted.
    fn counts(&self) -> (u64, u64, u64) {
        with_session!(&self.now, s => (s.p.steps(), s.refused, s.p.saturated_samples()))
    }

    /// The sum of the refused delta angles `[x, y, z]` (rad, body axes): the rotation a refused
    /// increment took with it (a NaN or infinite one is not counted: its angle is unknown).
    fn lost_angle(&self) -> [f64; 3] {
        with_session!(&self.now, s => s.lost)
    }

    /// Replaces the attitude (normalized); the counters, the input model's samples and the clock stay.
    fn set_attitude(&mut self, q: [f64; 4]) -> PyResult<()> {
        with_session!(&mut self.now, s => s.p.set_attitude(quat(q))).map_err(config_error)
    }

    /// An estimator's attitude correction: `q ← q ⊗ exp(d)` (`body`) or `exp(d) ⊗ q` (rad).
    fn rotate(&mut self, d: [f64; 3], body: bool) -> PyResult<()> {
        with_session!(&mut self.now, s => {
            if body {
                s.p.rotate_body(vec3(d))
            } else {
                s.p.rotate_reference(vec3(d))
            }
        })
        .map_err(config_error)
    }

    /// An estimator's bias correction (rad/s): the fixed bias or the estimator's estimate moves by `d` (a
    /// fixed bias of `d` where there was none), and so do the samples the input model keeps; both or
    /// neither.
    fn correct_bias(&mut self, d: [f64; 3]) -> PyResult<()> {
        with_session!(&mut self.now, s => s.correct_bias(vec3(d))).map_err(config_error)
    }

    /// Back to the state it was made with.
    fn reset(&mut self) {
        self.now = self.made;
    }
}

fn error_kind(e: &Error) -> String {
    let debug = format!("{e:?}");
    debug
        .split([' ', '{', '('])
        .next()
        .unwrap_or("")
        .to_string()
}

fn parse_scheme(name: &str) -> PyResult<SchemeKind> {
    Ok(match name {
        "euler" => SchemeKind::Euler,
        "rk2" => SchemeKind::Rk2,
        "rk3" => SchemeKind::Rk3,
        "rk4" => SchemeKind::Rk4,
        "rk5" => SchemeKind::Rk5,
        "expmap" => SchemeKind::ExpMap,
        "magnus4" => SchemeKind::Magnus4,
        "cf4" => SchemeKind::Cf4,
        _ => return Err(PyValueError::new_err(format!("unknown scheme {name:?}"))),
    })
}

fn parse_stabilizer(name: &str, every: u32) -> PyResult<StabilizerKind> {
    Ok(match name {
        "off" => StabilizerKind::Off,
        "normalize" => StabilizerKind::Normalize,
        "first_order" => StabilizerKind::FirstOrder,
        "every" => StabilizerKind::Every(every),
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown stabilizer {name:?}"
            )))
        }
    })
}

fn parse_coning(name: &str) -> PyResult<ConingKind> {
    Ok(match name {
        "uncorrected" => ConingKind::Uncorrected,
        "one_plus_previous" => ConingKind::OnePlusPrevious,
        "two_sample" => ConingKind::TwoSample,
        "three_sample" => ConingKind::ThreeSample,
        "four_sample" => ConingKind::FourSample,
        "five_sample" => ConingKind::FiveSample,
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown coning correction {name:?}"
            )))
        }
    })
}

fn parse_input(name: &str, coning: &str) -> PyResult<InputKind> {
    Ok(match name {
        "hold" => InputKind::Hold,
        "linear" => InputKind::Linear,
        "history" => InputKind::History,
        "twice_rate" => InputKind::TwiceRate,
        "gauss_points" => InputKind::GaussPoints,
        "delta_angles" => InputKind::DeltaAngles(parse_coning(coning)?),
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown input model {name:?}"
            )))
        }
    })
}

fn axis_remap(name: &str) -> PyResult<AxisRemap> {
    AxisRemap::ALL
        .into_iter()
        .find(|r| format!("{r:?}") == name)
        .ok_or_else(|| {
            PyValueError::new_err(format!("unknown axis remap {name:?} (e.g. \"PyNxPz\")"))
        })
}

fn config_error(e: Error) -> PyErr {
    PyValueError::new_err(format!("{} ({})", e, error_kind(&e)))
}

/// A vector from Python's floats, in precision `T`.
fn vec3<T: Real>(v: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(v[0]), T::from_f64(v[1]), T::from_f64(v[2]))
}

/// A quaternion `[w, x, y, z]` from Python's floats, in precision `T`.
fn quat<T: Real>(q: [f64; 4]) -> Quat<T> {
    Quat::new(
        T::from_f64(q[0]),
        T::from_f64(q[1]),
        T::from_f64(q[2]),
        T::from_f64(q[3]),
    )
}

/// A vector as Python gets it.
fn f64x3<T: Real>(v: Vec3<T>) -> [f64; 3] {
    [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
}

/// A quaternion as a row `[w, x, y, z]`.
fn quat_row<T: Real>(q: Quat<T>) -> [T; 4] {
    [q.w, q.x, q.y, q.z]
}

/// A quaternion row `[w, x, y, z]` → aerospace Euler angles `[yaw, pitch, roll]`.
fn quat_to_euler_zyx<T: Real>([w, x, y, z]: [T; 4]) -> [T; 3] {
    let e = Quat::new(w, x, y, z).to_euler_zyx();
    [e.yaw, e.pitch, e.roll]
}

/// Aerospace Euler angles `[yaw, pitch, roll]` → a quaternion row.
fn euler_zyx_to_quat<T: Real>([yaw, pitch, roll]: [T; 3]) -> [T; 4] {
    quat_row(Quat::from_euler_zyx(EulerZyx { yaw, pitch, roll }))
}

/// A quaternion row `[w, x, y, z]` → classical Euler angles `[psi, theta, phi]`.
fn quat_to_euler_zxz<T: Real>([w, x, y, z]: [T; 4]) -> [T; 3] {
    let e = Quat::new(w, x, y, z).to_euler_zxz();
    [e.psi, e.theta, e.phi]
}

/// Classical Euler angles `[psi, theta, phi]` → a quaternion row.
fn euler_zxz_to_quat<T: Real>([psi, theta, phi]: [T; 3]) -> [T; 4] {
    quat_row(Quat::from_euler_zxz(EulerZxz { psi, theta, phi }))
}

fn map_rows<'py, T: Real + numpy::Element, const I: usize, const O: usize>(
    py: Python<'py>,
    a: PyReadonlyArray2<'py, T>,
    f: impl Fn([T; I]) -> [T; O] + Send + Sync,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let (rows, rest) = a.as_slice()?.as_chunks::<I>();
    if !rest.is_empty() {
        return Err(PyValueError::new_err(format!("expected shape (N, {I})")));
    }
    let n = rows.len();
    let out: Vec<[T; O]> = py.detach(|| rows.iter().map(|r| f(*r)).collect());
    out.into_flattened().into_pyarray(py).reshape([n, O])
}

/// Calibrated rates (N, 3): `M · (s ⊙ (r − o))` per row, the core's `Calibration::apply`.
fn calibrate<'py, T: Real + numpy::Element>(
    py: Python<'py>,
    gyr: PyReadonlyArray2<'py, T>,
    c: CalibrationArgs,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let cal = calibration::<T>(c).map_err(config_error)?;
    map_rows(py, gyr, |r: [T; 3]| {
        let w = cal.apply(GyroSample::new(Vec3::new(r[0], r[1], r[2]))).rate;
        [w.x, w.y, w.z]
    })
}

/// One noise term of a fit as Python gets it: the density, the coefficient and its standard error, whether
/// the curve shows it, and the density's interval at two standard errors.
fn term(t: &Term) -> (f64, f64, f64, bool, f64, f64) {
    let (lo, hi) = t.interval(2.0);
    (
        t.value(),
        t.coefficient,
        t.std_error,
        t.is_identified(),
        lo,
        hi,
    )
}

/// A fit as Python gets it: the three terms, the points fitted, the τ range and the misfit.
type FitTuple = (
    (f64, f64, f64, bool, f64, f64),
    (f64, f64, f64, bool, f64, f64),
    (f64, f64, f64, bool, f64, f64),
    u32,
    (f64, f64),
    f64,
);

fn fit_tuple(f: &NoiseFit) -> FitTuple {
    (
        term(&f.white),
        term(&f.instability),
        term(&f.random_walk),
        f.points,
        f.tau_range,
        f.misfit,
    )
}

/// The Allan variance of 3-axis samples at rest (N, 3), `dt` apart, at octave cluster times (the core's
/// `noise::AllanVariance`, 32 octaves: clusters of up to 2³¹ samples), and the noise fitted to the
/// clusters with τ ≥ `min_tau`, pooled over the axes and per axis (`noise::NoiseFit`). Returns (τ, the
/// variance per axis, the differences) per octave, the pooled fit, and the three per-axis fits (None
/// where too few points).
#[allow(clippy::type_complexity)]
#[pyfunction]
fn allan<'py>(
    py: Python<'py>,
    samples: PyReadonlyArray2<'py, f64>,
    dt: f64,
    min_tau: f64,
) -> PyResult<(
    Vec<(f64, [f64; 3], u32)>,
    Option<FitTuple>,
    [Option<FitTuple>; 3],
)> {
    let (rows, rest) = samples.as_slice()?.as_chunks::<3>();
    if !rest.is_empty() {
        return Err(PyValueError::new_err("expected shape (N, 3)"));
    }
    let avar = py
        .detach(|| -> Result<AllanVariance<f64, 32>, Error> {
            let mut a = AllanVariance::<f64, 32>::new(dt)?;
            for r in rows {
                a.push(Vec3::new(r[0], r[1], r[2]))?;
            }
            Ok(a)
        })
        .map_err(config_error)?;
    let clusters = avar
        .clusters()
        .map(|c| {
            (
                c.tau,
                [c.variance.x, c.variance.y, c.variance.z],
                c.differences,
            )
        })
        .collect();
    let pooled = NoiseFit::pooled_from(&avar, min_tau).map(|f| fit_tuple(&f));
    let axes = [0, 1, 2].map(|k| NoiseFit::axis(&avar, k, min_tau).map(|f| fit_tuple(&f)));
    Ok((clusters, pooled, axes))
}

/// The loop a Rust user writes for the default configuration (ExpMap, History, FirstOrder, plain
/// accumulator, a fixed period), with static types (compiled for each precision), on the same buffer;
/// timed in Rust. Returns the seconds it took (the output allocation included, as in `integrate`) and its
/// attitudes.
fn rust_loop<'py, T: Real + numpy::Element>(
    py: Python<'py>,
    gyr: PyReadonlyArray2<'py, T>,
    period: f64,
) -> PyResult<(f64, Bound<'py, PyArray2<T>>)> {
    let (rows, _) = gyr.as_slice()?.as_chunks::<3>();
    let n = rows.len();
    let (seconds, out) = py
        .detach(|| -> Result<(f64, Vec<[T; 4]>), Error> {
            let start = Instant::now();
            let mut period = FixedPeriod::<T>::new(period)?;
            let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)?;
            let mut out = vec![[T::ZERO; 4]; n];
            for (r, o) in rows.iter().zip(out.iter_mut()) {
                let dt = period.next_dt();
                if p.push(GyroSample::new(Vec3::new(r[0], r[1], r[2])), dt)
                    .is_err()
                {
                    period.carry_over(dt);
                }
                *o = quat_row(p.attitude());
            }
            Ok((start.elapsed().as_secs_f64(), out))
        })
        .map_err(config_error)?;
    Ok((
        seconds,
        out.into_flattened().into_pyarray(py).reshape([n, 4])?,
    ))
}

/// The module's functions of an array, one per line `name(array: precision, arguments) = generic(more)`:
/// pyo3 exports concrete signatures only, so each precision has its own function, which passes the array
/// (in that precision), its arguments and `more` to the generic function and returns what it returns.
/// `add_precision_fns` adds them all to the module.
macro_rules! precision_fns {
    ($($name:ident($a:ident: $t:ty $(, $arg:ident: $ty:ty)*) = $generic:ident($($more:expr),*);)*) => {
        $(
            #[pyfunction]
            fn $name<'py>(
                py: Python<'py>,
                $a: PyReadonlyArray2<'py, $t>,
                $($arg: $ty),*
            ) -> PyResult<Bound<'py, PyAny>> {
                $generic(py, $a $(, $arg)* $(, $more)*)?.into_bound_py_any(py)
            }
        )*

        fn add_precision_fns(m: &Bound<'_, PyModule>) -> PyResult<()> {
            $(m.add_function(wrap_pyfunction!($name, m)?)?;)*
            Ok(())
        }
    };
}

precision_fns! {
    calibrate_f32(gyr: f32, c: CalibrationArgs) = calibrate();
    calibrate_f64(gyr: f64, c: CalibrationArgs) = calibrate();
    to_euler_zyx_f32(q: f32) = map_rows(quat_to_euler_zyx);
    to_euler_zyx_f64(q: f64) = map_rows(quat_to_euler_zyx);
    from_euler_zyx_f32(e: f32) = map_rows(euler_zyx_to_quat);
    from_euler_zyx_f64(e: f64) = map_rows(euler_zyx_to_quat);
    to_euler_zxz_f32(q: f32) = map_rows(quat_to_euler_zxz);
    to_euler_zxz_f64(q: f64) = map_rows(quat_to_euler_zxz);
    from_euler_zxz_f32(e: f32) = map_rows(euler_zxz_to_quat);
    from_euler_zxz_f64(e: f64) = map_rows(euler_zxz_to_quat);
    rust_loop_f32(gyr: f32, period: f64) = rust_loop();
    rust_loop_f64(gyr: f64, period: f64) = rust_loop();
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeStream>()?;
    add_precision_fns(m)?;
    m.add_function(wrap_pyfunction!(allan, m)?)?;
    m.add(
        "AXIS_REMAPS",
        AxisRemap::ALL.map(|r| format!("{r:?}")).to_vec(),
    )?;
    Ok(())
}
