//! Target `estimator`: the estimator's door on arbitrary input, f32 and f64.
//!
//! - `GyroNoise`: refused iff a density is negative, NaN or infinite (`InvalidNoise`).
//! - `Step::held_rate` / `Step::between`: arbitrary rotation vectors, steps, noises and attitudes;
//!   refusals typed in the documented order (rotation, then step; a non-finite or zero attitude), and `Ok`
//!   ⇒ every entry finite, `Φθθ` orthogonal within `64ε` where the rotation is finite, `Qθθ`'s and
//!   `Qbb`'s diagonals non-negative.
//! - `Ud`: built from an arbitrary diagonal or matrix (refused as documented), then an arbitrary sequence
//!   of `predict` or `predict_compensated` (arbitrary or plausible Φ and Q) and `update` (arbitrary or plausible rows and
//!   variances): `Err` ⇒ the factors unchanged bit for bit; `Ok` ⇒ `U` unit upper triangular, `D` finite
//!   and non-negative, `matrix()` symmetric bit for bit, and an update's innovation variance at least the
//!   measurement's variance (rounding allowed) with a finite gain.
//! - Corrections on a recommended propagator between pushes: `rotate_body`, `rotate_reference` and
//!   `correct_bias` with arbitrary vectors: `Err` ⇒ the propagator unchanged bit for bit (an f32 rotation
//!   beyond 16384 rad is `StepAngleBeyondStability`); `Ok` ⇒ finite, a
//!   rotation keeps `|q|` within `8ε` of its value (plus the rotation's own rounding, scaled by its angle),
//!   and a bias correction leaves the attitude, the counters and the steps bit for bit.

use super::{Bytes, Fz, RATE, UNIT};
use quatprop::covariance::Ud;
use quatprop::error_state::{GyroNoise, Step};
use quatprop::{Error, GyroSample, Propagator, Quat, Vec3};

/// Decodes and checks one input.
pub fn run(data: &[u8]) {
    crate::by_precision(data, check::<f32>, check::<f64>)
}

fn check<T: Fz>(b: &mut Bytes<'_>) {
    let noise = noise::<T>(b);
    let mut ud = covariance::<T>(b);
    let mut p =
        Propagator::recommended(Quat::<T>::IDENTITY).expect("the identity is a unit quaternion");
    let mut previous_dt = T::from_f64(1e-3);
    let mut start = p.attitude();
    while !b.is_empty() {
        match b.below(6) {
            0 => {
                let phi = b.vec::<T>([1e-3, 0.1, 2.0, 10.0]);
                let dt = b.dt(previous_dt);
                step(Step::held_rate(phi, dt, &noise), phi.is_finite(), dt);
            }
            1 => {
                let (q0, q1) = if b.bool() {
                    (start, p.attitude())
                } else {
                    (b.quat(), b.quat())
                };
                let dt = b.dt(previous_dt);
                step(Step::between(q0, q1, dt, &noise), true, dt);
                start = p.attitude();
            }
            2 => predict(b, &mut ud, &noise),
            3 => update(b, &mut ud),
            4 => correct(b, &mut p),
            _ => {
                let w = b.vec::<T>(RATE);
                let dt = b.dt(previous_dt);
                if p.push(GyroSample::new(w), dt).is_ok() {
                    previous_dt = dt;
                }
            }
        }
        check_factors(&ud);
    }
}

fn noise<T: Fz>(b: &mut Bytes<'_>) -> GyroNoise<T> {
    let (arw, walk) = (
        b.real::<T>([1e-4, 1e-3, 1.0, 1e3]),
        b.real::<T>([1e-6, 1e-4, 1.0, 1e3]),
    );
    let valid = |v: T| v >= T::ZERO && v.is_finite();
    match GyroNoise::new(arw, walk) {
        Ok(n) => {
            assert!(valid(arw) && valid(walk));
            assert_eq!(
                (n.arw().bits(), n.bias_walk().bits()),
                (arw.bits(), walk.bits())
            );
            n
        }
        Err(e) => {
            assert_eq!(e, Error::InvalidNoise);
            assert!(!(valid(arw) && valid(walk)));
            GyroNoise::new(T::from_f64(1e-3), T::from_f64(1e-5)).expect("valid densities")
        }
    }
}

