//! Worst-case stack use of a push, for every configuration in f32 on the Cortex-M4F (every input model ×
//! scheme × stabilizer × accumulator of `quatprop_firmware::configs`), measured by painting: the free stack
//! below SP is filled with a pattern, a propagator is built, warmed up and pushed until it has taken a full
//! step (History: four samples), and the deepest overwritten word gives the depth. The figure includes the
//! propagator value itself and the calls into `push`. Every configuration runs twice: small steps (the
//! polynomial / Taylor paths) and 0.3 rad steps (300 rad/s at 1 kHz: the exponential maps' trigonometric
//! branch, which calls libm). Then the estimator's predict step (issue 28) in f32: `Step::between` two
//! attitudes with `matrices()`, `covariance::Ud::<f32, 6>::predict` and one scalar `Ud::update`, each on
//! its own (the `Ud` copied into the measured call, the matrices and row prepared outside it). Then the front
//! end's in-motion estimators past their 3 s start-up (`quatprop_firmware::motion`'s body at 1 kHz, so that
//! their Kalman filters run): `frontend::CalibrationEstimator::correct` + `update` and
//! `frontend::MotionBias`'s bias + `update`, each on its own, the estimator copied into the measured call.
//! Exits with status 1 if any depth exceeds its bound.
//! Run: `cd firmware && cargo run --release --bin stack`.
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use quatprop::accumulate::Accumulator;
use quatprop::covariance::Ud;
use quatprop::error_state::{GyroNoise, Step};
use quatprop::frontend::{CalibrationEstimator, MotionBias};
use quatprop::scheme::Scheme;
use quatprop::stabilize::Stabilizer;
use quatprop::{GyroSample, Propagator, Quat, Vec3};
use quatprop_firmware::configs::{each_input, Input, Label, Visitor};
use quatprop_firmware::exit::exit;
use quatprop_firmware::motion::{Motion, PERIOD, WARM_UP};

/// Bound for steps on the polynomial / Taylor paths (bytes). Measured with rustc 1.95 (quatprop 0.2): 248
/// (Hold + Euler) to 1012 (History + SchemeKind + Normalize + Kahan); DeltaAngles needs 840–930. The bound
/// leaves about 25 % for compiler drift.
const BOUND_SMALL: usize = 1280;
/// Bound with the exponential maps' trigonometric branch (libm's `sinf`/`cosf` argument reduction keeps
/// arrays on the stack): measured up to 1712 (DeltaAngles + Magnus4).
const BOUND_LARGE: usize = 2048;
/// Bound for each of the estimator's calls (bytes). Measured with rustc 1.95: 1036 (predict, the `Ud` copy
/// included), 896 (`Step::between` with its matrices), 588 (update); about 25 % over the largest.
const BOUND_ESTIMATOR: usize = 1280;
/// Bound for each of the front end's in-motion estimators' samples (bytes, the estimator's copy included).
/// Measured with rustc 1.95: 4528 (`CalibrationEstimator`: its 1152-byte value, the copy `update` keeps to
/// restore on a non-finite result, the 12-state filter's matrices), 1304 (`MotionBias`); about 25 % over
/// the largest.
const BOUND_FRONT_END: usize = 5632;

/// The stack depth of `f` (bytes below this function's frame, by painting) and what `f` returned.
#[inline(never)]
fn measure(f: &dyn Fn() -> u64) -> (usize, u64) {
    /// The pattern painted below the frame.
    const PAINT: u32 = 0xA5A5_A5A5;
    /// Painted depth below the measuring frame (bytes): above every bound.
    const DEPTH: usize = 8192;
    /// Margin left unpainted under the measuring function's own frame (bytes).
    const MARGIN: usize = 64;
    let sp = cortex_m::register::msp::read() as usize;
    let top = sp - MARGIN;
    let bottom = sp - DEPTH;
    let mut a = bottom;
    while a < top {
        // SAFETY: [bottom, top) is free stack below the current frame (4 KB of the 4 MB RAM), no interrupt
        // is enabled, and it is only written here and read back below.
        unsafe { core::ptr::write_volatile(a as *mut u32, PAINT) };
        a += 4;
    }
    let steps = f();
    let mut lowest = top;
    let mut a = bottom;
    while a < top {
        // SAFETY: as above.
        if unsafe { core::ptr::read_volatile(a as *const u32) } != PAINT {
            lowest = a;
            break;
        }
        a += 4;
    }
    (sp - lowest, steps)
}

