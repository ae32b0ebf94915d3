//! The input models as the checks see them: how to make a model's sample from a vector, and an
//! independent mirror of each model's documented step schedule (which push closes a step) with a bound on
//! the angle of the step being closed.

use super::Fz;
use quatprop::input::coning::ConingCorrection;
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::{DeltaAngle, GyroSample, Vec3};

/// An input model driven by the checks.
pub trait Model<T: Fz>: InputModel<T> + PartialEq + core::fmt::Debug {
    /// The model's sample carrying `v` (a rate, or an angle increment).
    fn sample(v: Vec3<T>, saturated: bool) -> Self::Sample;
    /// A fresh mirror of this model's schedule.
    fn schedule(&self) -> Schedule;
}

/// Which schedule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A step per sample.
    Hold,
    /// The first sample starts; then a step per sample.
    Linear,
    /// As Linear (the cubic builds up; spacing changes restart it at the last sample).
    History,
    /// Start, then (middle, end) pairs.
    TwiceRate,
    /// (first, second) pairs; the second closes.
    Gauss,
    /// `n` increments per update.
    Delta(usize),
}

/// The documented schedule of an input model, kept independently of the library: the samples since the
/// last step boundary (their magnitude and dt), and the last increment of the previous delta-angle update.
#[derive(Clone, Copy, Debug)]
pub struct Schedule {
    kind: Kind,
    /// Samples kept (magnitude, dt), oldest first; `len` of them valid.
    kept: [(f64, f64); 5],
    len: usize,
    /// History: samples since the last restart (the cubic uses up to 4).
    history: [f64; 3],
    history_len: usize,
    /// Delta angles: |last increment| of the previous update.
    previous: Option<f64>,
}

impl Schedule {
    /// A mirror of a fresh model of `kind`.
    pub fn new(kind: Kind) -> Self {
        Self {
            kind,
            kept: [(0.0, 0.0); 5],
            len: 0,
            history: [0.0; 3],
            history_len: 0,
            previous: None,
        }
    }

    /// The kind mirrored.
    pub fn kind(&self) -> Kind {
        self.kind
    }

    /// Whether the next accepted sample closes a step.
    pub fn closes(&self) -> bool {
        match self.kind {
            Kind::Hold => true,
            Kind::Linear => self.len >= 1,
            Kind::History => self.history_len >= 1,
            Kind::TwiceRate => self.len == 2,
            Kind::Gauss => self.len == 1,
            Kind::Delta(n) => self.len + 1 >= n.clamp(1, 5),
        }
    }

    /// An upper bound of `h · max_{c∈[0,1]} |ω(c)|` (rad) for the step that a sample of magnitude `m`
    /// (rate, or increment for delta angles) and interval `dt` would close. The interpolants' Lebesgue
    /// constants on [0, 1]: History's cubic through −2, −1, 0, 1: 1.625 (at c = ½), and at the samples'
    /// true times with consecutive spacings within `History::GAP_RATIO` = 2.5 of each other at most 7.22
    /// (nodes 1, 0, −0.4, −0.56: each spacing 2.5 times the one before; a dropped sample, nodes 1, 0,
    /// −0.5, −1: 3.05); its quadratic start step with the start correction: 1.5; TwiceRate's quadratic
    /// through 0, ½, 1: 1.25;
    /// the Gauss line extrapolated to the ends: 1 + 2·0.366 = 1.732. Delta angles: the coning formulas'
    /// `|φ| ≤ S + 2.73·S² + |Δθ_prev|·S/12`, `S = Σ|Δθᵢ|` (largest weight 1375/504).
    pub fn step_angle(&self, m: f64, dt: f64) -> f64 {
        let kept = &self.kept[..self.len];
        let max_kept = kept.iter().fold(m, |a, &(k, _)| a.max(k));
        let sum_dt = kept.iter().fold(dt, |a, &(_, d)| a + d);
        match self.kind {
            Kind::Hold => m * dt,
            Kind::Linear => max_kept * dt,
            Kind::History => {
                let max = self.history[..self.history_len]
                    .iter()
                    .fold(m, |a, &k| a.max(k));
                7.25 * max * dt
            }
            Kind::TwiceRate => 1.25 * max_kept * sum_dt,
            Kind::Gauss => 1.74 * max_kept * sum_dt,
            Kind::Delta(_) => {
                let s = kept.iter().fold(m, |a, &(k, _)| a + k);
                s + 3.0 * s * s + self.previous.unwrap_or(0.0) * s / 12.0
            }
        }
    }

