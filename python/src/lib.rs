//! `quatprop._native`: the extension behind the `quatprop` Python package.
//!
//! The Python layer (`pysrc/quatprop/__init__.py`) validates and converts the arguments; this module runs
//! the core library's own loop over the whole buffer with the GIL released. The configuration is the
//! core's run-time [`Config`]; the loop ([`Run`]) is a [`Visit`] of the [`Configured`] propagator it
//! builds, so it is compiled for each scheme × input model × accumulator, and for each precision and time
//! base: the inner loop is the code a Rust user writes with those types (the stabilizer and the coning
//! correction are the core's run-time enums, [`StabilizerKind`] and [`ConingKind`]).

// As in the core: `!(t > last)` is written so that a NaN lands in the error branch.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use std::time::Instant;

use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use quatprop::accumulate::Accumulator;
use quatprop::config::{AccumulatorKind, Config, Configured, InputKind, Visit};
use quatprop::frontend::{Alignment, AxisRemap, BiasEstimator, FixedBias, FixedPeriod, TickClock};
use quatprop::input::coning::ConingKind;
use quatprop::input::{History, InputModel};
use quatprop::scheme::{ExpMap, Scheme, SchemeKind};
use quatprop::stabilize::{FirstOrder, Stabilizer, StabilizerKind};
use quatprop::{
    DeltaAngle, Error, EulerZxz, EulerZyx, GyroSample, Propagator, Quat, Real, Refused, Vec3,
};

/// A sample type built from one row `[x, y, z]` of the input buffer.
trait FromRow<T>: Copy {
    fn from_row(r: [T; 3]) -> Self;
}

impl<T: Real> FromRow<T> for GyroSample<T> {
    #[inline(always)]
    fn from_row(r: [T; 3]) -> Self {
        GyroSample::new(Vec3::new(r[0], r[1], r[2]))
    }
}

impl<T: Real> FromRow<T> for DeltaAngle<T> {
    #[inline(always)]
    fn from_row(r: [T; 3]) -> Self {
        DeltaAngle::new(Vec3::new(r[0], r[1], r[2]))
    }
}

/// Where each sample's `dt` comes from. One value per call, matched per sample, so that each
/// propagator type has one call site of `push` and the compiler inlines it into the loop (with one
/// loop per time base it did not, and `integrate` took 1.3x to 1.6x the same Rust loop).
#[derive(Clone, Copy)]
enum Time<'a, T> {
    /// A fixed period: the core's [`FixedPeriod`], exactly as [`Propagator::push_burst`] uses it.
    Fixed(FixedPeriod<T>),
    /// Timestamps in seconds (f64). The first accepted sample starts the stream (`Propagator::start`);
    /// each later one is pushed with `dt = T(t_k − t_last + carry)`, where `t_last` is the last
    /// *accepted* timestamp and `carry` (f64) the part of the previous intervals that rounding to `T`
    /// left out. So the `dt`s sum to `t_last − t_first` within half an ulp of one `dt` (in f64 the carry
    /// stays zero and `dt = t_k − t_last` as computed in f64, exact by Sterbenz whenever
    /// `t_last ≥ t_k / 2`).
    Seconds {
        stamps: &'a [f64],
        last: Option<f64>,
        carry: f64,
    },
    /// Integer timestamps: the core's [`TickClock`], exactly as [`Propagator::push_burst_timed`] uses it.
    Ticks {
        stamps: &'a [u32],
        clock: TickClock<T>,
    },
}

impl<T: Real> Time<'_, T> {
    /// How many samples it has times for (`None`: any number).
    fn len(&self) -> Option<usize> {
        match self {
            Time::Fixed(_) => None,
            Time::Seconds { stamps, .. } => Some(stamps.len()),
            Time::Ticks { stamps, .. } => Some(stamps.len()),
        }
    }

    /// Sample `i`'s interval, the time base advanced past it: `Some(dt)`, or `None` for the first
    /// timestamp of a stream (its sample starts the stream). On error nothing changed.
    #[inline(always)]
    fn advance(&mut self, i: usize) -> Result<Option<T>, Error> {
        match self {
            Time::Fixed(period) => Ok(Some(period.next_dt())),
            Time::Seconds {
                stamps,
                last,
                carry,
            } => {
                let t = stamps.get(i).copied().unwrap_or(f64::NAN);
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
            Time::Ticks { stamps, clock } => {
                let tick = stamps.get(i).copied().unwrap_or(0);
                let (next, dt) = clock.advance(tick)?;
                *clock = next;
                Ok(dt)
            }
        }
    }

    /// After a refused sample (`before`: the time base before it): the next interval covers the refused
    /// one. A period gives the interval back ([`FixedPeriod::carry_over`]); timestamps count from the
    /// last accepted one.
    #[inline(always)]
    fn refused(&mut self, dt: Option<T>, before: Self) {
        match self {
            Time::Fixed(period) => {
                if let Some(dt) = dt {
                    period.carry_over(dt);
                }
            }
            _ => *self = before,
        }
    }
}

