//! Target `dispatch`: every run-time kind is its zero-sized (or small) type, bit for bit. The same
//! arbitrary calls (pushes of raw or plausible samples and `dt`s, `restart_input`, `set_attitude`) go to a
//! propagator built with `SchemeKind::X` / `StabilizerKind::X` / `ConingKind::X` and to one built with the
//! type `X`; after every call the results are equal (the same `Ok`, or the same error with the same
//! payload), and so are the attitudes' bit patterns, the norm error's bits and every counter. The records
//! (`information`, `validate`, `name`, `samples`) are equal too.

use super::model::Model;
use super::push::stabilizer;
use super::{quat_bits, Bytes, Fz, ANGLE, RATE};
use quatprop::input::coning::{
    ConingCorrection, ConingKind, FiveSample, FourSample, OnePlusPrevious, ThreeSample, TwoSample,
    Uncorrected,
};
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::scheme::{Cf4, Euler, ExpMap, Magnus4, Rk2, Rk3, Rk4, Rk5, Scheme, SchemeKind};
use quatprop::stabilize::{Every, FirstOrder, Normalize, Off, Stabilizer, StabilizerKind};
use quatprop::{Propagator, Quat};
use std::fmt::Debug;

/// Decodes and checks one input.
pub fn run(data: &[u8]) {
    crate::by_check_and_precision(data, 3, check::<f32>, check::<f64>)
}

fn check<T: Fz>(b: &mut Bytes<'_>, which: usize) {
    let q0 = b.quat::<T>();
    match which {
        0 => {
            let z = stabilizer(b);
            let input = b.below(6);
            macro_rules! pair {
                ($kind:expr, $ty:expr) => {{
                    assert_eq!(
                        Scheme::<T>::information(&$kind),
                        Scheme::<T>::information(&$ty)
                    );
                    with_input(b, input, q0, ($kind, z), ($ty, z))
                }};
            }
            // Spelled out per kind, as the coning table below: each arm names a run-time kind's own type,
            // which only a match can pick from the index.
            match b.below(8) {
                0 => pair!(SchemeKind::Euler, Euler),
                1 => pair!(SchemeKind::Rk2, Rk2),
                2 => pair!(SchemeKind::Rk3, Rk3),
                3 => pair!(SchemeKind::Rk4, Rk4),
                4 => pair!(SchemeKind::Rk5, Rk5),
                5 => pair!(SchemeKind::ExpMap, ExpMap),
                6 => pair!(SchemeKind::Magnus4, Magnus4),
                _ => pair!(SchemeKind::Cf4, Cf4),
            }
        }
        1 => {
            let s = SchemeKind::ALL[b.below(8)];
            let input = b.below(6);
            macro_rules! pair {
                ($kind:expr, $ty:expr) => {{
                    assert_eq!($kind.validate(), $ty.validate());
                    with_input(b, input, q0, (s, $kind), (s, $ty))
                }};
            }
            match b.below(4) {
                0 => pair!(StabilizerKind::Off, Off),
                1 => pair!(StabilizerKind::Normalize, Normalize),
                2 => pair!(StabilizerKind::FirstOrder, FirstOrder),
                _ => {
                    let n = u32::from(b.u8() % 8);
                    pair!(StabilizerKind::Every(n), Every(n))
                }
            }
        }
        _ => {
            let s = SchemeKind::ALL[b.below(8)];
            let z = stabilizer(b);
            macro_rules! pair {
                ($kind:expr, $ty:expr) => {{
                    assert_eq!($kind.name(), $ty.name());
                    assert_eq!($kind.samples(), $ty.samples());
                    let a = Propagator::new(q0, s, DeltaAngles::new($kind), z);
                    let c = Propagator::new(q0, s, DeltaAngles::new($ty), z);
                    same(b, a, c)
                }};
            }
            match b.below(6) {
                0 => pair!(ConingKind::Uncorrected, Uncorrected),
                1 => pair!(ConingKind::OnePlusPrevious, OnePlusPrevious),
                2 => pair!(ConingKind::TwoSample, TwoSample),
                3 => pair!(ConingKind::ThreeSample, ThreeSample),
                4 => pair!(ConingKind::FourSample, FourSample),
                _ => pair!(ConingKind::FiveSample, FiveSample),
            }
        }
    }
}

fn with_input<T: Fz, S1, Z1, S2, Z2>(
    b: &mut Bytes<'_>,
    input: usize,
    q0: Quat<T>,
    (s1, z1): (S1, Z1),
    (s2, z2): (S2, Z2),
) where
    S1: Scheme<T> + Debug + PartialEq,
    S2: Scheme<T> + Debug + PartialEq,
    Z1: Stabilizer + Debug + PartialEq,
    Z2: Stabilizer + Debug + PartialEq,
{
    macro_rules! go {
        ($i:expr) => {
            same(
                b,
                Propagator::new(q0, s1, $i, z1),
                Propagator::new(q0, s2, $i, z2),
            )
        };
    }
    match input {
        0 => go!(Hold),
        1 => go!(Linear::new()),
        2 => go!(History::new()),
        3 => go!(TwiceRate::new()),
        4 => go!(GaussPoints::new()),
        _ => {
            let k = ConingKind::ALL[b.below(6)];
            go!(DeltaAngles::new(k))
        }
    }
}

fn same<T: Fz, S1, I1, Z1, S2, I2, Z2>(
    b: &mut Bytes<'_>,
    a: Result<Propagator<T, S1, I1, Z1>, quatprop::Error>,
    c: Result<Propagator<T, S2, I2, Z2>, quatprop::Error>,
) where
    S1: Scheme<T> + Debug + PartialEq,
    S2: Scheme<T> + Debug + PartialEq,
    Z1: Stabilizer + Debug + PartialEq,
    Z2: Stabilizer + Debug + PartialEq,
    I1: Model<T>,
    I2: InputModel<T, Sample = I1::Sample> + Debug + PartialEq,
{
    let (mut a, mut c) = match (a, c) {
        (Ok(a), Ok(c)) => (a, c),
        (a, c) => {
            assert_eq!(a.err(), c.err());
            return;
        }
    };
    let delta = matches!(a.input().schedule().kind(), super::model::Kind::Delta(_));
    let mut last_dt = T::from_f64(1e-3);
    for _ in 0..256 {
        if b.is_empty() {
            break;
        }
        let op = b.u8() % 16;
        let (ra, rc) = match op {
            13 => {
                a.restart_input();
                c.restart_input();
                (Ok(()), Ok(()))
            }
            14 => {
                let q = b.quat::<T>();
                (a.set_attitude(q), c.set_attitude(q))
            }
            _ => {
                let v = b.vec::<T>(if delta { ANGLE } else { RATE });
                let s = I1::sample(v, b.bool());
                let dt = b.dt(last_dt);
                last_dt = dt;
                (a.push(s, dt), c.push(s, dt))
            }
        };
        // Debug text: equal errors with equal payloads, a NaN step angle included.
        if !(ra.is_ok() && rc.is_ok()) {
            super::assert_same_text(&ra, &rc, &"result: kind vs type");
        }
        assert_eq!(quat_bits(a.attitude()), quat_bits(c.attitude()));
        assert_eq!(a.norm_error().bits(), c.norm_error().bits());
        assert_eq!(
            (a.steps(), a.corrections(), a.saturated_samples()),
            (c.steps(), c.corrections(), c.saturated_samples())
        );
    }
}
