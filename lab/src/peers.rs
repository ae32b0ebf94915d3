//! Peer updates, implemented here from their published formulas (lab only; see shared notes/peers.md).
//! All run in f32 on the same samples as quatprop; rates in rad/s, body frame, `q ← q ⊗ (…)`.

use quatprop::{Quat, Vec3};

/// Fusion's `FusionFastInverseSqrt` (FusionMath.h): Pizer's constant 0x5F1F1412 and one refined Newton step.
#[allow(clippy::excessive_precision)] // Fusion's published constants, digit for digit
pub fn fusion_fast_inverse_sqrt(x: f32) -> f32 {
    let i = 0x5F1F_1412_i32.wrapping_sub((x.to_bits() as i32) >> 1);
    let y = f32::from_bits(i as u32);
    y * (1.690_002_3 - 0.714_158_17 * x * y * y)
}

fn mul_pure(q: Quat<f32>, v: Vec3<f32>) -> Quat<f32> {
    q * Quat::from_parts(0.0, v)
}

/// Fusion-style (FusionAhrs.c, gyroscope part): Euler `q += q ⊗ (0, ω) · dt/2`, then normalized with the fast
/// inverse square root.
pub fn fusion_euler(q: Quat<f32>, w: Vec3<f32>, dt: f32) -> Quat<f32> {
    let q = q + mul_pure(q, w * (0.5 * dt));
    q * fusion_fast_inverse_sqrt(q.norm_squared())
}

/// `ahrs` crate (Madgwick/Mahony gyro-only update): Euler `q += ½ q ⊗ (0, ω) dt`, exact normalization.
pub fn ahrs_euler(q: Quat<f32>, w: Vec3<f32>, dt: f32) -> Quat<f32> {
    let q = q + mul_pure(q, w * (0.5 * dt));
    q * (1.0 / q.norm_squared().sqrt())
}

/// glam `Quat::from_scaled_axis` (exact sin/cos; identity at zero) on the trapezoid mean rate, then
/// `normalize` — the PX4/glam-style exponential map.
pub fn glam_trapezoid(q: Quat<f32>, w0: Vec3<f32>, w1: Vec3<f32>, dt: f32) -> Quat<f32> {
    let v = (w0 + w1) * (0.5 * dt);
    let angle = v.norm_squared().sqrt();
    let e = if angle == 0.0 {
        Quat::IDENTITY
    } else {
        let (s, c) = (0.5 * angle).sin_cos();
        Quat::from_parts(c, v * (s / angle))
    };
    let q = q * e;
    q * (1.0 / q.norm_squared().sqrt())
}

/// nalgebra-style: classic RK4 on `q' = ½ q ⊗ (0, ω(t))` with ω linear between the samples, then
/// `renormalize` (exact).
pub fn rk4_renormalize(q: Quat<f32>, w0: Vec3<f32>, w1: Vec3<f32>, dt: f32) -> Quat<f32> {
    let f = |y: Quat<f32>, w: Vec3<f32>| mul_pure(y, w * 0.5);
    let wm = (w0 + w1) * 0.5;
    let k1 = f(q, w0);
    let k2 = f(q + k1 * (0.5 * dt), wm);
    let k3 = f(q + k2 * (0.5 * dt), wm);
    let k4 = f(q + k3 * dt, w1);
    let q = q + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (dt / 6.0);
    q * (1.0 / q.norm_squared().sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fusion_inverse_sqrt_is_close_but_biased() {
        // Relative error of the fast inverse square root near 1 (what keeps Fusion's |q| at ~1.00012).
        let r = fusion_fast_inverse_sqrt(1.0);
        assert!((r - 1.0).abs() < 1e-3, "{r}");
        assert!(r != 1.0);
    }
}