/// The loop: every sample into the propagator, its attitude after every sample into `out`. A refused
/// sample either stops the loop (`mask` is `None`) or is flagged and skipped, the state as after the last
/// accepted sample and its interval carried into the next one. It runs on a copy of the propagator in
/// this frame, written back at the end, as the core's bursts do: behind the `&mut` the state would go
/// through memory at every step.
#[inline(always)]
fn run<T, S, I, Z, A>(
    prop: &mut Propagator<T, S, I, Z, A>,
    mut time: Time<'_, T>,
    rows: &[[T; 3]],
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
    let n = time.len().map_or(rows.len(), |n| n.min(rows.len()));
    let mut result = Ok(());
    for (index, (row, o)) in rows[..n].iter().zip(out.iter_mut()).enumerate() {
        let before = time;
        let sample = I::Sample::from_row(*row);
        let pushed = time.advance(index).and_then(|dt| {
            match dt {
                Some(dt) => p.push(sample, dt),
                None => p.start(sample),
            }
            .inspect_err(|_| time.refused(dt, before))
        });
        if let Err(error) = pushed {
            match mask.as_deref_mut().and_then(|m| m.get_mut(index)) {
                Some(m) => *m = true,
                None => {
                    result = Err(Refused { index, error });
                    break;
                }
            }
        }
        let q = p.attitude();
        *o = [q.w, q.x, q.y, q.z];
    }
    *prop = local;
    result
}

/// [`run`] as a [`Visit`] of the configured propagator: compiled for each scheme × input model ×
/// accumulator and precision.
struct Run<'a, T> {
    time: Time<'a, T>,
    rows: &'a [[T; 3]],
    out: &'a mut [[T; 4]],
    mask: Option<&'a mut [bool]>,
}

impl<T: Real> Visit<T> for Run<'_, T> {
    type Output = Result<(), Refused>;
    fn rates<S, I, A>(self, p: &mut Propagator<T, S, I, StabilizerKind, A>) -> Self::Output
    where
        S: Scheme<T>,
        I: InputModel<T, Sample = GyroSample<T>>,
        A: Accumulator<T>,
    {
        run(p, self.time, self.rows, self.out, self.mask)
    }
    fn deltas<S, I, A>(self, p: &mut Propagator<T, S, I, StabilizerKind, A>) -> Self::Output
    where
        S: Scheme<T>,
        I: InputModel<T, Sample = DeltaAngle<T>>,
        A: Accumulator<T>,
    {
        run(p, self.time, self.rows, self.out, self.mask)
    }
}

#[derive(Clone, Copy)]
enum TimeSel<'a> {
    Fixed(f64),
    Seconds(&'a [f64]),
    Ticks(&'a [u32], f64, u32),
}

#[derive(Clone, Copy)]
enum BiasSel<T> {
    None,
    Fixed(Vec3<T>),
    Estimator {
        window: u32,
        gate: T,
        memory: u32,
        initial: Option<Vec3<T>>,
    },
}

/// One call of `integrate`: the propagator's configuration and what the binding adds around it.
struct Job<'a, T> {
    config: Config,
    q0: Quat<T>,
    time: TimeSel<'a>,
    alignment: Option<Alignment<T>>,
    bias: BiasSel<T>,
}

/// What went wrong before the loop (a bad configuration) or in it (a refused sample).
enum Failure {
    Config(Error),
    Refused(Refused),
}