/// Builds a propagator and pushes until it took a full step; returns its step count.
#[inline(never)]
fn pushed<S: Scheme<f32>, I: Input, Z: Stabilizer, A: Accumulator<f32>>(
    scheme: S,
    input: I,
    stabilizer: Z,
    accumulator: A,
    rate: f32,
) -> u64 {
    let dt = black_box(1.0e-3 / input.per_step() as f32);
    let w = black_box(Vec3::new(rate, -0.2, 0.3));
    let Ok(p) = Propagator::new(black_box(Quat::IDENTITY), scheme, input, stabilizer) else {
        return 0;
    };
    let mut p = p.with_accumulator(accumulator);
    for _ in 0..input.warm_up() + input.per_step() {
        let _ = black_box(p.push(input.sample(w, dt), dt));
    }
    black_box(p).steps()
}

#[derive(Default)]
struct Worst {
    /// Deepest small-step and large-step figures of the current (input, scheme) row.
    row: Option<(&'static str, &'static str, usize, usize)>,
    small: usize,
    large: usize,
    small_at: Option<Label>,
    large_at: Option<Label>,
    configurations: u32,
    ok: bool,
}

impl Worst {
    fn flush(&mut self) {
        if let Some((input, scheme, s, l)) = self.row.take() {
            defmt::println!(
                "stack {=str} {=str} small={=usize} large={=usize}",
                input,
                scheme,
                s,
                l
            );
        }
    }
}

impl Visitor for Worst {
    // The signature is `Visitor::visit`'s, as the trait declares it.
    fn visit<S, I, Z, A>(
        &mut self,
        scheme: S,
        input: I,
        stabilizer: Z,
        accumulator: A,
        label: Label,
    ) where
        S: Scheme<f32>,
        I: Input,
        Z: Stabilizer,
        A: Accumulator<f32>,
    {
        let (s, s_steps) = measure(&|| pushed(scheme, input, stabilizer, accumulator, 0.1));
        let (l, l_steps) = measure(&|| pushed(scheme, input, stabilizer, accumulator, 300.0));
        self.configurations += 1;
        let stepped = s_steps > 0 && l_steps > 0;
        if !stepped {
            defmt::println!(
                "stack {=str} {=str} {=str} {=str}: no step taken",
                label.input,
                label.scheme,
                label.stabilizer,
                label.accumulator
            );
        }
        self.ok &= stepped && s > 0 && s <= BOUND_SMALL && l > 0 && l <= BOUND_LARGE;
        match self.row {
            Some((i, sc, ref mut rs, ref mut rl)) if i == label.input && sc == label.scheme => {
                *rs = (*rs).max(s);
                *rl = (*rl).max(l);
            }
            _ => {
                self.flush();
                self.row = Some((label.input, label.scheme, s, l));
            }
        }
        if s > self.small {
            self.small = s;
            self.small_at = Some(label);
        }
        if l > self.large {
            self.large = l;
            self.large_at = Some(label);
        }
    }
}

