//! The configurations the studies compare, and one integrator type that runs any of them over a sample stream.
//!
//! A configuration is either quatprop (scheme × stabilizer × input model × accumulator) or a peer. Every
//! quatprop configuration is monomorphized (the zero-sized scheme and stabilizer types a firmware would name),
//! so host timings are those of the code a user links, not of an enum dispatch. Peers that exist as Rust
//! crates are used as crates (`ahrs`, `nalgebra`, `glam`); Fusion (C) is implemented from its published
//! formulas in [`crate::peers`].
//!
//! Streams: a sample is a body rate (rad/s) and the time since the previous sample (s; ignored for the first
//! sample of a stream). Every step an integrator refuses is counted with its first error: nothing is dropped
//! silently.

use crate::peers;
use quatprop::accumulate::{Accumulator, Kahan, Plain};
use quatprop::scheme::{Cf4, Euler, ExpMap, Magnus4, Method, Rk2, Rk3, Rk4, Rk5, Scheme};
use quatprop::stabilize::{Baumgarte, Every, FirstOrder, Normalize, Off, Stabilizer};
use quatprop::{Error, Propagator, Quat, Real, SampleHistory, Vec3};

/// One gyro sample of a stream: rate (rad/s, body frame) and the time since the previous sample (s).
#[derive(Clone, Copy, Debug)]
pub struct Sample<T> {
    pub w: Vec3<T>,
    pub dt: T,
}

/// How a quatprop configuration turns the samples into a rate model for each step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// `step_hold` with the newest sample (what Fusion and Madgwick do).
    Hold,
    /// `step_linear` between the two samples bracketing the step.
    Linear,
    /// `step_history`: the last four samples, fourth order, no latency. After a gap (a step longer than
    /// 1.5 nominal periods) the history restarts and the gap is bridged by a linear step.
    History,
    /// `step_mid`: one step per two sample intervals with the quadratic through three samples (the same
    /// samples, half the steps).
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
    /// Baumgarte with gain k (1/s).
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
        method: Method,
        stab: Stab,
        input: Input,
        compensated: bool,
    },
    Peer(Peer),
}

impl Config {
    pub const fn qp(method: Method, stab: Stab, input: Input) -> Self {
        Config::Quatprop {
            method,
            stab,
            input,
            compensated: false,
        }
    }

    pub fn label(&self) -> String {
        match *self {
            Config::Quatprop {
                method,
                stab,
                input,
                compensated,
            } => format!(
                "quatprop {} {} + {}{}",
                method.name(),
                input.name(),
                stab.name(),
                if compensated { ", compensated" } else { "" }
            ),
            Config::Peer(p) => p.name().into(),
        }
    }

    pub fn is_peer(&self) -> bool {
        matches!(self, Config::Peer(_))
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
    /// f64 version; the library refused the configuration).
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
                compensated,
            } => build_quatprop(method, stab, input, compensated, q0, nominal_dt)
                .map_err(|e| format!("{}: {e:?}", self.label())),
            Config::Peer(p) => T::peer(p, q0, nominal_dt).ok_or_else(|| {
                format!(
                    "{} has no {} version",
                    p.name(),
                    core::any::type_name::<T>()
                )
            }),
        }
    }
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

/// f32 and f64 as the lab needs them: quatprop's `Real` plus the peers' scalar types.
pub trait LabReal: Real + nalgebra::RealField + Copy {
    /// The peer's integrator in this precision, if the peer has one.
    fn peer(p: Peer, q0: Quat<Self>, nominal_dt: Self) -> Option<Box<dyn Integrator<Self>>>;
}

impl LabReal for f32 {
    fn peer(p: Peer, q0: Quat<f32>, nominal_dt: f32) -> Option<Box<dyn Integrator<f32>>> {
        Some(match p {
            Peer::Fusion => Box::new(FusionRun { q: q0, prev: false }),
            Peer::GlamScaledAxis => Box::new(GlamRun {
                q: glam::Quat::from_xyzw(q0.x, q0.y, q0.z, q0.w),
                prev: None,
            }),
            _ => nalgebra_peer(p, q0, nominal_dt)?,
        })
    }
}

impl LabReal for f64 {
    fn peer(p: Peer, q0: Quat<f64>, nominal_dt: f64) -> Option<Box<dyn Integrator<f64>>> {
        Some(match p {
            Peer::Fusion => return None,
            Peer::GlamScaledAxis => Box::new(DGlamRun {
                q: glam::DQuat::from_xyzw(q0.x, q0.y, q0.z, q0.w),
                prev: None,
            }),
            _ => nalgebra_peer(p, q0, nominal_dt)?,
        })
    }
}

// ------------------------------------------------------------------------------------------------ quatprop

