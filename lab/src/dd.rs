//! Double-double arithmetic (hi + lo, about 106 bits) for the references at physical time over 10⁸ steps:
//! the rotation angle of a constant rate, and the phase of a cone, at t = k·0.001 s exactly.

use quatprop::{Quat, Vec3};

/// The constant rate of the time-base and long-horizon studies: a skewed unit axis, |ω| = 1 rad/s before
/// rounding to f32.
pub const AXIS: Vec3<f64> = Vec3::new(0.36, -0.48, 0.80);

/// `hi + lo` with |lo| ≤ ½ ulp(hi).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dd {
    pub hi: f64,
    pub lo: f64,
}

fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    Dd {
        hi: s,
        lo: (a - (s - bb)) + (b - bb),
    }
}

/// Veltkamp's split: `a = hi + lo` with 26-bit halves (exact products between them).
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

/// Dekker's TwoProduct: `a·b = p + e` exactly (no FMA: `f64::mul_add` is a slow library call on a
/// baseline x86-64 target).
fn two_prod(a: f64, b: f64) -> Dd {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    Dd {
        hi: p,
        lo: ((ah * bh - p) + ah * bl + al * bh) + al * bl,
    }
}

impl Dd {
    pub const fn new(hi: f64, lo: f64) -> Self {
        Self { hi, lo }
    }
    pub fn from(x: f64) -> Self {
        Self { hi: x, lo: 0.0 }
    }
    fn norm(hi: f64, lo: f64) -> Self {
        let s = hi + lo;
        Self {
            hi: s,
            lo: lo - (s - hi),
        }
    }
    pub fn add(self, o: Dd) -> Dd {
        let s = two_sum(self.hi, o.hi);
        Self::norm(s.hi, s.lo + self.lo + o.lo)
    }
    pub fn sub(self, o: Dd) -> Dd {
        self.add(Dd::new(-o.hi, -o.lo))
    }
    pub fn mul(self, o: Dd) -> Dd {
        let p = two_prod(self.hi, o.hi);
        Self::norm(p.hi, p.lo + self.hi * o.lo + self.lo * o.hi)
    }
    pub fn div(self, o: Dd) -> Dd {
        let q1 = self.hi / o.hi;
        let r = self.sub(o.mul(Dd::from(q1)));
        let q2 = r.hi / o.hi;
        let r = r.sub(o.mul(Dd::from(q2)));
        let q3 = r.hi / o.hi;
        Self::norm(q1, q2).add(Dd::from(q3))
    }
    pub fn sqrt(self) -> Dd {
        let s = self.hi.sqrt();
        let r = self.sub(Dd::from(s).mul(Dd::from(s)));
        Self::norm(s, r.hi / (2.0 * s))
    }
    /// `self − n·m` with n = floor(self / m): the remainder in [0, m).
    pub fn rem(self, m: Dd) -> Dd {
        let n = (self.hi / m.hi).floor();
        let mut r = self.sub(m.mul(Dd::from(n)));
        if r.hi < 0.0 {
            r = r.add(m);
        }
        if r.hi >= m.hi {
            r = r.sub(m);
        }
        r
    }
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
}

/// 2π in double-double.
pub const TWO_PI: Dd = Dd::new(core::f64::consts::TAU, 2.449_293_598_294_706_4e-16);
/// √2 in double-double.
pub const SQRT_2: Dd = Dd::new(core::f64::consts::SQRT_2, -9.667_293_313_452_913e-17);

/// t = k / rate_hz (s) in double-double: the physical time of sample k.
pub fn time(k: u64, rate_hz: u32) -> Dd {
    // k < 2^53: exact in f64.
    Dd::from(k as f64).div(Dd::from(rate_hz as f64))
}

/// The exact attitude after a constant body rate `w` (rad/s, the f32 sample's value) for time `t`, from
/// the identity: exp(w t / 2), with |w|·t reduced modulo 4π in double-double.
pub fn constant_rate_attitude(w: Vec3<f64>, t: Dd) -> Quat<f64> {
    // |w|² of f32 values: each square exact in f64; the sum and root in double-double.
    let sq = Dd::from(w.x * w.x)
        .add(Dd::from(w.y * w.y))
        .add(Dd::from(w.z * w.z));
    let n = sq.sqrt();
    let four_pi = TWO_PI.add(TWO_PI);
    let angle = n.mul(t).rem(four_pi).to_f64();
    let axis = w * (1.0 / n.to_f64());
    let (s, c) = (0.5 * angle).sin_cos();
    Quat::new(c, s * axis.x, s * axis.y, s * axis.z)
}

/// The phase of a cone at a frequency incommensurate with the sample rate, at sample k: the cycles
/// `k·period_in_cycles` reduced to [0, 1) and scaled by 2π, all in double-double.
#[derive(Clone, Copy, Debug)]
pub struct ConePhase {
    /// Cycles per sample interval.
    per_sample: Dd,
}

impl ConePhase {
    /// A cone at 1/√2 Hz (Ω = 2π/√2) sampled at `rate_hz`.
    pub fn over_sqrt2(rate_hz: u32) -> Self {
        Self {
            per_sample: Dd::from(1.0).div(Dd::from(rate_hz as f64).mul(SQRT_2)),
        }
    }
    /// Ω·t_k reduced to [0, 2π) (rad).
    pub fn at(&self, k: u64) -> f64 {
        let frac = Dd::from(k as f64).mul(self.per_sample).rem(Dd::from(1.0));
        TWO_PI.mul(frac).to_f64()
    }
    /// Ω·h, the phase advance over one sample interval (rad).
    pub fn per_sample_angle(&self) -> f64 {
        TWO_PI.mul(self.per_sample).to_f64()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn double_double_is_exact_where_f64_is_not() {
        let t = time(100_000_001, 1000);
        assert_eq!(t.hi, 100_000.001);
        // 100000.001 is not a double: the low part holds the rest.
        assert!(t.lo != 0.0 && (t.lo.abs()) < 1e-11);
        let r = Dd::from(2.0).sqrt();
        assert_eq!(r.hi, SQRT_2.hi);
        assert!((r.lo - SQRT_2.lo).abs() < 1e-31, "{r:?}");
        // 10^5/√2 cycles: the fraction matches a 40-digit value (70710.67811865475244008443621…).
        let f = time(100_000_000, 1000).div(SQRT_2).rem(Dd::from(1.0));
        assert!(
            (f.to_f64() - 0.678_118_654_752_440_1).abs() < 1e-15,
            "{f:?}"
        );
        let phase = ConePhase::over_sqrt2(1000).at(100_000_000);
        assert!((phase - 2.0 * core::f64::consts::PI * 0.678_118_654_752_440_1).abs() < 1e-14);
        // Dekker's product is exact: (1 + 2^-30)^2 = 1 + 2^-29 + 2^-60.
        let x = 1.0 + 2f64.powi(-30);
        assert_eq!(
            two_prod(x, x),
            Dd::new(1.0 + 2f64.powi(-29), 2f64.powi(-60))
        );
    }
}