/// The front end, applied to every sample before the loop: alignment (sensor to body axes), then the
/// bias (in body axes), exactly as the README's quick start composes them per sample. A sample the bias
/// estimator refuses (NaN) is passed on unchanged, so the propagator refuses it too.
fn front_end<T: Real>(
    rows: &[[T; 3]],
    alignment: Option<Alignment<T>>,
    bias: BiasSel<T>,
) -> Result<Vec<[T; 3]>, Error> {
    let mut fixed = None;
    let mut estimator = None;
    match bias {
        BiasSel::None => {}
        BiasSel::Fixed(b) => fixed = Some(FixedBias::new(b)?),
        BiasSel::Estimator {
            window,
            gate,
            memory,
            initial,
        } => {
            let e = BiasEstimator::from_samples(window, gate, memory)?;
            estimator = Some(match initial {
                Some(b) => e.with_initial(b)?,
                None => e,
            });
        }
    }
    Ok(rows
        .iter()
        .map(|r| {
            let mut s = GyroSample::<T>::from_row(*r);
            if let Some(a) = &alignment {
                s = a.apply(s);
            }
            if let Some(b) = &fixed {
                s = b.apply(s);
            }
            if let Some(e) = estimator.as_mut() {
                s = e.update(s).unwrap_or(s);
            }
            [s.rate.x, s.rate.y, s.rate.z]
        })
        .collect())
}

fn integrate_impl<T: Real>(
    cfg: &Job<'_, T>,
    rows: &[[T; 3]],
    out: &mut [[T; 4]],
    mask: Option<&mut [bool]>,
) -> Result<(), Failure> {
    let processed;
    let rows = if cfg.alignment.is_some() || !matches!(cfg.bias, BiasSel::None) {
        processed = front_end(rows, cfg.alignment, cfg.bias).map_err(Failure::Config)?;
        &processed[..]
    } else {
        rows
    };
    let mut p: Configured<T> = cfg.config.build(cfg.q0).map_err(Failure::Config)?;
    let time = match cfg.time {
        TimeSel::Fixed(period) => Time::Fixed(FixedPeriod::new(period).map_err(Failure::Config)?),
        TimeSel::Seconds(stamps) => Time::Seconds {
            stamps,
            last: None,
            carry: 0.0,
        },
        TimeSel::Ticks(stamps, frequency, bits) => Time::Ticks {
            stamps,
            clock: TickClock::new(frequency, bits).map_err(Failure::Config)?,
        },
    };
    p.visit(Run {
        time,
        rows,
        out,
        mask,
    })
    .map_err(Failure::Refused)
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

fn vec3<T: Real>(v: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(v[0]), T::from_f64(v[1]), T::from_f64(v[2]))
}

/// The refused sample, if any: `(index, kind, reason)`.
type RefusedInfo = Option<(usize, String, String)>;

