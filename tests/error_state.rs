//! The error-state step's closed form against an f64 Van Loan discretization of the continuous model, in
//! f64 and f32, on both sides of the series/closed-form switch; `Step::between` against the exact
//! composition of per-step transitions; refusals.

// Matrix code reads clearest with the indices of its formulas.
#![allow(clippy::needless_range_loop)]

use quatprop::error_state::{GyroNoise, Step};
use quatprop::{Error, GyroSample, Propagator, Quat, Vec3};

type M<const N: usize> = [[f64; N]; N];

fn mul<const N: usize>(a: &M<N>, b: &M<N>) -> M<N> {
    let mut c = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            c[i][j] = (0..N).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn transpose<const N: usize>(a: &M<N>) -> M<N> {
    let mut t = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            t[j][i] = a[i][j];
        }
    }
    t
}

/// `exp(a)` by scaling and squaring of a 30-term Taylor series (the scaled norm below 1/2: the
/// truncation is below 1e-40, the squarings cost a few ulps each).
fn expm<const N: usize>(a: &M<N>) -> M<N> {
    let norm = a
        .iter()
        .map(|r| r.iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut squarings = 0;
    let mut scale = 1.0;
    while norm * scale > 0.5 {
        scale *= 0.5;
        squarings += 1;
    }
    let mut s = [[0.0; N]; N];
    let mut term = [[0.0; N]; N];
    for i in 0..N {
        s[i][i] = 1.0;
        term[i][i] = 1.0;
    }
    let scaled = a.map(|r| r.map(|v| v * scale));
    for k in 1..30 {
        term = mul(&term, &scaled).map(|r| r.map(|v| v / k as f64));
        for i in 0..N {
            for j in 0..N {
                s[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..squarings {
        s = mul(&s, &s);
    }
    s
}

fn skew(v: [f64; 3]) -> M<3> {
    [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]]
}

/// Van Loan (1978): `exp([[−F, G Qc Gᵀ], [0, Fᵀ]] dt) = [[·, Φ⁻¹ Q], [0, Φᵀ]]` for the continuous model
/// `δθ' = −[ω×]δθ − δb − n_g`, `δb' = n_b`.
fn van_loan(omega: [f64; 3], dt: f64, arw: f64, walk: f64) -> (M<6>, M<6>) {
    let w = skew(omega);
    let mut m = [[0.0; 12]; 12];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = w[i][j] * dt; // −F_θθ = [ω×]
            m[6 + j][6 + i] = -w[i][j] * dt; // Fᵀ
        }
        m[i][3 + i] = dt; // −F_θb = I
        m[6 + 3 + i][6 + i] = -dt; // (F_θb)ᵀ = −I
        m[i][6 + i] = arw * arw * dt;
        m[3 + i][6 + 3 + i] = walk * walk * dt;
    }
    let e = expm(&m);
    let mut phi_t = [[0.0; 6]; 6];
    let mut upper = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            phi_t[i][j] = e[6 + i][6 + j];
            upper[i][j] = e[i][6 + j];
        }
    }
    let phi = transpose(&phi_t);
    (phi, mul(&phi, &upper))
}

/// Largest `|a − b|` over the entries, each relative to `√(b_ii b_jj)` (a covariance) or to 1 (`unit`).
fn rel_err(a: &M<6>, b: &M<6>, unit: bool) -> f64 {
    let mut e: f64 = 0.0;
    for i in 0..6 {
        for j in 0..6 {
            let scale = if unit {
                1.0
            } else {
                (b[i][i] * b[j][j]).sqrt()
            };
            e = e.max((a[i][j] - b[i][j]).abs() / scale);
        }
    }
    e
}

/// Rotation vectors on both sides of the series' bound (|φ| = 2) and far beyond; rates and steps such
/// that the bias terms of Q are not negligible beside the white noise.
const CASES: &[([f64; 3], f64)] = &[
    ([0.0, 0.0, 0.0], 0.01),
    ([1e-7, -2e-7, 3e-7], 0.001),
    ([0.003, -0.004, 0.012], 0.01),
    ([0.3, -0.2, 0.1], 0.5),
    ([1.0, 1.2, -1.1], 1.0),
    ([0.0, 0.0, 1.999_999_9], 1.0),
    ([0.0, 0.0, 2.000_000_1], 1.0),
    ([2.0, -1.5, 0.7], 3.0),
    ([7.0, 3.0, -6.0], 2.0),
];
const ARW: f64 = 0.3;
const WALK: f64 = 0.7;

