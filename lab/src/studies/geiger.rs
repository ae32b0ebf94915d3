//! The seed paper's figures: N(t) under RK4 (Fig. 1) and the limit N∞ against the Baumgarte gain k (Fig. 2).

use crate::plot::{plot, Axis, Series};
use crate::table::{self, Csv, Table};
use crate::unchecked::held_step;
use crate::report::Ctx;
use crate::study::{CsvFile, NoArgs, Study};
use quatprop::input::Hold;
use quatprop::scheme::{Baumgarte, Rk4};
use quatprop::stabilize::{Normalize, Off};
use quatprop::{GyroSample, Propagator, Quat, Vec3};
use serde::{Deserialize, Serialize};

/// The seed paper's two figures (sub-command `geiger`).
pub struct Geiger;

// The `Study` impl each study spells out (its name, files and run: lab/README.md, adding a study).
impl Study for Geiger {
    type Args = NoArgs;
    const NAME: &'static str = "geiger";
    const ABOUT: &'static str = "The seed paper's Fig. 1 (N(t) under RK4) and Fig. 2 (N∞ against the Baumgarte gain k)";
    const CSV: &'static [CsvFile] = &[
        CsvFile::data::<Fig1Row>(),
        CsvFile::data::<Fig2Row>(),
        CsvFile::table::<GainRow>(),
    ];
    fn figures(&self) -> Vec<String> {
        vec!["geiger_fig1".into(), "geiger_fig2".into()]
    }
    fn run(&self, ctx: &mut Ctx, _: &NoArgs) {
        ctx.section("geiger fig 1", figure1);
        // Gains per step angle, log-spaced over six decades: 400 resolve the two optimal gains' dips.
        let points = ctx.scale.pick(60, 400, 400);
        ctx.section("geiger fig 2", |c| figure2(c, points));
    }
}

// Every CSV row type derives serde the same way: strict columns, read back as written.

/// Fig. 1: N after each step.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Fig1Row {
    pub t_s: f64,
    pub n_off: f64,
    pub n_closed_form: f64,
    pub n_baumgarte: f64,
    pub n_normalize: f64,
}
impl Csv for Fig1Row {
    const FILE: &'static str = "geiger_fig1.csv";
}

/// Fig. 2: N∞ at one (H|ω|, k).
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Fig2Row {
    pub h_omega: f64,
    pub k: f64,
    /// The fixed point (NaN when none was found near 0).
    pub n_inf: f64,
    pub attracting: bool,
}
impl Csv for Fig2Row {
    const FILE: &'static str = "geiger_fig2.csv";
}

/// Fig. 2's optimal gains per step angle.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct GainRow {
    pub h_omega: f64,
    pub optimal_k1: Option<f64>,
    pub optimal_k2: Option<f64>,
    pub diverges_above_k: Option<f64>,
    pub library_refuses_above_k: f64,
}
impl Csv for GainRow {
    const FILE: &'static str = "geiger_fig2_gains.csv";
}
impl Table for GainRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "H\\|ω\\|",
            "optimal k₁",
            "optimal k₂",
            "iteration diverges for k above",
            "library refuses 4kH > 1.393 (half RK4's real-axis interval) above k =",
        ]);
        let fmt = |r: Option<f64>, d: usize| r.map_or("–".to_string(), |v| format!("{v:.d$}"));
        for r in rows {
            t += &format!(
                "| {:.4} | {} | {} | {} | {:.4} |\n",
                r.h_omega,
                fmt(r.optimal_k1, 6),
                fmt(r.optimal_k2, 6),
                fmt(r.diverges_above_k, 3),
                r.library_refuses_above_k
            );
        }
        t
    }
}

