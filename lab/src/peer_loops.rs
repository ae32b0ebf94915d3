//! Each peer as its users write it: one plain loop over a stream, the peer's state in a local, the peer's
//! call once per sample. The lab's peer wrappers (`configs.rs`, fed piece by piece through `Integrator`)
//! must give these loops' attitudes bit for bit (tested there) and cost what they cost: the work-precision
//! headline times each loop beside its wrapper in the same sweep (table `work_precision_peer_loops.csv`).
//!
//! A stream's first sample only starts it (its interval is not integrated), as in the wrappers.

use crate::peer_types::{ahrs_vec, from_ahrs, from_na, na_vec, to_ahrs, to_na, NaQuat, PeerReal};
use crate::peers;
use crate::sample::Sample;
use quatprop::{Quat, Vec3};

/// Fusion: `fusion_euler` per sample (the newest sample over its interval).
pub fn fusion(q0: Quat<f32>, samples: &[Sample<f32>]) -> Quat<f32> {
    let mut q = q0;
    for s in samples.iter().skip(1) {
        q = peers::fusion_euler(q, s.w, s.dt);
    }
    q
}

/// `ahrs`: `Madgwick::update_gyro` per sample (its fixed `sample_period`; the sample's dt is not used).
pub fn ahrs_madgwick<T: PeerReal>(q0: Quat<T>, sample_period: T, samples: &[Sample<T>]) -> Quat<T> {
    use ahrs::Ahrs as _;
    let mut madgwick = ahrs::Madgwick::new_with_quat(sample_period, T::ZERO, to_ahrs(q0));
    for s in samples.iter().skip(1) {
        madgwick.update_gyro(&ahrs_vec(s.w));
    }
    from_ahrs(&madgwick.quat)
}

/// nalgebra: classic RK4 on `q' = ½ q ⊗ (0, ω)` with linear rates, then `UnitQuaternion::new_normalize`.
pub fn nalgebra_rk4<T: PeerReal>(q0: Quat<T>, samples: &[Sample<T>]) -> Quat<T> {
    let mut q = to_na(q0);
    for pair in samples.windows(2) {
        q = nalgebra_rk4_step(q, pair[0].w, pair[1].w, pair[1].dt);
    }
    from_na(&q)
}

/// One step of [`nalgebra_rk4`] over an interval `h` whose rate goes linearly from `w0` to `w1` (its
/// wrapper in `configs.rs` takes the same step, so the two agree bit for bit).
#[inline]
pub fn nalgebra_rk4_step<T: PeerReal>(q: NaQuat<T>, w0: Vec3<T>, w1: Vec3<T>, h: T) -> NaQuat<T> {
    let half = T::HALF;
    let (two, six) = (T::TWO, <T as quatprop::Real>::from_f64(6.0));
    let f = |y: &nalgebra::Quaternion<T>, w: Vec3<T>| {
        y * nalgebra::Quaternion::from_imag(na_vec(w * half))
    };
    let wm = (w0 + w1) * half;
    let y = q.into_inner();
    let k1 = f(&y, w0);
    let k2 = f(&(y + k1 * (h * half)), wm);
    let k3 = f(&(y + k2 * (h * half)), wm);
    let k4 = f(&(y + k3 * h), w1);
    NaQuat::new_normalize(y + (k1 + k2 * two + k3 * two + k4) * (h / six))
}

/// nalgebra: `q *= UnitQuaternion::from_scaled_axis(ω̄ dt)` on the trapezoid mean rate.
pub fn nalgebra_scaled_axis<T: PeerReal>(q0: Quat<T>, samples: &[Sample<T>]) -> Quat<T> {
    let mut q = to_na(q0);
    for pair in samples.windows(2) {
        let v = (pair[0].w + pair[1].w) * (T::HALF * pair[1].dt);
        q *= nalgebra::UnitQuaternion::from_scaled_axis(na_vec(v));
    }
    from_na(&q)
}

/// glam's loop in one precision: `q = (q * Quat::from_scaled_axis(ω̄ dt)).normalize()` on the trapezoid
/// mean rate. A macro: glam's f32 and f64 quaternions are distinct types with no trait in common.
macro_rules! glam_scaled_axis_loop {
    ($(#[$doc:meta])* $name:ident, $real:ty, $quat:ty, $vec:ty) => {
        $(#[$doc])*
        pub fn $name(q0: Quat<$real>, samples: &[Sample<$real>]) -> Quat<$real> {
            let mut q = <$quat>::from(mint::Quaternion::from(q0));
            for pair in samples.windows(2) {
                let v = (pair[0].w + pair[1].w) * (0.5 * pair[1].dt);
                let v = <$vec>::from(mint::Vector3::from(v));
                q = (q * <$quat>::from_scaled_axis(v)).normalize();
            }
            Quat::from_mint(q)
        }
    };
}
glam_scaled_axis_loop!(
    /// glam (f32): `q = (q * Quat::from_scaled_axis(ω̄ dt)).normalize()` on the trapezoid mean rate.
    glam_scaled_axis, f32, glam::Quat, glam::Vec3
);
glam_scaled_axis_loop!(
    /// glam (f64): the same with `DQuat`.
    dglam_scaled_axis, f64, glam::DQuat, glam::DVec3
);

#[cfg(test)]
mod tests {
    use crate::sample::Sample;
    use quatprop::Quat;

    /// A plain loop over a one-sample stream does nothing (the first sample only starts).
    #[test]
    fn a_first_sample_only_starts() {
        let s = [Sample {
            w: quatprop::Vec3::new(1.0f32, 2.0, 3.0),
            dt: 0.0,
        }];
        let q = Quat::<f32>::IDENTITY;
        assert_eq!(super::fusion(q, &s), q);
        assert_eq!(super::glam_scaled_axis(q, &s), q);
        assert_eq!(super::nalgebra_scaled_axis(q, &s), q);
        assert_eq!(super::nalgebra_rk4(q, &s), q);
        assert_eq!(super::ahrs_madgwick(q, 1e-3, &s), q);
    }
}
