//! The configurations the studies compare, and one integrator type that runs any of them over a sample stream.
//!
//! A configuration is either quatprop (scheme × stabilizer × input model × accumulator) or a peer. A
//! quatprop configuration is the library's run-time `config::Config`; its loop is compiled for the scheme,
//! input model and accumulator types a firmware would name (`Configured::visit`), with the library's
//! run-time `StabilizerKind`, so host timings are those of the code a user links. Baumgarte is, since
//! quatprop 0.2, a right-hand-side option of the Runge–Kutta schemes (`scheme::Baumgarte` with `stabilize::Off`):
//! a Baumgarte configuration of an exponential-map scheme does not exist and is not built. Peers that exist as Rust
//! crates are used as crates (`ahrs`, `nalgebra`, `glam`); Fusion (C) is implemented from its published
//! formulas in [`crate::peers`]. Each peer's wrapper here is checked against the same peer call in a plain
//! loop ([`crate::peer_loops`]).
//!
//! Streams: a sample is a body rate (rad/s) and the time since the previous sample (s; ignored for the first
//! sample of a stream). Each sample is one `Propagator::push`. Every step an integrator refuses is counted with
//! its first error: nothing is dropped silently.

use crate::peer_types::{ahrs_vec, from_ahrs, from_na, na_vec, to_ahrs, to_na, NaQuat, PeerReal};
use crate::sample::Sample;
use crate::{peer_loops, peers};
use quatprop::accumulate::Accumulator;
use quatprop::config::{
    AccumulatorKind, Config as LibConfig, Configured, DeltaModel, InputKind, RateModel, Visit,
    Visited,
};
use quatprop::scheme::{Scheme, SchemeKind};
use quatprop::stabilize::StabilizerKind;
use quatprop::{Error, GyroSample, Quat, Real, Vec3};

/// A scheme's short name (`"Rk4"`), from the library's record.
pub fn scheme_name(m: SchemeKind) -> &'static str {
    m.information().name
}

/// Every scheme whose right-hand side can carry Baumgarte's term (the explicit Runge–Kutta schemes).
pub fn is_runge_kutta(m: SchemeKind) -> bool {
    matches!(
        m,
        SchemeKind::Euler | SchemeKind::Rk2 | SchemeKind::Rk3 | SchemeKind::Rk4 | SchemeKind::Rk5
    )
}

/// The input model of a quatprop configuration: how the samples become a rate function for each step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// `input::Hold`: the newest sample held over its interval (what Fusion and Madgwick do).
    Hold,
    /// `input::Linear`: linear between the two samples bracketing the step.
    Linear,
    /// `input::History`: the cubic through the last four samples at their true times, fourth order, no
    /// latency, under jitter and across a dropped sample too; only a gap (a dt more than 2.5 times the
    /// previous one, or less than its inverse: two or more samples missing) restarts it at the last sample,
    /// bridging that interval linearly, and the start correction makes it fourth order again from there.
    History,
    /// `input::TwiceRate`: one step per two sample intervals with the quadratic through three samples (the
    /// same samples, half the steps).
    Mid,
}

impl Input {
    pub const ALL: [Input; 4] = [Input::Hold, Input::Linear, Input::History, Input::Mid];
    pub fn name(self) -> &'static str {
        match self {
            Input::Hold => "hold",
            Input::Linear => "linear",
            Input::History => "history",
            Input::Mid => "mid",
        }
    }
}

/// The stabilizer of a quatprop configuration (the library's types; parameters fixed here).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stab {
    Off,
    Normalize,
    FirstOrder,
    /// Exact normalization after every n-th step.
    Every(u32),
    /// Baumgarte with gain k (1/s): the scheme wrapped in `scheme::Baumgarte` (Runge–Kutta schemes only),
    /// stabilizer `Off`.
    Baumgarte(f64),
}

impl Stab {
    pub const ALL: [Stab; 5] = [
        Stab::Off,
        Stab::Normalize,
        Stab::FirstOrder,
        Stab::Every(16),
        Stab::Baumgarte(0.5),
    ];
    pub fn name(self) -> String {
        match self {
            Stab::Off => "Off".into(),
            Stab::Normalize => "Normalize".into(),
            Stab::FirstOrder => "FirstOrder".into(),
            Stab::Every(n) => format!("Every({n})"),
            Stab::Baumgarte(k) => format!("Baumgarte(k={k})"),
        }
    }
}

