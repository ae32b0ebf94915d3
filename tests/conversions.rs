//! Test 6 of the core issue: conversions round-trip within stated tolerances (in units of ε of the type),
//! q and −q are the same rotation, and the Euler angles stay accurate at and near gimbal lock, where the
//! seed's eq. (5)-(6) `acos` form loses half the digits.

mod support;

use quatprop::{EulerZxz, EulerZyx, Quat, Real, Vec3};
use support::Xorshift;

/// Round trips land within this many ε (angle between rotations, rad).
const ROUND_TRIP_EPS: f64 = 16.0;

/// Deterministic pseudo-random unit quaternions (xorshift64*), plus hand-picked hard cases.
fn samples<T: Real>() -> Vec<Quat<T>> {
    let mut rng = Xorshift::new();
    let mut next = move || rng.signed();
    let mut v: Vec<Quat<T>> = (0..2000)
        .map(|_| Quat::from_f64(Quat::new(next(), next(), next(), next())))
        .filter_map(|q: Quat<T>| q.normalized())
        .collect();
    for q in [
        Quat::new(1.0, 0.0, 0.0, 0.0),
        Quat::new(0.0, 1.0, 0.0, 0.0), // rotations by π
        Quat::new(0.0, 0.0, 1.0, 0.0),
        Quat::new(0.0, 0.0, 0.0, 1.0),
        Quat::new(1e-9, 0.6, 0.8, 0.0),
        Quat::new(0.5, 0.5, 0.5, 0.5),
    ] {
        v.push(Quat::<T>::from_f64(q).normalized().unwrap());
    }
    v
}

/// Euler round trips of f32 go through micromath's `atan2` with the `micromath` feature: bounded by 0.008 rad
/// there (tests/micromath.rs), by `ROUND_TRIP_EPS` otherwise.
fn euler_tol_eps<T: Real>() -> f64 {
    if cfg!(feature = "micromath") && T::EPSILON.to_f64() > 1e-10 {
        0.008 / T::EPSILON.to_f64()
    } else {
        ROUND_TRIP_EPS
    }
}

fn same_rotation<T: Real>(a: Quat<T>, b: Quat<T>, tol_eps: f64, what: &str) {
    let angle = a.to_f64().angle_to(b.to_f64());
    let tol = tol_eps * T::EPSILON.to_f64();
    assert!(angle <= tol, "{what}: {a:?} vs {b:?}: {angle:e} > {tol:e}");
}

/// Near a gimbal lock: the middle angle read back, `got`, within `tol` (rad) of the one `put` in, and the
/// angles read back still the rotation `q` (`back` is the quaternion they make).
fn check_near_lock(
    what: &str,
    delta: f64,
    (got, put): (f64, f64),
    tol: f64,
    q: Quat<f64>,
    back: Quat<f64>,
) {
    assert!((got - put).abs() <= tol, "δ={delta}: {what} {got} vs {put}");
    same_rotation(q, back, ROUND_TRIP_EPS, &format!("{what} near lock"));
}

fn mat_close<T: Real>(a: [[T; 3]; 3], b: [[f64; 3]; 3], tol: f64, what: &str) {
    for i in 0..3 {
        for j in 0..3 {
            assert!(
                (a[i][j].to_f64() - b[i][j]).abs() <= tol,
                "{what} [{i}][{j}]: {:?} vs {}",
                a[i][j],
                b[i][j]
            );
        }
    }
}

fn rx(a: f64) -> [[f64; 3]; 3] {
    let (s, c) = a.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}
fn ry(a: f64) -> [[f64; 3]; 3] {
    let (s, c) = a.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}
fn rz(a: f64) -> [[f64; 3]; 3] {
    let (s, c) = a.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}
fn mm(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            for k in 0..3 {
                r[i][j] += a[i][k] * b[k][j];
            }
        }
    }
    r
}

fn round_trips<T: Real>() {
    let eps = T::EPSILON.to_f64();
    for q in samples::<T>() {
        // Matrix.
        let r = q.to_rotation_matrix();
        let back = Quat::from_rotation_matrix(r).unwrap();
        same_rotation(q, back, ROUND_TRIP_EPS, "matrix");
        assert!(back.w >= T::ZERO);
        // The matrix rotates like the quaternion.
        let v = Vec3::<T>::from_f64(Vec3::new(0.3, -1.1, 0.7));
        let rv = Vec3::new(
            r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z,
            r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
            r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z,
        );
        assert!((rv - q.rotate(v)).to_f64().norm() <= 8.0 * eps * 1.4);
        // Negated quaternion: same matrix, same rotation.
        mat_close(
            (-q).to_rotation_matrix(),
            r.map(|row| row.map(|e| e.to_f64())),
            0.0,
            "−q matrix",
        );
        // Euler ZYX and ZXZ.
        let e = q.to_euler_zyx();
        same_rotation(q, Quat::from_euler_zyx(e), euler_tol_eps::<T>(), "zyx");
        assert_eq!((-q).to_euler_zyx().pitch, e.pitch);
        same_rotation(
            q,
            Quat::from_euler_zyx((-q).to_euler_zyx()),
            euler_tol_eps::<T>(),
            "−q zyx",
        );
        let z = q.to_euler_zxz();
        same_rotation(q, Quat::from_euler_zxz(z), euler_tol_eps::<T>(), "zxz");
        same_rotation(
            q,
            Quat::from_euler_zxz((-q).to_euler_zxz()),
            euler_tol_eps::<T>(),
            "−q zxz",
        );
        // Ranges.
        let pi = core::f64::consts::PI;
        assert!(e.pitch.to_f64().abs() <= pi / 2.0 + eps);
        // T's π rounds up in f32 (3.14159274): allow one ε.
        let pi_t = pi * (1.0 + eps);
        assert!(e.yaw.to_f64().abs() <= pi_t && e.roll.to_f64().abs() <= pi_t);
        assert!(z.theta.to_f64() >= 0.0 && z.theta.to_f64() <= pi + eps);
        // Axis-angle and rotation vector.
        let (axis, angle) = q.to_axis_angle();
        assert!(angle.to_f64() >= 0.0 && angle.to_f64() <= pi + 4.0 * eps);
        same_rotation(
            q,
            Quat::from_axis_angle(axis, angle).unwrap(),
            ROUND_TRIP_EPS,
            "axis-angle",
        );
        same_rotation(
            q,
            Quat::from_rotation_vector(q.to_rotation_vector()),
            ROUND_TRIP_EPS,
            "rotation vector",
        );
    }
}