/// Fig. 1: constant rotation |ω| = 1 rad/s about z, 30 steps per period, 30 periods (the seed's setting);
/// N(t) without stabilization, with Baumgarte k = 0.5, with normalization, and the closed form (1 − β)^j − 1.
fn figure1(ctx: &mut Ctx) -> String {
    let h = 2.0 * core::f64::consts::PI / 30.0;
    let w = Vec3::new(0.0, 0.0, 1.0);
    let steps = 900;
    let beta = (h.powi(6) / 4608.0) * (1.0 - h * h / 32.0);
    let mut off = Propagator::new(Quat::<f64>::IDENTITY, Rk4, Hold, Off).unwrap();
    let rk4_baumgarte = Baumgarte::new(Rk4, 0.5).unwrap();
    let mut baum = Propagator::new(Quat::<f64>::IDENTITY, rk4_baumgarte, Hold, Off).unwrap();
    let mut norm = Propagator::new(Quat::<f64>::IDENTITY, Rk4, Hold, Normalize).unwrap();
    let (mut a, mut b, mut c, mut d) = (vec![], vec![], vec![], vec![]);
    let mut rows = Vec::new();
    for j in 1..=steps {
        off.push(GyroSample::new(w), h).unwrap();
        baum.push(GyroSample::new(w), h).unwrap();
        norm.push(GyroSample::new(w), h).unwrap();
        let t = j as f64 * h;
        let closed = (1.0 - beta).powi(j) - 1.0;
        a.push((t, -off.norm_error()));
        b.push((t, -closed));
        c.push((t, -baum.norm_error()));
        d.push((t, norm.norm_error().abs().max(1e-18)));
        rows.push(Fig1Row {
            t_s: t,
            n_off: off.norm_error(),
            n_closed_form: closed,
            n_baumgarte: baum.norm_error(),
            n_normalize: norm.norm_error(),
        });
    }
    ctx.rows(&rows);
    ctx.plot(|dir| {
        plot(
            dir,
            "geiger_fig1",
            "Seed Fig. 1: norm error N(t), RK4, H|ω| = 2π/30",
            Axis {
                label: "t (s)",
                log: false,
            },
            Axis {
                label: "−N = 1 − |q|² (|N| for Normalize; dimensionless)",
                log: true,
            },
            &[
                Series::line("RK4, no stabilization", a),
                Series::line("closed form (1 − β)^j − 1", b).dashed(),
                Series::line("RK4 + Baumgarte k = 0.5", c),
                Series::line("RK4 + Normalize (|N|)", d),
            ],
        )
    });
    format!(
        "### The seed's Fig. 1: N(t) under RK4\n\n![N(t)](geiger_fig1.png)\n\n\
         Constant rotation |ω| = 1 rad/s, 30 steps per period, 30 periods. Without stabilization N follows the \
         closed form (1 − β)^j − 1 with β = {beta:.4e} (the two curves coincide: final N = {:.6e} vs {:.6e}); \
         Baumgarte k = 0.5 jumps to N₁ = {:.3e} on the first step and settles at N∞ = {:.4e}; normalization holds \
         |N| at {:.1e}.\n",
        off.norm_error(),
        (1.0 - beta).powi(steps) - 1.0,
        first_step_n(0.5, h),
        baum.norm_error(),
        norm.norm_error().abs()
    )
}

fn first_step_n(k: f64, h: f64) -> f64 {
    let b = Baumgarte::new(Rk4, k).unwrap();
    let mut p = Propagator::new(Quat::<f64>::IDENTITY, b, Hold, Off).unwrap();
    p.push(GyroSample::new(Vec3::new(0.0, 0.0, 1.0)), h)
        .unwrap();
    p.norm_error()
}

/// One RK4 + Baumgarte step of a permanent rotation about z from |q|² = 1 + n: returns the new N.
/// By symmetry the map depends on N only (the seed's eq. (9)); computed with one unchecked step
/// (`q + scheme.increment(…)`, [`crate::unchecked`]).
fn step_map(k: f64, h: f64, n: f64) -> f64 {
    let q = Quat::new((1.0 + n).sqrt(), 0.0, 0.0, 0.0);
    let b = Baumgarte::new(Rk4, k).expect("k > 0");
    held_step(&b, q, Vec3::new(0.0, 0.0, 1.0), h).norm_error()
}

/// N∞: the fixed point of the step map near 0 (Newton on F(N) − N with a numerical derivative), and whether
/// it attracts (|F'(N∞)| < 1). `None` if no fixed point is found near 0.
fn n_infinity(k: f64, h: f64) -> Option<(f64, bool)> {
    let mut n = 0.0;
    for _ in 0..60 {
        let f = step_map(k, h, n) - n;
        let d = 1e-7 * (1.0 + n.abs());
        let fp = (step_map(k, h, n + d) - step_map(k, h, n - d)) / (2.0 * d) - 1.0;
        if fp == 0.0 || !fp.is_finite() {
            return None;
        }
        let next = n - f / fp;
        if !next.is_finite() || next.abs() > 0.5 {
            return None;
        }
        if (next - n).abs() < 1e-17 + 1e-13 * n.abs() {
            n = next;
            break;
        }
        n = next;
    }
    let d = 1e-7;
    let slope = (step_map(k, h, n + d) - step_map(k, h, n - d)) / (2.0 * d);
    Some((n, slope.abs() < 1.0))
}