/// A peer's attitude update, run on the same streams.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Peer {
    /// Fusion (C): Euler with the newest sample + fast inverse square root (formulas in `peers.rs`; f32 only).
    Fusion,
    /// The `ahrs` crate: `Madgwick::update_gyro` (Euler with the newest sample, fixed sample period).
    AhrsMadgwick,
    /// nalgebra `UnitQuaternion`: classic RK4 on `q' = ½ q ⊗ (0, ω)` with linear rates, `new_normalize`.
    NalgebraRk4,
    /// nalgebra `q * UnitQuaternion::from_scaled_axis(ω̄ dt)` on the trapezoid mean rate (no renormalization).
    NalgebraScaledAxis,
    /// glam `(q * Quat::from_scaled_axis(ω̄ dt)).normalize()` on the trapezoid mean rate (the PX4 form).
    GlamScaledAxis,
}

impl Peer {
    pub const ALL: [Peer; 5] = [
        Peer::Fusion,
        Peer::AhrsMadgwick,
        Peer::NalgebraRk4,
        Peer::NalgebraScaledAxis,
        Peer::GlamScaledAxis,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Peer::Fusion => "peer: Fusion Euler + fast inverse sqrt",
            Peer::AhrsMadgwick => "peer: ahrs Madgwick::update_gyro",
            Peer::NalgebraRk4 => "peer: nalgebra RK4 + renormalize",
            Peer::NalgebraScaledAxis => "peer: nalgebra from_scaled_axis",
            Peer::GlamScaledAxis => "peer: glam from_scaled_axis + normalize",
        }
    }
}

/// One configuration of a study.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Config {
    Quatprop {
        method: SchemeKind,
        stab: Stab,
        input: Input,
        accumulator: Acc,
    },
    Peer(Peer),
    /// A peer's plain hand-written loop (`crate::peer_loops`): the same peer call in the form its users write,
    /// timed beside the peer's wrapper to check that the wrapper costs what the loop costs.
    PeerLoop(Peer),
}

/// How a quatprop configuration adds its increments (`quatprop::accumulate`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Acc {
    /// `Plain`: rounded addition.
    Plain,
    /// `Kahan`: compensated addition.
    Kahan,
    /// `FloatFloat`: a float-float state advanced by exact products.
    FloatFloat,
}

impl Config {
    pub const fn qp(method: SchemeKind, stab: Stab, input: Input) -> Self {
        Config::Quatprop {
            method,
            stab,
            input,
            accumulator: Acc::Plain,
        }
    }

    /// The same quatprop configuration with another accumulator (a peer stays as it is).
    pub const fn with(self, acc: Acc) -> Self {
        match self {
            Config::Quatprop {
                method,
                stab,
                input,
                ..
            } => Config::Quatprop {
                method,
                stab,
                input,
                accumulator: acc,
            },
            peer => peer,
        }
    }

    // Each method matches on the configuration's variants and names the fields it uses.
    pub fn label(&self) -> String {
        match *self {
            Config::Quatprop {
                method,
                stab,
                input,
                accumulator,
            } => format!(
                "quatprop {} {} + {}{}",
                scheme_name(method),
                input.name(),
                stab.name(),
                match accumulator {
                    Acc::Plain => "",
                    Acc::Kahan => ", Kahan",
                    Acc::FloatFloat => ", FloatFloat",
                }
            ),
            Config::Peer(p) => p.name().into(),
            Config::PeerLoop(p) => format!("plain loop: {}", p.name().trim_start_matches("peer: ")),
        }
    }

    /// A peer, as wrapped for the studies or as its plain loop.
    pub fn is_peer(&self) -> bool {
        matches!(self, Config::Peer(_) | Config::PeerLoop(_))
    }

    /// Whether quatprop has this configuration: Baumgarte wraps the Runge–Kutta schemes only.
    pub fn exists(&self) -> bool {
        match *self {
            Config::Quatprop {
                method,
                stab: Stab::Baumgarte(_),
                ..
            } => is_runge_kutta(method),
            _ => true,
        }
    }

    /// Steps per sample interval (½ for the mid input, 1 otherwise).
    pub fn steps_per_sample(&self) -> f64 {
        match self {
            Config::Quatprop {
                input: Input::Mid, ..
            } => 0.5,
            _ => 1.0,
        }
    }

