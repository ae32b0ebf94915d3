//! The predict step of an attitude estimator: the error-state transition and process noise of one
//! interval of propagation, for the attitude error and the gyro bias.
//!
//! An error-state (multiplicative) Kalman filter runs beside the [`Propagator`](crate::Propagator): the
//! propagator carries the attitude `q̂` and integrates rates with the bias estimate `b̂` removed; the filter
//! carries the covariance of the small error between them and the truth, and its update hands back a
//! correction ([`Propagator::rotate_body`](crate::Propagator::rotate_body),
//! [`Propagator::correct_bias`](crate::Propagator::correct_bias)). This module gives the filter's predict
//! step in closed form; [`crate::covariance`] keeps the covariance in a form that stays valid in `f32`.
//!
//! # Conventions
//! - The error state is `x = (δθ, δb)` (rad, rad/s): `q = q̂ ⊗ exp_q(δθ)` (the attitude error in the
//!   **body** frame; Hamilton product, `q` body to reference) and `b = b̂ + δb` (body axes).
//! - The gyro measures `ω_m = ω + b + n_g`; the bias walks, `ḃ = n_b`; `n_g`, `n_b` white, with the
//!   spectral densities of [`GyroNoise`]. The propagator integrates `ω̂ = ω_m − b̂`.
//! - Then `δθ' = −[ω̂×] δθ − δb − n_g` and `δb' = n_b`. Over an interval of length `Δt` in which the body
//!   turned by the rotation vector `φ` (body frame, `q̂(t₁) = q̂(t₀) ⊗ exp_q(φ)`), with the rate held at
//!   `φ/Δt` (Trawny & Roumeliotis, *Indirect Kalman Filter for 3D Attitude Estimation*, 2005, §2.4, in
//!   this convention; `U = [φ×]`, `x = |φ|`):
//!
//! ```text
//! Φ = | Φθθ  Φθb |   Φθθ = exp(−U) = I − (sin x / x) U + ((1 − cos x)/x²) U²     (the rotation taken, transposed)
//!     |  0    I  |   Φθb = −Δt (I − ((1 − cos x)/x²) U + ((x − sin x)/x³) U²)
//!
//! Q = | Qθθ  Qθb |   Qθθ = σ_g² Δt I + σ_b² Δt³ (I/3 + ((x³/3 + 2 sin x − 2x)/x⁵) U²)
//!     | Qθbᵀ Qbb |   Qθb = −σ_b² Δt² (I/2 − ((x − sin x)/x³) U + ((x²/2 − 1 + cos x)/x⁴) U²)
//!                    Qbb = σ_b² Δt I
//! ```
//!
//! Each coefficient is evaluated without cancellation (a Taylor series up to `x = 2`), and the `U²` terms
//! are folded into the identity where that cancels (`I/3 + c₄U² = 2c₂ I + c₄φφᵀ`, with `c₂ = (x − sin
//! x)/x³` and `c₄` its neighbour above: both non-negative, so `Qθθ`'s diagonal is, in any rounding). The
//! whole is checked against an `f64` Van Loan discretization of the continuous model (within 2.4e-15;
//! `f32` within 1.5 ε of `f64`: `tests/error_state.rs`).
//!
//! # At a rate of its own
//! The covariance need not be propagated at every attitude step. [`Step::between`] takes the attitude at
//! both ends of an interval of `n` steps: `Φθθ` is then exactly the rotation the propagator took (its
//! input model included), and `Φθb` and `Q` hold the interval's mean rate: `Φθb`'s error relative to `Δt`
//! is at most `|ω̇| Δt²/12` (the first moment of the rate over the interval; 1.2e-4 for a rate changing
//! at 35 rad/s² over 10 ms, `tests/error_state.rs`), `Q`'s far less (its white-noise part, `σ_g² Δt I`,
//! is exact whatever the rotation).
//!
//! ```
//! use quatprop::error_state::{GyroNoise, Step};
//! use quatprop::{GyroSample, Propagator, Quat, Vec3};
//! // A datasheet: angle random walk 0.2 °/√h, bias random walk 5 °/h/√h.
//! let noise = GyroNoise::<f64>::from_datasheet(0.2, 5.0)?;
//! let mut p = Propagator::recommended(Quat::IDENTITY)?;
//! let yaw = GyroSample::new(Vec3::new(0.0, 0.0, 1.0)); // 1 rad/s
//! p.start(yaw)?;
//! let start = p.attitude();
//! for _ in 0..10 {
//!     p.push(yaw, 1.0e-3)?; // 1 kHz
//! }
//! let step = Step::between(start, p.attitude(), 10.0e-3, &noise)?; // one covariance step per 10
//! let (phi, q) = step.matrices();
//! assert!((phi[0][0] - 0.01_f64.cos()).abs() < 1e-12); // 10 mrad of yaw in Φθθ
//! assert!((phi[0][3] + 10.0e-3).abs() < 1e-6); // a bias error integrates into the angle
//! let arw = 0.2_f64.to_radians() / 60.0; // rad/√s
//! assert!((q[0][0] / (arw * arw * 10.0e-3) - 1.0).abs() < 1e-4); // white noise: σ_g² Δt
//! # Ok::<(), quatprop::Error>(())
//! ```

mod step;

/// The gyro's noise densities the predict step takes (defined in [`crate::noise`], where they are also
/// identified from a recording).
pub use crate::noise::GyroNoise;
pub use step::{ProcessNoise, Step, Transition};
