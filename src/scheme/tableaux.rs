//! The five explicit Runge–Kutta tableaux, with their sources. Unused entries are zero.
//!
//! ```text
//!  Euler          Rk2 (midpoint)    Rk3 (Kutta)            Rk4 (classic)
//!  0 |            0  |               0  |                   0  |
//! ---+---         1/2| 1/2           1/2| 1/2               1/2| 1/2
//!    | 1          ---+---------      1  | -1   2            1/2| 0    1/2
//!                    | 0    1        ---+---------------    1  | 0    0    1
//!                                       | 1/6  2/3  1/6     ---+---------------------
//!                                                              | 1/6  1/3  1/3  1/6
//! ```
//! Rk5 is the fifth-order solution of Dormand–Prince 5(4) (its first six stages; the seventh only
//! serves the embedded error estimate).

use super::tableau::{ButcherTableau, MAX_STAGES};
use super::Information;

const Z: [f64; MAX_STAGES] = [0.0; MAX_STAGES];

/// A Runge–Kutta scheme's type, written once for all five: the unit struct (with the doc comments given)
/// and its [`ButcherTableau`] from its order, its number of stages and its coefficients `c`, `a` (by
/// row) and `b`.
macro_rules! tableau {
    (
        $(#[doc = $doc:expr])*
        $name:ident: order $order:expr, stages $stages:expr,
        c $c:expr,
        a $a:expr,
        b $b:expr $(,)?
    ) => {
        $(#[doc = $doc])*
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        pub struct $name;

        impl ButcherTableau for $name {
            const NAME: &'static str = stringify!($name);
            const ORDER: u32 = $order;
            const STAGES: usize = $stages;
            const C: [f64; MAX_STAGES] = $c;
            const A: [[f64; MAX_STAGES]; MAX_STAGES] = $a;
            const B: [f64; MAX_STAGES] = $b;
        }
    };
}

tableau!(
    /// Forward Euler (RK1): one stage, order 1. `|R(ix)|² = 1 + x²`: gains norm every step.
    /// Source: Hairer, Nørsett, Wanner, *Solving ODEs I*, §II.1.
    Euler: order 1, stages 1,
    c Z,
    a [Z; MAX_STAGES],
    b [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
);

tableau!(
    /// Explicit midpoint rule (RK2): two stages, order 2. `|R(ix)|² = 1 + x⁴/4`: gains norm every step.
    /// Source: Hairer, Nørsett, Wanner, *Solving ODEs I*, eq. (II.1.3) (Runge 1895).
    Rk2: order 2, stages 2,
    c [0.0, 1.0 / 2.0, 0.0, 0.0, 0.0, 0.0],
    a [Z, [1.0 / 2.0, 0.0, 0.0, 0.0, 0.0, 0.0], Z, Z, Z, Z],
    b [0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
);

tableau!(
    /// Kutta's third-order method (RK3). `|R(ix)|² = 1 − x⁴/12 + x⁶/36`: stable for `h|ω| ≤ 2√3`.
    /// Source: Kutta (1901); Hairer, Nørsett, Wanner, *Solving ODEs I*, Table II.1.1 (left).
    Rk3: order 3, stages 3,
    c [0.0, 1.0 / 2.0, 1.0, 0.0, 0.0, 0.0],
    a [
        Z,
        [ 1.0 / 2.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [-1.0,       2.0, 0.0, 0.0, 0.0, 0.0],
        Z, Z, Z,
    ],
    b [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0, 0.0, 0.0, 0.0],
);

tableau!(
    /// The classic fourth-order Runge–Kutta method, the seed paper's integrator.
    /// `|R(ix)|² = 1 − x⁶/72 + x⁸/576 = 1 − β` (the seed's eq. (3)): stable for `h|ω| ≤ 4√2`.
    /// Source: Kutta (1901); Hairer, Nørsett, Wanner, *Solving ODEs I*, Table II.1.2 (left).
    Rk4: order 4, stages 4,
    c [0.0, 1.0 / 2.0, 1.0 / 2.0, 1.0, 0.0, 0.0],
    a [
        Z,
        [1.0 / 2.0, 0.0,       0.0, 0.0, 0.0, 0.0],
        [0.0,       1.0 / 2.0, 0.0, 0.0, 0.0, 0.0],
        [0.0,       0.0,       1.0, 0.0, 0.0, 0.0],
        Z, Z,
    ],
    b [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0, 0.0, 0.0],
);

tableau!(
    /// Fifth-order solution of Dormand–Prince 5(4), six stages.
    ///
    /// Its stability polynomial is `R = T₅(z) + z⁶/600`, so `|R(ix)|² = 1 − x⁶/1800 + O(x⁸)`: it loses norm like
    /// RK4 (Cash–Karp and Butcher's RK5, with `z⁶` coefficients 1/800 and 1/1280 below 1/720, gain norm near
    /// zero instead). Stable for step angles `h·max|ω|` up to ≈ 1.99 (its `information().step_angle_limit`;
    /// see docs/schemes.md).
    /// Source: Dormand & Prince, J. Comput. Appl. Math. 6 (1980) 19–26, Table 2; Hairer, Nørsett, Wanner,
    /// *Solving ODEs I*, Table II.5.2.
    Rk5: order 5, stages 6,
    c [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0],
    a [
        Z,
        [1.0 / 5.0,            0.0,                   0.0,                  0.0,               0.0,                 0.0],
        [3.0 / 40.0,           9.0 / 40.0,            0.0,                  0.0,               0.0,                 0.0],
        [44.0 / 45.0,          -56.0 / 15.0,          32.0 / 9.0,           0.0,               0.0,                 0.0],
        [19372.0 / 6561.0,     -25360.0 / 2187.0,     64448.0 / 6561.0,     -212.0 / 729.0,    0.0,                 0.0],
        [9017.0 / 3168.0,      -355.0 / 33.0,         46732.0 / 5247.0,     49.0 / 176.0,      -5103.0 / 18656.0,   0.0],
    ],
    b [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scheme::tableau::stability_polynomial;

    type V = [f64; MAX_STAGES];

    fn dot(a: &V, b: &V) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }
    fn had(a: &V, b: &V) -> V {
        core::array::from_fn(|i| a[i] * b[i])
    }
    fn mat(a: &[[f64; MAX_STAGES]; MAX_STAGES], v: &V) -> V {
        core::array::from_fn(|i| dot(&a[i], v))
    }

    /// Residuals of the order conditions for trees of order 1 … 5 (Butcher; Hairer–Nørsett–Wanner Table II.2.2),
    /// grouped by order.
    fn order_condition_residuals<Tab: ButcherTableau>() -> [[f64; 9]; 5] {
        let (a, b, c) = (&Tab::A, &Tab::B, &Tab::C);
        let one = [1.0; MAX_STAGES];
        let c2 = had(c, c);
        let c3 = had(&c2, c);
        let ac = mat(a, c);
        let ac2 = mat(a, &c2);
        let aac = mat(a, &ac);
        let mut r = [[0.0; 9]; 5];
        r[0][0] = dot(b, &one) - 1.0;
        r[1][0] = dot(b, c) - 1.0 / 2.0;
        r[2][0] = dot(b, &c2) - 1.0 / 3.0;
        r[2][1] = dot(b, &ac) - 1.0 / 6.0;
        r[3][0] = dot(b, &c3) - 1.0 / 4.0;
        r[3][1] = dot(b, &had(c, &ac)) - 1.0 / 8.0;
        r[3][2] = dot(b, &ac2) - 1.0 / 12.0;
        r[3][3] = dot(b, &aac) - 1.0 / 24.0;
        r[4][0] = dot(b, &had(&c3, c)) - 1.0 / 5.0;
        r[4][1] = dot(b, &had(&c2, &ac)) - 1.0 / 10.0;
        r[4][2] = dot(b, &had(c, &ac2)) - 1.0 / 15.0;
        r[4][3] = dot(b, &had(c, &aac)) - 1.0 / 30.0;
        r[4][4] = dot(b, &had(&ac, &ac)) - 1.0 / 20.0;
        r[4][5] = dot(b, &mat(a, &c3)) - 1.0 / 20.0;
        r[4][6] = dot(b, &mat(a, &had(c, &ac))) - 1.0 / 40.0;
        r[4][7] = dot(b, &mat(a, &ac2)) - 1.0 / 60.0;
        r[4][8] = dot(b, &mat(a, &aac)) - 1.0 / 120.0;
        r
    }

    fn check<Tab: ButcherTableau>() {
        // Row sums: c_i = Σ_j a_ij.
        for i in 0..Tab::STAGES {
            let s: f64 = Tab::A[i].iter().sum();
            assert!((s - Tab::C[i]).abs() < 1e-14, "{} row {i}", Tab::NAME);
        }
        // Explicit: A strictly lower triangular; unused entries zero.
        for i in 0..MAX_STAGES {
            for j in i..MAX_STAGES {
                assert_eq!(Tab::A[i][j], 0.0, "{} a[{i}][{j}]", Tab::NAME);
            }
            if i >= Tab::STAGES {
                assert_eq!(Tab::B[i], 0.0);
                assert_eq!(Tab::C[i], 0.0);
            }
        }
        let r = order_condition_residuals::<Tab>();
        for (k, group) in r.iter().enumerate() {
            let order = k as u32 + 1;
            let worst = group.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            if order <= Tab::ORDER {
                assert!(
                    worst < 1e-14,
                    "{}: order-{order} condition off by {worst:e}",
                    Tab::NAME
                );
            } else if order == Tab::ORDER + 1 {
                assert!(
                    worst > 1e-6,
                    "{} satisfies order {order}: its order is understated",
                    Tab::NAME
                );
            }
        }
        // The stability polynomial computed from the tableau agrees with the exact 1/m! used by the crate.
        let raw = stability_polynomial(&Tab::A, &Tab::B, Tab::STAGES);
        for (m, (x, y)) in raw.iter().zip(Tab::STABILITY_POLYNOMIAL.iter()).enumerate() {
            assert!((x - y).abs() < 1e-15, "{} r{m}: {x} vs {y}", Tab::NAME);
        }
    }

    #[test]
    fn tableaux_satisfy_their_order_conditions_and_no_more() {
        check::<Euler>();
        check::<Rk2>();
        check::<Rk3>();
        check::<Rk4>();
        check::<Rk5>();
    }

    #[test]
    fn dormand_prince_sixth_coefficient_is_one_over_600() {
        // R(z) = T₅(z) + z⁶/600: γ = 1/600 > 1/720, so |R(ix)|² = 1 − x⁶/1800 + … loses norm near zero.
        let r = Rk5::STABILITY_POLYNOMIAL;
        assert!((r[6] - 1.0 / 600.0).abs() < 1e-17);
        let dev = crate::scheme::tableau::norm_factor_deviation(&r);
        assert!((dev[3] + 1.0 / 1800.0).abs() < 1e-16, "{}", dev[3]);
    }
}

macro_rules! information {
    ($($t:ident),+) => {$(
        impl $t {
            /// What this scheme is: order, stability bounds, norm factor ([`Information`]), computed from its
            /// tableau at compile time.
            #[must_use]
            pub const fn information(self) -> Information {
                <$t as ButcherTableau>::INFORMATION
            }
        }
    )+};
}
information!(Euler, Rk2, Rk3, Rk4, Rk5);