support::tests_in_f32_and_f64!(round_trips => round_trips_f32, round_trips_f64);

#[test]
fn euler_conventions_match_elementary_rotation_matrices() {
    for (a, b, c) in [
        (0.3_f64, -0.7_f64, 2.1_f64),
        (-2.9, 1.2, 0.4),
        (1.0, 0.2, -1.0),
    ] {
        let q = Quat::from_euler_zyx(EulerZyx {
            yaw: a,
            pitch: b.clamp(-1.5, 1.5),
            roll: c,
        });
        mat_close(
            q.to_rotation_matrix(),
            mm(mm(rz(a), ry(b.clamp(-1.5, 1.5))), rx(c)),
            1e-15,
            "zyx",
        );
        let theta = b.abs();
        let q = Quat::from_euler_zxz(EulerZxz {
            psi: a,
            theta,
            phi: c,
        });
        mat_close(
            q.to_rotation_matrix(),
            mm(mm(rz(a), rx(theta)), rz(c)),
            1e-15,
            "zxz",
        );
        // The seed's eq. (5): cos ϑ = w² − x² − y² + z².
        let cos5 = q.w * q.w - q.x * q.x - q.y * q.y + q.z * q.z;
        assert!((cos5 - theta.cos()).abs() < 1e-15);
        // And the angles come back.
        let z = q.to_euler_zxz();
        assert!(
            (z.psi - a).abs() < 1e-14
                && (z.theta - theta).abs() < 1e-14
                && (z.phi - c).abs() < 1e-14
        );
    }
    // A body x axis rotated by yaw 90° points along reference y.
    let q = Quat::from_euler_zyx(EulerZyx {
        yaw: core::f64::consts::FRAC_PI_2,
        pitch: 0.0,
        roll: 0.0,
    });
    assert!((q.rotate(Vec3::new(1.0, 0.0, 0.0)) - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-15);
}

#[test]
fn middle_angle_stays_accurate_at_and_near_gimbal_lock() {
    let half_pi = core::f64::consts::FRAC_PI_2;
    let mut acos_worst: f64 = 0.0;
    for delta in [1e-3, 1e-6, 1e-9, 1e-12, 0.0] {
        // ZYX near pitch = +90° and −90°.
        for sign in [1.0, -1.0] {
            let pitch = sign * (half_pi - delta);
            let q = Quat::from_euler_zyx(EulerZyx {
                yaw: 0.4,
                pitch,
                roll: -0.3,
            });
            let e = q.to_euler_zyx();
            // Still the same rotation (at the lock only yaw ∓ roll is defined, and it is kept).
            let (back, tol) = (Quat::from_euler_zyx(e), 4.0 * f64::EPSILON);
            check_near_lock("pitch", delta, (e.pitch, pitch), tol, q, back);
        }
        // ZXZ near ϑ = 0 (the seed's frame barrier).
        let theta = delta;
        let q = Quat::from_euler_zxz(EulerZxz {
            psi: 0.4,
            theta,
            phi: -0.3,
        });
        let z = q.to_euler_zxz();
        let (back, tol) = (
            Quat::from_euler_zxz(z),
            4.0 * f64::EPSILON * theta.max(f64::EPSILON),
        );
        check_near_lock("theta", delta, (z.theta, theta), tol, q, back);
        // The seed's eq. (5) through acos: error of order √ε at the barrier.
        let acos_theta = (q.w * q.w - q.x * q.x - q.y * q.y + q.z * q.z)
            .clamp(-1.0, 1.0)
            .acos();
        acos_worst = acos_worst.max((acos_theta - theta).abs());
    }
    println!("acos form's worst error near the barrier: {acos_worst:e} rad");
    assert!(
        acos_worst > 1e-9,
        "the seed's form should visibly fail: {acos_worst:e}"
    );
}

#[test]
fn degenerate_inputs_are_refused_by_fallible_conversions() {
    assert!(Quat::from_axis_angle(Vec3::<f64>::ZERO, 1.0).is_none());
    assert!(Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), f64::NAN).is_none());
    assert!(Quat::<f64>::from_rotation_matrix([[f64::NAN; 3]; 3]).is_none());
    assert!(Quat::<f64>::from_rotation_matrix([[0.0; 3]; 3]).is_none());
    // A reflection is not a rotation.
    assert!(Quat::<f64>::from_rotation_matrix([
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0]
    ])
    .is_none());
    let (axis, angle) = Quat::<f32>::IDENTITY.to_axis_angle();
    assert_eq!((axis, angle), (Vec3::new(1.0, 0.0, 0.0), 0.0));
}
