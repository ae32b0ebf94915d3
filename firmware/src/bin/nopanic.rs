//! Panic-freedom proven by the linker: `Propagator::push` (and construction, `with_accumulator`,
//! `set_attitude`, `restart_input` and the getters) is called with opaque inputs for every input model ×
//! scheme (the eight zero-sized ones, the run-time `SchemeKind`, Baumgarte on each Runge–Kutta scheme) ×
//! stabilizer (four zero-sized, the run-time `StabilizerKind`) × accumulator (`Plain`, `Kahan`): see
//! `quatprop_firmware::configs`. The panic handler is the `panic-never` crate's, which references a symbol
//! that does not exist, so if any panic path is still reachable after optimization the link fails. The
//! sensor front end (`CountScale`, `Calibration`, `AxisRemap`, `Alignment`, `FixedBias`, `BiasEstimator` (with its
//! drift, noise model, accelerometer gate, temperature model and variance), `MotionBias`,
//! `CalibrationEstimator` (`with_motion_noise`, `correct`, `update`, `at_rest` and the getters),
//! `SampleTiming`, `FixedPeriod`, `TickClock`), the noise identification (`noise::AllanVariance` and `NoiseFit`) and the
//! fixed-point propagator (`fixed::Q30Propagator`: `new`, `push`, `push_burst`,
//! `restart_input`, the getters) are called once, with opaque inputs, in every image; `start` and the FIFO bursts
//! (`push_burst` at a fixed period, `push_burst_timed` with sensor ticks) for every input model ×
//! accumulator through the run-time `SchemeKind` × `StabilizerKind` (whose dispatch reaches every scheme's
//! and stabilizer's code; one image with the bursts on every zero-sized combination too would not fit the
//! boards' 4 MB flash).
//!
//! The estimator's predict step and its corrections, with opaque inputs (the predict step once, in every
//! image with Hold: all of them but the M0's per-input images): `error_state`
//! (`GyroNoise`, `Step::held_rate`, `Step::between`, `matrices`) and `covariance::Ud::<f32, 6>`
//! (`from_diagonal`, `from_matrix`, `predict`, `predict_compensated`, `update`, `matrix`, `variances`), once; and
//! `Propagator::rotate_body`, `rotate_reference` and `correct_bias` for every input model × accumulator
//! (beside the bursts: `correct_bias` is the input model's, the rotations go through the accumulator), with
//! `FixedBias::correct_bias` in the front end. The `nopanic-config` image calls the same three on `Configured`.
//!
//! With the feature `nopanic-config`, the image is the run-time configuration instead: a
//! `config::Configured` built from an opaque `Config`, every call on it with rate samples and delta angles
//! (`push`, `start`, `push_burst`, `push_burst_timed`, `set_attitude`, `restart_input`, the getters), which
//! reaches the loop of every scheme × input model × accumulator, and a burst through `visit_compact`.
//!
//! Built, not run:
//! `cargo build --release --target <triple> --no-default-features --features panic-never --bin nopanic`.
//! For the micro:bit's 256 KB flash, add one `nopanic-<input>` feature per image (none: every input model)
//! and `nopanic-plain` or `nopanic-kahan` (neither: both accumulators), and if that is still too large,
//! `nopanic-schemes` (the compile-time schemes) or `nopanic-baumgarte` (Baumgarte and the run-time scheme;
//! neither: both groups). `nopanic-selftest` adds a reachable
//! `unwrap()` on `None`: that image must fail to link.
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use quatprop::accumulate::{Accumulator, Kahan, Plain};
use quatprop::config::{AccumulatorKind, Config, DeltaModel, InputKind, RateModel, Visit, Visited};
use quatprop::covariance::Ud;
use quatprop::error_state::{GyroNoise, Step};
use quatprop::fixed::Q30Propagator;
use quatprop::frontend::{
    Alignment, Aux, AxisRemap, BiasEstimator, Calibration, CalibrationEstimator, CountScale,
    FixedBias, FixedPeriod, MotionBias, SampleTiming, TickClock,
};
use quatprop::input::coning::{ConingKind, TwoSample};
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, Linear, TwiceRate};
use quatprop::noise::{AllanVariance, NoiseFit};
use quatprop::scheme::{Scheme, SchemeKind};
use quatprop::stabilize::{Stabilizer, StabilizerKind};
use quatprop::{DeltaAngle, GyroSample, Propagator, Quat, Vec3};
use quatprop_firmware::configs::{each_scheme, Input, Label, Visitor};