#[test]
fn held_rate_step_matches_van_loan_in_f64() {
    let noise = GyroNoise::new(ARW, WALK).unwrap();
    let mut worst: (f64, f64) = (0.0, 0.0);
    for &(phi, dt) in CASES {
        let step = Step::held_rate(Vec3::new(phi[0], phi[1], phi[2]), dt, &noise).unwrap();
        let (p, q) = step.matrices();
        let (pv, qv) = van_loan(phi.map(|v| v / dt), dt, ARW, WALK);
        let (ep, eq) = (
            rel_err(&p, &pv, true) / dt.max(1.0),
            rel_err(&q, &qv, false),
        );
        println!(
            "|φ| = {:.3e}, dt {dt}: Φ {ep:.2e}, Q {eq:.2e}",
            Vec3::new(phi[0], phi[1], phi[2]).norm()
        );
        worst = (worst.0.max(ep), worst.1.max(eq));
    }
    // Measured: Φ 1.2e-15, Q 2.0e-15 at worst (|φ| ≈ 2.6: the closed forms' one lost digit, and Van
    // Loan's own squarings).
    assert!(worst.0 < 1e-14 && worst.1 < 1e-14, "{worst:?}");
}

#[test]
fn held_rate_step_in_f32_is_the_f64_step_to_f32_precision() {
    let n64 = GyroNoise::new(ARW, WALK).unwrap();
    let n32 = GyroNoise::new(ARW as f32, WALK as f32).unwrap();
    let mut worst: (f64, f64) = (0.0, 0.0);
    for &(phi, dt) in CASES {
        // The same inputs: the f32 ones, widened.
        let p32 = phi.map(|v| v as f32);
        let dt32 = dt as f32;
        let s32 = Step::held_rate(Vec3::new(p32[0], p32[1], p32[2]), dt32, &n32).unwrap();
        let s64 = Step::held_rate(
            Vec3::new(p32[0].into(), p32[1].into(), p32[2].into()),
            dt32.into(),
            &GyroNoise::new(f64::from(n32.arw()), f64::from(n32.bias_walk())).unwrap(),
        )
        .unwrap();
        let _ = n64;
        let (a, qa) = s32.matrices();
        let (b, qb) = s64.matrices();
        let widen = |m: [[f32; 6]; 6]| m.map(|r| r.map(f64::from));
        let ep = rel_err(&widen(a), &b, true) / f64::from(dt32).max(1.0);
        let eq = rel_err(&widen(qa), &qb, false);
        worst = (worst.0.max(ep), worst.1.max(eq));
    }
    let eps = f64::from(f32::EPSILON);
    println!(
        "f32 against f64: Φ {:.2} ε, Q {:.2} ε",
        worst.0 / eps,
        worst.1 / eps
    );
    // Measured: Φ 1.5 ε, Q 0.9 ε.
    assert!(worst.0 < 4.0 * eps && worst.1 < 4.0 * eps, "{worst:?}");
}

/// A propagator's attitudes over 10 steps of a rate that changes fast (a 5 Hz oscillation of 1 rad/s on
/// a 1 rad/s spin), then `Step::between` over the 10 against the product of the 10 exact steps (Van
/// Loan per step at each step's own mean rate, composed: Φ = Φ₁₀…Φ₁, Q = Φ Q Φᵀ + Qₖ).
#[test]
fn between_takes_the_rotation_taken_and_the_mean_rate() {
    let noise = GyroNoise::new(ARW, WALK).unwrap();
    let h = 1.0e-3;
    let rate = |t: f64| {
        let s = (2.0 * std::f64::consts::PI * 5.0 * t).sin();
        Vec3::new(s, 0.5 * s, 1.0)
    };
    let mut p = Propagator::recommended(Quat::IDENTITY).unwrap();
    p.start(GyroSample::new(rate(0.0))).unwrap();
    for k in 1..=30 {
        p.push(GyroSample::new(rate(k as f64 * h)), h).unwrap();
    }
    let start = p.attitude();
    let mut phi = [[0.0; 6]; 6];
    let mut q = [[0.0; 6]; 6];
    for (i, row) in phi.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for k in 31..=40 {
        let before = p.attitude();
        p.push(GyroSample::new(rate(k as f64 * h)), h).unwrap();
        let r = (before.conjugate() * p.attitude()).to_rotation_vector();
        let (ps, qs) = van_loan([r.x / h, r.y / h, r.z / h], h, ARW, WALK);
        phi = mul(&ps, &phi);
        q = mul(&mul(&ps, &q), &transpose(&ps));
        for i in 0..6 {
            for j in 0..6 {
                q[i][j] += qs[i][j];
            }
        }
    }
    let (pb, qb) = Step::between(start, p.attitude(), 10.0 * h, &noise)
        .unwrap()
        .matrices();
    let mut rot: f64 = 0.0;
    let mut bias: f64 = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            rot = rot.max((pb[i][j] - phi[i][j]).abs());
            bias = bias.max((pb[i][j + 3] - phi[i][j + 3]).abs() / (10.0 * h));
        }
    }
    let eq = rel_err(&qb, &q, false);
    println!("between vs composed: Φθθ {rot:.2e}, Φθb {bias:.2e} (relative to Δt), Q {eq:.2e}");
    // Φθθ is the rotation taken: exact. Φθb holds the mean rate: ∫ (u − t₀) ω(u) du differs from its
    // mean-rate value by ω̇ Δt³/12, so its error relative to Δt is up to |ω̇| Δt²/12 = 2.6e-4 here (|ω̇| ≤
    // 10π·1.12 rad/s²); measured 1.2e-4. Q's error is smaller (1.4e-6): its white-noise part is exact.
    let bound = 10.0 * std::f64::consts::PI * 1.25_f64.sqrt() * (10.0 * h) * (10.0 * h) / 12.0;
    assert!(rot < 1e-14, "{rot}");
    assert!(
        bias < bound && bias > bound / 10.0,
        "{bias} against {bound}"
    );
    assert!(eq < 1e-5, "{eq}");
}

