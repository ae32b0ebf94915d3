//! The state types through serde (feature `serde`): a propagator stored and restored goes on as before.
//! Runs in `.ci/package` (`cargo test --all-features`); the default `cargo test` compiles it empty.
#![cfg(feature = "serde")]

use quatprop::config::{AccumulatorKind, Config, Configured, InputKind};
use quatprop::input::coning::ConingKind;
use quatprop::{DeltaAngle, Quat, Vec3};

/// A configured propagator stored and restored mid-stream goes on bit for bit as the original.
#[test]
fn a_configured_propagator_round_trips_through_serde() {
    let c = Config {
        input: InputKind::DeltaAngles(ConingKind::ThreeSample),
        accumulator: AccumulatorKind::FloatFloat,
        ..Config::RECOMMENDED
    };
    let mut p: Configured<f32> = c.build(Quat::IDENTITY).unwrap();
    let d = |k: u32| DeltaAngle::new(Vec3::new(1e-3 * k as f32, 2e-3, -1e-3));
    for k in 0..7 {
        p.push(d(k), 1e-3).unwrap();
    }
    let json = serde_json::to_string(&p).unwrap();
    let mut q: Configured<f32> = serde_json::from_str(&json).unwrap();
    assert_eq!(q, p);
    for k in 7..20 {
        p.push(d(k), 1e-3).unwrap();
        q.push(d(k), 1e-3).unwrap();
    }
    // The whole state, attitude (high and low parts) and counters included.
    assert_eq!(q, p);
}
