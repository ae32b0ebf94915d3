//! Every propagator configuration as concrete types, for the programs that must cover them all (`nopanic`,
//! `stack`): each input model × each scheme (the eight zero-sized ones, the run-time `SchemeKind`, and
//! Baumgarte on each Runge–Kutta scheme) × each post-step stabilizer (four zero-sized, the run-time
//! `StabilizerKind`) × each accumulator (`Plain`, `Kahan`, `FloatFloat`). A program implements [`Visitor`] and gets one
//! monomorphized call per configuration.

use core::hint::black_box;
use quatprop::accumulate::{Accumulator, FloatFloat, Kahan, Plain};
use quatprop::input::coning::{ConingCorrection, ConingKind, TwoSample};
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::scheme::{
    Baumgarte, Cf4, Euler, ExpMap, Magnus4, Rk2, Rk3, Rk4, Rk5, RungeKutta, Scheme, SchemeKind,
};
use quatprop::stabilize::{Every, FirstOrder, Normalize, Off, Stabilizer, StabilizerKind};
use quatprop::{DeltaAngle, GyroSample, Vec3};

/// An input model as the programs feed it: its samples from a rate, and its cadence.
pub trait Input: InputModel<f32> {
    /// Short label.
    fn name(&self) -> &'static str;
    /// Samples per step once started.
    fn per_step(&self) -> u32;
    /// Samples before every step is a full one (samples that only start the model or build its history).
    fn warm_up(&self) -> u32;
    /// The sample for the rate `w` (rad/s) over the sample interval `dt` (s).
    fn sample(&self, w: Vec3<f32>, dt: f32) -> Self::Sample;
}

/// [`Input`] for the models fed rates (a [`GyroSample`] per push): each one's label, samples per step and
/// warm-up.
macro_rules! rate_inputs {
    ($($model:ty: $name:literal, per step $per_step:literal, warm-up $warm_up:literal;)*) => {$(
        impl Input for $model {
            fn name(&self) -> &'static str {
                $name
            }
            fn per_step(&self) -> u32 {
                $per_step
            }
            fn warm_up(&self) -> u32 {
                $warm_up
            }
            #[inline(always)]
            fn sample(&self, w: Vec3<f32>, _dt: f32) -> GyroSample<f32> {
                GyroSample::new(w)
            }
        }
    )*};
}

rate_inputs! {
    Hold: "hold", per step 1, warm-up 0;
    Linear<f32>: "linear", per step 1, warm-up 1;
    History<f32>: "history", per step 1, warm-up 3;
    TwiceRate<f32>: "twice-rate", per step 2, warm-up 1;
    GaussPoints<f32>: "gauss-points", per step 2, warm-up 0;
}

impl<C: ConingCorrection> Input for DeltaAngles<f32, C> {
    fn name(&self) -> &'static str {
        match self.correction().samples() {
            1 => "delta-angles-1",
            2 => "delta-angles-2",
            3 => "delta-angles-3",
            4 => "delta-angles-4",
            _ => "delta-angles-5",
        }
    }
    fn per_step(&self) -> u32 {
        self.correction().samples() as u32
    }
    fn warm_up(&self) -> u32 {
        0
    }
    #[inline(always)]
    fn sample(&self, w: Vec3<f32>, dt: f32) -> DeltaAngle<f32> {
        DeltaAngle::new(w * dt)
    }
}

/// Labels of one configuration.
#[derive(Clone, Copy, Debug)]
pub struct Label {
    /// Input model.
    pub input: &'static str,
    /// Scheme (`Rk4+Baumgarte` for the stabilized right-hand side, `SchemeKind` for the run-time choice).
    pub scheme: &'static str,
    /// Post-step stabilizer.
    pub stabilizer: &'static str,
    /// Accumulator.
    pub accumulator: &'static str,
}

/// What a program does with each configuration.
pub trait Visitor {
    /// Visit the `Plain` accumulator (a program for a small flash may split the set over several images).
    const PLAIN: bool = true;
    /// Visit the `Kahan` accumulator.
    const KAHAN: bool = true;
    /// Visit the `FloatFloat` accumulator.
    const FLOAT_FLOAT: bool = true;
    /// Visit the schemes without Baumgarte (the eight zero-sized ones and `SchemeKind`).
    const SCHEMES: bool = true;
    /// Visit Baumgarte on each Runge–Kutta scheme.
    const BAUMGARTE: bool = true;