    /// An integrator starting at `q0` for samples `nominal_dt` apart, or why there is none (Fusion has no
    /// f64 version; Baumgarte with a scheme that is not Runge–Kutta; the library refused the configuration).
    pub fn build<T: LabReal>(
        &self,
        q0: Quat<T>,
        nominal_dt: T,
    ) -> Result<Box<dyn Integrator<T>>, String> {
        match *self {
            Config::Quatprop {
                method,
                stab,
                input,
                accumulator,
            } => build_quatprop(method, stab, input, accumulator, q0)
                .map_err(|e| format!("{}: {e}", self.label())),
            Config::Peer(p) => T::peer(p, q0, nominal_dt).ok_or_else(|| no_version::<T>(p)),
            Config::PeerLoop(p) => match T::peer_loop(p, q0, nominal_dt, &[]) {
                Some(_) => Ok(Box::new(PeerLoopRun {
                    peer: p,
                    q0,
                    nominal_dt,
                    samples: Vec::new(),
                })),
                None => Err(no_version::<T>(p)),
            },
        }
    }
}

fn no_version<T>(p: Peer) -> String {
    format!(
        "{} has no {} version",
        p.name(),
        core::any::type_name::<T>()
    )
}

impl Config {
    /// One timed run over a whole stream from `q0` (samples `samples[1].dt` apart): host ns per sample
    /// interval, or `None` if there is no such integrator. A wrapper is built before the clock starts and fed
    /// the stream in one `feed`; a peer's plain loop is one call. The attitude is kept from the optimizer.
    pub fn time_run<T: LabReal>(&self, q0: Quat<T>, samples: &[Sample<T>]) -> Option<f64> {
        use std::hint::black_box;
        let n = samples.len().checked_sub(1).filter(|&n| n > 0)? as f64;
        let dt = samples[1].dt;
        let t0 = match *self {
            Config::PeerLoop(p) => {
                let t0 = std::time::Instant::now();
                black_box(T::peer_loop(p, q0, dt, black_box(samples))?);
                t0
            }
            _ => {
                let mut r = self.build::<T>(q0, dt).ok()?;
                let t0 = std::time::Instant::now();
                r.feed(black_box(samples));
                black_box(r.attitude());
                t0
            }
        };
        Some(t0.elapsed().as_nanos() as f64 / n)
    }
}

/// Floating-point precision of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    F32,
    F64,
}

impl Precision {
    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}

/// The comparison set of a scene: every scheme with linear input, the fourth-order sample-history and mid
/// inputs, all with FirstOrder, and every peer.
pub fn scheme_set() -> Vec<Config> {
    let mut v: Vec<Config> = SchemeKind::ALL
        .iter()
        .map(|&m| Config::qp(m, Stab::FirstOrder, Input::Linear))
        .collect();
    for m in [SchemeKind::Rk4, SchemeKind::ExpMap, SchemeKind::Magnus4] {
        v.push(Config::qp(m, Stab::FirstOrder, Input::History));
    }
    v.push(Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::Mid));
    let history = Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::History);
    v.push(history.with(Acc::Kahan));
    v.push(history.with(Acc::FloatFloat));
    v.extend(Peer::ALL.iter().map(|&p| Config::Peer(p)));
    v
}

/// Every scheme × stabilizer × input model (plain accumulator) that exists: Baumgarte with the Runge–Kutta
/// schemes only.
pub fn full_grid() -> Vec<Config> {
    let mut v = Vec::new();
    for m in SchemeKind::ALL {
        for s in Stab::ALL {
            for i in Input::ALL {
                let c = Config::qp(m, s, i);
                if c.exists() {
                    v.push(c);
                }
            }
        }
    }
    v
}

/// The error's variant name (`StepAngleBeyondStability`, …), "?" for none.
pub fn error_kind(e: Option<Error>) -> String {
    e.map_or(String::from("?"), |e| {
        let s = format!("{e:?}");
        s.split([' ', '{']).next().unwrap_or("").to_string()
    })
}

/// Runs a configuration over a stream, sample by sample.
pub trait Integrator<T> {
    /// Consumes samples (the first sample ever fed only starts the stream).
    fn feed(&mut self, samples: &[Sample<T>]);
    fn attitude(&self) -> Quat<T>;
    /// Steps refused so far and the first refusal's error (peers never refuse).
    fn refused(&self) -> (u64, Option<Error>) {
        (0, None)
    }
}

