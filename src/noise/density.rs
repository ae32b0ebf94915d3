//! A gyro's noise densities, from a datasheet or from an Allan variance fit.

use super::{NoiseFit, FLICKER_FLOOR};
use crate::{Error, Real};

/// The white noise and the bias random walk of a gyro, as spectral densities in SI units: `arw` (rad/√s
/// = rad/s/√Hz, the angle random walk) and `bias_walk` (rad/s/√s, the rate random walk of the bias). The
/// same on every axis.
///
/// Datasheets give them as an angle random walk in °/√h (or a noise density in °/s/√Hz, `°/√h =
/// 60 · °/s/√Hz`) and a bias random walk in °/h/√h, both read off an Allan deviation plot (IEEE Std
/// 952-1997: the ARW at τ = 1 h on the −½ slope, the rate random walk at τ = 3 h on the +½ slope). A
/// datasheet's *bias instability* (°/h, the flat bottom of the plot) is not a random walk;
/// [`GyroNoise::with_bias_instability`] turns it into one over a correlation time.
///
/// ```
/// use quatprop::error_state::GyroNoise;
/// let n = GyroNoise::<f64>::from_datasheet(0.2, 5.0)?;        // ARW 0.2 °/√h, RRW 5 °/h/√h
/// assert!((n.arw() - 0.2_f64.to_radians() / 60.0).abs() < 1e-18);  // rad/√s
/// let d = GyroNoise::<f64>::from_noise_density_dps(0.005, 0.0)?;  // 0.005 °/s/√Hz (a MEMS part)
/// assert!((d.arw() - 0.3_f64.to_radians() / 60.0).abs() < 1e-18); // = 0.3 °/√h
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GyroNoise<T> {
    arw: T,
    bias_walk: T,
}

const DEG: f64 = core::f64::consts::PI / 180.0;

impl<T: Real> GyroNoise<T> {
    /// From SI densities: `arw` in rad/√s (= rad/s/√Hz), `bias_walk` in rad/s/√s.
    ///
    /// # Errors
    /// [`Error::InvalidNoise`] if either is negative, NaN or infinite.
    pub fn new(arw: T, bias_walk: T) -> Result<Self, Error> {
        let ok = |v: T| v >= T::ZERO && v.is_finite();
        if ok(arw) && ok(bias_walk) {
            Ok(Self { arw, bias_walk })
        } else {
            Err(Error::InvalidNoise)
        }
    }

    /// From a datasheet: angle random walk in °/√h, bias (rate) random walk in °/h/√h.
    ///
    /// # Errors
    /// [`Error::InvalidNoise`] if either is negative, NaN or infinite.
    pub fn from_datasheet(
        arw_deg_per_sqrt_hour: f64,
        bias_walk_deg_per_hour_per_sqrt_hour: f64,
    ) -> Result<Self, Error> {
        Self::new(
            T::from_f64(arw_deg_per_sqrt_hour * DEG / 60.0),
            T::from_f64(bias_walk_deg_per_hour_per_sqrt_hour * DEG / (3600.0 * 60.0)),
        )
    }

    /// From a MEMS datasheet's rate noise density in °/s/√Hz and a bias random walk in °/h/√h.
    ///
    /// # Errors
    /// [`Error::InvalidNoise`] if either is negative, NaN or infinite.
    pub fn from_noise_density_dps(
        density_dps_per_sqrt_hz: f64,
        bias_walk_deg_per_hour_per_sqrt_hour: f64,
    ) -> Result<Self, Error> {
        Self::from_datasheet(
            density_dps_per_sqrt_hz * 60.0,
            bias_walk_deg_per_hour_per_sqrt_hour,
        )
    }

    /// A bias instability `sigma` (°/h, the Allan deviation's floor) taken as a first-order Gauss–Markov
    /// bias of standard deviation `sigma` and correlation time `tau` (s), modelled as the random walk with
    /// the same driving noise, `2σ²/τ` (rad²/s³): exact for intervals much shorter than `tau`, and it
    /// lets the variance grow without bound beyond (conservative). Replaces the bias random walk.
    ///
    /// # Errors
    /// [`Error::InvalidNoise`] if `sigma` is negative or `tau` not positive, or either is not finite.
    pub fn with_bias_instability(self, sigma_deg_per_hour: f64, tau: f64) -> Result<Self, Error> {
        if !(sigma_deg_per_hour >= 0.0
            && sigma_deg_per_hour.is_finite()
            && tau > 0.0
            && tau.is_finite())
        {
            return Err(Error::InvalidNoise);
        }
        let sigma = sigma_deg_per_hour * DEG / 3600.0;
        Self::new(self.arw, T::from_f64(sigma * libm::sqrt(2.0 / tau)))
    }

    /// From an Allan variance fit of the gyro at rest ([`NoiseFit`], in rad/s): the white noise's density
    /// as the angle random walk, and as the bias random walk the fitted rate random walk plus the bias
    /// instability taken as a Gauss–Markov bias whose correlation time is the longest τ fitted
    /// (`K² + 2σ_B²/τ_max`, `σ_B = 0.664 B` the floor: as [`GyroNoise::with_bias_instability`]). A term
    /// the recording did not identify counts with its fitted value (often zero): give a datasheet's value
    /// with [`GyroNoise::new`] where the recording was too short to show it.
    ///
    /// # Errors
    /// [`Error::InvalidNoise`] if a density is not finite (a fit of no points cannot be made).
    pub fn from_fit(fit: &NoiseFit) -> Result<Self, Error> {
        let floor = FLICKER_FLOOR * fit.instability.coefficient;
        let tau = fit.tau_range.1;
        let walk = fit.random_walk.coefficient + if tau > 0.0 { 2.0 * floor / tau } else { 0.0 };
        Self::new(
            T::from_f64(fit.white.value()),
            T::from_f64(libm::sqrt(walk)),
        )
    }

    /// The angle random walk (rad/√s): the white rate noise's density `σ_g`.
    #[must_use]
    pub fn arw(&self) -> T {
        self.arw
    }

    /// The bias random walk (rad/s/√s): the bias's driving noise density `σ_b`.
    #[must_use]
    pub fn bias_walk(&self) -> T {
        self.bias_walk
    }
}
