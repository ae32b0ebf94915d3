//! Target `conversions`: every conversion on arbitrary bit patterns (no panic), exact array and mint round
//! trips, and round trips within derived bounds for finite unit quaternions, f32 and f64.
//!
//! Bounds, `ε` the working precision's epsilon, angles measured in f64 on the widened values (for f64 the
//! measurement itself costs up to 16ε, added to each bound):
//! - unit quaternion `u = normalized(q)`: `|N(u)| ≤ 4ε` (scaling by the largest component, one square root,
//!   one division and four products);
//! - rotation vector `exp(log u)`: the log's `2 atan2(s, w)/s` and the exponential each carry a few ε of
//!   relative error in the angle and a few ε absolute per component: `≤ (8 + 4|φ|)ε`;
//! - rotation matrix and back (Shepperd: the pivot is ≥ 1, so each component is a difference of entries
//!   with ≤ 6ε error each, times ½/√pivot ≤ ½, then normalized): `≤ 32ε`;
//! - Euler ZYX / ZXZ and back (half-angle `atan2` forms, then three half-angle quaternions multiplied):
//!   `≤ 32ε` (at the gimbal lock the split of the outer angles is arbitrary but their sum is kept);
//! - axis-angle and back: as the rotation vector, `≤ (8 + 4·angle)ε`; angles in their ranges up to
//!   `π(1 + 4ε)` (π rounded to T, then a few roundings);
//! - `rotate(v)` against the matrix product: `≤ 16ε|v|` per the same rounding counts.

use super::{angle64, norm64, quat_bits, vec_bits, Bytes, Fz, RATE};
use quatprop::{EulerZxz, EulerZyx, Quat, Vec3};

/// Decodes and checks one input.
pub fn run(data: &[u8]) {
    crate::by_precision(data, check::<f32>, check::<f64>)
}

