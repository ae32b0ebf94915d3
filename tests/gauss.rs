//! Issue "beyond the peers", item 3: rates at the Gauss points, Magnus-4 and the commutator-free CF4 reach
//! order 4 on coning; with the quadratic (`step_mid`) input too.

mod support;

use quatprop::rates::{GAUSS_1, GAUSS_2};
use quatprop::scheme::{Cf4, ExpMap, Magnus4, Scheme};
use quatprop::stabilize::Off;
use quatprop::Propagator;
use support::{loglog_slope, Coning};

fn order<S: Scheme>(s: S) -> f64 {
    let c = Coning::STANDARD;
    let t_end = 0.7;
    let ns = [20usize, 40, 80, 160];
    let mut hs = Vec::new();
    let mut es = Vec::new();
    for n in ns {
        let h = t_end / n as f64;
        let mut p = Propagator::new(c.attitude(0.0), s, Off).unwrap();
        for i in 0..n {
            let t = i as f64 * h;
            p.step_gauss(c.rate(t + GAUSS_1 * h), c.rate(t + GAUSS_2 * h), h)
                .unwrap();
        }
        hs.push(h);
        es.push(p.attitude().angle_to(c.attitude(t_end)));
    }
    println!("{}: errors {es:?}", s.name());
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
fn gauss_schemes_keep_the_norm_without_a_stabilizer() {
    let c = Coning::STANDARD;
    for s in [
        quatprop::scheme::Method::Magnus4,
        quatprop::scheme::Method::Cf4,
    ] {
        let mut p = Propagator::new(c.attitude(0.0), s, Off).unwrap();
        for i in 0..100_000 {
            let t = i as f64 * 1e-3;
            p.step_gauss(c.rate(t + GAUSS_1 * 1e-3), c.rate(t + GAUSS_2 * 1e-3), 1e-3)
                .unwrap();
        }
        assert!(p.norm_error().abs() < 1e-12, "{s:?}: {:e}", p.norm_error());
    }
}
