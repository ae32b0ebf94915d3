//! The seed paper's test case: a torque-free asymmetric rigid body, with its exact rate from Jacobi elliptic
//! functions and its attitude from the angular momentum direction plus one quadrature (notes/numerics.md).
//! Both are validated here, not trusted: the rate against Euler's equations, the attitude against the rate
//! (2 q* ⊗ q' = ω) and against a tight-step fourth-order propagation.

use crate::scene::Scene;
use quatprop::{Quat, Vec3};

/// 5-point Gauss–Legendre nodes and weights on [−1, 1].
const GL5_X: [f64; 5] = [
    0.0,
    -0.538_469_310_105_683,
    0.538_469_310_105_683,
    -0.906_179_845_938_664,
    0.906_179_845_938_664,
];
const GL5_W: [f64; 5] = [
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_5,
    0.478_628_670_499_366_5,
    0.236_926_885_056_189_1,
    0.236_926_885_056_189_1,
];

/// Jacobi elliptic functions (sn, cn, dn)(u | m), 0 ≤ m ≤ 1, by the AGM and descending Landen
/// transformation (Abramowitz & Stegun 16.4).
pub fn ellipj(u: f64, m: f64) -> (f64, f64, f64) {
    if m < 1e-12 {
        // A&S 16.13: first order in m.
        let (s, c) = u.sin_cos();
        let t = 0.25 * m * (u - s * c);
        return (s - t * c, c + t * s, 1.0 - 0.5 * m * s * s);
    }
    if m >= 1.0 - 1e-15 {
        let sech = 1.0 / u.cosh();
        return (u.tanh(), sech, sech);
    }
    let mut a = [0.0f64; 32];
    let mut c = [0.0f64; 32];
    a[0] = 1.0;
    let mut b = (1.0 - m).sqrt();
    c[0] = m.sqrt();
    let mut n = 0;
    while c[n].abs() > 1e-17 && n < 30 {
        a[n + 1] = 0.5 * (a[n] + b);
        c[n + 1] = 0.5 * (a[n] - b);
        b = (a[n] * b).sqrt();
        n += 1;
    }
    let mut phi = (1u64 << n) as f64 * a[n] * u;
    for k in (1..=n).rev() {
        phi = 0.5 * (phi + (c[k] / a[k] * phi.sin()).asin());
    }
    let (s, co) = phi.sin_cos();
    // dn² = 1 − m sn² = (1 − m) + m cn²: a sum of positive terms. (A&S's cos φ₀ / cos(φ₁ − φ₀) is 0/0 at
    // u = K, where the Dzhanibekov scene starts; it gave a 0.57 Euler-equation residual there.)
    (s, co, ((1.0 - m) + m * co * co).sqrt())
}

/// Torque-free body with principal moments I1 < I2 < I3, energy T and momentum |L| (L² > 2 T I2: rotation
/// about the axis of largest inertia, the nutating motion of the seed's example).
pub struct RigidBody {
    pub key: &'static str,
    pub name: &'static str,
    /// Scene time 0 is body time `t0` (the Dzhanibekov scene starts in the quiet phase, not mid-flip).
    t0: f64,
    i: [f64; 3],
    amp: [f64; 3],
    nu: f64,
    m: f64,
    l: f64,
    /// φ at t = 0 is 0; φ(t) by composite Gauss–Legendre quadrature of φ' on a fine grid.
    phi_step: f64,
    phi_table: Vec<f64>,
}

impl RigidBody {
    /// The seed-like gyroscope: I = (1, 2, 3), ω(0) = (0.5, 0, 1.2)·… chosen with L² > 2T·I2.
    pub fn asymmetric(horizon: f64) -> Self {
        Self::new(
            "asymmetric",
            "asymmetric gyroscope (the seed's case)",
            [1.0, 2.0, 3.0],
            [1.0, 0.0, 1.5],
            0.0,
            horizon,
        )
    }