struct Exercise;

const ONE_ACCUMULATOR: bool = cfg!(feature = "nopanic-plain")
    || cfg!(feature = "nopanic-kahan")
    || cfg!(feature = "nopanic-floatfloat");

impl Visitor for Exercise {
    // An accumulator feature selects that accumulator only; none selects every one.
    const PLAIN: bool = !ONE_ACCUMULATOR || cfg!(feature = "nopanic-plain");
    const KAHAN: bool = !ONE_ACCUMULATOR || cfg!(feature = "nopanic-kahan");
    const FLOAT_FLOAT: bool = !ONE_ACCUMULATOR || cfg!(feature = "nopanic-floatfloat");
    const SCHEMES: bool = !cfg!(feature = "nopanic-baumgarte") || cfg!(feature = "nopanic-schemes");
    const BAUMGARTE: bool =
        !cfg!(feature = "nopanic-schemes") || cfg!(feature = "nopanic-baumgarte");

    fn visit<S, I, Z, A>(&mut self, scheme: S, input: I, stabilizer: Z, accumulator: A, _: Label)
    where
        S: Scheme<f32>,
        I: Input,
        Z: Stabilizer,
        A: Accumulator<f32>,
    {
        exercise(scheme, input, stabilizer, accumulator);
    }
}

#[inline(never)]
fn exercise<S: Scheme<f32>, I: Input, Z: Stabilizer, A: Accumulator<f32>>(
    scheme: S,
    input: I,
    stabilizer: Z,
    accumulator: A,
) {
    let q0 = black_box(Quat::new(1.0_f32, 0.0, 0.0, 0.0));
    let Ok(p) = Propagator::new(q0, scheme, input, stabilizer) else {
        return;
    };
    let mut p = p.with_accumulator(accumulator);
    for _ in 0..black_box(8) {
        let dt = black_box(1.0e-3_f32);
        let sample = black_box(input.sample(black_box(Vec3::new(0.1, -0.2, 0.3)), dt));
        let _ = black_box(p.push(sample, dt));
    }
    let _ = black_box(p.set_attitude(black_box(q0)));
    if black_box(true) {
        p.restart_input();
    }
    black_box((p.attitude(), p.norm_error(), p.steps(), p.corrections()));
    black_box((p.saturated_samples(), p.input(), p.scheme(), p.stabilizer()));
}

const ALL: bool = !cfg!(any(
    feature = "nopanic-hold",
    feature = "nopanic-linear",
    feature = "nopanic-history",
    feature = "nopanic-twice-rate",
    feature = "nopanic-gauss-points",
    feature = "nopanic-delta-two-sample",
    feature = "nopanic-delta-angles"
));

/// A stream's first sample, then FIFO bursts at the exact period and with sensor timestamps, on the run-time
/// scheme and stabilizer choice.
#[inline(never)]
fn bursts<I: Input, A: Accumulator<f32>>(input: I, accumulator: A) {
    let q0 = black_box(Quat::new(1.0_f32, 0.0, 0.0, 0.0));
    let scheme = black_box(SchemeKind::ExpMap);
    let Ok(p) = Propagator::new(q0, scheme, input, black_box(StabilizerKind::FirstOrder)) else {
        return;
    };
    let mut p = p.with_accumulator(accumulator);
    let s = black_box(input.sample(black_box(Vec3::new(0.1, -0.2, 0.3)), 1.0e-3));
    let _ = black_box(p.start(s));
    let burst = black_box([s; 4]);
    if let Ok(mut period) = FixedPeriod::new(black_box(1.0e-3)) {
        let n = black_box(4);
        let _ = black_box(p.push_burst(burst.get(..n).unwrap_or(&[]), &mut period));
    }
    let timed = black_box([(s, 1_000_u32), (s, 2_000), (s, 3_000), (s, 4_000)]);
    if let Ok(mut clock) = TickClock::new(black_box(1.0e6), black_box(32)) {
        let _ = black_box(p.push_burst_timed(&timed, &mut clock));
    }
    // An estimator's correction: the attitude in either frame, the bias the input model keeps.
    let _ = black_box(p.rotate_body(black_box(Vec3::new(1.0e-3, -2.0e-3, 5.0e-4))));
    let _ = black_box(p.rotate_reference(black_box(Vec3::new(-1.0e-3, 0.0, 2.0e-3))));
    let _ = black_box(p.correct_bias(black_box(Vec3::new(1.0e-4, 0.0, -2.0e-4))));
    black_box((p.attitude(), p.steps(), p.saturated_samples()));
}