/// f32 and f64 as the lab needs them: the peers' scalars ([`PeerReal`]: quatprop's `Real` plus nalgebra's and
/// `ahrs`'s), with each peer's integrator and plain loop in this precision. Only Fusion (f32 only) and glam
/// (a quaternion type per precision) differ by precision; each precision says only that, and the dispatch
/// over the peers is written once.
pub trait LabReal: PeerReal {
    /// Fusion's integrator, if Fusion has this precision.
    fn fusion_peer(q0: Quat<Self>) -> Option<Box<dyn Integrator<Self>>>;
    /// Fusion's plain loop, if Fusion has this precision.
    fn fusion_loop(q0: Quat<Self>, samples: &[Sample<Self>]) -> Option<Quat<Self>>;
    /// glam's integrator on this precision's quaternion type.
    fn glam_peer(q0: Quat<Self>) -> Box<dyn Integrator<Self>>;
    /// glam's plain loop on this precision's quaternion type.
    fn glam_loop(q0: Quat<Self>, samples: &[Sample<Self>]) -> Quat<Self>;

    /// The peer's integrator in this precision, if the peer has one.
    fn peer(p: Peer, q0: Quat<Self>, nominal_dt: Self) -> Option<Box<dyn Integrator<Self>>> {
        Some(match p {
            Peer::Fusion => Self::fusion_peer(q0)?,
            Peer::GlamScaledAxis => Self::glam_peer(q0),
            Peer::AhrsMadgwick => Box::new(AhrsRun {
                m: ahrs::Madgwick::new_with_quat(nominal_dt, Self::ZERO, to_ahrs(q0)),
                prev: false,
            }),
            Peer::NalgebraRk4 => Box::new(NalgebraRk4Run {
                q: to_na(q0),
                prev: None,
            }),
            Peer::NalgebraScaledAxis => Box::new(NalgebraAxisRun {
                q: to_na(q0),
                prev: None,
            }),
        })
    }
    /// The peer's plain loop (`crate::peer_loops`) over a whole stream from `q0`: its attitude after the
    /// last sample, if the peer has this precision.
    fn peer_loop(
        p: Peer,
        q0: Quat<Self>,
        nominal_dt: Self,
        samples: &[Sample<Self>],
    ) -> Option<Quat<Self>> {
        Some(match p {
            Peer::Fusion => Self::fusion_loop(q0, samples)?,
            Peer::GlamScaledAxis => Self::glam_loop(q0, samples),
            Peer::AhrsMadgwick => peer_loops::ahrs_madgwick(q0, nominal_dt, samples),
            Peer::NalgebraRk4 => peer_loops::nalgebra_rk4(q0, samples),
            Peer::NalgebraScaledAxis => peer_loops::nalgebra_scaled_axis(q0, samples),
        })
    }
}

impl LabReal for f32 {
    fn fusion_peer(q0: Quat<f32>) -> Option<Box<dyn Integrator<f32>>> {
        Some(Box::new(FusionRun { q: q0, prev: false }))
    }
    fn fusion_loop(q0: Quat<f32>, samples: &[Sample<f32>]) -> Option<Quat<f32>> {
        Some(peer_loops::fusion(q0, samples))
    }
    fn glam_peer(q0: Quat<f32>) -> Box<dyn Integrator<f32>> {
        Box::new(GlamRun::new(q0))
    }
    fn glam_loop(q0: Quat<f32>, samples: &[Sample<f32>]) -> Quat<f32> {
        peer_loops::glam_scaled_axis(q0, samples)
    }
}

impl LabReal for f64 {
    fn fusion_peer(_: Quat<f64>) -> Option<Box<dyn Integrator<f64>>> {
        None
    }
    fn fusion_loop(_: Quat<f64>, _: &[Sample<f64>]) -> Option<Quat<f64>> {
        None
    }
    fn glam_peer(q0: Quat<f64>) -> Box<dyn Integrator<f64>> {
        Box::new(DGlamRun::new(q0))
    }
    fn glam_loop(q0: Quat<f64>, samples: &[Sample<f64>]) -> Quat<f64> {
        peer_loops::dglam_scaled_axis(q0, samples)
    }
}

/// A peer's plain loop as an [`Integrator`] for the accuracy runs: it keeps the samples fed so far and runs
/// the loop over all of them from the start for each attitude (so pieces change nothing). Its timed runs
/// call the loop itself ([`Config::time_run`]), not this.
struct PeerLoopRun<T> {
    peer: Peer,
    q0: Quat<T>,
    nominal_dt: T,
    samples: Vec<Sample<T>>,
}
impl<T: LabReal> Integrator<T> for PeerLoopRun<T> {
    fn feed(&mut self, samples: &[Sample<T>]) {
        self.samples.extend_from_slice(samples);
    }
    fn attitude(&self) -> Quat<T> {
        T::peer_loop(self.peer, self.q0, self.nominal_dt, &self.samples).unwrap_or(self.q0)
    }
}

