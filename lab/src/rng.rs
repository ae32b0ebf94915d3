//! The lab's random numbers: deterministic, so the studies that use noise are reproducible bit for bit.

/// splitmix64: a small deterministic generator (the study is reproducible bit for bit).
pub struct Rng(pub u64);
impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let u1 = self.uniform().max(1e-300);
        let u2 = self.uniform();
        (-2.0 * u1.ln()).sqrt() * (2.0 * core::f64::consts::PI * u2).cos()
    }
}

/// Standard normals by the ziggurat method (Marsaglia and Tsang, 2000, in Doornik's 2005 form: 128 layers,
/// the layer and the uniform from separate bits of a draw, here its low 7 and top 53): no logarithm or
/// exponential on the fast path (97 % of the draws), for the studies that need billions of normals.
pub struct Gaussian {
    rng: Rng,
    /// The layers' right edges, x₀ (the base strip's equivalent width) down to x₁₂₈ = 0.
    x: [f64; LAYERS + 1],
    /// x_{i+1} / x_i: below it, a point of layer i is under the density for certain.
    ratio: [f64; LAYERS],
}

const LAYERS: usize = 128;
/// The base layer's right edge, and each layer's area.
const ZIG_R: f64 = 3.442_619_855_899;
const ZIG_V: f64 = 9.912_563_035_262_17e-3;

impl Gaussian {
    pub fn new(seed: u64) -> Self {
        let mut x = [0.0; LAYERS + 1];
        let mut f = (-0.5 * ZIG_R * ZIG_R).exp();
        x[0] = ZIG_V / f;
        x[1] = ZIG_R;
        for i in 2..LAYERS {
            x[i] = (-2.0 * (ZIG_V / x[i - 1] + f).ln()).sqrt();
            f = (-0.5 * x[i] * x[i]).exp();
        }
        x[LAYERS] = 0.0;
        let mut ratio = [0.0; LAYERS];
        for i in 0..LAYERS {
            ratio[i] = x[i + 1] / x[i];
        }
        Self {
            rng: Rng(seed),
            x,
            ratio,
        }
    }

    /// The next standard normal.
    pub fn next(&mut self) -> f64 {
        loop {
            let bits = self.rng.next_u64();
            let i = (bits & 0x7F) as usize;
            // Uniform in [−1, 1) from the top 53 bits (through i64: a single conversion instruction).
            let u = ((bits >> 11) as i64 as f64) * (1.0 / (1u64 << 52) as f64) - 1.0;
            if u.abs() < self.ratio[i] {
                return u * self.x[i];
            }
            if i == 0 {
                return self.tail(u < 0.0);
            }
            let x = u * self.x[i];
            let f0 = (-0.5 * (self.x[i] * self.x[i] - x * x)).exp();
            let f1 = (-0.5 * (self.x[i + 1] * self.x[i + 1] - x * x)).exp();
            if f1 + self.rng.uniform() * (f0 - f1) < 1.0 {
                return x;
            }
        }
    }

    /// Beyond ZIG_R (Marsaglia's tail method).
    fn tail(&mut self, negative: bool) -> f64 {
        loop {
            let x = (1.0 - self.rng.uniform()).ln() / ZIG_R;
            let y = (1.0 - self.rng.uniform()).ln();
            if -2.0 * y >= x * x {
                return if negative { x - ZIG_R } else { ZIG_R - x };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ziggurat's moments and tail fractions are the standard normal's (4·10⁶ draws: the moments to a
    /// few of their standard errors, the fractions beyond 1, 2, 3 and 3.44 (the base layer's edge)).
    #[test]
    fn the_ziggurat_draws_standard_normals() {
        let mut g = Gaussian::new(3);
        let n = 4_000_000;
        let (mut m1, mut m2, mut m4) = (0.0, 0.0, 0.0);
        let mut beyond = [0_u32; 4];
        let edges = [1.0, 2.0, 3.0, ZIG_R];
        for _ in 0..n {
            let v = g.next();
            m1 += v;
            m2 += v * v;
            m4 += v * v * v * v;
            for (b, e) in beyond.iter_mut().zip(edges) {
                *b += u32::from(v.abs() > e);
            }
        }
        let nf = n as f64;
        let (m1, m2, m4) = (m1 / nf, m2 / nf, m4 / nf);
        assert!(m1.abs() < 4.0 / nf.sqrt(), "mean {m1}");
        assert!((m2 - 1.0).abs() < 4.0 * (2.0 / nf).sqrt(), "variance {m2}");
        assert!(
            (m4 - 3.0).abs() < 4.0 * (96.0 / nf).sqrt(),
            "fourth moment {m4}"
        );
        // P(|Z| > e) = erfc(e/√2).
        let expected = [
            0.317_310_507_862_914,
            0.045_500_263_896_358,
            0.002_699_796_063_260,
            5.761_085e-4,
        ];
        for ((b, p), e) in beyond.iter().zip(expected).zip(edges) {
            let got = f64::from(*b) / nf;
            let se = (p * (1.0 - p) / nf).sqrt();
            assert!((got - p).abs() < 4.0 * se, "beyond {e}: {got} against {p}");
        }
    }
}
