//! The quiet-core gate: whether a host-time measurement ran while this core was at its quiet speed.
//!
//! The machines the lab runs on are shared virtual machines, and on them the same code runs at two speeds
//! that alternate, whatever this machine's own load. Measured with a quatprop f32 step (ExpMap, linear input)
//! over a fixed stream: about 35 ns per sample in spells of up to ~1.5 s, about 47 ns in spells of up to ~40
//! s. A dependent floating-point chain runs at the same speed in both, so it is not the clock rate, and a busy
//! loop on this machine's other core does not cause it; it behaves like another tenant's work on the same
//! physical core, which slows arithmetic that depends on spare execution units. The slow spell slows a
//! sample-history step (more independent arithmetic) more than a linear step, so a sweep whose timed runs
//! all fell in one spell read the history/linear ratio as 1.23 or as 1.43, depending on the spell.
//!
//! The gate tells the spells apart with a probe: a fixed workload (that same f32 ExpMap + linear step over
//! [`Quiet::PROBE_SAMPLES`] samples) timed around every measured run. The probe's least time in this
//! process is its quiet speed; a run is *quiet* when the probes on both sides of it are within
//! [`Quiet::TOLERANCE`] of that. A study keeps timing until every configuration has enough quiet runs, and
//! the probe must have been watched for a while in the process (60 s at `--full`: the sweep's `Timing`)
//! before its least is trusted as the quiet speed (the quiet spells are short and can be absent for tens of
//! seconds).

use quatprop::input::Linear;
use quatprop::scheme::ExpMap;
use quatprop::stabilize::FirstOrder;
use quatprop::{GyroSample, Propagator, Quat, Vec3};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// The probe and what it has seen in this process.
pub struct Quiet {
    rates: Vec<Vec3<f32>>,
    /// The probe's least time in this process (ns per sample): the quiet speed.
    best: f64,
    /// Wall time spent watching the probe (timed rounds) in this process.
    watched: Duration,
}

impl Default for Quiet {
    fn default() -> Self {
        Self::new()
    }
}

impl Quiet {
    /// Samples per probe run (~40 µs).
    pub const PROBE_SAMPLES: usize = 1000;
    /// A run is quiet when the probes around it took at most this much more than the quiet speed. The two
    /// speeds are ~30 % apart; the probe's own spread within the quiet spell is under 8 %.
    pub const TOLERANCE: f64 = 0.10;
    pub fn new() -> Self {
        // A 1 Hz cone of half-angle 0.1 rad at 1 kHz (any smooth rate would do: only the speed is used).
        let rates = (0..Self::PROBE_SAMPLES)
            .map(|k| {
                let t = k as f64 * 1e-3;
                let w = std::f64::consts::TAU;
                Vec3::new(
                    (0.1 * w * (w * t).cos()) as f32,
                    (0.1 * w * (w * t).sin()) as f32,
                    0.005,
                )
            })
            .collect();
        Self {
            rates,
            best: f64::INFINITY,
            watched: Duration::ZERO,
        }
    }

    /// Times the probe (the lesser of two runs, ns per sample) and updates the quiet speed.
    pub fn probe(&mut self) -> f64 {
        let mut least = f64::INFINITY;
        for _ in 0..2 {
            let Ok(mut p) = Propagator::new(Quat::IDENTITY, ExpMap, Linear::new(), FirstOrder)
            else {
                return f64::INFINITY;
            };
            let t0 = Instant::now();
            for &w in black_box(&self.rates[..]) {
                let _ = p.push(GyroSample::new(w), 1.0e-3f32);
            }
            black_box(p.attitude());
            least = least.min(t0.elapsed().as_nanos() as f64 / Self::PROBE_SAMPLES as f64);
        }
        self.best = self.best.min(least);
        least
    }

    /// Whether a run ran at the quiet speed, from the slower of the probes on its two sides (ns per sample).
    pub fn is_quiet(&self, probe: f64) -> bool {
        probe <= self.best * (1.0 + Self::TOLERANCE)
    }

    /// Adds the wall time of a stretch of timed rounds.
    pub fn watched(&mut self, d: Duration) {
        self.watched += d;
    }

    /// Whether the probe has been watched for `need` in this process (its least time taken as the quiet
    /// speed).
    pub fn calibrated(&self, need: Duration) -> bool {
        self.watched >= need
    }

    /// The quiet speed (ns per probe sample) seen so far.
    #[cfg(test)]
    pub fn speed(&self) -> f64 {
        self.best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quiet_is_relative_to_the_least_probe() {
        let mut q = Quiet::new();
        let p = q.probe();
        assert!(p.is_finite() && p > 0.0, "probe {p}");
        assert_eq!(q.speed(), p);
        assert!(q.is_quiet(p * (1.0 + 0.5 * Quiet::TOLERANCE)));
        assert!(!q.is_quiet(p * (1.0 + 2.0 * Quiet::TOLERANCE)));
        let need = Duration::from_secs(60);
        assert!(!q.calibrated(need));
        q.watched(need);
        assert!(q.calibrated(need));
    }
}