// ------------------------------------------------------------------------------------------------ quatprop

/// The library's run-time configuration for a lab configuration (Baumgarte: the gain on a Runge–Kutta
/// scheme, with no post-step stabilizer).
fn library_config(method: SchemeKind, stab: Stab, input: Input, accumulator: Acc) -> LibConfig {
    let (stabilizer, baumgarte_gain) = match stab {
        Stab::Off => (StabilizerKind::Off, None),
        Stab::Normalize => (StabilizerKind::Normalize, None),
        Stab::FirstOrder => (StabilizerKind::FirstOrder, None),
        Stab::Every(n) => (StabilizerKind::Every(n), None),
        Stab::Baumgarte(k) => (StabilizerKind::Off, Some(k)),
    };
    LibConfig {
        scheme: method,
        baumgarte_gain,
        input: match input {
            Input::Hold => InputKind::Hold,
            Input::Linear => InputKind::Linear,
            Input::History => InputKind::History,
            Input::Mid => InputKind::TwiceRate,
        },
        stabilizer,
        accumulator: match accumulator {
            Acc::Plain => AccumulatorKind::Plain,
            Acc::Kahan => AccumulatorKind::Kahan,
            Acc::FloatFloat => AccumulatorKind::FloatFloat,
        },
    }
}

/// A quatprop configuration over a stream: the library's [`Configured`] propagator, fed by [`Feed`].
struct QuatpropRun<T: Real> {
    p: Configured<T>,
    /// After a refused step the stream continues from the refused sample (the interval is dropped and
    /// counted, the lab's policy since 0.1): for `Linear` and `TwiceRate` the sample starts the model
    /// afresh (`Propagator::start`), since the library leaves a refused sample's model untouched, which
    /// would make the next step span the refused interval too. `History` keeps its 0.1 behaviour (the
    /// refused sample is not part of the history).
    restart_on_refusal: bool,
    /// The first sample of the stream has been seen.
    started: bool,
    refused: u64,
    first_error: Option<Error>,
}

/// One [`Integrator::feed`] as a [`Visit`]: the loop is compiled for each scheme × input model ×
/// accumulator, and the propagator (its input model included) lives in a local during the loop, as it
/// would in a firmware's interrupt handler.
struct Feed<'a, T> {
    samples: &'a [Sample<T>],
    start_first: bool,
    restart_on_refusal: bool,
    refused: &'a mut u64,
    first: &'a mut Option<Error>,
}

impl<T: Real> Visit<T> for Feed<'_, T> {
    type Output = ();
    fn rates<S: Scheme<T>, I: RateModel<T>, A: Accumulator<T>>(self, p: &mut Visited<T, S, I, A>) {
        let mut local = *p;
        let mut rest = self.samples;
        if self.start_first {
            if let Some((s0, tail)) = rest.split_first() {
                rest = tail;
                // The stream's first sample has no interval before it (its dt is meaningless, 0 in sensor
                // streams): it only starts the model (Hold keeps nothing of it).
                if let Err(e) = local.start(GyroSample::new(s0.w)) {
                    refuse(self.refused, self.first, e);
                }
            }
        }
        for s in rest {
            if let Err(e) = local.push(GyroSample::new(s.w), s.dt) {
                // Cold: only refused steps reach the body.
                refuse(self.refused, self.first, e);
                if self.restart_on_refusal {
                    let _ = local.start(GyroSample::new(s.w));
                }
            }
        }
        *p = local;
    }
    fn deltas<S: Scheme<T>, I: DeltaModel<T>, A: Accumulator<T>>(
        self,
        _: &mut Visited<T, S, I, A>,
    ) {
        // The lab's streams are rates; no lab configuration takes delta angles.
        for _ in self.samples {
            refuse(self.refused, self.first, Error::WrongSampleKind);
        }
    }
}

impl<T: Real> Integrator<T> for QuatpropRun<T> {
    fn feed(&mut self, samples: &[Sample<T>]) {
        let (mut refused, mut first) = (0u64, None);
        let start_first = !self.started && !samples.is_empty();
        self.started |= start_first;
        self.p.visit(Feed {
            samples,
            start_first,
            restart_on_refusal: self.restart_on_refusal,
            refused: &mut refused,
            first: &mut first,
        });
        self.refused += refused;
        if self.first_error.is_none() {
            self.first_error = first;
        }
    }
    fn attitude(&self) -> Quat<T> {
        self.p.attitude()
    }
    fn refused(&self) -> (u64, Option<Error>) {
        (self.refused, self.first_error)
    }
}

