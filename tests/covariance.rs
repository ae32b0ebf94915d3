//! The UD covariance: Thornton's predict and Bierman's update against the plain formulas in f64, its
//! invariants after many random operations, and its refusals (state unchanged).

// Matrix code reads clearest with the indices of its formulas.
#![allow(clippy::needless_range_loop)]

use quatprop::covariance::Ud;
use quatprop::Error;

type M = [[f64; 6]; 6];

/// xorshift64*: a reproducible stream in [−1, 1).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let v = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        v as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn matrix(&mut self) -> M {
        let mut m = [[0.0; 6]; 6];
        for row in &mut m {
            for e in row.iter_mut() {
                *e = self.next();
            }
        }
        m
    }
    /// A random SPD matrix `A Aᵀ + s I` with eigenvalues spread by `spread`.
    fn spd(&mut self, spread: f64) -> M {
        let mut a = self.matrix();
        for (i, row) in a.iter_mut().enumerate() {
            let s = spread.powf(i as f64 / 5.0);
            for e in row.iter_mut() {
                *e *= s;
            }
        }
        let mut p = mul(&a, &transpose(&a));
        for (i, row) in p.iter_mut().enumerate() {
            row[i] += 1e-3;
        }
        p
    }
}

fn mul(a: &M, b: &M) -> M {
    let mut c = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            c[i][j] = (0..6).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn transpose(a: &M) -> M {
    let mut t = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            t[j][i] = a[i][j];
        }
    }
    t
}

/// Largest `|a − b|` relative to `√(s_ii s_jj)`.
fn rel_err_to(a: &M, b: &M, s: &M) -> f64 {
    let mut e: f64 = 0.0;
    for i in 0..6 {
        for j in 0..6 {
            e = e.max((a[i][j] - b[i][j]).abs() / (s[i][i] * s[j][j]).sqrt());
        }
    }
    e
}

fn rel_err(a: &M, b: &M) -> f64 {
    rel_err_to(a, b, b)
}

#[test]
fn predict_and_update_are_the_plain_formulas_in_f64() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let p = rng.spd(1e4);
        let mut ud = Ud::<f64, 6>::from_matrix(&p).unwrap();
        assert!(rel_err(&ud.matrix(), &p) < 1e-13);
        let phi = rng.matrix();
        let q = rng.spd(10.0);
        ud.predict(&phi, &q).unwrap();
        let mut reference = mul(&mul(&phi, &p), &transpose(&phi));
        for i in 0..6 {
            for j in 0..6 {
                reference[i][j] += q[i][j];
            }
        }
        worst = worst.max(rel_err(&ud.matrix(), &reference));
        // One scalar update: P − P hᵀ h P / (h P hᵀ + r), K = P hᵀ / (h P hᵀ + r).
        let h: [f64; 6] = core::array::from_fn(|_| rng.next());
        let r = 0.1 + rng.next().abs();
        let ph: [f64; 6] = core::array::from_fn(|i| (0..6).map(|k| reference[i][k] * h[k]).sum());
        let s = (0..6).map(|i| h[i] * ph[i]).sum::<f64>() + r;
        let gain = ud.update(&h, r).unwrap();
        assert!((gain.innovation_variance / s - 1.0).abs() < 1e-13);
        let mut posterior = reference;
        for i in 0..6 {
            assert!(
                (gain.gain[i] - ph[i] / s).abs() < 1e-12 * (reference[i][i] / s).sqrt().max(1.0)
            );
            for j in 0..6 {
                posterior[i][j] -= ph[i] * ph[j] / s;
            }
        }
        // Relative to the prior: the plain formula's subtraction (the reference) cancels where the
        // measurement shrinks a variance, by up to ε times the prior.
        worst = worst.max(rel_err_to(&ud.matrix(), &posterior, &reference));
        assert!(ud.d().iter().all(|&d| d >= 0.0));
    }
    println!("UD against the plain formulas, f64: {worst:.2e}");
    assert!(worst < 1e-13, "{worst}");
}

#[test]
fn factors_stay_valid_through_many_random_operations_in_f32() {
    let mut rng = Rng(7);
    let mut ud = Ud::<f32, 6>::from_diagonal([1.0; 6]).unwrap();
    for k in 0..20_000 {
        // A near-identity transition and a small noise: the variances grow in three directions.
        let mut phi = [[0.0_f32; 6]; 6];
        for (i, row) in phi.iter_mut().enumerate() {
            row[i] = 1.0;
            row[(i + 1) % 6] = 0.01 * rng.next() as f32;
        }
        let mut q = [[0.0_f32; 6]; 6];
        for (i, row) in q.iter_mut().enumerate() {
            row[i] = if i < 3 { 1e-6 } else { 1e-12 };
        }
        ud.predict(&phi, &q).unwrap();
        if k % 3 == 0 {
            let h: [f32; 6] = [1.0, rng.next() as f32, 0.0, 0.0, 0.0, 0.0];
            ud.update(&h, 1e-4).unwrap();
        }
    }
    let u = ud.u();
    for i in 0..6 {
        assert_eq!(u[i][i], 1.0);
        for j in 0..i {
            assert_eq!(u[i][j], 0.0);
        }
    }
    assert!(
        ud.d().iter().all(|&d| d >= 0.0 && d.is_finite()),
        "{:?}",
        ud.d()
    );
    let p = ud.matrix();
    for i in 0..6 {
        for j in 0..6 {
            assert_eq!(p[i][j].to_bits(), p[j][i].to_bits());
        }
    }
}