    /// The intermediate-axis (Dzhanibekov) flip: I = (1, 2, 3) next to the separatrix (L² − 2T·I2 = 1e-4,
    /// 1.6e-6 of L²; parameter m = 1 − 6.25e-6), starting in the quiet phase (spin about the intermediate axis,
    /// |ω| ≈ 4 rad/s) a quarter period (K(m)/ν = 3.19 s) before the first flip. The body flips every
    /// 2K(m)/ν = 6.39 s: the spin axis turns over in about a second, with ω2 reversing sign.
    pub fn dzhanibekov(horizon: f64) -> Self {
        let w1 = 4.0f64;
        // I3(I3 − I2) w3² − I1(I2 − I1) w1² = δ: just on the I3 side of the separatrix.
        let w3 = ((w1 * w1 + 1e-4) / 3.0).sqrt();
        let name = "intermediate-axis (Dzhanibekov) flip";
        let probe = Self::new(
            "dzhanibekov",
            name,
            [1.0, 2.0, 3.0],
            [w1, 0.0, w3],
            0.0,
            0.0,
        );
        let quarter = probe.quarter_period();
        Self::new(
            "dzhanibekov",
            name,
            [1.0, 2.0, 3.0],
            [w1, 0.0, w3],
            quarter,
            horizon,
        )
    }

    /// Parameter m of the Jacobi functions (1 on the separatrix).
    #[cfg(test)]
    pub fn parameter(&self) -> f64 {
        self.m
    }

    /// K(m)/ν: a quarter of the period of ω (s), K by the AGM: K = π / (2 AGM(1, √(1 − m))).
    pub fn quarter_period(&self) -> f64 {
        let (mut a, mut g) = (1.0f64, (1.0 - self.m).sqrt());
        while (a - g).abs() > 1e-16 * a {
            (a, g) = (0.5 * (a + g), (a * g).sqrt());
        }
        core::f64::consts::PI / (2.0 * a) / self.nu
    }

    /// Constructs the motion with ω(0) = w0 at body time 0 (ω2(0) must be 0, ω1(0), ω3(0) > 0), seen from
    /// body time `t0` on, the reference tabulated to scene time `horizon`.
    fn new(
        key: &'static str,
        name: &'static str,
        i: [f64; 3],
        w0: [f64; 3],
        t0: f64,
        horizon: f64,
    ) -> Self {
        let [i1, i2, i3] = i;
        let t2 = i1 * w0[0] * w0[0] + i2 * w0[1] * w0[1] + i3 * w0[2] * w0[2]; // 2T
        let l2 = (i1 * w0[0]).powi(2) + (i2 * w0[1]).powi(2) + (i3 * w0[2]).powi(2);
        let a1 = ((t2 * i3 - l2) / (i1 * (i3 - i1))).sqrt();
        let a2 = ((t2 * i3 - l2) / (i2 * (i3 - i2))).sqrt();
        let a3 = ((l2 - t2 * i1) / (i3 * (i3 - i1))).sqrt();
        let nu = ((i3 - i2) * (l2 - t2 * i1) / (i1 * i2 * i3)).sqrt();
        let m = (i2 - i1) * (t2 * i3 - l2) / ((i3 - i2) * (l2 - t2 * i1));
        let mut body = Self {
            key,
            name,
            t0,
            i,
            amp: [a1, a2, a3],
            nu,
            m,
            l: l2.sqrt(),
            phi_step: 1e-3,
            phi_table: Vec::new(),
        };
        // φ(t) on a grid: 5-point Gauss–Legendre per cell (error far below f64 rounding for smooth φ').
        let cells = ((t0 + horizon) / body.phi_step).ceil() as usize + 2;
        let mut acc = 0.0;
        body.phi_table.push(0.0);
        for k in 0..cells {
            acc += body.cell_integral(k as f64 * body.phi_step, body.phi_step);
            body.phi_table.push(acc);
        }
        body
    }

    fn omega(&self, t: f64) -> [f64; 3] {
        let (sn, cn, dn) = ellipj(self.nu * t, self.m);
        [self.amp[0] * cn, self.amp[1] * sn, self.amp[2] * dn]
    }

    /// φ' = |L| (I1 ω1² + I2 ω2²) / (I1² ω1² + I2² ω2²).
    fn phi_rate(&self, t: f64) -> f64 {
        let [w1, w2, _] = self.omega(t);
        let [i1, i2, _] = self.i;
        self.l * (i1 * w1 * w1 + i2 * w2 * w2) / (i1 * i1 * w1 * w1 + i2 * i2 * w2 * w2)
    }

    fn phi(&self, t: f64) -> f64 {
        if t < 0.0 {
            // Before t = 0 (central differences at 0): −∫_t^0 φ' by the same 5-point rule.
            return -self.cell_integral(t, -t);
        }
        let k = (t / self.phi_step).floor() as usize;
        let t0 = k as f64 * self.phi_step;
        let base = self.phi_table.get(k).copied().unwrap_or(f64::NAN);
        // The remainder of the cell by the same rule.
        let h = t - t0;
        if h <= 0.0 {
            return base;
        }
        base + self.cell_integral(t0, h)
    }