#[cold]
#[inline(never)]
fn refuse(count: &mut u64, first: &mut Option<Error>, e: Error) {
    *count += 1;
    first.get_or_insert(e);
}

fn build_quatprop<T: Real>(
    method: SchemeKind,
    stab: Stab,
    input: Input,
    accumulator: Acc,
    q0: Quat<T>,
) -> Result<Box<dyn Integrator<T>>, String> {
    let config = library_config(method, stab, input, accumulator);
    match config.build(q0) {
        Ok(p) => Ok(Box::new(QuatpropRun {
            p,
            restart_on_refusal: matches!(input, Input::Linear | Input::Mid),
            started: false,
            refused: 0,
            first_error: None,
        })),
        Err(Error::BaumgarteNeedsRungeKutta) => Err(BAUMGARTE_RK_ONLY.to_string()),
        Err(e) => Err(format!("{e:?}")),
    }
}

/// Why a Baumgarte configuration of an exponential-map scheme cannot be built.
const BAUMGARTE_RK_ONLY: &str =
    "Baumgarte is a right-hand-side option of the Runge–Kutta schemes only (quatprop 0.2)";

// ------------------------------------------------------------------------------------------------ peers
//
// Every wrapper keeps its peer's state in locals for the whole `feed` and writes it back once at the end,
// as a user's loop does: a store to `self` per sample lies under the next sample's wide load, which the CPU
// cannot forward, and the steps stop overlapping (measured: nalgebra's and glam's `from_scaled_axis`
// wrappers took twice their plain loops' time). `peer_loops.rs` holds the plain loops they are checked
// against.

struct FusionRun {
    q: Quat<f32>,
    prev: bool,
}
impl Integrator<f32> for FusionRun {
    fn feed(&mut self, samples: &[Sample<f32>]) {
        let (mut q, mut prev) = (self.q, self.prev);
        for s in samples {
            if prev {
                q = peers::fusion_euler(q, s.w, s.dt);
            }
            prev = true;
        }
        (self.q, self.prev) = (q, prev);
    }
    fn attitude(&self) -> Quat<f32> {
        self.q
    }
}

/// glam's loop (`q * Quat::from_scaled_axis(v)`, normalized), one per precision: glam's f32 and f64
/// quaternions are distinct types with no trait in common.
macro_rules! glam_run {
    ($name:ident, $real:ty, $quat:ty, $vec:ty) => {
        struct $name {
            q: $quat,
            prev: Option<Vec3<$real>>,
        }
        impl $name {
            /// From `q0`, before the stream's first sample.
            fn new(q0: Quat<$real>) -> Self {
                Self {
                    q: <$quat>::from(mint::Quaternion::from(q0)),
                    prev: None,
                }
            }
        }
        impl Integrator<$real> for $name {
            fn feed(&mut self, samples: &[Sample<$real>]) {
                let (mut q, mut prev) = (self.q, self.prev);
                for s in samples {
                    if let Some(w0) = prev {
                        let v = (w0 + s.w) * (0.5 * s.dt);
                        let v = <$vec>::from(mint::Vector3::from(v));
                        q = (q * <$quat>::from_scaled_axis(v)).normalize();
                    }
                    prev = Some(s.w);
                }
                (self.q, self.prev) = (q, prev);
            }
            fn attitude(&self) -> Quat<$real> {
                Quat::from_mint(self.q)
            }
        }
    };
}
glam_run!(GlamRun, f32, glam::Quat, glam::Vec3);
glam_run!(DGlamRun, f64, glam::DQuat, glam::DVec3);

/// `ahrs` has no time argument: it integrates every sample over its fixed `sample_period` (jitter and gaps
/// are invisible to it).
struct AhrsRun<T: LabReal> {
    m: ahrs::Madgwick<T>,
    prev: bool,
}
impl<T: LabReal> Integrator<T> for AhrsRun<T> {
    fn feed(&mut self, samples: &[Sample<T>]) {
        use ahrs::Ahrs as _;
        let mut m = self.m;
        // The stream's first sample only starts it.
        let from = usize::from(!self.prev).min(samples.len());
        for s in &samples[from..] {
            m.update_gyro(&ahrs_vec(s.w));
        }
        self.m = m;
        self.prev |= !samples.is_empty();
    }
    fn attitude(&self) -> Quat<T> {
        from_ahrs(&self.m.quat)
    }
}

