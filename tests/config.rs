//! The run-time configuration (`quatprop::config`): validation, and every configuration bit for bit the
//! static types it stands for, one sample at a time and in bursts, refusals included.

use quatprop::accumulate::{Accumulator, FloatFloat, Kahan, Plain};
use quatprop::config::{
    AccumulatorKind, Config, Configured, DeltaModel, InputKind, RateModel, Visit, Visited,
};
use quatprop::frontend::{FixedPeriod, TickClock};
use quatprop::input::coning::ConingKind;
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::scheme::{Baumgarte, Rk3, Scheme, SchemeKind};
use quatprop::stabilize::{Stabilizer, StabilizerKind};
use quatprop::{DeltaAngle, Error, GyroSample, Propagator, Quat, Real, Refused, Vec3};

const INPUTS: [InputKind; 11] = [
    InputKind::Hold,
    InputKind::Linear,
    InputKind::History,
    InputKind::TwiceRate,
    InputKind::GaussPoints,
    InputKind::DeltaAngles(ConingKind::Uncorrected),
    InputKind::DeltaAngles(ConingKind::OnePlusPrevious),
    InputKind::DeltaAngles(ConingKind::TwoSample),
    InputKind::DeltaAngles(ConingKind::ThreeSample),
    InputKind::DeltaAngles(ConingKind::FourSample),
    InputKind::DeltaAngles(ConingKind::FiveSample),
];
const STABILIZERS: [StabilizerKind; 4] = [
    StabilizerKind::Off,
    StabilizerKind::Normalize,
    StabilizerKind::FirstOrder,
    StabilizerKind::Every(3),
];
const ACCUMULATORS: [AccumulatorKind; 3] = [
    AccumulatorKind::Plain,
    AccumulatorKind::Kahan,
    AccumulatorKind::FloatFloat,
];

/// Every configuration: each scheme (the Runge–Kutta ones also with Baumgarte's term) × input × stabilizer
/// × accumulator.
fn every_config() -> Vec<Config> {
    let mut all = Vec::new();
    for scheme in SchemeKind::ALL {
        let rk = scheme.information().real_axis_limit.is_finite();
        let gains: &[Option<f64>] = if rk { &[None, Some(0.5)] } else { &[None] };
        for &baumgarte_gain in gains {
            for input in INPUTS {
                for stabilizer in STABILIZERS {
                    for accumulator in ACCUMULATORS {
                        all.push(Config {
                            scheme,
                            baumgarte_gain,
                            input,
                            stabilizer,
                            accumulator,
                        });
                    }
                }
            }
        }
    }
    all
}

/// A coning motion at 400 Hz (incommensurate frequencies), with a NaN at sample 7 and a step angle far
/// beyond every bounded scheme at sample 23.
fn rates<T: Real>() -> Vec<Vec3<T>> {
    (0..60)
        .map(|k| {
            let t = k as f64 * 2.5e-3;
            let mut w = [
                0.7 * (7.3 * t).sin(),
                0.7 * (7.3 * t).cos(),
                0.2 + 0.3 * (1.9 * t).sin(),
            ];
            if k == 7 {
                w[1] = f64::NAN;
            }
            if k == 23 {
                w[0] = 5.0e3;
            }
            Vec3::new(T::from_f64(w[0]), T::from_f64(w[1]), T::from_f64(w[2]))
        })
        .collect()
}

const DT: f64 = 2.5e-3;

/// A burst through `Configured::visit_compact` (scheme matched per step), for the rates or the deltas.
struct CompactBurst<'a, T> {
    rates: &'a [GyroSample<T>],
    deltas: &'a [DeltaAngle<T>],
    period: &'a mut FixedPeriod<T>,
}

// Both loops spelled out with their bounds: they are `Visit`'s signatures, which every implementation
// repeats (the C API's and the firmware's too).
impl<T: Real> Visit<T> for CompactBurst<'_, T> {
    type Output = Result<usize, Refused>;
    fn rates<S: Scheme<T>, I: RateModel<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        p.push_burst(self.rates, self.period)
    }
    fn deltas<S: Scheme<T>, I: DeltaModel<T>, A: Accumulator<T>>(
        self,
        p: &mut Visited<T, S, I, A>,
    ) -> Self::Output {
        p.push_burst(self.deltas, self.period)
    }
}

