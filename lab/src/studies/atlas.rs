//! Stability atlas: the per-step norm factor and the attitude error of one held-rate step against H|ω|, for
//! every scheme, measured with one unchecked step (`q + increment`, so it can go beyond the bounds), with the measured
//! stability bound next to the one derived from the tableau.

use crate::configs::scheme_name;
use crate::plot::{plot, Axis, Series};
use crate::table::{self, Csv, Table};
use crate::unchecked::held_step;
use crate::report::Ctx;
use crate::study::{CsvFile, NoArgs, Study};
use quatprop::scheme::SchemeKind;
use quatprop::{Quat, Vec3};
use serde::{Deserialize, Serialize};

/// The stability atlas (sub-command `atlas`).
pub struct Atlas;

impl Study for Atlas {
    type Args = NoArgs;
    const NAME: &'static str = "atlas";
    const ABOUT: &'static str = "Per-step norm factor and error against the step angle, measured stability bounds";
    const CSV: &'static [CsvFile] = &[CsvFile::data::<AtlasRow>(), CsvFile::table::<BoundRow>()];
    fn figures(&self) -> Vec<String> {
        vec!["stability_norm".into(), "stability_error".into()]
    }
    fn run(&self, ctx: &mut Ctx, _: &NoArgs) {
        // Step angles over five decades; the measured bounds agree with the tableau's to the grid spacing,
        // so the default runs the full grid (a fraction of a second).
        let n = ctx.scale.pick(120, 2000, 2000);
        ctx.section("stability atlas", |c| atlas(c, n));
    }
}

/// One step of one scheme at one step angle.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AtlasRow {
    pub scheme: String,
    pub step_angle_rad: f64,
    pub norm_factor_minus_one: f64,
    pub attitude_error_per_step_rad: f64,
}
impl Csv for AtlasRow {
    const FILE: &'static str = "stability_atlas.csv";
}

/// The stability bound of one scheme: from the tableau and measured.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BoundRow {
    pub scheme: String,
    /// From the tableau (rad; infinite: none).
    pub bound_from_tableau_rad: f64,
    /// First H|ω| where the norm factor crosses its level (empty: never).
    pub measured_rad: Option<f64>,
}
impl Csv for BoundRow {
    const FILE: &'static str = "stability_bounds.csv";
}
impl Table for BoundRow {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&[
            "scheme",
            "bound from the tableau (rad)",
            "measured: first H\\|ω\\| where the norm factor crosses its level",
            "agreement",
        ]);
        for r in rows {
            let theory = r.bound_from_tableau_rad;
            t += &format!(
                "| {} | {} | {} | {} |\n",
                r.scheme,
                if theory.is_finite() {
                    format!("{theory:.4}")
                } else {
                    "none".into()
                },
                r.measured_rad
                    .map_or("never (norm factor ≤ 1 everywhere)".into(), |a| format!(
                        "{a:.4}"
                    )),
                match (theory.is_finite(), r.measured_rad) {
                    (true, Some(a)) => format!("{:+.2}%", 100.0 * (a / theory - 1.0)),
                    (false, None) => "exact".into(),
                    _ => "–".into(),
                }
            );
        }
        t
    }
}

fn atlas(ctx: &mut Ctx, n: usize) -> String {
    let angles: Vec<f64> = (0..n)
        .map(|i| 10f64.powf(-4.0 + 5.0 * i as f64 / (n - 1) as f64))
        .collect();
    let axis = Vec3::new(0.36, -0.48, 0.8);
    let mut norm_series = Vec::new();
    let mut err_series = Vec::new();
    let mut rows = Vec::new();
    let mut bounds = Vec::new();
    for m in SchemeKind::ALL {
        let info = m.information();
        let mut np = Vec::new();
        let mut ep = Vec::new();
        let mut crossed = None;
        let level_is_two = info.step_angle_limit.is_finite() && info.norm_change(1e-2) > 0.0;
        for &a in &angles {
            ctx.tick();
            let q = Quat::<f64>::IDENTITY;
            let next = held_step(&m, q, axis * a, 1.0);
            let f = next.norm_squared() - 1.0;
            let exact = Quat::from_rotation_vector(axis * a);
            let e = next.normalized().map_or(f64::NAN, |u| u.angle_to(exact));
            np.push((a, f.abs().max(1e-20)));
            ep.push((a, e.max(1e-20)));
            rows.push(AtlasRow {
                scheme: info.name.into(),
                step_angle_rad: a,
                norm_factor_minus_one: f,
                attitude_error_per_step_rad: e,
            });
            let level = if level_is_two { 1.0 } else { 0.0 };
            // 1e-12 stays clear of f64 rounding in the exact schemes' large-angle trigonometry.
            if crossed.is_none() && f > level + 1e-12 && a > 1e-3 {
                crossed = Some(a);
            }
        }
        bounds.push(BoundRow {
            scheme: info.name.into(),
            bound_from_tableau_rad: info.step_angle_limit,
            measured_rad: crossed,
        });
        norm_series.push(Series::line(scheme_name(m), np));
        err_series.push(Series::line(scheme_name(m), ep));
    }
    ctx.rows(&rows);
    let table = ctx.table(&bounds);
    ctx.plot(|dir| {
        plot(
            dir,
            "stability_norm",
            "Per-step norm change | |R(ix)|^2 - 1 | against the step angle",
            Axis {
                label: "step angle H|ω| (rad)",
                log: true,
            },
            Axis {
                label: "||q₁|² − 1| after one step (dimensionless)",
                log: true,
            },
            &norm_series,
        )
    });
    ctx.plot(|dir| {
        plot(
            dir,
            "stability_error",
            "Attitude error of one step against the step angle",
            Axis {
                label: "step angle H|ω| (rad)",
                log: true,
            },
            Axis {
                label: "attitude error of one step (rad)",
                log: true,
            },
            &err_series,
        )
    });
    format!(
        "### Stability atlas\n\n![norm](stability_norm.png)\n\n![error](stability_error.png)\n\n\
         One held-rate step from the identity, f64, H|ω| from 1e-4 to 10 rad. Dissipative schemes' bound is where \
         |R(ix)|² first exceeds 1; for Euler and RK2 (which gain norm at every step) the admitted bound is where \
         one step doubles |q|². Sampled on a grid of {n} log-spaced angles, so agreement is to the grid spacing.\n\n{table}"
    )
}