/// The estimator's predict step and update on opaque inputs: the error state's step (held rate and between
/// two attitudes), the covariance's factorization, predict, update and read-outs.
#[inline(never)]
fn estimator() {
    let Ok(noise) = GyroNoise::<f32>::new(black_box(8.7e-4), black_box(4.0e-6)) else {
        return;
    };
    let dt = black_box(1.0e-2_f32);
    let held = Step::held_rate(black_box(Vec3::new(0.01_f32, -0.02, 0.005)), dt, &noise);
    let start = black_box(Quat::new(1.0_f32, 0.0, 0.0, 0.0));
    let end = black_box(Quat::new(0.999_95_f32, 0.005, -0.005, 0.0));
    let between = Step::between(start, end, dt, &noise);
    let variances = black_box([1.0e-2_f32, 2.0e-3, 5.0e-4, 1.0e-6, 4.0e-7, 1.0e-7]);
    let Ok(mut ud) = Ud::<f32, 6>::from_diagonal(variances) else {
        return;
    };
    if let Ok(m) = Ud::<f32, 6>::from_matrix(&black_box(ud.matrix())) {
        ud = m;
    }
    for step in [held, between].into_iter().flatten() {
        let (phi, q) = step.matrices();
        let _ = black_box(ud.predict(&black_box(phi), &black_box(q)));
        let _ = black_box(ud.predict_compensated(&black_box(phi), &black_box(q)));
    }
    let h = black_box([0.0_f32, -0.97, -0.2, 0.0, 0.0, 0.0]);
    if let Ok(gain) = ud.update(&h, black_box(1.0e-3)) {
        black_box(gain);
    }
    black_box((ud.matrix(), ud.variances(), ud.u(), ud.d()));
}

/// Every configuration of `input` (`each_scheme`) and its bursts, if this image has the input model: its
/// feature is `selected`, or no input model's feature is named. Inlined, so that `selected` is a constant
/// and an image without the model links none of its code.
#[inline(always)]
fn every_call_on<I: Input>(selected: bool, input: I) {
    if ALL || selected {
        each_scheme(&mut Exercise, input);
        bursts_each(input);
    }
}

/// `bursts` on both accumulators (as the image's accumulator features select).
fn bursts_each<I: Input>(input: I) {
    if Exercise::PLAIN {
        bursts(input, Plain);
    }
    if Exercise::KAHAN {
        bursts(input, Kahan::new());
    }
}