macro_rules! integrate_fn {
    ($name:ident, $t:ty) => {
        /// See `quatprop.integrate`; arguments already validated by the Python layer.
        #[pyfunction]
        #[pyo3(signature = (gyr, period, t, ticks, tick_hz, tick_bits, scheme, stabilizer, every, input, coning,
            kahan, q0, mask, remap, matrix, bias, estimator))]
        #[allow(clippy::too_many_arguments)]
        fn $name<'py>(
            py: Python<'py>,
            gyr: PyReadonlyArray2<'py, $t>,
            period: Option<f64>,
            t: Option<PyReadonlyArray1<'py, f64>>,
            ticks: Option<PyReadonlyArray1<'py, u32>>,
            tick_hz: f64,
            tick_bits: u32,
            scheme: &str,
            stabilizer: &str,
            every: u32,
            input: &str,
            coning: &str,
            kahan: bool,
            q0: [f64; 4],
            mask: bool,
            remap: Option<&str>,
            matrix: Option<[[f64; 3]; 3]>,
            bias: Option<[f64; 3]>,
            estimator: Option<(u32, f64, u32, Option<[f64; 3]>)>,
        ) -> PyResult<(Bound<'py, PyArray2<$t>>, Option<Bound<'py, PyArray1<bool>>>, RefusedInfo)> {
            let flat = gyr.as_slice()?;
            let (rows, rest) = flat.as_chunks::<3>();
            if !rest.is_empty() {
                return Err(PyValueError::new_err("gyr must have shape (N, 3)"));
            }
            let n = rows.len();
            let t_slice = match &t {
                Some(a) => Some(a.as_slice()?),
                None => None,
            };
            let tick_slice = match &ticks {
                Some(a) => Some(a.as_slice()?),
                None => None,
            };
            let time = match (period, t_slice, tick_slice) {
                (Some(p), None, None) => TimeSel::Fixed(p),
                (None, Some(ts), None) if ts.len() == n => TimeSel::Seconds(ts),
                (None, None, Some(ts)) if ts.len() == n => TimeSel::Ticks(ts, tick_hz, tick_bits),
                _ => return Err(PyValueError::new_err("give exactly one of dt, t[N], ticks[N]")),
            };
            let alignment = match (remap, matrix) {
                (Some(r), None) => Some(Alignment::from(axis_remap(r)?)),
                (None, Some(m)) => Some(
                    Alignment::from_matrix(m.map(|row| row.map(<$t>::from_f64))).map_err(config_error)?,
                ),
                (None, None) => None,
                _ => return Err(PyValueError::new_err("give alignment as a remap name or a matrix, not both")),
            };
            let bias = match (bias, estimator) {
                (None, None) => BiasSel::None,
                (Some(b), None) => BiasSel::Fixed(vec3(b)),
                (None, Some((window, gate, memory, initial))) => BiasSel::Estimator {
                    window,
                    gate: <$t>::from_f64(gate),
                    memory,
                    initial: initial.map(vec3),
                },
                _ => return Err(PyValueError::new_err("give a fixed bias or an estimator, not both")),
            };
            let cfg = Job {
                config: Config {
                    scheme: parse_scheme(scheme)?,
                    baumgarte_gain: None,
                    input: parse_input(input, coning)?,
                    stabilizer: parse_stabilizer(stabilizer, every)?,
                    accumulator: if kahan { AccumulatorKind::Kahan } else { AccumulatorKind::Plain },
                },
                q0: Quat::new(
                    <$t>::from_f64(q0[0]),
                    <$t>::from_f64(q0[1]),
                    <$t>::from_f64(q0[2]),
                    <$t>::from_f64(q0[3]),
                ),
                time,
                alignment,
                bias,
            };
            let (out, flags, result) = py.detach(|| {
                let mut out = vec![[0.0 as $t; 4]; n];
                let mut flags = if mask { vec![false; n] } else { Vec::new() };
                let m = if mask { Some(&mut flags[..]) } else { None };
                let result = integrate_impl(&cfg, rows, &mut out, m);
                (out, flags, result)
            });
            let refused = match result {
                Ok(()) => None,
                Err(Failure::Config(e)) => return Err(config_error(e)),
                Err(Failure::Refused(r)) => Some((r.index, error_kind(&r.error), r.error.to_string())),
            };
            let q = out.into_flattened().into_pyarray(py).reshape([n, 4])?;
            let flags = if mask { Some(flags.into_pyarray(py)) } else { None };
            Ok((q, flags, refused))
        }
    };
}

integrate_fn!(integrate_f32, f32);
integrate_fn!(integrate_f64, f64);

macro_rules! euler_fns {
    ($to_zyx:ident, $from_zyx:ident, $to_zxz:ident, $from_zxz:ident, $t:ty) => {
        /// Quaternions (N, 4) → aerospace Euler angles (N, 3) = (yaw, pitch, roll).
        #[pyfunction]
        fn $to_zyx<'py>(
            py: Python<'py>,
            q: PyReadonlyArray2<'py, $t>,
        ) -> PyResult<Bound<'py, PyArray2<$t>>> {
            map_rows::<$t, 4, 3>(py, q, |[w, x, y, z]| {
                let e = Quat::new(w, x, y, z).to_euler_zyx();
                [e.yaw, e.pitch, e.roll]
            })
        }
        /// Aerospace Euler angles (N, 3) = (yaw, pitch, roll) → quaternions (N, 4).
        #[pyfunction]
        fn $from_zyx<'py>(
            py: Python<'py>,
            e: PyReadonlyArray2<'py, $t>,
        ) -> PyResult<Bound<'py, PyArray2<$t>>> {
            map_rows::<$t, 3, 4>(py, e, |[yaw, pitch, roll]| {
                let q = Quat::from_euler_zyx(EulerZyx { yaw, pitch, roll });
                [q.w, q.x, q.y, q.z]
            })
        }
        /// Quaternions (N, 4) → classical Euler angles (N, 3) = (psi, theta, phi).
        #[pyfunction]
        fn $to_zxz<'py>(
            py: Python<'py>,
            q: PyReadonlyArray2<'py, $t>,
        ) -> PyResult<Bound<'py, PyArray2<$t>>> {
            map_rows::<$t, 4, 3>(py, q, |[w, x, y, z]| {
                let e = Quat::new(w, x, y, z).to_euler_zxz();
                [e.psi, e.theta, e.phi]
            })
        }
        /// Classical Euler angles (N, 3) = (psi, theta, phi) → quaternions (N, 4).
        #[pyfunction]
        fn $from_zxz<'py>(
            py: Python<'py>,
            e: PyReadonlyArray2<'py, $t>,
        ) -> PyResult<Bound<'py, PyArray2<$t>>> {
            map_rows::<$t, 3, 4>(py, e, |[psi, theta, phi]| {
                let q = Quat::from_euler_zxz(EulerZxz { psi, theta, phi });
                [q.w, q.x, q.y, q.z]
            })
        }
    };
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

