//! The estimator's predict step on the Cortex-M4F (issue 28), counted with SysTick under QEMU `-icount
//! shift=10` like `bench` (a program of its own, as `burst` is, so the grid's figures keep `bench`'s code
//! layout: a second caller of the recommended `push` changes what the compiler inlines into the grid's loop).
//! In f32 on the recommended configuration (ExpMap + History + FirstOrder, Plain) at 1 kHz, |omega| about
//! 1.2 rad/s, an ICM-42688-class gyro's noise, and a covariance with spread eigenvalues and correlations:
//! - the push alone, and with the covariance propagated every step and every 10th step
//!   (`error_state::Step::between` the attitudes at both ends of the interval, `matrices`, then
//!   `covariance::Ud::<f32, 6>::predict`), per attitude step over 80 steps;
//! - `Step::between` alone, `Ud::predict` alone, one scalar `Ud::update` (an inclination row) and a
//!   correction (`Propagator::rotate_body` + `correct_bias`), per call over 64 calls.
//!
//! Then the front end's in-motion estimators on a body turning under gravity at 1 kHz
//! (`quatprop_firmware::motion`: a gyro with a gain error and a residual bias, the accelerometer), past
//! their 3 s start-up so that their Kalman filters run on every sample: `frontend::CalibrationEstimator`
//! (`correct` of the rate, then `update`: twelve states, bias and gain) and, for comparison,
//! `frontend::MotionBias` (the bias subtracted, then `update`: three states), per sample over 64 samples
//! (four loops of 16, each inside one wrap of SysTick).
//!
//! Each figure is (instructions of the loop with the call − instructions of the same loop without it) / n,
//! with opaque inputs (`black_box`) and results kept. Prints `bench estimator <what> <figure>` and
//! `bench front-end <what> <figure>`; exits 1 if any call was refused, the covariance stopped being finite
//! and positive, or the calibration estimator's gain covariance did not shrink over its samples (its
//! Kalman update did not run).
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use quatprop::accumulate::Plain;
use quatprop::covariance::Ud;
use quatprop::error_state::{GyroNoise, Step};
use quatprop::frontend::{CalibrationEstimator, MotionBias};
use quatprop::input::History;
use quatprop::scheme::ExpMap;
use quatprop::stabilize::FirstOrder;
use quatprop::{GyroSample, Propagator, Quat, Vec3};
use quatprop_firmware::bench_input::rates;
use quatprop_firmware::configs::Input;
use quatprop_firmware::exit::exit;
use quatprop_firmware::icount::{per_x100, Counter};
use quatprop_firmware::motion::{Motion, PERIOD, WARM_UP};

/// Step (s).
const H: f32 = 1.0e-3;