/// Every front-end call once, with opaque inputs.
#[inline(never)]
fn front_end() {
    let Ok(scale) = CountScale::<f32>::full_scale_dps(black_box(2000.0)) else {
        return;
    };
    let s = scale.sample(black_box([1, -2, i16::MAX]));
    let m = [[1.0_f32, 0.01, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let s = match Calibration::new(
        black_box(Vec3::new(0.01, 0.0, -0.02)),
        black_box(Vec3::new(1.01, 0.99, 1.0)),
        black_box(m),
    ) {
        Ok(c) => c.apply(s),
        Err(_) => s,
    };
    let s = black_box(AxisRemap::PyNxPz).apply(s);
    let identity = [[1.0_f32, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let s = match Alignment::from_matrix(black_box(identity)) {
        Ok(a) => a.apply(s),
        Err(_) => s,
    };
    if let Ok(mut b) = FixedBias::new(black_box(Vec3::new(0.01_f32, 0.0, 0.0))) {
        black_box(b.apply(s));
        let delta = black_box(Vec3::new(1.0e-4, 0.0, -2.0e-4));
        if b.correct_bias(delta).is_ok() {
            black_box(b.apply(s));
        }
    }
    if let Ok(e) = BiasEstimator::<f32>::new(black_box(1.0), black_box(1.0e-3), black_box(0.05)) {
        let noise = GyroNoise::new(black_box(1.0e-4), black_box(0.0));
        let e = e
            .with_drift(black_box(2.0e-5))
            .and_then(|e| e.with_accel_gate(black_box(0.5)))
            .and_then(|e| e.with_temperature_model(black_box(0.5)))
            .and_then(|e| noise.and_then(|n| e.with_noise(&n)));
        if let Ok(mut e) =
            e.and_then(|e| e.with_initial(black_box(Vec3::new(0.0, 0.0, 0.01)), black_box(1.0e-3)))
        {
            let aux = Aux {
                accel: black_box(Some(Vec3::new(0.0, 0.0, 9.81))),
                temperature: black_box(Some(25.0)),
            };
            for _ in 0..black_box(3) {
                let _ = black_box(e.update(black_box(s)));
                let _ = black_box(e.update_with(black_box(s), aux));
            }
            black_box((
                e.bias(),
                e.variance(),
                e.is_learned(),
                e.bias_at(black_box(30.0)),
                e.temperature_slope(),
            ));
        }
    }
    if let Ok(mut avar) = AllanVariance::<f32, 16>::new(black_box(1.0e-3)) {
        for _ in 0..black_box(3) {
            let _ = black_box(avar.push(black_box(s.rate)));
        }
        for c in avar.clusters() {
            black_box(c);
        }
        black_box(NoiseFit::pooled_from(&avar, black_box(0.0)));
        black_box(NoiseFit::axis(&avar, black_box(1), black_box(0.0)));
        if let Some(fit) = NoiseFit::pooled(&avar) {
            let _ = black_box(GyroNoise::<f32>::from_fit(&fit));
            black_box((
                fit.white.value(),
                fit.white.interval(black_box(2.0)),
                fit.random_walk.is_identified(),
                fit.variance(black_box(1.0)),
            ));
        }
    }
    if let Ok(mut m) = MotionBias::<f32>::new(black_box(1.0e-3)) {
        for _ in 0..black_box(3) {
            let _ = black_box(m.update(
                black_box(s.rate),
                black_box(Vec3::new(0.1, 0.0, 9.8)),
                1.0e-3,
            ));
        }
        m.at_rest();
        black_box(m.bias());
    }
    let calibration = CalibrationEstimator::<f32>::with_motion_noise(
        black_box(1.0e-3),
        black_box(0.01),
        black_box(0.0087),
        black_box(3.0e-3),
    );
    if let Ok(mut c) = calibration {
        for _ in 0..black_box(3) {
            let rate = black_box(c.correct(black_box(s)).rate);
            let _ = black_box(c.update(
                black_box(rate),
                black_box(Vec3::new(0.1, 0.0, 9.8)),
                black_box(1.0e-3),
            ));
        }
        if black_box(true) {
            c.at_rest();
        }
        black_box((
            c.calibration(),
            c.gain(),
            c.gain_std_dev(),
            c.gain_observed(),
        ));
        black_box((c.bias(), c.bias_std_dev()));
    }
    let timing = SampleTiming::<f32>::interval_mean().with_group_delay(black_box(2.0e-3));
    if let Ok(t) = timing {
        black_box(t.increment(black_box(s), black_box(1.0e-3)));
        black_box(t.ahead(black_box(Quat::IDENTITY), black_box(s.rate)));
    }
    if let Ok(mut period) = FixedPeriod::<f32>::new(black_box(1.0e-3)) {
        black_box(period.next_dt());
        period.carry_over(black_box(1.0e-3));
        black_box(period.period());
    }
    if let Ok(mut clock) = TickClock::<f32>::new(black_box(1.0e6), black_box(16)) {
        let _ = black_box(clock.dt(black_box(5)));
        let _ = black_box(clock.advance(black_box(70_000)));
        black_box(clock.gaps());
        clock.restart();
    }
    let fixed = Q30Propagator::new(
        black_box(Quat::<f32>::IDENTITY),
        black_box(1.0e-3),
        black_box(1.0e-3),
    );
    if let Ok(mut p) = fixed {
        for _ in 0..black_box(4) {
            let _ = black_box(p.push(black_box([1, -2, i16::MAX])));
        }
        let _ = black_box(p.push_burst(black_box(&[[3, 4, 5], [i16::MIN, 0, 7]])));
        p.restart_input();
        black_box((
            p.attitude(),
            p.attitude_q30(),
            p.steps(),
            p.saturated_samples(),
        ));
    }
}

/// A burst through `Configured::visit_compact` (the scheme matched per step).
struct CompactBurst<'a> {
    rates: &'a [GyroSample<f32>],
    deltas: &'a [DeltaAngle<f32>],
    period: &'a mut FixedPeriod<f32>,
}

impl Visit<f32> for CompactBurst<'_> {
    type Output = Result<usize, quatprop::Refused>;
    // The signatures are `config::Visit`'s, one method per sample type.
    fn rates<S: Scheme<f32>, I: RateModel<f32>, A: Accumulator<f32>>(
        self,
        p: &mut Visited<f32, S, I, A>,
    ) -> Self::Output {
        p.push_burst(self.rates, self.period)
    }
    fn deltas<S: Scheme<f32>, I: DeltaModel<f32>, A: Accumulator<f32>>(
        self,
        p: &mut Visited<f32, S, I, A>,
    ) -> Self::Output {
        p.push_burst(self.deltas, self.period)
    }
}

/// Every call on the run-time configuration, from an opaque `Config`.
#[inline(never)]
fn configured() {
    let config = black_box(Config {
        scheme: SchemeKind::Rk4,
        baumgarte_gain: Some(0.5),
        input: InputKind::DeltaAngles(ConingKind::ThreeSample),
        stabilizer: StabilizerKind::Every(3),
        accumulator: AccumulatorKind::FloatFloat,
    });
    let Ok(mut p) = config.build::<f32>(black_box(Quat::new(1.0, 0.0, 0.0, 0.0))) else {
        return;
    };
    let w = black_box(GyroSample::new(Vec3::new(0.1_f32, -0.2, 0.3)));
    let d = black_box(DeltaAngle::new(Vec3::new(1e-4_f32, -2e-4, 3e-4)));
    let _ = black_box(p.start(w));
    let _ = black_box(p.start(d));
    let _ = black_box(p.push(w, black_box(1.0e-3)));
    let _ = black_box(p.push(d, black_box(1.0e-3)));
    let rates = black_box([w; 4]);
    let deltas = black_box([d; 4]);
    if let Ok(mut period) = FixedPeriod::new(black_box(1.0e-3)) {
        let _ = black_box(p.push_burst(&rates, &mut period));
        let _ = black_box(p.push_burst(&deltas, &mut period));
        let _ = black_box(p.visit_compact(CompactBurst {
            rates: &rates,
            deltas: &deltas,
            period: &mut period,
        }));
    }
    if let Ok(mut clock) = TickClock::new(black_box(1.0e6), black_box(32)) {
        let _ = black_box(p.push_burst_timed(&black_box([(w, 1_000_u32), (w, 2_000)]), &mut clock));
        let _ = black_box(p.push_burst_timed(&black_box([(d, 3_000_u32), (d, 4_000)]), &mut clock));
    }
    let _ = black_box(p.rotate_body(black_box(Vec3::new(1.0e-3, -2.0e-3, 5.0e-4))));
    let _ = black_box(p.rotate_reference(black_box(Vec3::new(-1.0e-3, 0.0, 2.0e-3))));
    let _ = black_box(p.correct_bias(black_box(Vec3::new(1.0e-4, 0.0, -2.0e-4))));
    let _ = black_box(p.set_attitude(black_box(Quat::new(0.0, 1.0, 0.0, 0.0))));
    if black_box(true) {
        p.restart_input();
    }
    black_box((p.attitude(), p.attitude_low(), p.norm_error(), p.config()));
    black_box((p.steps(), p.corrections(), p.saturated_samples()));
}

#[entry]
fn main() -> ! {
    front_end();
    // The estimator's calls do not depend on the input model: on the M0, whose images are one per input
    // model (256 KB), they go with Hold's, the smallest.
    if ALL || cfg!(feature = "nopanic-hold") {
        estimator();
    }
    if cfg!(feature = "nopanic-config") {
        configured();
        loop {
            cortex_m::asm::wfi();
        }
    }
    every_call_on(cfg!(feature = "nopanic-hold"), Hold);
    every_call_on(cfg!(feature = "nopanic-linear"), Linear::new());
    every_call_on(cfg!(feature = "nopanic-history"), History::new());
    every_call_on(cfg!(feature = "nopanic-twice-rate"), TwiceRate::new());
    every_call_on(cfg!(feature = "nopanic-gauss-points"), GaussPoints::new());
    every_call_on(
        cfg!(feature = "nopanic-delta-two-sample"),
        DeltaAngles::new(TwoSample),
    );
    // Every coning correction's code, behind the run-time choice.
    every_call_on(
        cfg!(feature = "nopanic-delta-angles"),
        DeltaAngles::new(black_box(ConingKind::FiveSample)),
    );
    if cfg!(feature = "nopanic-selftest") {
        // A reachable panic: this image must NOT link (shows the proof can fail).
        black_box(black_box(None::<u32>).unwrap());
    }
    loop {
        cortex_m::asm::wfi();
    }
}