fn step<T: Fz>(s: Result<Step<T>, Error>, phi_finite: bool, dt: T) {
    match s {
        Err(e) => {
            let dt_ok = dt > T::ZERO && dt.is_finite();
            match e {
                Error::NonFiniteRate => assert!(!phi_finite),
                Error::NonPositiveStep => assert!(dt.is_finite() && !(dt > T::ZERO)),
                Error::NonFiniteStep => assert!(!dt.is_finite()),
                Error::NonFiniteResult => assert!(dt_ok),
                Error::StepAngleBeyondStability { step_angle, limit } => {
                    assert!(
                        T::NAME == "f32" && limit == 8192.0 && step_angle > limit && dt_ok,
                        "{}: step_angle {step_angle}, limit {limit}, dt {dt}",
                        T::NAME
                    )
                }
                Error::ZeroQuaternion | Error::NonFiniteQuaternion => {}
                other => panic!("{}: unexpected {other:?}", T::NAME),
            }
        }
        Ok(s) => {
            let (phi, q) = s.matrices();
            assert!(phi.iter().chain(q.iter()).flatten().all(|v| v.is_finite()));
            // Φθθ ΦθθᵀΦ = I within rounding.
            for i in 0..3 {
                for j in 0..3 {
                    let dot: f64 = (0..3)
                        .map(|k| phi[i][k].to_f64() * phi[j][k].to_f64())
                        .sum();
                    let expected = if i == j { 1.0 } else { 0.0 };
                    assert!(
                        (dot - expected).abs() <= 64.0 * T::EPS,
                        "{}: Φθθ not orthogonal: {dot}",
                        T::NAME
                    );
                }
            }
            for i in 0..6 {
                assert!(
                    q[i][i] >= T::ZERO,
                    "{}: negative noise variance {:?}",
                    T::NAME,
                    q[i][i]
                );
            }
        }
    }
}

fn covariance<T: Fz>(b: &mut Bytes<'_>) -> Ud<T, 6> {
    let fallback = || Ud::from_diagonal([T::ONE; 6]).expect("a unit diagonal");
    if b.bool() {
        let d: [T; 6] = core::array::from_fn(|_| b.real([1e-6, 1e-2, 1.0, 1e3]));
        match Ud::from_diagonal(d) {
            Ok(u) => {
                assert!(d.iter().all(|&v| v >= T::ZERO && v.is_finite()));
                u
            }
            Err(e) => {
                assert_eq!(e, Error::InvalidCovariance);
                assert!(!d.iter().all(|&v| v >= T::ZERO && v.is_finite()));
                fallback()
            }
        }
    } else {
        // A matrix: arbitrary, or A Aᵀ of an arbitrary A (symmetric positive semi-definite up to rounding).
        let a: [[T; 6]; 6] = core::array::from_fn(|_| core::array::from_fn(|_| b.real(UNIT)));
        let m = if b.bool() {
            a
        } else {
            core::array::from_fn(|i| {
                core::array::from_fn(|j| (0..6).fold(T::ZERO, |s, k| s + a[i][k] * a[j][k]))
            })
        };
        match Ud::from_matrix(&m) {
            Ok(u) => {
                assert!(m.iter().flatten().all(|v| v.is_finite()));
                u
            }
            Err(e) => {
                assert_eq!(e, Error::InvalidCovariance);
                fallback()
            }
        }
    }
}

fn predict<T: Fz>(b: &mut Bytes<'_>, ud: &mut Ud<T, 6>, noise: &GyroNoise<T>) {
    let before = *ud;
    let (phi, q) = if b.bool() {
        let r = b.vec::<T>([1e-3, 0.1, 1.0, 4.0]);
        let dt = b.dt(T::from_f64(1e-2));
        match Step::held_rate(r, dt, noise) {
            Ok(s) => s.matrices(),
            Err(_) => return,
        }
    } else {
        let m = |b: &mut Bytes<'_>| -> [[T; 6]; 6] {
            core::array::from_fn(|_| core::array::from_fn(|_| b.real(UNIT)))
        };
        (m(b), m(b))
    };
    let r = if b.bool() {
        ud.predict(&phi, &q)
    } else {
        ud.predict_compensated(&phi, &q)
    };
    match r {
        Ok(()) => {}
        Err(e) => {
            assert_eq!(e, Error::InvalidCovariance);
            assert_eq!(
                *ud,
                before,
                "{}: a refused predict changed the factors",
                T::NAME
            );
        }
    }
}