struct NalgebraRk4Run<T: LabReal> {
    q: NaQuat<T>,
    prev: Option<Vec3<T>>,
}
impl<T: LabReal> Integrator<T> for NalgebraRk4Run<T> {
    fn feed(&mut self, samples: &[Sample<T>]) {
        let (mut q_run, mut prev) = (self.q, self.prev);
        for s in samples {
            if let Some(w0) = prev {
                q_run = peer_loops::nalgebra_rk4_step(q_run, w0, s.w, s.dt);
            }
            prev = Some(s.w);
        }
        (self.q, self.prev) = (q_run, prev);
    }
    fn attitude(&self) -> Quat<T> {
        from_na(&self.q)
    }
}

struct NalgebraAxisRun<T: LabReal> {
    q: NaQuat<T>,
    prev: Option<Vec3<T>>,
}
impl<T: LabReal> Integrator<T> for NalgebraAxisRun<T> {
    fn feed(&mut self, samples: &[Sample<T>]) {
        let (Some(first), Some(last)) = (samples.first(), samples.last()) else {
            return;
        };
        let mut q = self.q;
        // The interval from the previous piece's last sample, then the piece's own intervals: the plain
        // loop's shape (a rate carried in an `Option` through the loop cost twice the loop's time: with the
        // sin/cos calls in between it lives on the stack, stored per sample and loaded wide).
        if let Some(w0) = self.prev {
            q *= NaQuat::from_scaled_axis(na_vec((w0 + first.w) * (T::HALF * first.dt)));
        }
        for pair in samples.windows(2) {
            let v = (pair[0].w + pair[1].w) * (T::HALF * pair[1].dt);
            q *= NaQuat::from_scaled_axis(na_vec(v));
        }
        (self.q, self.prev) = (q, Some(last.w));
    }
    fn attitude(&self) -> Quat<T> {
        from_na(&self.q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use quatprop::input::{History, Hold, InputModel, Linear, TwiceRate};
    use quatprop::scheme::Rk4;
    use quatprop::stabilize::FirstOrder;
    use quatprop::Propagator;

    fn stream(rates_z: &[f64], dt: f64) -> Vec<Sample<f64>> {
        rates_z
            .iter()
            .enumerate()
            .map(|(k, &wz)| Sample {
                w: Vec3::new(0.1, 0.0, wz),
                // A sensor stream's first sample has no interval before it (dt = 0).
                dt: if k == 0 { 0.0 } else { dt },
            })
            .collect()
    }

    fn run(c: Config, s: &[Sample<f64>]) -> (Quat<f64>, u64) {
        let mut r = c.build::<f64>(Quat::IDENTITY, 0.1).unwrap();
        // In two feeds, as the studies do between checkpoints.
        r.feed(&s[..2]);
        r.feed(&s[2..]);
        (r.attitude(), r.refused().0)
    }

    fn by_hand<I: InputModel<f64, Sample = GyroSample<f64>>>(
        input: I,
        pushes: &[(f64, f64)],
    ) -> Quat<f64> {
        let mut p = Propagator::new(Quat::IDENTITY, Rk4, input, FirstOrder).unwrap();
        for &(wz, dt) in pushes {
            p.push(GyroSample::new(Vec3::new(0.1, 0.0, wz)), dt)
                .unwrap();
        }
        p.attitude()
    }

    /// Each lab input is the library's model fed one push per sample; `Hold` skips the stream's first
    /// sample (no interval before it), the others take it as their start whatever its dt.
    #[test]
    fn inputs_are_the_library_models_pushed_per_sample() {
        let s = stream(&[0.5, 0.7, 0.6, 0.9, 1.2], 0.1);
        let qp = |i| Config::qp(SchemeKind::Rk4, Stab::FirstOrder, i);
        let all: Vec<(f64, f64)> = [0.5, 0.7, 0.6, 0.9, 1.2].map(|w| (w, 0.1)).to_vec();
        assert_eq!(run(qp(Input::Hold), &s), (by_hand(Hold, &all[1..]), 0));
        assert_eq!(
            run(qp(Input::Linear), &s),
            (by_hand(Linear::new(), &all), 0)
        );
        assert_eq!(
            run(qp(Input::History), &s),
            (by_hand(History::new(), &all), 0)
        );
        assert_eq!(
            run(qp(Input::Mid), &s),
            (by_hand(TwiceRate::new(), &all), 0)
        );
    }

    /// A refused step is counted and its interval dropped; the stream continues from the refused sample
    /// (the lab's policy since 0.1): with linear input, 100 rad/s at 0.1 s is beyond Rk4's 5.66 rad, so both
    /// steps touching it are refused and the run equals one that restarts at the sample after it.
    #[test]
    fn a_refused_step_drops_its_interval_and_continues_from_that_sample() {
        let s = stream(&[0.5, 0.7, 100.0, 0.9, 1.2], 0.1);
        let c = Config::qp(SchemeKind::Rk4, Stab::FirstOrder, Input::Linear);
        let expected = {
            let mut p = Propagator::new(Quat::IDENTITY, Rk4, Linear::new(), FirstOrder).unwrap();
            for (wz, restart) in [(0.5, false), (0.7, false), (0.9, true), (1.2, false)] {
                if restart {
                    p.restart_input();
                }
                p.push(GyroSample::new(Vec3::new(0.1, 0.0, wz)), 0.1)
                    .unwrap();
            }
            p.attitude()
        };
        assert_eq!(run(c, &s), (expected, 2));
        let mut r = c.build::<f64>(Quat::IDENTITY, 0.1).unwrap();
        r.feed(&s);
        assert!(matches!(
            r.refused().1,
            Some(Error::StepAngleBeyondStability { .. })
        ));
    }

    /// The mint conversions keep every component in its place (scalar first here, last in glam/nalgebra).
    #[test]
    fn mint_conversions_round_trip_through_the_peers() {
        let q = Quat::new(0.5f32, -0.5, 0.25, 0.8);
        let g = glam::Quat::from(mint::Quaternion::from(q));
        assert_eq!((g.w, g.x, g.y, g.z), (q.w, q.x, q.y, q.z));
        assert_eq!(Quat::from_mint(g), q);
        let n = nalgebra::Quaternion::from(mint::Quaternion::from(q));
        assert_eq!((n.w, n.i, n.j, n.k), (q.w, q.x, q.y, q.z));
        assert_eq!(Quat::from_mint(n), q);
        let v = Vec3::new(1.0f64, 2.0, 3.0);
        assert_eq!(na_vec(v), nalgebra::Vector3::new(1.0, 2.0, 3.0));
    }

    /// Each peer wrapper, fed in pieces as the studies feed it, ends on its plain loop's attitude bit for bit,
    /// in every precision the peer has, on a stream whose rates and steps are not round.
    fn wrappers_match<T: LabReal>() {
        let (samples, _) = crate::scene::stream::<T>(&crate::scenes::Coning, 1000, 0.7537);
        let q0 = Quat::<T>::from_f64(Quat::from_rotation_vector(Vec3::new(0.3, -0.2, 0.1)));
        let dt = samples[1].dt;
        for p in Peer::ALL {
            let Some(lp) = T::peer_loop(p, q0, dt, &samples) else {
                assert!(Config::Peer(p).build::<T>(q0, dt).is_err(), "{p:?}");
                continue;
            };
            let mut w = Config::Peer(p).build::<T>(q0, dt).unwrap();
            for piece in [
                &samples[..1],
                &samples[1..2],
                &samples[2..300],
                &samples[300..],
            ] {
                w.feed(piece);
            }
            let mut l = Config::PeerLoop(p).build::<T>(q0, dt).unwrap();
            l.feed(&samples[..123]);
            l.feed(&samples[123..]);
            let bits = |q: Quat<T>| q.to_f64();
            assert_eq!(bits(w.attitude()), bits(lp), "{p:?} wrapper");
            assert_eq!(bits(l.attitude()), bits(lp), "{p:?} loop fed in pieces");
            assert_ne!(bits(lp), bits(q0), "{p:?} moved");
        }
    }

    #[test]
    fn wrappers_are_their_plain_loops_bit_for_bit() {
        wrappers_match::<f32>();
        wrappers_match::<f64>();
    }

    /// Baumgarte exists for the Runge–Kutta schemes only.
    #[test]
    fn baumgarte_builds_for_runge_kutta_schemes_only() {
        for m in SchemeKind::ALL {
            let c = Config::qp(m, Stab::Baumgarte(0.5), Input::Linear);
            assert_eq!(c.exists(), is_runge_kutta(m));
            assert_eq!(
                c.build::<f32>(Quat::IDENTITY, 1e-3).is_ok(),
                c.exists(),
                "{m:?}"
            );
        }
    }
}
