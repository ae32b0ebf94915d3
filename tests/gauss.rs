//! Issue "beyond the peers", item 3: rates at the Gauss points (`input::GaussPoints`), Magnus-4 and the
//! commutator-free CF4 reach order 4 on coning; with the quadratic (`input::TwiceRate`) input too
//! (tests/order.rs covers every scheme × input model).

mod support;

use quatprop::input::GaussPoints;
use quatprop::scheme::{Cf4, ExpMap, Magnus4, Scheme, SchemeKind};
use quatprop::stabilize::Off;
use quatprop::{GyroSample, Propagator, Vec3};
use support::{loglog_slope, Coning, GAUSS_1, GAUSS_2};

fn order<S: Scheme<f64>>(s: S) -> f64 {
    let c = Coning::STANDARD;
    let t_end = 0.7;
    let ns = [20usize, 40, 80, 160];
    let mut hs = Vec::new();
    let mut es = Vec::new();
    for n in ns {
        let h = t_end / n as f64;
        let mut p = Propagator::new(c.attitude(0.0), s, GaussPoints::new(), Off).unwrap();
        for i in 0..n {
            let t = i as f64 * h;
            p.push(GyroSample::new(c.rate(t + GAUSS_1 * h)), h / 2.0)
                .unwrap();
            p.push(GyroSample::new(c.rate(t + GAUSS_2 * h)), h / 2.0)
                .unwrap();
        }
        assert_eq!(p.steps(), n as u64, "two pushes per step");
        hs.push(h);
        es.push(p.attitude().angle_to(c.attitude(t_end)));
    }
    println!("{}: errors {es:?}", s.information().name);
    loglog_slope(&hs, &es)
}

#[test]
fn gauss_point_schemes_are_fourth_order_on_coning() {
    for (name, slope) in [
        ("Magnus4", order(Magnus4)),
        ("Cf4", order(Cf4)),
        ("ExpMap", order(ExpMap)),
    ] {
        println!("{name}: order {slope:.3}");
        assert!((slope - 4.0).abs() < 0.15, "{name}: {slope}");
    }
}

#[test]
fn gauss_nodes_are_the_two_point_rule() {
    // The test's own nodes: symmetric about ½, √3/3 apart, and the two-point rule integrates c³ exactly.
    assert!((GAUSS_1 + GAUSS_2 - 1.0).abs() < 1e-16);
    assert!((GAUSS_2 - GAUSS_1 - 3f64.sqrt() / 3.0).abs() < 1e-16);
    assert!((0.5 * (GAUSS_1.powi(3) + GAUSS_2.powi(3)) - 0.25).abs() < 1e-16);
}

#[test]
fn magnus4_with_gauss_points_is_expmap_bit_for_bit() {
    // Magnus4 reads the segment at the Gauss nodes; GaussPoints returns its samples exactly there, so the
    // two are the same computation (the scheme docs say so).
    let c = Coning::STANDARD;
    let mut a = Propagator::new(c.attitude(0.0), Magnus4, GaussPoints::new(), Off).unwrap();
    let mut b = Propagator::new(c.attitude(0.0), ExpMap, GaussPoints::new(), Off).unwrap();
    for i in 0..1000 {
        let t = i as f64 * 1e-3;
        for node in [GAUSS_1, GAUSS_2] {
            let s = GyroSample::new(c.rate(t + node * 1e-3));
            a.push(s, 5e-4).unwrap();
            b.push(s, 5e-4).unwrap();
        }
        assert_eq!(a.attitude(), b.attitude(), "step {i}");
    }
}

#[test]
fn gauss_schemes_keep_the_norm_without_a_stabilizer() {
    let c = Coning::STANDARD;
    for s in [SchemeKind::Magnus4, SchemeKind::Cf4] {
        let mut p = Propagator::new(c.attitude(0.0), s, GaussPoints::new(), Off).unwrap();
        for i in 0..100_000 {
            let t = i as f64 * 1e-3;
            p.push(GyroSample::new(c.rate(t + GAUSS_1 * 1e-3)), 5e-4)
                .unwrap();
            p.push(GyroSample::new(c.rate(t + GAUSS_2 * 1e-3)), 5e-4)
                .unwrap();
        }
        assert!(p.norm_error().abs() < 1e-12, "{s:?}: {:e}", p.norm_error());
    }
    // A pending first sample moves nothing.
    let mut p = Propagator::new(c.attitude(0.0), Cf4, GaussPoints::new(), Off).unwrap();
    p.push(GyroSample::new(Vec3::new(1.0, 2.0, 3.0)), 5e-4)
        .unwrap();
    assert_eq!((p.steps(), p.attitude()), (0, c.attitude(0.0)));
}