/// Fig. 2: |N∞| against k (log axes) at several step angles; the two optimal k (zeros of N∞) to 6 digits,
/// and where the iteration diverges; `points` gains per step angle.
fn figure2(ctx: &mut Ctx, points: usize) -> String {
    let mut out = String::from(
        "### The seed's Fig. 2: N∞ against the Baumgarte gain k\n\n![N∞(k)](geiger_fig2.png)\n\n\
         Permanent rotation |ω| = 1 rad/s under RK4. N∞ is the fixed point of the per-step map N → F(N) (the seed's \
         eq. (9), evaluated as one unchecked step `q + increment` of the library's `Baumgarte(Rk4, k)`), found by Newton iteration; it is marked divergent \
         where |F'(N∞)| ≥ 1. The optimal gains are the zeros of N∞(k), located by bisection on sign changes.\n\n",
    );
    let mut series = Vec::new();
    let mut rows = Vec::new();
    let mut gains = Vec::new();
    for hw in [0.1, 0.2, 0.5, 2.0 * core::f64::consts::PI / 30.0] {
        let ks: Vec<f64> = (0..points)
            .map(|i| 10f64.powf(-4.0 + 6.0 * i as f64 / (points - 1) as f64))
            .collect();
        let mut pts = Vec::new();
        let mut prev: Option<(f64, f64)> = None;
        let mut roots = Vec::new();
        let mut diverge_at = None;
        for &k in &ks {
            ctx.tick();
            match n_infinity(k, hw) {
                Some((n, true)) => {
                    pts.push((k, n.abs().max(1e-20)));
                    rows.push(Fig2Row {
                        h_omega: hw,
                        k,
                        n_inf: n,
                        attracting: true,
                    });
                    if let Some((k0, n0)) = prev {
                        if n0.signum() != n.signum() && n0 != 0.0 {
                            roots.push(bisect(k0, k, hw));
                        }
                    }
                    prev = Some((k, n));
                }
                other => {
                    rows.push(Fig2Row {
                        h_omega: hw,
                        k,
                        n_inf: other.map_or(f64::NAN, |o| o.0),
                        attracting: false,
                    });
                    if diverge_at.is_none() && k > 1e-2 {
                        diverge_at = Some(k);
                    }
                    prev = None;
                }
            }
        }
        gains.push(GainRow {
            h_omega: hw,
            optimal_k1: roots.first().copied(),
            optimal_k2: roots.get(1).copied(),
            diverges_above_k: diverge_at,
            library_refuses_above_k: Baumgarte::new(Rk4, 0.0).expect("k = 0").gain_step_limit()
                / (4.0 * hw),
        });
        series.push(Series::line(format!("H|ω| = {hw:.3} rad"), pts));
    }
    ctx.rows(&rows);
    out += &ctx.table(&gains);
    ctx.plot(|dir| {
        plot(
            dir,
            "geiger_fig2",
            "Seed Fig. 2: |N∞| against Baumgarte k (RK4, |ω| = 1 rad/s)",
            Axis {
                label: "k (1/s)",
                log: true,
            },
            Axis {
                label: "|N∞| (dimensionless)",
                log: true,
            },
            &series,
        )
    });
    out
}

/// The zero of N∞(k) between k0 and k1, to 6 significant digits.
fn bisect(mut a: f64, mut b: f64, hw: f64) -> f64 {
    let f = |k: f64| n_infinity(k, hw).map_or(f64::NAN, |v| v.0);
    let fa = f(a);
    for _ in 0..80 {
        let m = (a * b).sqrt();
        let fm = f(m);
        if fm.signum() == fa.signum() {
            a = m;
        } else {
            b = m;
        }
        if (b - a) / b < 1e-9 {
            break;
        }
    }
    (a * b).sqrt()
}