    /// ∫_{t0}^{t0+h} φ' dt by 5-point Gauss–Legendre.
    fn cell_integral(&self, t0: f64, h: f64) -> f64 {
        let mut s = 0.0;
        for (x, w) in GL5_X.iter().zip(GL5_W) {
            s += w * self.phi_rate(t0 + 0.5 * h * (1.0 + x));
        }
        0.5 * h * s
    }
}

impl Scene for RigidBody {
    fn key(&self) -> &'static str {
        self.key
    }
    fn name(&self) -> &'static str {
        self.name
    }
    fn rate(&self, t: f64) -> Vec3<f64> {
        let w = self.omega(self.t0 + t);
        Vec3::new(w[0], w[1], w[2])
    }
    /// R = Rz(φ) Rx(θ) Rz(ψ) (body to inertial, inertial z along L): cos θ = I3 ω3/|L|,
    /// ψ = atan2(I1 ω1, I2 ω2).
    fn attitude(&self, t: f64) -> Quat<f64> {
        let t = self.t0 + t;
        let [w1, w2, w3] = self.omega(t);
        let [i1, i2, i3] = self.i;
        let theta = (i3 * w3 / self.l).clamp(-1.0, 1.0).acos();
        let psi = (i1 * w1).atan2(i2 * w2);
        let rz = |a: f64| Quat::new((0.5 * a).cos(), 0.0, 0.0, (0.5 * a).sin());
        let rx = |a: f64| Quat::new((0.5 * a).cos(), (0.5 * a).sin(), 0.0, 0.0);
        rz(self.phi(t)) * rx(theta) * rz(psi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jacobi_functions_at_the_limits_and_identities() {
        for &u in &[0.0, 0.3, 1.7, -2.2, 5.0] {
            for &m in &[0.0, 1e-13, 0.1, 0.5, 0.9, 0.999_999, 1.0] {
                let (sn, cn, dn) = ellipj(u, m);
                assert!((sn * sn + cn * cn - 1.0).abs() < 1e-13, "u={u} m={m}");
                assert!((m * sn * sn + dn * dn - 1.0).abs() < 1e-13, "u={u} m={m}");
            }
            let (s, c, d) = ellipj(u, 0.0);
            assert!((s - u.sin()).abs() < 1e-15 && (c - u.cos()).abs() < 1e-15 && d == 1.0);
            let (s, c, d) = ellipj(u, 1.0);
            assert!(
                (s - u.tanh()).abs() < 1e-15
                    && (c - 1.0 / u.cosh()).abs() < 1e-15
                    && (d - c).abs() < 1e-15
            );
        }
        // Near m = 1 the AGM result approaches the limit continuously.
        let (s, _, _) = ellipj(0.8, 1.0 - 1e-10);
        assert!((s - 0.8f64.tanh()).abs() < 1e-9);
        // Derivative identity: d sn/du = cn dn (central difference).
        let (u, m, h) = (0.9, 0.6, 1e-6);
        let d = (ellipj(u + h, m).0 - ellipj(u - h, m).0) / (2.0 * h);
        let (_, c, dn) = ellipj(u, m);
        assert!((d - c * dn).abs() < 1e-8);
    }

    #[test]
    fn rate_satisfies_eulers_equations_and_attitude_matches_the_rate() {
        let b = RigidBody::asymmetric(20.0);
        let [i1, i2, i3] = b.i;
        for &t in &[0.0, 0.4, 3.1, 7.7, 15.2] {
            let h = 1e-6;
            let w = b.omega(t);
            let wp = b.omega(t + h);
            let wm = b.omega(t - h);
            let dw: Vec<f64> = (0..3).map(|k| (wp[k] - wm[k]) / (2.0 * h)).collect();
            let res = [
                i1 * dw[0] - (i2 - i3) * w[1] * w[2],
                i2 * dw[1] - (i3 - i1) * w[2] * w[0],
                i3 * dw[2] - (i1 - i2) * w[0] * w[1],
            ];
            assert!(
                res.iter().all(|r| r.abs() < 1e-7),
                "t={t}: Euler residual {res:?}"
            );
            // 2 q* q' = (0, ω).
            let dq = (b.attitude(t + h) - b.attitude(t - h)) * (0.5 / h);
            let omega = b.attitude(t).conjugate() * dq * 2.0;
            let r = b.rate(t);
            assert!(
                (omega.vector() - r).norm() < 1e-6 && omega.w.abs() < 1e-6,
                "t={t}: {omega:?} vs {r:?}"
            );
        }
    }

    #[test]
    fn dzhanibekov_reference_flips_and_is_validated() {
        let horizon = 13.0;
        let b = RigidBody::dzhanibekov(horizon);
        let m = b.parameter();
        let quarter = b.quarter_period();
        println!(
            "Dzhanibekov: m = 1 - {:.3e}, quarter period {quarter:.4} s",
            1.0 - m
        );
        assert!(1.0 - m > 1e-7 && 1.0 - m < 1e-5, "m = {m}");
        // Quiet phase at scene time 0: nearly all the rate on the intermediate axis.
        let w = b.rate(0.0);
        assert!(w.y.abs() > 0.999 * w.norm(), "{w:?}");
        // Flips (ω2 changes sign) at scene times K/ν (3K/ν, …) and nowhere else.
        let mut flips = Vec::new();
        let mut prev = b.rate(0.0).y;
        for k in 1..=13_000 {
            let t = k as f64 * 1e-3;
            let y = b.rate(t).y;
            if y.signum() != prev.signum() {
                flips.push(t);
            }
            prev = y;
        }
        assert_eq!(flips.len(), 2, "{flips:?}");
        assert!((flips[0] - quarter).abs() < 2e-3 && (flips[1] - 3.0 * quarter).abs() < 2e-3);
        // Euler's equations and 2 q* q' = (0, ω), across a flip.
        let [i1, i2, i3] = b.i;
        for &t in &[0.0, quarter - 0.3, quarter, quarter + 0.2, 11.5] {
            let h = 1e-6;
            let (w, wp, wm) = (b.rate(t), b.rate(t + h), b.rate(t - h));
            let dw = (wp - wm) * (0.5 / h);
            let res = [
                i1 * dw.x - (i2 - i3) * w.y * w.z,
                i2 * dw.y - (i3 - i1) * w.z * w.x,
                i3 * dw.z - (i1 - i2) * w.x * w.y,
            ];
            assert!(res.iter().all(|r| r.abs() < 1e-6), "t={t}: {res:?}");
            let dq = (b.attitude(t + h) - b.attitude(t - h)) * (0.5 / h);
            let omega = b.attitude(t).conjugate() * dq * 2.0;
            assert!((omega.vector() - w).norm() < 1e-6, "t={t}");
        }
        // Against a tight Magnus-4 propagation through the first flip.
        use crate::scene::gauss_step;
        use quatprop::input::GaussPoints;
        use quatprop::scheme::Magnus4;
        use quatprop::stabilize::Normalize;
        let h = 1e-4;
        let mut p =
            quatprop::Propagator::new(b.attitude(0.0), Magnus4, GaussPoints::new(), Normalize)
                .unwrap();
        let n = 80_000;
        for k in 0..n {
            let t = k as f64 * h;
            gauss_step(&mut p, |c| b.rate(t + c * h), h).unwrap();
        }
        let e = p.attitude().angle_to(b.attitude(n as f64 * h));
        println!("Dzhanibekov reference vs Magnus-4 at h = 1e-4 over 8 s: {e:.2e} rad");
        assert!(e < 1e-9, "reference vs Magnus-4 through the flip: {e:e}");
    }

    #[test]
    fn reference_agrees_with_a_tight_fourth_order_propagation() {
        use crate::scene::gauss_step;
        use quatprop::input::GaussPoints;
        use quatprop::scheme::Magnus4;
        use quatprop::stabilize::Normalize;
        let b = RigidBody::asymmetric(10.0);
        let h = 1e-4;
        let mut p =
            quatprop::Propagator::new(b.attitude(0.0), Magnus4, GaussPoints::new(), Normalize)
                .unwrap();
        for k in 0..100_000 {
            let t = k as f64 * h;
            gauss_step(&mut p, |c| b.rate(t + c * h), h).unwrap();
        }
        let e = p.attitude().angle_to(b.attitude(10.0));
        assert!(e < 1e-10, "reference vs Magnus-4 at h = 1e-4: {e:e}");
    }
}