fn check<T: Fz>(b: &mut Bytes<'_>) {
    let q = b.quat::<T>();
    let v = b.vec::<T>(RATE);
    let angle: T = b.real(RATE);
    let m = {
        let mut m = [[T::ZERO; 3]; 3];
        for e in m.iter_mut().flatten() {
            *e = b.real(super::UNIT);
        }
        m
    };
    let e3: [T; 3] = [b.real(RATE), b.real(RATE), b.real(RATE)];

    // No panic, whatever the input.
    let _ = q.to_euler_zyx();
    let _ = q.to_euler_zxz();
    let _ = q.to_rotation_matrix();
    let _ = q.to_axis_angle();
    let _ = q.to_rotation_vector();
    let _ = q.normalized();
    let _ = q.inverse();
    let _ = q.norm();
    let _ = q.norm_error();
    let _ = q.rotate(v);
    let _ = q.angle_to(Quat::from_rotation_vector(v));
    let _ = Quat::from_rotation_matrix(m);
    let _ = Quat::from_axis_angle(v, angle);
    let _ = Quat::from_euler_zyx(EulerZyx {
        yaw: e3[0],
        pitch: e3[1],
        roll: e3[2],
    });
    let _ = Quat::from_euler_zxz(EulerZxz {
        psi: e3[0],
        theta: e3[1],
        phi: e3[2],
    });
    let _ = v.normalized();
    let _ = v.norm();

    // Arrays and mint: exact, bit for bit (NaN payloads included).
    let a: [T; 4] = q.into();
    assert_eq!(quat_bits(Quat::from(a)), quat_bits(q));
    let a3: [T; 3] = v.into();
    assert_eq!(vec_bits(Vec3::from(a3)), vec_bits(v));
    #[cfg(feature = "mint")]
    {
        let mq: mint::Quaternion<T> = q.into();
        assert_eq!(mq.s.bits(), q.w.bits());
        assert_eq!(quat_bits(Quat::from(mq)), quat_bits(q));
        assert_eq!(quat_bits(Quat::from_mint(mq)), quat_bits(q));
        let mv: mint::Vector3<T> = v.into();
        assert_eq!(vec_bits(Vec3::from(mv)), vec_bits(v));
        assert_eq!(vec_bits(Vec3::from_mint(mv)), vec_bits(v));
    }

    // Round trips of a finite unit quaternion.
    let Some(u) = q.normalized() else {
        assert!(
            !(q.w.is_finite() && q.x.is_finite() && q.y.is_finite() && q.z.is_finite())
                || [q.w, q.x, q.y, q.z].iter().all(|c| *c == T::ZERO),
            "normalized refused {q:?}"
        );
        return;
    };
    let eps = T::EPS;
    let meas = 16.0 * f64::EPSILON;
    let n = u.norm_error().to_f64().abs();
    assert!(n <= 4.0 * eps, "normalized: N = {n:e}");

    let phi = u.to_rotation_vector();
    let back = Quat::from_rotation_vector(phi);
    let d = angle64(u, back);
    let bound = (8.0 + 4.0 * norm64(phi)) * eps + meas;
    assert!(d <= bound, "rotation vector: {d:e} > {bound:e} for {u:?}");

    let r = u.to_rotation_matrix();
    let back =
        Quat::from_rotation_matrix(r).expect("the matrix of a unit quaternion is a rotation");
    let d = angle64(u, back);
    assert!(d <= 32.0 * eps + meas, "matrix: {d:e} for {u:?}");

    let e = u.to_euler_zyx();
    let d = angle64(u, Quat::from_euler_zyx(e));
    assert!(
        d <= 32.0 * eps + meas,
        "Euler ZYX: {d:e} for {u:?} -> {e:?}"
    );
    let pi = core::f64::consts::PI;
    // Ranges up to rounding: π rounded to T, then a few roundings of relative ε each.
    let top = pi * (1.0 + 4.0 * eps);
    assert!(e.pitch.to_f64().abs() <= top / 2.0, "{e:?}");
    assert!(
        e.yaw.to_f64().abs() <= top && e.roll.to_f64().abs() <= top,
        "{e:?}"
    );

    let e = u.to_euler_zxz();
    let d = angle64(u, Quat::from_euler_zxz(e));
    assert!(
        d <= 32.0 * eps + meas,
        "Euler ZXZ: {d:e} for {u:?} -> {e:?}"
    );
    let th = e.theta.to_f64();
    assert!((0.0..=top).contains(&th), "{e:?}");

    let (axis, ang) = u.to_axis_angle();
    let an = ang.to_f64();
    // The angle is |φ| with φ = u·2atan2(s, w)/s: atan2, the division, the product and the norm round.
    assert!((0.0..=top).contains(&an), "angle {an}");
    assert!((norm64(axis) - 1.0).abs() <= 4.0 * eps, "axis {axis:?}");
    let back = Quat::from_axis_angle(axis, ang).expect("a unit axis and a finite angle");
    let d = angle64(u, back);
    let bound = (8.0 + 4.0 * an) * eps + meas;
    assert!(d <= bound, "axis-angle: {d:e} > {bound:e} for {u:?}");

    // rotate(v) is the matrix product, for vectors that cannot overflow.
    let nv = norm64(v);
    if nv.is_finite() && nv <= T::BIG / 8.0 {
        let rv = u.rotate(v).to_f64();
        let r = r.map(|row| row.map(|x| x.to_f64()));
        let w = v.to_f64();
        let mv = Vec3::new(
            r[0][0] * w.x + r[0][1] * w.y + r[0][2] * w.z,
            r[1][0] * w.x + r[1][1] * w.y + r[1][2] * w.z,
            r[2][0] * w.x + r[2][1] * w.y + r[2][2] * w.z,
        );
        let diff = norm64(rv - mv);
        let bound = 16.0 * eps * nv + 64.0 * T::TINY;
        assert!(diff <= bound, "rotate vs matrix: {diff:e} > {bound:e}");
    }
}