/// The static propagator a configuration stands for, fed one sample at a time: its attitude, counters and
/// the refused indices. The scheme is the run-time `SchemeKind` (or Baumgarte on the static Runge–Kutta
/// type), whose arithmetic is the static scheme's.
fn reference<T: Real>(c: &Config, q0: Quat<T>) -> (Quat<T>, Quat<T>, [u64; 3], Vec<usize>) {
    fn run<T: Real, S: Scheme<T>, I: InputModel<T>, A: Accumulator<T>>(
        p: Propagator<T, S, I, StabilizerKind, A>,
        sample: impl Fn(Vec3<T>) -> I::Sample,
        low: impl Fn(&A) -> Quat<T>,
    ) -> (Quat<T>, Quat<T>, [u64; 3], Vec<usize>) {
        let mut p = p;
        let mut refused = Vec::new();
        for (k, w) in rates::<T>().into_iter().enumerate() {
            if p.push(sample(w), T::from_f64(DT)).is_err() {
                refused.push(k);
            }
        }
        let counters = [p.steps(), p.corrections(), p.saturated_samples()];
        (p.attitude(), low(&p.accumulator()), counters, refused)
    }
    fn with_acc<T: Real, S: Scheme<T>, I: InputModel<T>>(
        c: &Config,
        q0: Quat<T>,
        s: S,
        i: I,
        sample: impl Fn(Vec3<T>) -> I::Sample,
    ) -> (Quat<T>, Quat<T>, [u64; 3], Vec<usize>) {
        let p = Propagator::new(q0, s, i, c.stabilizer).unwrap();
        match c.accumulator {
            AccumulatorKind::Plain => run(p.with_accumulator(Plain), sample, |_| Quat::ZERO),
            AccumulatorKind::Kahan => run(p.with_accumulator(Kahan::new()), sample, |_| Quat::ZERO),
            AccumulatorKind::FloatFloat => {
                run(p.with_accumulator(FloatFloat::new()), sample, |a| a.low())
            }
        }
    }
    fn with_input<T: Real, S: Scheme<T>>(
        c: &Config,
        q0: Quat<T>,
        s: S,
    ) -> (Quat<T>, Quat<T>, [u64; 3], Vec<usize>) {
        let gyro = |w| GyroSample::new(w);
        match c.input {
            InputKind::Hold => with_acc(c, q0, s, Hold::new(), gyro),
            InputKind::Linear => with_acc(c, q0, s, Linear::new(), gyro),
            InputKind::History => with_acc(c, q0, s, History::new(), gyro),
            InputKind::TwiceRate => with_acc(c, q0, s, TwiceRate::new(), gyro),
            InputKind::GaussPoints => with_acc(c, q0, s, GaussPoints::new(), gyro),
            InputKind::DeltaAngles(k) => with_acc(c, q0, s, DeltaAngles::new(k), |w| {
                DeltaAngle::new(w * T::from_f64(DT))
            }),
        }
    }
    match c.baumgarte_gain {
        None => with_input(c, q0, c.scheme),
        Some(k) => {
            let k = T::from_f64(k);
            match c.scheme {
                SchemeKind::Euler => {
                    with_input(c, q0, Baumgarte::new(quatprop::scheme::Euler, k).unwrap())
                }
                SchemeKind::Rk2 => {
                    with_input(c, q0, Baumgarte::new(quatprop::scheme::Rk2, k).unwrap())
                }
                SchemeKind::Rk3 => with_input(c, q0, Baumgarte::new(Rk3, k).unwrap()),
                SchemeKind::Rk4 => {
                    with_input(c, q0, Baumgarte::new(quatprop::scheme::Rk4, k).unwrap())
                }
                SchemeKind::Rk5 => {
                    with_input(c, q0, Baumgarte::new(quatprop::scheme::Rk5, k).unwrap())
                }
                _ => unreachable!("validated"),
            }
        }
    }
}

