//! Fusion (a C library): its gyroscope update, implemented here from its published source (FusionAhrs.c).
//! The Rust peers (`ahrs`, `nalgebra`, `glam`) are used as crates (`crate::configs`, their types converted
//! in `crate::peer_types`). Fusion's bias estimator runs as its own code (imufusion) in
//! python/benchmarks/bias.py. f32; rates in rad/s, body frame, `q ← q ⊗ (…)`.

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