struct QuatpropRun<T: Real, S: Scheme, Z: Stabilizer<T>, A: Accumulator<T>> {
    p: Propagator<T, S, Z, A>,
    input: Input,
    prev: Option<Vec3<T>>,
    mid: Option<(Vec3<T>, T)>,
    history: SampleHistory<T>,
    gap: T,
    refused: u64,
    first_error: Option<Error>,
}

impl<T: Real, S: Scheme, Z: Stabilizer<T>, A: Accumulator<T>> Integrator<T>
    for QuatpropRun<T, S, Z, A>
{
    fn feed(&mut self, samples: &[Sample<T>]) {
        // One loop per input model, so the step loop itself has no dispatch; the state lives in locals
        // during the loop (as it would in a firmware's interrupt handler) and is written back once.
        let (mut p, mut prev, mut history) = (self.p, self.prev, self.history);
        let (mut refused, mut first) = (0u64, None);
        // Cold: only refused steps reach the body.
        let mut note = |r: Result<(), Error>| {
            if let Err(e) = r {
                refuse(&mut refused, &mut first, e);
            }
        };
        match self.input {
            Input::Hold => {
                for s in samples {
                    if prev.is_some() {
                        note(p.step_hold(s.w, s.dt));
                    }
                    prev = Some(s.w);
                }
            }
            Input::Linear => {
                for s in samples {
                    if let Some(w0) = prev {
                        note(p.step_linear(w0, s.w, s.dt));
                    }
                    prev = Some(s.w);
                }
            }
            Input::History => {
                for s in samples {
                    match prev {
                        Some(w0) if s.dt > self.gap => {
                            // A gap: bridge it linearly, restart the history at this sample.
                            note(p.step_linear(w0, s.w, s.dt));
                            history.clear();
                            history.push(s.w);
                        }
                        _ => note(p.step_history(&mut history, s.w, s.dt)),
                    }
                    prev = Some(s.w);
                }
            }
            Input::Mid => {
                for s in samples {
                    match (prev, self.mid) {
                        (None, _) => prev = Some(s.w),
                        (Some(_), None) => self.mid = Some((s.w, s.dt)),
                        (Some(w0), Some((wm, dt1))) => {
                            note(p.step_mid(w0, wm, s.w, dt1 + s.dt));
                            prev = Some(s.w);
                            self.mid = None;
                        }
                    }
                }
            }
        }
        (self.p, self.prev, self.history) = (p, prev, history);
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

fn boxed<T: Real, S: Scheme + 'static, Z: Stabilizer<T> + 'static>(
    q0: Quat<T>,
    s: S,
    z: Z,
    input: Input,
    compensated: bool,
    nominal_dt: T,
) -> Result<Box<dyn Integrator<T>>, Error> {
    let gap = nominal_dt * <T as Real>::from_f64(1.5);
    Ok(if compensated {
        Box::new(QuatpropRun::<T, S, Z, Kahan<T>> {
            p: Propagator::new_compensated(q0, s, z)?,
            input,
            prev: None,
            mid: None,
            history: SampleHistory::new(),
            gap,
            refused: 0,
            first_error: None,
        })
    } else {
        Box::new(QuatpropRun::<T, S, Z, Plain> {
            p: Propagator::new(q0, s, z)?,
            input,
            prev: None,
            mid: None,
            history: SampleHistory::new(),
            gap,
            refused: 0,
            first_error: None,
        })
    })
}

fn build_quatprop<T: Real>(
    method: Method,
    stab: Stab,
    input: Input,
    compensated: bool,
    q0: Quat<T>,
    nominal_dt: T,
) -> Result<Box<dyn Integrator<T>>, Error> {
    macro_rules! with_stab {
        ($s:expr) => {
            match stab {
                Stab::Off => boxed(q0, $s, Off, input, compensated, nominal_dt),
                Stab::Normalize => boxed(q0, $s, Normalize, input, compensated, nominal_dt),
                Stab::FirstOrder => boxed(q0, $s, FirstOrder, input, compensated, nominal_dt),
                Stab::Every(n) => boxed(q0, $s, Every(n), input, compensated, nominal_dt),
                Stab::Baumgarte(k) => boxed(
                    q0,
                    $s,
                    Baumgarte {
                        k: <T as Real>::from_f64(k),
                    },
                    input,
                    compensated,
                    nominal_dt,
                ),
            }
        };
    }
    match method {
        Method::Euler => with_stab!(Euler),
        Method::Rk2 => with_stab!(Rk2),
        Method::Rk3 => with_stab!(Rk3),
        Method::Rk4 => with_stab!(Rk4),
        Method::Rk5 => with_stab!(Rk5),
        Method::ExpMap => with_stab!(ExpMap),
        Method::Magnus4 => with_stab!(Magnus4),
        Method::Cf4 => with_stab!(Cf4),
    }
}

// ------------------------------------------------------------------------------------------------ peers

struct FusionRun {
    q: Quat<f32>,
    prev: bool,
}
impl Integrator<f32> for FusionRun {
    fn feed(&mut self, samples: &[Sample<f32>]) {
        for s in samples {
            if self.prev {
                self.q = peers::fusion_euler(self.q, s.w, s.dt);
            }
            self.prev = true;
        }
    }
    fn attitude(&self) -> Quat<f32> {
        self.q
    }
}

struct GlamRun {
    q: glam::Quat,
    prev: Option<Vec3<f32>>,
}
impl Integrator<f32> for GlamRun {
    fn feed(&mut self, samples: &[Sample<f32>]) {
        for s in samples {
            if let Some(w0) = self.prev {
                let v = (w0 + s.w) * (0.5 * s.dt);
                self.q = (self.q * glam::Quat::from_scaled_axis(glam::Vec3::new(v.x, v.y, v.z)))
                    .normalize();
            }
            self.prev = Some(s.w);
        }
    }
    fn attitude(&self) -> Quat<f32> {
        Quat::new(self.q.w, self.q.x, self.q.y, self.q.z)
    }
}

struct DGlamRun {
    q: glam::DQuat,
    prev: Option<Vec3<f64>>,
}
impl Integrator<f64> for DGlamRun {
    fn feed(&mut self, samples: &[Sample<f64>]) {
        for s in samples {
            if let Some(w0) = self.prev {
                let v = (w0 + s.w) * (0.5 * s.dt);
                self.q = (self.q * glam::DQuat::from_scaled_axis(glam::DVec3::new(v.x, v.y, v.z)))
                    .normalize();
            }
            self.prev = Some(s.w);
        }
    }
    fn attitude(&self) -> Quat<f64> {
        Quat::new(self.q.w, self.q.x, self.q.y, self.q.z)
    }
}

type NaQuat<T> = nalgebra::UnitQuaternion<T>;

fn to_na<T: LabReal>(q: Quat<T>) -> NaQuat<T> {
    NaQuat::new_normalize(nalgebra::Quaternion::new(q.w, q.x, q.y, q.z))
}
fn from_na<T: LabReal>(q: &NaQuat<T>) -> Quat<T> {
    Quat::new(q.w, q.i, q.j, q.k)
}
fn na_vec<T: LabReal>(v: Vec3<T>) -> nalgebra::Vector3<T> {
    nalgebra::Vector3::new(v.x, v.y, v.z)
}

fn nalgebra_peer<T: LabReal>(
    p: Peer,
    q0: Quat<T>,
    nominal_dt: T,
) -> Option<Box<dyn Integrator<T>>> {
    Some(match p {
        Peer::AhrsMadgwick => Box::new(AhrsRun {
            m: ahrs::Madgwick::new_with_quat(nominal_dt, T::ZERO, to_na(q0)),
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
        Peer::Fusion | Peer::GlamScaledAxis => return None,
    })
}

/// `ahrs` has no time argument: it integrates every sample over its fixed `sample_period` (jitter and gaps
/// are invisible to it).
struct AhrsRun<T: LabReal> {
    m: ahrs::Madgwick<T>,
    prev: bool,
}
impl<T: LabReal> Integrator<T> for AhrsRun<T> {
    fn feed(&mut self, samples: &[Sample<T>]) {
        use ahrs::Ahrs as _;
        for s in samples {
            if self.prev {
                self.m.update_gyro(&na_vec(s.w));
            }
            self.prev = true;
        }
    }
    fn attitude(&self) -> Quat<T> {
        from_na(&self.m.quat)
    }
}

struct NalgebraRk4Run<T: LabReal> {
    q: NaQuat<T>,
    prev: Option<Vec3<T>>,
}
impl<T: LabReal> Integrator<T> for NalgebraRk4Run<T> {
    fn feed(&mut self, samples: &[Sample<T>]) {
        let half = T::HALF;
        let f = |y: &nalgebra::Quaternion<T>, w: Vec3<T>| {
            y * nalgebra::Quaternion::from_imag(na_vec(w * half))
        };
        for s in samples {
            if let Some(w0) = self.prev {
                let (w1, h) = (s.w, s.dt);
                let wm = (w0 + w1) * half;
                let q = self.q.into_inner();
                let k1 = f(&q, w0);
                let k2 = f(&(q + k1 * (h * half)), wm);
                let k3 = f(&(q + k2 * (h * half)), wm);
                let k4 = f(&(q + k3 * h), w1);
                let two = T::TWO;
                let six = <T as Real>::from_f64(6.0);
                self.q = NaQuat::new_normalize(q + (k1 + k2 * two + k3 * two + k4) * (h / six));
            }
            self.prev = Some(s.w);
        }
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
        for s in samples {
            if let Some(w0) = self.prev {
                let v = (w0 + s.w) * (T::HALF * s.dt);
                self.q *= NaQuat::from_scaled_axis(na_vec(v));
            }
            self.prev = Some(s.w);
        }
    }
    fn attitude(&self) -> Quat<T> {
        from_na(&self.q)
    }
}