fn update<T: Fz>(b: &mut Bytes<'_>, ud: &mut Ud<T, 6>) {
    let before = *ud;
    let h: [T; 6] = core::array::from_fn(|_| b.real(UNIT));
    let r = b.real::<T>([1e-8, 1e-4, 1.0, 1e3]);
    match ud.update(&h, r) {
        Ok(g) => {
            assert!(r > T::ZERO && r.is_finite());
            assert!(g.gain.iter().all(|v| v.is_finite()));
            assert!(g.innovation_variance.to_f64() >= r.to_f64() * (1.0 - 4.0 * T::EPS));
        }
        Err(e) => {
            match e {
                Error::InvalidNoise => assert!(!(r > T::ZERO && r.is_finite())),
                Error::InvalidCovariance => {}
                other => panic!("{}: unexpected {other:?}", T::NAME),
            }
            assert_eq!(
                *ud,
                before,
                "{}: a refused update changed the factors",
                T::NAME
            );
        }
    }
}

fn check_factors<T: Fz>(ud: &Ud<T, 6>) {
    let (u, d) = (ud.u(), ud.d());
    for i in 0..6 {
        assert!(
            d[i] >= T::ZERO && d[i].is_finite(),
            "{}: D = {d:?}",
            T::NAME
        );
        assert_eq!(u[i][i].bits(), T::ONE.bits());
        for j in 0..6 {
            if j < i {
                assert_eq!(u[i][j].bits(), T::ZERO.bits());
            } else {
                assert!(u[i][j].is_finite());
            }
        }
    }
    // matrix() may overflow for huge factors; where finite it is symmetric bit for bit.
    let m = ud.matrix();
    for i in 0..6 {
        for j in 0..6 {
            assert_eq!(m[i][j].bits(), m[j][i].bits());
        }
    }
}

fn correct<T: Fz>(
    b: &mut Bytes<'_>,
    p: &mut Propagator<
        T,
        quatprop::scheme::ExpMap,
        quatprop::input::History<T>,
        quatprop::stabilize::FirstOrder,
    >,
) {
    let before = *p;
    let which = b.below(3);
    let v = b.vec::<T>([1e-6, 1e-2, 1.0, 10.0]);
    let r = match which {
        0 => p.rotate_body(v),
        1 => p.rotate_reference(v),
        _ => p.correct_bias(v),
    };
    match r {
        Err(e) => {
            match e {
                Error::NonFiniteRate | Error::NonFiniteResult => {}
                Error::StepAngleBeyondStability { step_angle, limit } => {
                    assert!(
                        T::NAME == "f32" && which < 2 && limit == 16384.0 && !(step_angle <= limit)
                    )
                }
                other => panic!("{}: unexpected {other:?}", T::NAME),
            }
            if e == Error::NonFiniteRate && which < 2 {
                assert!(!v.is_finite());
            }
            assert_eq!(
                *p,
                before,
                "{}: a refused correction changed the propagator",
                T::NAME
            );
        }
        Ok(()) => {
            assert!(v.is_finite());
            assert!(p.attitude().is_finite());
            assert_eq!(p.steps(), before.steps());
            if which == 2 {
                assert_eq!(
                    super::quat_bits(p.attitude()),
                    super::quat_bits(before.attitude())
                );
            } else {
                let (n0, n1) = (before.attitude().to_f64(), p.attitude().to_f64());
                let norm = |q: Quat<f64>| (q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z).sqrt();
                let angle = Vec3::new(v.x.to_f64(), v.y.to_f64(), v.z.to_f64()).norm();
                let slack = 8.0 * T::EPS * (1.0 + angle.min(4.0)) * norm(n0);
                assert!(
                    (norm(n1) - norm(n0)).abs() <= slack,
                    "{}: |q| {} → {}",
                    T::NAME,
                    norm(n0),
                    norm(n1)
                );
            }
        }
    }
}