#[test]
fn refusals() {
    let noise = GyroNoise::<f32>::new(1e-3, 1e-5).unwrap();
    let v = Vec3::new(0.1, 0.0, 0.0);
    assert_eq!(
        Step::held_rate(Vec3::new(f32::NAN, 0.0, 0.0), 1e-3, &noise),
        Err(Error::NonFiniteRate)
    );
    assert_eq!(Step::held_rate(v, 0.0, &noise), Err(Error::NonPositiveStep));
    assert_eq!(
        Step::held_rate(v, -1.0, &noise),
        Err(Error::NonPositiveStep)
    );
    assert_eq!(
        Step::held_rate(v, f32::INFINITY, &noise),
        Err(Error::NonFiniteStep)
    );
    assert_eq!(
        Step::held_rate(v, f32::NAN, &noise),
        Err(Error::NonFiniteStep)
    );
    // σ_b² Δt³ overflows f32.
    let loud = GyroNoise::<f32>::new(1e10, 1e10).unwrap();
    assert_eq!(Step::held_rate(v, 1e7, &loud), Err(Error::NonFiniteResult));
    // f32 takes the step path's sine, which covers 8192 rad (f64: libm, any angle).
    assert_eq!(
        Step::held_rate(Vec3::new(0.0, 9000.0, 0.0), 1.0, &noise),
        Err(Error::StepAngleBeyondStability {
            step_angle: 9000.0,
            limit: 8192.0
        })
    );
    assert!(Step::held_rate(Vec3::new(0.0, 8000.0, 0.0), 1.0, &noise).is_ok());
    let n64 = GyroNoise::<f64>::new(1e-3, 1e-5).unwrap();
    assert!(Step::held_rate(Vec3::new(0.0, 9000.0, 0.0), 1.0, &n64).is_ok());
    let z = Quat::new(0.0, 0.0, 0.0, 0.0);
    assert_eq!(
        Step::between(z, Quat::IDENTITY, 1e-3, &noise),
        Err(Error::ZeroQuaternion)
    );
    let nan = Quat::new(f32::NAN, 0.0, 0.0, 0.0);
    assert_eq!(
        Step::between(Quat::IDENTITY, nan, 1e-3, &noise),
        Err(Error::NonFiniteQuaternion)
    );
    for (a, b) in [(-1.0, 0.0), (0.0, f64::NAN), (f64::INFINITY, 0.0)] {
        assert_eq!(
            GyroNoise::<f32>::from_datasheet(a, b),
            Err(Error::InvalidNoise)
        );
    }
    let n = GyroNoise::<f32>::from_datasheet(0.2, 5.0).unwrap();
    assert_eq!(n.with_bias_instability(3.0, 0.0), Err(Error::InvalidNoise));
    // 3 °/h over 100 s: √(2σ²/τ) = 3/3600 °/s · √0.02.
    let gm = n.with_bias_instability(3.0, 100.0).unwrap();
    let expected = (3.0_f64 / 3600.0).to_radians() * (0.02_f64).sqrt();
    assert!((f64::from(gm.bias_walk()) / expected - 1.0).abs() < 1e-6);
    assert_eq!(gm.arw(), n.arw());
}