/// Every configuration one sample at a time against its static types; with `bursts`, also in bursts
/// (`push_burst`, `visit_compact`) against single pushes.
fn check_every_config<T: Real>(bursts: bool) {
    let q0 = Quat::new(
        T::from_f64(0.9),
        T::from_f64(0.1),
        T::from_f64(-0.3),
        T::from_f64(0.2),
    );
    let rates = rates::<T>();
    let mut checked = 0;
    for c in every_config() {
        let (q_ref, low_ref, counters_ref, refused_ref) = reference(&c, q0);
        let delta = c.takes_delta_angles();
        let dt = T::from_f64(DT);
        // One sample at a time.
        let mut p: Configured<T> = c.build(q0).unwrap();
        assert_eq!(p.config(), c);
        let mut refused = Vec::new();
        for (k, &w) in rates.iter().enumerate() {
            let before = p;
            let r = if delta {
                p.push(DeltaAngle::new(w * dt), dt)
            } else {
                p.push(GyroSample::new(w), dt)
            };
            if r.is_err() {
                assert_eq!(p, before, "{c:?}: a refused sample changed the state");
                refused.push(k);
            }
        }
        let counters = [p.steps(), p.corrections(), p.saturated_samples()];
        assert_eq!(
            (p.attitude(), p.attitude_low(), counters, &refused),
            (q_ref, low_ref, counters_ref, &refused_ref),
            "{c:?}"
        );
        checked += 1;
        if !bursts {
            continue;
        }
        // In bursts of 5 at a fixed period: after a refusal, the rest of the burst.
        let mut b: Configured<T> = c.build(q0).unwrap();
        let mut period = FixedPeriod::<T>::new(DT).unwrap();
        let gyro: Vec<GyroSample<T>> = rates.iter().map(|&w| GyroSample::new(w)).collect();
        let deltas: Vec<DeltaAngle<T>> = rates.iter().map(|&w| DeltaAngle::new(w * dt)).collect();
        let mut compact: Configured<T> = c.build(q0).unwrap();
        let mut compact_period = FixedPeriod::<T>::new(DT).unwrap();
        let mut burst_refused = Vec::new();
        let mut at = 0;
        while at < rates.len() {
            let end = (at + 5).min(rates.len());
            let r = if delta {
                b.push_burst(&deltas[at..end], &mut period)
            } else {
                b.push_burst(&gyro[at..end], &mut period)
            };
            let rc = compact.visit_compact(CompactBurst {
                rates: &gyro[at..end],
                deltas: &deltas[at..end],
                period: &mut compact_period,
            });
            assert_eq!((r, compact_period), (rc, period), "{c:?}: compact");
            match r {
                Ok(n) => at += n,
                Err(Refused { index, .. }) => {
                    burst_refused.push(at + index);
                    at += index + 1;
                }
            }
        }
        // The period carries a refused interval into the next sample's dt (the single pushes above did
        // not), so only the refusals and the counters must agree, and the bits with the period's own
        // single-sample loop.
        assert_eq!(burst_refused, refused_ref, "{c:?}");
        let mut s: Configured<T> = c.build(q0).unwrap();
        let mut period = FixedPeriod::<T>::new(DT).unwrap();
        for k in 0..rates.len() {
            let dt = period.next_dt();
            let r = if delta {
                s.push(deltas[k], dt)
            } else {
                s.push(gyro[k], dt)
            };
            if r.is_err() {
                period.carry_over(dt);
            }
        }
        assert_eq!(s, b, "{c:?}: bursts differ from single pushes");
        assert_eq!(compact, b, "{c:?}: visit_compact differs from visit");
    }
    // 3 exponential maps + 5 Runge–Kutta × 2 = 13 schemes × 11 inputs × 4 stabilizers × 3 accumulators.
    assert_eq!(checked, 13 * 11 * 4 * 3);
}

#[test]
fn every_config_is_its_static_types_bit_for_bit_f32() {
    check_every_config::<f32>(true);
}

/// f64 one sample at a time (the bursts' code is the same generic code as f32's; compiling it for f64
/// too doubles this test's build).
#[test]
fn every_config_is_its_static_types_bit_for_bit_f64() {
    check_every_config::<f64>(false);
}

#[test]
fn invalid_configurations_are_refused_with_their_error() {
    let q0 = Quat::<f32>::IDENTITY;
    let bad = |c: Config| c.build(q0).err();
    let every0 = Config {
        stabilizer: StabilizerKind::Every(0),
        ..Config::RECOMMENDED
    };
    assert_eq!(bad(every0), Some(Error::InvalidStabilizer));
    let exp_gain = Config {
        baumgarte_gain: Some(0.5),
        ..Config::RECOMMENDED
    };
    assert_eq!(bad(exp_gain), Some(Error::BaumgarteNeedsRungeKutta));
    for k in [-1.0, f64::NAN, f64::INFINITY] {
        let c = Config {
            scheme: SchemeKind::Rk4,
            baumgarte_gain: Some(k),
            ..Config::RECOMMENDED
        };
        assert_eq!(bad(c), Some(Error::InvalidGain), "{k}");
    }
    // Finite in f64, infinite in f32.
    let huge = Config {
        scheme: SchemeKind::Rk4,
        baumgarte_gain: Some(1e300),
        ..Config::RECOMMENDED
    };
    assert_eq!(bad(huge), Some(Error::InvalidGain));
    assert!(huge.build(Quat::<f64>::IDENTITY).is_ok());
    assert_eq!(
        Config::RECOMMENDED
            .build(Quat::<f32>::new(0.0, 0.0, 0.0, 0.0))
            .err(),
        Some(Error::ZeroQuaternion)
    );
    assert_eq!(
        Config::RECOMMENDED
            .build(Quat::<f32>::new(f32::NAN, 0.0, 0.0, 0.0))
            .err(),
        Some(Error::NonFiniteQuaternion)
    );
    assert_eq!(Config::default(), Config::RECOMMENDED);
}