#[test]
fn semi_definite_noise_and_covariance_are_taken() {
    // No bias walk: Q is zero on the bias block; a covariance with a zero variance.
    let mut ud = Ud::<f64, 6>::from_diagonal([1e-2, 1e-2, 0.0, 1e-4, 1e-4, 0.0]).unwrap();
    let mut phi = [[0.0; 6]; 6];
    let mut q = [[0.0; 6]; 6];
    for i in 0..6 {
        phi[i][i] = 1.0;
        if i < 3 {
            phi[i][i + 3] = -0.01;
            q[i][i] = 1e-8;
        }
    }
    ud.predict(&phi, &q).unwrap();
    let p = ud.matrix();
    assert!((p[0][0] - (1e-2 + 1e-4 * 1e-4 + 1e-8)).abs() < 1e-17);
    assert!((p[2][2] - 1e-8).abs() < 1e-22);
    assert_eq!(p[5][5], 0.0);
    let back = Ud::<f64, 6>::from_matrix(&p).unwrap();
    let b = back.matrix();
    let diff = (0..36)
        .map(|k| (b[k / 6][k % 6] - p[k / 6][k % 6]).abs())
        .fold(0.0, f64::max);
    assert!(diff < 1e-17, "{diff}");
    assert_eq!(back.d()[5], 0.0);
}

#[test]
fn refusals_leave_the_factors_unchanged() {
    let mut rng = Rng(3);
    let p = rng.spd(100.0);
    let mut ud = Ud::<f64, 6>::from_matrix(&p).unwrap();
    let before = ud;
    let eye: M = core::array::from_fn(|i| core::array::from_fn(|j| f64::from(u8::from(i == j))));
    let mut bad = eye;
    bad[2][4] = f64::NAN;
    assert_eq!(ud.predict(&bad, &eye), Err(Error::InvalidCovariance));
    assert_eq!(ud.predict(&eye, &bad), Err(Error::InvalidCovariance));
    let mut huge = eye;
    huge[0][0] = 1e200;
    assert_eq!(ud.predict(&huge, &eye), Err(Error::InvalidCovariance)); // overflows
    let h = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    for r in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(ud.update(&h, r), Err(Error::InvalidNoise));
    }
    assert_eq!(
        ud.update(&[f64::NAN; 6], 1.0),
        Err(Error::InvalidCovariance)
    );
    assert_eq!(ud, before);

    // Not what it claims: asymmetric, indefinite, not finite, a negative variance.
    let mut asym = p;
    asym[1][3] *= 1.001;
    assert_eq!(Ud::from_matrix(&asym), Err(Error::InvalidCovariance));
    let mut indefinite = eye;
    indefinite[0][1] = 2.0;
    indefinite[1][0] = 2.0;
    assert_eq!(Ud::from_matrix(&indefinite), Err(Error::InvalidCovariance));
    let mut nan = eye;
    nan[5][5] = f64::NAN;
    assert_eq!(Ud::from_matrix(&nan), Err(Error::InvalidCovariance));
    assert_eq!(
        Ud::from_diagonal([1.0, -1e-30, 1.0, 1.0, 1.0, 1.0]),
        Err(Error::InvalidCovariance)
    );
    assert_eq!(
        Ud::<f32, 6>::from_diagonal([f32::INFINITY; 6]),
        Err(Error::InvalidCovariance)
    );
}

/// A variance nothing observes, growing by increments below half its ulp (the heading of an
/// inclination-only filter: 1e-11 rad² per step on 1e-2): the plain predict drops every one, the
/// compensated one carries them as f64 does.
#[test]
fn compensated_predict_keeps_increments_below_the_ulp() {
    let eye: [[f32; 6]; 6] =
        core::array::from_fn(|i| core::array::from_fn(|j| f32::from(u8::from(i == j))));
    let mut q = [[0.0_f32; 6]; 6];
    q[2][2] = 1e-11;
    let start = [1e-4, 1e-4, 1e-2, 1e-6, 1e-6, 1e-6];
    let mut plain = Ud::<f32, 6>::from_diagonal(start).unwrap();
    let mut carried = plain;
    let n = 1_000_000;
    for _ in 0..n {
        plain.predict(&eye, &q).unwrap();
        carried.predict_compensated(&eye, &q).unwrap();
    }
    let exact = 1e-2_f64 + f64::from(1e-11_f32) * f64::from(n);
    let widen = |u: &Ud<f32, 6>| f64::from(u.d()[2]);
    let (e_plain, e_carried) = (
        (widen(&plain) / exact - 1.0).abs(),
        (widen(&carried) / exact - 1.0).abs(),
    );
    println!("heading variance after 1e6 steps: plain {e_plain:.2e}, compensated {e_carried:.2e} relative");
    assert_eq!(plain.d()[2], 1e-2); // every increment lost
    assert!(e_carried < 1e-7, "{e_carried}");
}
