//! Fusion (a C library): its gyroscope update and its run-time bias estimator `FusionOffset`, implemented
//! here from its published source (FusionAhrs.c, FusionOffset.c); with the `fusion-c` feature the real
//! `FusionOffset` too, compiled from Fusion's C source by the `fusion-imu-sys` crate. The Rust peers
//! (`ahrs`, `nalgebra`, `glam`) are used as crates (`crate::configs`). f32; rates in rad/s (FusionOffset:
//! °/s, as Fusion takes them), body frame, `q ← q ⊗ (…)`.

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

/// Fusion's `FusionOffset` (FusionOffset.c), statement for statement: rates in °/s, f32.
///
/// `filterCoefficient = 2π·fc/fs` with fc = 0.02 Hz; the offset is subtracted first; the timer restarts
/// whenever an axis of the corrected rate exceeds 3 °/s; after 5 s of stillness (the timer counts samples
/// up to `5·fs`) every sample adds `corrected · filterCoefficient` to the offset (a first-order low-pass).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FusionOffset {
    filter_coefficient: f32,
    timeout: u32,
    timer: u32,
    offset: [f32; 3],
}

impl FusionOffset {
    /// `CUTOFF_FREQUENCY` (Hz).
    pub const CUTOFF_FREQUENCY: f32 = 0.02;
    /// `TIMEOUT` (s).
    pub const TIMEOUT: u32 = 5;
    /// `THRESHOLD` (°/s).
    pub const THRESHOLD: f32 = 3.0;

    /// `FusionOffsetInitialise(offset, sampleRate)`.
    pub fn new(sample_rate: u32) -> Self {
        // C: 2.0f * (float) M_PI * CUTOFF_FREQUENCY * (1.0f / (float) sampleRate), left to right in float.
        let pi = core::f64::consts::PI as f32;
        Self {
            filter_coefficient: 2.0f32
                * pi
                * Self::CUTOFF_FREQUENCY
                * (1.0f32 / sample_rate as f32),
            timeout: Self::TIMEOUT * sample_rate,
            timer: 0,
            offset: [0.0; 3],
        }
    }

    /// `FusionOffsetUpdate(offset, gyroscope)`: the corrected rate (°/s).
    pub fn update(&mut self, gyroscope: [f32; 3]) -> [f32; 3] {
        let g = [
            gyroscope[0] - self.offset[0],
            gyroscope[1] - self.offset[1],
            gyroscope[2] - self.offset[2],
        ];
        if g.iter().any(|a| a.abs() > Self::THRESHOLD) {
            self.timer = 0;
            return g;
        }
        if self.timer < self.timeout {
            self.timer += 1;
            return g;
        }
        for (o, a) in self.offset.iter_mut().zip(g) {
            *o += a * self.filter_coefficient;
        }
        g
    }

    /// The offset estimate (°/s).
    pub fn offset(&self) -> [f32; 3] {
        self.offset
    }

    /// The filter coefficient (per sample).
    pub fn filter_coefficient(&self) -> f32 {
        self.filter_coefficient
    }
}

/// The real `FusionOffset`: Fusion's C code (vendored by `fusion-imu-sys`, compiled by its build script).
#[cfg(feature = "fusion-c")]
pub struct FusionOffsetC {
    inner: fusion_imu_sys::FusionOffset,
}

#[cfg(feature = "fusion-c")]
impl FusionOffsetC {
    /// `FusionOffsetInitialise(offset, sampleRate)` in C.
    pub fn new(sample_rate: u32) -> Self {
        let mut o = core::mem::MaybeUninit::<fusion_imu_sys::FusionOffset>::uninit();
        // SAFETY: FusionOffsetInitialise writes every field of the struct it is given.
        unsafe {
            fusion_imu_sys::FusionOffsetInitialise(o.as_mut_ptr(), sample_rate);
            Self {
                inner: o.assume_init(),
            }
        }
    }

    /// `FusionOffsetUpdate(offset, gyroscope)` in C: the corrected rate (°/s).
    pub fn update(&mut self, gyroscope: [f32; 3]) -> [f32; 3] {
        let v = fusion_imu_sys::FusionVector { array: gyroscope };
        // SAFETY: a valid, initialised struct; FusionVector is a union of float[3] and {x, y, z}: both
        // views are plain floats, so reading `array` is always defined.
        unsafe { fusion_imu_sys::FusionOffsetUpdate(&mut self.inner, v).array }
    }

    /// The offset estimate (°/s).
    pub fn offset(&self) -> [f32; 3] {
        // SAFETY: as above (a union of plain floats).
        unsafe { self.inner.gyroscopeOffset.array }
    }

    /// The filter coefficient the C code computed.
    pub fn filter_coefficient(&self) -> f32 {
        self.inner.filterCoefficient
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The re-implementation's timing: nothing learned during the first 5 s of stillness (5000 samples at
    /// 1 kHz fill the timer), then offset += corrected · 2π·0.02/1000 each sample.
    #[test]
    fn fusion_offset_waits_five_seconds_then_low_passes() {
        let mut f = FusionOffset::new(1000);
        assert_eq!(
            f.filter_coefficient(),
            2.0 * (core::f64::consts::PI as f32) * 0.02 * 0.001
        );
        for _ in 0..5000 {
            assert_eq!(f.update([1.0, -1.0, 0.5]), [1.0, -1.0, 0.5]);
        }
        assert_eq!(f.offset(), [0.0; 3]);
        f.update([1.0, -1.0, 0.5]);
        assert_eq!(f.offset()[0], f.filter_coefficient());
        // A moving sample (4 °/s > 3 °/s) restarts the timer: 5000 more still samples before learning again.
        f.update([4.0, 0.0, 0.0]);
        let before = f.offset();
        for _ in 0..5000 {
            f.update([1.0, -1.0, 0.5]);
        }
        assert_eq!(f.offset(), before);
    }

    /// With the `fusion-c` feature: the C code and the re-implementation agree bit for bit.
    #[cfg(feature = "fusion-c")]
    #[test]
    fn fusion_offset_c_and_reimplementation_agree_bit_for_bit() {
        let (mut c, mut r) = (FusionOffsetC::new(1000), FusionOffset::new(1000));
        assert_eq!(
            c.filter_coefficient().to_bits(),
            r.filter_coefficient().to_bits()
        );
        for k in 0..20_000u32 {
            let x = (k as f32 * 0.37).sin();
            let g = [
                0.6 + 0.1 * x,
                -0.4 - 0.05 * x,
                if k % 7000 == 0 { 5.0 } else { 0.25 },
            ];
            assert_eq!(c.update(g).map(f32::to_bits), r.update(g).map(f32::to_bits));
            assert_eq!(c.offset().map(f32::to_bits), r.offset().map(f32::to_bits));
        }
    }

    #[test]
    fn fusion_inverse_sqrt_is_close_but_biased() {
        // Relative error of the fast inverse square root near 1 (what keeps Fusion's |q| at ~1.00012).
        let r = fusion_fast_inverse_sqrt(1.0);
        assert!((r - 1.0).abs() < 1e-3, "{r}");
        assert!(r != 1.0);
    }
}