#[test]
fn a_sample_of_the_other_kind_is_refused_and_changes_nothing() {
    let w = Vec3::new(0.1_f32, 0.2, 0.3);
    let mut rate = Config::RECOMMENDED.build(Quat::IDENTITY).unwrap();
    rate.push(GyroSample::new(w), 1e-3).unwrap();
    let before = rate;
    assert_eq!(
        rate.push(DeltaAngle::new(w), 1e-3),
        Err(Error::WrongSampleKind)
    );
    assert_eq!(rate.start(DeltaAngle::new(w)), Err(Error::WrongSampleKind));
    let mut period = FixedPeriod::new(1e-3).unwrap();
    let period_before = period;
    assert_eq!(
        rate.push_burst(&[DeltaAngle::new(w); 3], &mut period),
        Err(Refused {
            index: 0,
            error: Error::WrongSampleKind
        })
    );
    assert_eq!(rate.push_burst::<DeltaAngle<f32>>(&[], &mut period), Ok(0));
    let mut clock = TickClock::new(1e6, 32).unwrap();
    let clock_before = clock;
    assert_eq!(
        rate.push_burst_timed(&[(DeltaAngle::new(w), 5)], &mut clock),
        Err(Refused {
            index: 0,
            error: Error::WrongSampleKind
        })
    );
    assert_eq!((rate, period, clock), (before, period_before, clock_before));

    let mut delta = Config {
        input: InputKind::DeltaAngles(ConingKind::TwoSample),
        ..Config::RECOMMENDED
    }
    .build(Quat::IDENTITY)
    .unwrap();
    let before = delta;
    assert_eq!(
        delta.push(GyroSample::new(w), 1e-3),
        Err(Error::WrongSampleKind)
    );
    assert_eq!(delta, before);
}

#[test]
fn timed_bursts_set_attitude_and_restart_match_the_static_types() {
    let mut s = Propagator::recommended(Quat::<f32>::IDENTITY).unwrap();
    let mut c = Config::RECOMMENDED.build(Quat::<f32>::IDENTITY).unwrap();
    let w = |k: u32| GyroSample::new(Vec3::new(0.3, -0.1 * k as f32, 1.0));
    let fifo: Vec<(GyroSample<f32>, u32)> = (0..20).map(|k| (w(k), 1000 * k + (k % 3))).collect();
    let (mut cs, mut cc) = (
        TickClock::new(1e6, 32).unwrap(),
        TickClock::new(1e6, 32).unwrap(),
    );
    assert_eq!(s.push_burst_timed(&fifo, &mut cs), Ok(20));
    assert_eq!(c.push_burst_timed(&fifo, &mut cc), Ok(20));
    assert_eq!((s.attitude(), s.steps()), (c.attitude(), c.steps()));
    s.restart_input();
    c.restart_input();
    let q = Quat::new(0.0, 2.0, 0.0, 0.0);
    s.set_attitude(q).unwrap();
    c.set_attitude(q).unwrap();
    for k in 0..5 {
        s.push(w(k), 1e-3).unwrap();
        c.push(w(k), 1e-3).unwrap();
    }
    assert_eq!(
        (s.attitude(), s.steps(), s.corrections()),
        (c.attitude(), c.steps(), c.corrections())
    );
    let before = c;
    assert_eq!(
        c.set_attitude(Quat::new(0.0, 0.0, 0.0, 0.0)),
        Err(Error::ZeroQuaternion)
    );
    assert_eq!(c, before);
}

/// The type the stabilizer check uses is `StabilizerKind` in both; its validation is the stabilizer's own.
#[test]
fn stabilizer_kind_validates_as_its_type() {
    assert_eq!(
        StabilizerKind::Every(0).validate(),
        Err(Error::InvalidStabilizer)
    );
    assert_eq!(StabilizerKind::Every(1).validate(), Ok(()));
}
