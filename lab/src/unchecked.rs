//! One unchecked step, beyond the library's bounds, for the studies that explore them (stability atlas,
//! the seed's Fig. 2 step map, the Baumgarte sweep): `q + scheme.increment(q, &segment, h)` with the lab's
//! own held-rate segment (the library's segments are crate-private).

use quatprop::input::Segment;
use quatprop::scheme::Scheme;
use quatprop::{Quat, Real, Vec3};

/// A body rate (rad/s) held constant over the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeldRate<T>(pub Vec3<T>);

impl<T: Real> Segment<T> for HeldRate<T> {
    fn rate_at(&self, _c: f64) -> Vec3<T> {
        self.0
    }
    fn held_rate(&self) -> Option<Vec3<T>> {
        Some(self.0)
    }
    fn half_angle(&self, hh: T) -> Vec3<T> {
        self.0 * hh
    }
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.0 * h).norm_squared()
    }
}

/// One step of `h` (s) from `q` with the rate `w` held, without the library's checks.
pub fn held_step<T: Real, S: Scheme<T>>(scheme: &S, q: Quat<T>, w: Vec3<T>, h: T) -> Quat<T> {
    q + scheme.increment(q, &HeldRate(w), h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use quatprop::input::Hold;
    use quatprop::scheme::{Baumgarte, ExpMap, Rk4, Rk5};
    use quatprop::stabilize::Off;
    use quatprop::{GyroSample, Propagator};

    /// Within the bounds the unchecked step is the propagator's step, bit for bit.
    #[test]
    fn matches_the_propagator_within_the_bounds() {
        fn check<S: Scheme<f64>>(s: S) {
            let w = Vec3::new(0.3, -1.1, 0.7);
            let h = 0.05;
            let mut p = Propagator::new(Quat::IDENTITY, s, Hold, Off).unwrap();
            let mut q = Quat::IDENTITY;
            for _ in 0..10 {
                p.push(GyroSample::new(w), h).unwrap();
                q = held_step(&s, q, w, h);
            }
            assert_eq!(p.attitude(), q);
        }
        check(Rk4);
        check(Rk5);
        check(ExpMap);
        check(Baumgarte::new(Rk4, 0.5).unwrap());
    }
}