/// Instructions of the loop of [`pushes_with_covariance`] without the push.
#[inline(never)]
fn baseline(c: &Counter, s: &[GyroSample<f32>; 8], dt: f32, n: u32) -> u32 {
    let t0 = c.now();
    for i in 0..n as usize {
        black_box((s[i & 7], dt));
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// The recommended configuration, the attitude the estimator's covariance runs beside.
type Recommended = Propagator<f32, ExpMap, History<f32>, FirstOrder, Plain>;

/// Attitude steps per estimator measurement: a multiple of 10, inside one wrap of SysTick with a predict
/// per step.
const EST_STEPS: u32 = 80;

/// Instructions of `n` pushes with the covariance propagated every `K` steps (`K` = 0: never, the push
/// alone in the same loop): `Step::between` the attitudes at both ends of the interval (`K` steps of
/// `dt`), then `Ud::predict`. Clears `ok` on any refusal.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn pushes_with_covariance<const K: usize>(
    c: &Counter,
    p: &mut Recommended,
    ud: &mut Ud<f32, 6>,
    noise: &GyroNoise<f32>,
    s: &[GyroSample<f32>; 8],
    dt: f32,
    n: u32,
    ok: &mut bool,
) -> u32 {
    let interval = dt * K as f32;
    let t0 = c.now();
    let mut start = p.attitude();
    let mut refused = false;
    for i in 0..n as usize {
        refused |= black_box(p.push(s[i & 7], dt)).is_err();
        if K != 0 && (i + 1) % K == 0 {
            let end = p.attitude();
            match Step::between(start, end, interval, noise) {
                Ok(step) => {
                    let (phi, q) = step.matrices();
                    refused |= ud.predict(&phi, &q).is_err();
                }
                Err(_) => refused = true,
            }
            start = end;
        }
    }
    let n = Counter::instructions(Counter::ticks(t0, c.now()));
    *ok &= !black_box(refused);
    n
}

/// Instructions of `n` calls of `Step::between` over opaque attitude pairs 10 ms apart.
#[inline(never)]
fn betweens(c: &Counter, qs: &[Quat<f32>; 9], noise: &GyroNoise<f32>, with: bool, n: u32) -> u32 {
    let t0 = c.now();
    for i in 0..n as usize {
        let (a, b, dt) = black_box((qs[i & 7], qs[(i & 7) + 1], 1.0e-2_f32));
        if with {
            let _ = black_box(Step::between(a, b, dt, noise));
        }
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// Instructions of `n` calls of `Ud::predict` on opaque `(Φ, Q)` pairs (or of the loop alone).
#[inline(never)]
fn predicts(
    c: &Counter,
    ud: &mut Ud<f32, 6>,
    m: &[StepMatrices; 4],
    with: bool,
    compensated: bool,
    n: u32,
) -> u32 {
    let t0 = c.now();
    for i in 0..n as usize {
        let (phi, q) = black_box(&m[i & 3]);
        if with {
            if compensated {
                let _ = black_box(ud.predict_compensated(phi, q));
            } else {
                let _ = black_box(ud.predict(phi, q));
            }
        }
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// `Φ` and `Q` of one covariance step.
type StepMatrices = ([[f32; 6]; 6], [[f32; 6]; 6]);

/// Instructions of `n` scalar updates with opaque rows (or of the loop alone).
#[inline(never)]
fn updates(c: &Counter, ud: &mut Ud<f32, 6>, h: &[[f32; 6]; 2], with: bool, n: u32) -> u32 {
    let t0 = c.now();
    for i in 0..n as usize {
        let (h, r) = black_box((&h[i & 1], 1.0e-3_f32));
        if with {
            let _ = black_box(ud.update(h, r));
        }
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// Instructions of `n` corrections (`rotate_body` + `correct_bias`) with opaque increments (or of the loop
/// alone).
#[inline(never)]
fn corrections(c: &Counter, p: &mut Recommended, d: &[Vec3<f32>; 8], with: bool, n: u32) -> u32 {
    let t0 = c.now();
    for i in 0..n as usize {
        let (dtheta, dbias) = black_box((d[i & 7] * 1.0e-3, d[(i + 3) & 7] * 1.0e-4));
        if with {
            let _ = black_box(p.rotate_body(dtheta));
            let _ = black_box(p.correct_bias(dbias));
        }
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// Prints `bench <group> <what> <v / 100>.<v % 100>` (`v`: instructions ×100).
fn report(group: &str, what: &str, v: u32) {
    defmt::println!(
        "bench {=str} {=str} {=u32}.{=u32:02}",
        group,
        what,
        v / 100,
        v % 100
    );
}

/// The estimator's predict step, in f32 on the recommended configuration at 1 kHz, |omega| about 1.2 rad/s;
/// a covariance with spread eigenvalues and correlations (0.1 rad and 0.3 mrad/s standard deviations, made
/// correlated by 200 ms of prediction and two inclination updates before the counts). Prints
/// `bench estimator <what> <instructions ×100 per step or per call>`.
fn estimator(c: &Counter, ok: &mut bool) {
    let report = |what: &str, v: u32| report("estimator", what, v);
    // An ICM-42688-class gyro: 0.0028 °/s/√Hz, bias random walk 5 °/h/√h.
    let Ok(noise) = GyroNoise::<f32>::from_noise_density_dps(0.0028, 5.0) else {
        *ok = false;
        return;
    };
    let noise = black_box(noise);
    let h = History::new();
    let dt = black_box(H);
    let s = black_box(rates().map(|w| h.sample(w, dt)));
    // Inclination rows: a component of the gravity direction in the body frame, g_b = (0.1, −0.2, 0.97),
    // observed through δθ: rows of [g_b×].
    let rows = black_box([
        [0.0_f32, -0.97, -0.2, 0.0, 0.0, 0.0],
        [0.97_f32, 0.0, -0.1, 0.0, 0.0, 0.0],
    ]);
    let Ok(fresh) = Ud::<f32, 6>::from_diagonal([1.0e-2, 1.0e-2, 1.0e-2, 1.0e-7, 1.0e-7, 1.0e-7])
    else {
        *ok = false;
        return;
    };
    let Ok(p0) = Propagator::new(Quat::IDENTITY, ExpMap, h, FirstOrder) else {
        *ok = false;
        return;
    };
    let mut p = p0;
    let mut ud = fresh;
    // Warm-up: History full, 200 ms of covariance steps, then two updates: a correlated covariance.
    for sample in s.iter().take(h.warm_up() as usize) {
        *ok &= p.push(*sample, dt).is_ok();
    }
    let warm = pushes_with_covariance::<10>(c, &mut p, &mut ud, &noise, &s, dt, 200, ok);
    black_box(warm);
    for row in &rows {
        *ok &= ud.update(row, 1.0e-3).is_ok();
    }
    let prior = ud;

    // The push alone, and with the covariance every step and every 10th.
    let mut q = p;
    let alone = pushes_with_covariance::<0>(c, &mut q, &mut ud, &noise, &s, dt, EST_STEPS, ok);
    let base = baseline(c, &s, dt, EST_STEPS);
    let per_step = |instructions| per_x100(instructions, base, EST_STEPS);
    report("push", per_step(alone));
    let mut q = p;
    ud = prior;
    let every = pushes_with_covariance::<1>(c, &mut q, &mut ud, &noise, &s, dt, EST_STEPS, ok);
    report("push+covariance-every-step", per_step(every));
    let mut q = p;
    ud = prior;
    let tenth = pushes_with_covariance::<10>(c, &mut q, &mut ud, &noise, &s, dt, EST_STEPS, ok);
    report("push+covariance-every-10th", per_step(tenth));

    // Step::between alone: attitudes 10 ms apart.
    let mut qs = [Quat::IDENTITY; 9];
    let mut q = p;
    qs[0] = q.attitude();
    for end in qs.iter_mut().skip(1) {
        for i in 0..10 {
            *ok &= q.push(s[i & 7], dt).is_ok();
        }
        *end = q.attitude();
    }
    let qs = black_box(qs);
    let n = 64;
    let v = per_x100(
        betweens(c, &qs, &noise, true, n),
        betweens(c, &qs, &noise, false, n),
        n,
    );
    report("Step::between", v);

    // Ud::predict alone, on the matrices of those intervals.
    let mut m = [([[0.0_f32; 6]; 6], [[0.0_f32; 6]; 6]); 4];
    for (k, mk) in m.iter_mut().enumerate() {
        match Step::between(qs[k], qs[k + 1], 1.0e-2, &noise) {
            Ok(step) => *mk = step.matrices(),
            Err(_) => *ok = false,
        }
    }
    let m = black_box(m);
    ud = prior;
    let with = predicts(c, &mut ud, &m, true, false, n);
    *ok &= ud.variances().iter().all(|v| v.is_finite() && *v > 0.0);
    let v = per_x100(with, predicts(c, &mut ud, &m, false, false, n), n);
    report("Ud::predict", v);
    ud = prior;
    let with = predicts(c, &mut ud, &m, true, true, n);
    *ok &= ud.variances().iter().all(|v| v.is_finite() && *v > 0.0);
    let v = per_x100(with, predicts(c, &mut ud, &m, false, true, n), n);
    report("Ud::predict_compensated", v);

    // One scalar update (an inclination row), alternating two rows.
    ud = prior;
    let with = updates(c, &mut ud, &rows, true, n);
    *ok &= ud.variances().iter().all(|v| v.is_finite() && *v > 0.0);
    let v = per_x100(with, updates(c, &mut ud, &rows, false, n), n);
    report("Ud::update", v);

    // A correction: rotate_body (mrad) + correct_bias (0.1 mrad/s).
    let d = black_box(rates());
    let mut q = p;
    let with = corrections(c, &mut q, &d, true, n);
    *ok &= q.attitude().is_finite();
    let v = per_x100(with, corrections(c, &mut q, &d, false, n), n);
    report("rotate_body+correct_bias", v);
}

/// Samples per loop of the front end's counts (16 × up to some 10 000 instructions: inside one wrap).
const FRONT_CHUNK: usize = 16;
/// Loops of the front end's counts.
const FRONT_CHUNKS: usize = 4;
/// Samples of the front end's counts.
const FRONT_SAMPLES: usize = FRONT_CHUNK * FRONT_CHUNKS;

/// A gyro reading and an accelerometer sample.
type Pair = (Vec3<f32>, Vec3<f32>);

/// Instructions of `call` on each (gyro reading, accelerometer) pair of `samples` at the sample period (or
/// of the loop alone): one sample of a front end's estimator `est`. `call` tells whether it was refused;
/// sets `refused` on any refusal.
#[inline(never)]
fn front_end_samples<E>(
    c: &Counter,
    est: &mut E,
    samples: &[Pair],
    with: bool,
    refused: &mut bool,
    call: impl Fn(&mut E, Vec3<f32>, Vec3<f32>, f32) -> bool,
) -> u32 {
    let t0 = c.now();
    for pair in samples {
        let ((w, a), dt) = black_box((*pair, PERIOD));
        if with {
            *refused |= call(est, w, a, dt);
        }
    }
    Counter::instructions(Counter::ticks(t0, c.now()))
}

/// One sample of `CalibrationEstimator`: `correct` of the reading `w`, then `update`; true if refused.
#[inline(always)]
fn calibration_sample(
    est: &mut CalibrationEstimator<f32>,
    w: Vec3<f32>,
    a: Vec3<f32>,
    dt: f32,
) -> bool {
    black_box(est.correct(GyroSample::new(w)));
    est.update(w, a, dt).is_err()
}

/// One sample of `MotionBias`: its bias subtracted from the reading `w`, then `update`; true if refused.
#[inline(always)]
fn motion_bias_sample(est: &mut MotionBias<f32>, w: Vec3<f32>, a: Vec3<f32>, dt: f32) -> bool {
    black_box(w - est.bias());
    est.update(w, a, dt).is_err()
}

/// The sum of the gain's standard deviations (a Kalman update shrinks it; nothing else changes it).
fn gain_spread(est: &CalibrationEstimator<f32>) -> f32 {
    est.gain_std_dev().iter().flatten().sum()
}

/// The front end's in-motion estimators at 1 kHz on `quatprop_firmware::motion`'s body, past their start-up
/// (3.1 s of samples first); prints `bench front-end <what> <instructions ×100 per sample>`.
fn front_end(c: &Counter, ok: &mut bool) {
    let report = |what: &str, v: u32| report("front-end", what, v);
    let (Ok(mut cal), Ok(mut mb)) = (
        CalibrationEstimator::<f32>::new(1.0e-3, 0.01, 0.0087),
        MotionBias::<f32>::new(1.0e-3),
    ) else {
        *ok = false;
        return;
    };
    let mut motion = Motion::new();
    for _ in 0..WARM_UP {
        let (w, a) = motion.next_sample();
        *ok &= !calibration_sample(&mut cal, w, a, PERIOD);
        *ok &= !motion_bias_sample(&mut mb, w, a, PERIOD);
    }
    let mut samples = [(Vec3::ZERO, Vec3::ZERO); FRONT_SAMPLES];
    for s in samples.iter_mut() {
        *s = motion.next_sample();
    }
    let samples = black_box(samples);
    let mut refused = false;
    let spread = gain_spread(&cal);
    let v = per_sample(&samples, |chunk, with| {
        front_end_samples(c, &mut cal, chunk, with, &mut refused, calibration_sample)
    });
    // The Kalman update ran: the gain's uncertainty shrank over the counted samples.
    *ok &= gain_spread(&cal) < spread;
    report("CalibrationEstimator::correct+update", v);
    let v = per_sample(&samples, |chunk, with| {
        front_end_samples(c, &mut mb, chunk, with, &mut refused, motion_bias_sample)
    });
    *ok &= mb.bias().is_finite();
    report("MotionBias::bias+update", v);
    *ok &= !refused;
}

/// Instructions ×100 per sample of a front end's calls over `samples`, counted `FRONT_CHUNK` samples at a
/// time (one loop inside one wrap of SysTick): `count(chunk, with)` gives the instructions of a loop over
/// `chunk` with the calls (`with`) or of the loop alone.
fn per_sample(samples: &[Pair], mut count: impl FnMut(&[Pair], bool) -> u32) -> u32 {
    let (mut with, mut without) = (0, 0);
    for chunk in samples.chunks(FRONT_CHUNK) {
        with += count(chunk, true);
        without += count(chunk, false);
    }
    per_x100(with, without, samples.len() as u32)
}

#[entry]
fn main() -> ! {
    let c = Counter::take();
    let mut ok = true;
    estimator(&c, &mut ok);
    defmt::println!("bench estimator done");
    front_end(&c, &mut ok);
    defmt::println!("bench front-end done");
    exit(ok)
}