/// The estimator's calls, each painted on its own; prints
/// `stack estimator between=<bytes> predict=<bytes> update=<bytes> (bound <bytes>)`.
fn estimator() -> bool {
    let Ok(noise) = GyroNoise::<f32>::from_noise_density_dps(0.0028, 5.0) else {
        return false;
    };
    let noise = black_box(noise);
    let start = black_box(Quat::new(1.0_f32, 0.0, 0.0, 0.0));
    let end = black_box(Quat::from_rotation_vector(Vec3::new(
        0.003_f32, -0.002, 0.01,
    )));
    let Ok(step) = Step::between(start, end, 1.0e-2, &noise) else {
        return false;
    };
    let (phi, q) = black_box(step.matrices());
    let variances = [1.0e-2_f32, 2.0e-3, 5.0e-4, 1.0e-6, 4.0e-7, 1.0e-7];
    let Ok(ud) = Ud::<f32, 6>::from_diagonal(black_box(variances)) else {
        return false;
    };
    let h = black_box([0.0_f32, -0.97, -0.2, 0.0, 0.0, 0.0]);
    let (between, ok_b) = measure(&|| match Step::between(start, end, 1.0e-2, &noise) {
        Ok(s) => {
            black_box(s.matrices());
            1
        }
        Err(_) => 0,
    });
    let (predict, ok_p) = measure(&|| {
        let mut u = black_box(ud);
        let r = u.predict(&phi, &q).is_ok();
        black_box(u);
        u64::from(r)
    });
    let (update, ok_u) = measure(&|| {
        let mut u = black_box(ud);
        let r = u.update(&h, 1.0e-3).is_ok();
        black_box(u);
        u64::from(r)
    });
    defmt::println!(
        "stack estimator between={=usize} predict={=usize} update={=usize} (bound {=usize})",
        between,
        predict,
        update,
        BOUND_ESTIMATOR
    );
    let within = |d: usize| d > 0 && d <= BOUND_ESTIMATOR;
    ok_b == 1 && ok_p == 1 && ok_u == 1 && within(between) && within(predict) && within(update)
}

/// The front end's in-motion estimators past their start-up, one sample each, painted on its own; prints
/// `stack front-end calibration=<bytes> motion-bias=<bytes> size=<bytes>/<bytes> (bound <bytes>)` (the
/// sizes: of the two estimators' values).
fn front_end() -> bool {
    let (Ok(mut cal), Ok(mut mb)) = (
        CalibrationEstimator::<f32>::new(1.0e-3, 0.01, 0.0087),
        MotionBias::<f32>::new(1.0e-3),
    ) else {
        return false;
    };
    let mut motion = Motion::new();
    let mut ok = true;
    for _ in 0..WARM_UP {
        let (w, a) = motion.next_sample();
        ok &= cal.update(w, a, PERIOD).is_ok() && mb.update(w, a, PERIOD).is_ok();
    }
    let (w, a) = black_box(motion.next_sample());
    let (calibration, ok_c) = measure(&|| {
        let mut e = black_box(cal);
        black_box(e.correct(GyroSample::new(w)));
        let r = e.update(w, a, PERIOD).is_ok();
        black_box(e);
        u64::from(r)
    });
    let (motion_bias, ok_m) = measure(&|| {
        let mut e = black_box(mb);
        black_box(w - e.bias());
        let r = e.update(w, a, PERIOD).is_ok();
        black_box(e);
        u64::from(r)
    });
    defmt::println!(
        "stack front-end calibration={=usize} motion-bias={=usize} size={=usize}/{=usize} (bound {=usize})",
        calibration,
        motion_bias,
        core::mem::size_of::<CalibrationEstimator<f32>>(),
        core::mem::size_of::<MotionBias<f32>>(),
        BOUND_FRONT_END
    );
    let within = |d: usize| d > 0 && d <= BOUND_FRONT_END;
    ok && ok_c == 1 && ok_m == 1 && within(calibration) && within(motion_bias)
}

fn at(l: Option<Label>) -> Label {
    l.unwrap_or(Label {
        input: "-",
        scheme: "-",
        stabilizer: "-",
        accumulator: "-",
    })
}

#[entry]
fn main() -> ! {
    let mut w = Worst {
        ok: true,
        ..Worst::default()
    };
    each_input(&mut w);
    w.flush();
    let (s, l) = (at(w.small_at), at(w.large_at));
    defmt::println!(
        "stack worst small-step {=usize} bytes (bound {=usize}) at {=str} {=str} {=str} {=str}",
        w.small,
        BOUND_SMALL,
        s.input,
        s.scheme,
        s.stabilizer,
        s.accumulator
    );
    defmt::println!(
        "stack worst large-step {=usize} bytes (bound {=usize}) at {=str} {=str} {=str} {=str}",
        w.large,
        BOUND_LARGE,
        l.input,
        l.scheme,
        l.stabilizer,
        l.accumulator
    );
    defmt::println!("stack configurations={=u32}", w.configurations);
    let estimator_ok = estimator();
    let front_end_ok = front_end();
    exit(w.ok && estimator_ok && front_end_ok)
}