euler_fns!(
    to_euler_zyx_f32,
    from_euler_zyx_f32,
    to_euler_zxz_f32,
    from_euler_zxz_f32,
    f32
);
euler_fns!(
    to_euler_zyx_f64,
    from_euler_zyx_f64,
    to_euler_zxz_f64,
    from_euler_zxz_f64,
    f64
);

/// The loop a Rust user writes for the default configuration (ExpMap, History, FirstOrder, plain
/// accumulator, a fixed period), with concrete types, on the same buffer; timed in Rust. Returns the
/// seconds it took (the output allocation included, as in `integrate`) and its attitudes.
macro_rules! rust_loop_fn {
    ($name:ident, $t:ty) => {
        #[pyfunction]
        fn $name<'py>(
            py: Python<'py>,
            gyr: PyReadonlyArray2<'py, $t>,
            period: f64,
        ) -> PyResult<(f64, Bound<'py, PyArray2<$t>>)> {
            let (rows, _) = gyr.as_slice()?.as_chunks::<3>();
            let n = rows.len();
            let (seconds, out) = py
                .detach(|| -> Result<(f64, Vec<[$t; 4]>), Error> {
                    let start = Instant::now();
                    let mut period = FixedPeriod::<$t>::new(period)?;
                    let mut p =
                        Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)?;
                    let mut out = vec![[0.0; 4]; n];
                    for (r, o) in rows.iter().zip(out.iter_mut()) {
                        let dt = period.next_dt();
                        if p.push(GyroSample::new(Vec3::new(r[0], r[1], r[2])), dt)
                            .is_err()
                        {
                            period.carry_over(dt);
                        }
                        let q = p.attitude();
                        *o = [q.w, q.x, q.y, q.z];
                    }
                    Ok((start.elapsed().as_secs_f64(), out))
                })
                .map_err(config_error)?;
            Ok((
                seconds,
                out.into_flattened().into_pyarray(py).reshape([n, 4])?,
            ))
        }
    };
}

rust_loop_fn!(rust_loop_f32, f32);
rust_loop_fn!(rust_loop_f64, f64);

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(integrate_f32, m)?)?;
    m.add_function(wrap_pyfunction!(integrate_f64, m)?)?;
    m.add_function(wrap_pyfunction!(to_euler_zyx_f32, m)?)?;
    m.add_function(wrap_pyfunction!(from_euler_zyx_f32, m)?)?;
    m.add_function(wrap_pyfunction!(to_euler_zxz_f32, m)?)?;
    m.add_function(wrap_pyfunction!(from_euler_zxz_f32, m)?)?;
    m.add_function(wrap_pyfunction!(to_euler_zyx_f64, m)?)?;
    m.add_function(wrap_pyfunction!(from_euler_zyx_f64, m)?)?;
    m.add_function(wrap_pyfunction!(to_euler_zxz_f64, m)?)?;
    m.add_function(wrap_pyfunction!(from_euler_zxz_f64, m)?)?;
    m.add_function(wrap_pyfunction!(rust_loop_f32, m)?)?;
    m.add_function(wrap_pyfunction!(rust_loop_f64, m)?)?;
    m.add(
        "AXIS_REMAPS",
        AxisRemap::ALL.map(|r| format!("{r:?}")).to_vec(),
    )?;
    Ok(())
}
