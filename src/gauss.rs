//! The two-point Gauss–Legendre rule on a step `[0, 1]`: nodes `½ ∓ √3/6`, weights `½`.
//! Written once here; the Gauss-point input ([`crate::input::GaussPoints`]) samples at these nodes and the
//! Gauss-point schemes ([`crate::scheme::Magnus4`], [`crate::scheme::Cf4`]) read the rate there.

/// `√3/6`: half the distance between the two nodes.
pub(crate) const HALF_GAP: f64 = 0.288_675_134_594_812_9;
/// The first node `½ − √3/6`.
pub(crate) const NODE_1: f64 = 0.5 - HALF_GAP;
/// The second node `½ + √3/6`.
pub(crate) const NODE_2: f64 = 0.5 + HALF_GAP;
/// `1/(NODE_2 − NODE_1) = √3`: turns the difference of the two node values into a slope per unit step.
pub(crate) const INV_GAP: f64 = 1.732_050_807_568_877_2;

#[cfg(test)]
mod tests {
    #[test]
    fn nodes_integrate_cubics_exactly() {
        // ∫₀¹ c³ dc = 1/4; the two-point rule is exact up to degree 3.
        let q = 0.5 * (super::NODE_1.powi(3) + super::NODE_2.powi(3));
        assert!((q - 0.25).abs() < 1e-16, "{q}");
        assert!((super::INV_GAP * (super::NODE_2 - super::NODE_1) - 1.0).abs() < 1e-15);
    }
}