    /// The length `h` (s) of the step that a sample with interval `dt` would close.
    pub fn step_length(&self, dt: f64) -> f64 {
        match self.kind {
            Kind::TwiceRate | Kind::Gauss | Kind::Delta(_) => {
                self.kept[..self.len].iter().fold(dt, |a, &(_, d)| a + d)
            }
            _ => dt,
        }
    }

    /// Commits an accepted sample.
    pub fn accept(&mut self, m: f64, dt: f64) {
        let closes = self.closes();
        match self.kind {
            Kind::Hold => {}
            Kind::Linear => {
                self.kept[0] = (m, dt);
                self.len = 1;
            }
            Kind::History => {
                if self.history_len < 3 {
                    self.history[self.history_len] = m;
                    self.history_len += 1;
                } else {
                    self.history = [self.history[1], self.history[2], m];
                }
            }
            Kind::TwiceRate | Kind::Gauss => {
                if closes {
                    self.len = 0;
                    if self.kind == Kind::TwiceRate {
                        // The end sample starts the next step.
                        self.kept[0] = (m, 0.0);
                        self.len = 1;
                    }
                } else {
                    // TwiceRate's first sample only starts the step: its interval is not in it.
                    let starts = self.kind == Kind::TwiceRate && self.len == 0;
                    self.kept[self.len] = (m, if starts { 0.0 } else { dt });
                    self.len += 1;
                }
            }
            Kind::Delta(_) => {
                if closes {
                    self.len = 0;
                    self.previous = Some(m);
                } else {
                    self.kept[self.len] = (m, dt);
                    self.len += 1;
                }
            }
        }
    }

    /// The model forgot its samples (`restart_input`).
    pub fn restart(&mut self) {
        *self = Self::new(self.kind);
    }

    /// The first sample of a stream (`InputModel::start`): Linear, History and TwiceRate keep it as the
    /// start of their next step; the others only restart.
    pub fn start(&mut self, m: f64) {
        self.restart();
        match self.kind {
            Kind::Linear | Kind::TwiceRate => {
                self.kept[0] = (m, 0.0);
                self.len = 1;
            }
            Kind::History => {
                self.history[0] = m;
                self.history_len = 1;
            }
            _ => {}
        }
    }
}

/// [`Model`] for the models fed rates (a [`GyroSample`] per push), each with its schedule's kind.
macro_rules! rate_models {
    ($($model:ty => $kind:expr),* $(,)?) => {$(
        impl<T: Fz> Model<T> for $model {
            fn sample(rate: Vec3<T>, saturated: bool) -> GyroSample<T> {
                GyroSample { rate, saturated }
            }
            fn schedule(&self) -> Schedule {
                Schedule::new($kind)
            }
        }
    )*};
}

rate_models! {
    Hold => Kind::Hold,
    Linear<T> => Kind::Linear,
    History<T> => Kind::History,
    TwiceRate<T> => Kind::TwiceRate,
    GaussPoints<T> => Kind::Gauss,
}

impl<T: Fz, C: ConingCorrection + PartialEq + core::fmt::Debug> Model<T> for DeltaAngles<T, C> {
    fn sample(v: Vec3<T>, saturated: bool) -> DeltaAngle<T> {
        DeltaAngle {
            angle: v,
            saturated,
        }
    }
    fn schedule(&self) -> Schedule {
        Schedule::new(Kind::Delta(self.correction().samples()))
    }
}
