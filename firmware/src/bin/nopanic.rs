//! Panic-freedom proven by the linker: `Propagator::push` (and construction, `with_accumulator`,
//! `set_attitude`, `restart_input` and the getters) is called with opaque inputs for every input model ×
//! scheme (the eight zero-sized ones, the run-time `SchemeKind`, Baumgarte on each Runge–Kutta scheme) ×
//! stabilizer (four zero-sized, the run-time `StabilizerKind`) × accumulator (`Plain`, `Kahan`): see
//! `quatprop_firmware::configs`. The panic handler is the `panic-never` crate's, which references a symbol
//! that does not exist, so if any panic path is still reachable after optimization the link fails.
//!
//! Built, not run:
//! `cargo build --release --target <triple> --no-default-features --features panic-never --bin nopanic`.
//! For the micro:bit's 256 KB flash, add one `nopanic-<input>` feature per image (none: every input model)
//! and `nopanic-plain` or `nopanic-kahan` (neither: both accumulators), and if that is still too large,
//! `nopanic-schemes` or `nopanic-baumgarte` (neither: both scheme groups). `nopanic-selftest` adds a reachable
//! `unwrap()` on `None`: that image must fail to link.
#![no_std]
#![no_main]

use core::hint::black_box;
use cortex_m_rt::entry;
use quatprop::accumulate::Accumulator;
use quatprop::input::coning::{ConingKind, TwoSample};
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, Linear, TwiceRate};
use quatprop::scheme::Scheme;
use quatprop::stabilize::Stabilizer;
use quatprop::{Propagator, Quat, Vec3};
use quatprop_firmware::configs::{each_scheme, Input, Label, Visitor};

struct Exercise;

impl Visitor for Exercise {
    const PLAIN: bool = !cfg!(feature = "nopanic-kahan") || cfg!(feature = "nopanic-plain");
    const KAHAN: bool = !cfg!(feature = "nopanic-plain") || cfg!(feature = "nopanic-kahan");
    const SCHEMES: bool = !cfg!(feature = "nopanic-baumgarte") || cfg!(feature = "nopanic-schemes");
    const BAUMGARTE: bool =
        !cfg!(feature = "nopanic-schemes") || cfg!(feature = "nopanic-baumgarte");

    fn visit<S, I, Z, A>(&mut self, scheme: S, input: I, stabilizer: Z, accumulator: A, _: Label)
    where
        S: Scheme<f32>,
        I: Input,
        Z: Stabilizer,
        A: Accumulator<f32>,
    {
        exercise(scheme, input, stabilizer, accumulator);
    }
}

#[inline(never)]
fn exercise<S: Scheme<f32>, I: Input, Z: Stabilizer, A: Accumulator<f32>>(
    scheme: S,
    input: I,
    stabilizer: Z,
    accumulator: A,
) {
    let q0 = black_box(Quat::new(1.0_f32, 0.0, 0.0, 0.0));
    let Ok(p) = Propagator::new(q0, scheme, input, stabilizer) else {
        return;
    };
    let mut p = p.with_accumulator(accumulator);
    for _ in 0..black_box(8) {
        let dt = black_box(1.0e-3_f32);
        let sample = black_box(input.sample(black_box(Vec3::new(0.1, -0.2, 0.3)), dt));
        let _ = black_box(p.push(sample, dt));
    }
    let _ = black_box(p.set_attitude(black_box(q0)));
    if black_box(true) {
        p.restart_input();
    }
    black_box((p.attitude(), p.norm_error(), p.steps(), p.corrections()));
    black_box((p.saturated_samples(), p.input(), p.scheme(), p.stabilizer()));
}

const ALL: bool = !cfg!(any(
    feature = "nopanic-hold",
    feature = "nopanic-linear",
    feature = "nopanic-history",
    feature = "nopanic-twice-rate",
    feature = "nopanic-gauss-points",
    feature = "nopanic-delta-two-sample",
    feature = "nopanic-delta-angles"
));

#[entry]
fn main() -> ! {
    let v = &mut Exercise;
    if ALL || cfg!(feature = "nopanic-hold") {
        each_scheme(v, Hold);
    }
    if ALL || cfg!(feature = "nopanic-linear") {
        each_scheme(v, Linear::new());
    }
    if ALL || cfg!(feature = "nopanic-history") {
        each_scheme(v, History::new());
    }
    if ALL || cfg!(feature = "nopanic-twice-rate") {
        each_scheme(v, TwiceRate::new());
    }
    if ALL || cfg!(feature = "nopanic-gauss-points") {
        each_scheme(v, GaussPoints::new());
    }
    if ALL || cfg!(feature = "nopanic-delta-two-sample") {
        each_scheme(v, DeltaAngles::new(TwoSample));
    }
    if ALL || cfg!(feature = "nopanic-delta-angles") {
        // Every coning correction's code, behind the run-time choice.
        each_scheme(v, DeltaAngles::new(black_box(ConingKind::FiveSample)));
    }
    if cfg!(feature = "nopanic-selftest") {
        // A reachable panic: this image must NOT link (shows the proof can fail).
        black_box(black_box(None::<u32>).unwrap());
    }
    loop {
        cortex_m::asm::wfi();
    }
}