    /// Called once per configuration with its values (the run-time kinds behind `black_box`).
    fn visit<S, I, Z, A>(
        &mut self,
        scheme: S,
        input: I,
        stabilizer: Z,
        accumulator: A,
        label: Label,
    ) where
        S: Scheme<f32>,
        I: Input,
        Z: Stabilizer,
        A: Accumulator<f32>;
}

/// Every input model, each with [`each_scheme`]: Hold, Linear, History, TwiceRate, GaussPoints,
/// DeltaAngles with TwoSample, and DeltaAngles with the run-time `ConingKind` (every correction's code).
pub fn each_input<V: Visitor>(v: &mut V) {
    each_scheme(v, Hold);
    each_scheme(v, Linear::new());
    each_scheme(v, History::new());
    each_scheme(v, TwiceRate::new());
    each_scheme(v, GaussPoints::new());
    each_scheme(v, DeltaAngles::new(TwoSample));
    each_scheme(v, DeltaAngles::new(black_box(ConingKind::FiveSample)));
}

/// Baumgarte's gain (1/s) in the configurations that use it.
pub const BAUMGARTE_K: f32 = 0.5;

/// Every scheme with `input`, each with every stabilizer and accumulator.
pub fn each_scheme<V: Visitor, I: Input>(v: &mut V, input: I) {
    if V::SCHEMES {
        each_stabilizer(v, input, Euler, "Euler");
        each_stabilizer(v, input, Rk2, "Rk2");
        each_stabilizer(v, input, Rk3, "Rk3");
        each_stabilizer(v, input, Rk4, "Rk4");
        each_stabilizer(v, input, Rk5, "Rk5");
        each_stabilizer(v, input, ExpMap, "ExpMap");
        each_stabilizer(v, input, Magnus4, "Magnus4");
        each_stabilizer(v, input, Cf4, "Cf4");
    }
    if V::BAUMGARTE {
        // The run-time scheme (every scheme's code behind one match) goes with the Baumgarte group, so that
        // the two halves of an image split by scheme group are about the same size (the M0's 256 KB).
        each_stabilizer(v, input, black_box(SchemeKind::Rk4), "SchemeKind");
        baumgarte(v, input, Euler, "Euler+Baumgarte");
        baumgarte(v, input, Rk2, "Rk2+Baumgarte");
        baumgarte(v, input, Rk3, "Rk3+Baumgarte");
        baumgarte(v, input, Rk4, "Rk4+Baumgarte");
        baumgarte(v, input, Rk5, "Rk5+Baumgarte");
    }
}

fn baumgarte<V: Visitor, I: Input, R: RungeKutta + Scheme<f32>>(
    v: &mut V,
    input: I,
    scheme: R,
    name: &'static str,
) {
    if let Ok(b) = Baumgarte::new(scheme, black_box(BAUMGARTE_K)) {
        each_stabilizer(v, input, b, name);
    }
}

fn each_stabilizer<V: Visitor, I: Input, S: Scheme<f32>>(
    v: &mut V,
    input: I,
    scheme: S,
    name: &'static str,
) {
    each_accumulator(v, input, scheme, Off, name, "Off");
    each_accumulator(v, input, scheme, Normalize, name, "Normalize");
    each_accumulator(v, input, scheme, FirstOrder, name, "FirstOrder");
    each_accumulator(v, input, scheme, Every(black_box(16)), name, "Every(16)");
    each_accumulator(
        v,
        input,
        scheme,
        black_box(StabilizerKind::FirstOrder),
        name,
        "StabilizerKind",
    );
}

fn each_accumulator<V: Visitor, I: Input, S: Scheme<f32>, Z: Stabilizer>(
    v: &mut V,
    input: I,
    scheme: S,
    stabilizer: Z,
    scheme_name: &'static str,
    stabilizer_name: &'static str,
) {
    let label = |accumulator| Label {
        input: input.name(),
        scheme: scheme_name,
        stabilizer: stabilizer_name,
        accumulator,
    };
    if V::PLAIN {
        v.visit(scheme, input, stabilizer, Plain, label("Plain"));
    }
    if V::KAHAN {
        v.visit(scheme, input, stabilizer, Kahan::new(), label("Kahan"));
    }
    if V::FLOAT_FLOAT {
        v.visit(
            scheme,
            input,
            stabilizer,
            FloatFloat::new(),
            label("FloatFloat"),
        );
    }
}
