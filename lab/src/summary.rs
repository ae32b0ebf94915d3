//! The report's opening summary: which configuration for a gyro, a sample rate and a horizon, and what it
//! costs on a Cortex-M4F, computed from this run's own figures (the full grid's f32 errors on coning,
//! `work_precision_grid.csv`) and the firmware bench's instruction counts (`firmware/bench-m4f.csv`).
//!
//! The rule: the integration's error over the horizon must stay below a tenth of the attitude error the
//! gyro's white noise alone makes in that time, `N·√T` (per axis, 1σ; `N` the rate noise density), so
//! that the attitude error is the sensor's, not the integrator's. The grid's error over its horizon `H`
//! grows linearly with time on coning (a drift, and in f32 with the plain accumulator a rounding walk that
//! grows as the step count: `long_horizon`'s growth exponents are near 1), so the error at `T` is taken as
//! `e(H)·T/H`. Of the configurations that pass at a rate, the one with the fewest M4F instructions per
//! second is named.

use crate::m4f_bench;
use crate::table::{self, Csv, Table};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The grid file this summary reads (written by the work–precision study in the same run).
pub const GRID_FILE: &str = "work_precision_grid.csv";

/// The Cortex-M4F clock of the CPU shares (the mps2-an386 board's and a common part's, e.g. STM32F407).
const M4F_HZ: f64 = 168.0e6;

/// A tenth: the integrator's share of the noise's angle error.
const SHARE: f64 = 0.1;

/// A gyro class and its rate noise density in °/s/√Hz, each from a datasheet or a class's typical figure.
const GYROS: [(&str, f64); 3] = [
    ("consumer MEMS, 0.005 °/s/√Hz (MPU-6000 datasheet)", 0.005),
    (
        "low-noise MEMS, 0.0028 °/s/√Hz (ICM-42688-P datasheet)",
        0.0028,
    ),
    // 0.01 °/√h = 0.01/60 °/√s.
    ("tactical grade, ARW 0.01 °/√h", 0.01 / 60.0),
];

/// The horizons (s).
const HORIZONS: [f64; 3] = [10.0, 60.0, 3600.0];

/// The columns of the grid this summary needs (the file has more).
#[derive(Deserialize)]
struct GridPoint {
    scene: String,
    precision: String,
    configuration: String,
    is_peer: bool,
    rate_hz: u32,
    samples: u64,
    max_error_rad: f64,
    refused_steps: u64,
}

/// A configuration the bench measured: its grid label and its f32 instructions per step.
struct Measured {
    label: String,
    instructions_per_step: f64,
}

/// The M4F bench's f32 rows as grid labels (`quatprop <scheme> <input> + <stabilizer>`).
fn bench(path: &Path) -> Result<Vec<Measured>, String> {
    Ok(m4f_bench::read(path)?
        .into_iter()
        .filter(|r| r.0 == "f32")
        .map(|(_, scheme, stab, input, n)| Measured {
            label: format!("quatprop {scheme} {input} + {stab}"),
            instructions_per_step: n,
        })
        .collect())
}

/// The grid's accepted f32 quatprop points on coning: (label, rate, max error, horizon in s).
fn grid(path: &Path) -> Result<Vec<(String, u32, f64, f64)>, String> {
    let mut r = csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut points = Vec::new();
    for p in r.deserialize::<GridPoint>() {
        let p = p.map_err(|e| format!("{}: {e}", path.display()))?;
        if p.scene == "coning"
            && p.precision == "f32"
            && !p.is_peer
            && p.refused_steps == 0
            && p.max_error_rad.is_finite()
        {
            let horizon = p.samples as f64 / f64::from(p.rate_hz);
            points.push((p.configuration, p.rate_hz, p.max_error_rad, horizon));
        }
    }
    Ok(points)
}

/// One cell of the summary: a gyro, a rate, a horizon, and the cheapest configuration that passes (an
/// empty configuration and NaN figures where none does).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SummaryRow {
    pub gyro: String,
    pub rate_hz: u32,
    pub horizon_s: f64,
    pub configuration: String,
    pub m4f_instructions_per_second: f64,
    pub m4f_cpu_share_percent: f64,
    pub error_rad: f64,
    pub budget_rad: f64,
}

impl Csv for SummaryRow {
    const FILE: &'static str = "summary.csv";
}

impl Table for SummaryRow {
    /// One line per gyro and rate, one column per horizon (in the rows' order).
    fn render(rows: &[Self]) -> String {
        let mut horizons: Vec<f64> = Vec::new();
        for r in rows {
            if !horizons.contains(&r.horizon_s) {
                horizons.push(r.horizon_s);
            }
        }
        let names: Vec<String> = horizons.iter().map(|&t| horizon_name(t)).collect();
        let mut cols = vec!["gyro", "rate (Hz)"];
        cols.extend(names.iter().map(String::as_str));
        let mut t = table::header(&cols);
        let mut keys: Vec<(&str, u32)> = Vec::new();
        for r in rows {
            if !keys.contains(&(r.gyro.as_str(), r.rate_hz)) {
                keys.push((r.gyro.as_str(), r.rate_hz));
            }
        }
        for (gyro, rate) in keys {
            t += &format!("| {} | {rate} |", table::cell(gyro));
            for &h in &horizons {
                let cell = rows
                    .iter()
                    .find(|r| r.gyro == gyro && r.rate_hz == rate && r.horizon_s == h)
                    .map_or_else(String::new, |r| {
                        if r.configuration.is_empty() {
                            format!(
                                "none at this rate (budget {} rad)",
                                table::sci(r.budget_rad, 2)
                            )
                        } else {
                            format!(
                                "{} ({} instr/s, {:.2} %; error {} of {} rad)",
                                r.configuration,
                                table::sci(r.m4f_instructions_per_second, 2),
                                r.m4f_cpu_share_percent,
                                table::sci(r.error_rad, 2),
                                table::sci(r.budget_rad, 2),
                            )
                        }
                    });
                t += &format!(" {} |", table::cell(&cell));
            }
            t.push('\n');
        }
        t
    }
}

/// The summary's text and rows, from the grid in `dir` and the bench at `bench_path`; `Err` names what
/// is missing or unreadable.
pub fn summary(dir: &Path, bench_path: &Path) -> Result<(String, Vec<SummaryRow>), String> {
    let measured = bench(bench_path)?;
    let points = grid(&dir.join(GRID_FILE))?;
    let mut rates: Vec<u32> = points.iter().map(|p| p.1).collect();
    rates.sort_unstable();
    rates.dedup();
    if rates.is_empty() || measured.is_empty() {
        return Err(format!(
            "{GRID_FILE} or the M4F bench holds no f32 coning point"
        ));
    }
    let horizon = points.iter().map(|p| p.3).fold(f64::NAN, f64::max);
    let text = format!(
        "## Which configuration for my gyro, rate and horizon\n\n\
         Computed from this run's figures: the cheapest configuration on the Cortex-M4F (instructions per \
         second of flight, `firmware/bench-m4f.csv`; the CPU share at {:.0} MHz and one cycle per \
         instruction) whose f32 error on coning (0.3 rad at 1 Hz, a hard motion: the full grid below, \
         {horizon:.2} s) stays, grown linearly to the horizon, below a tenth of the angle the gyro's white \
         noise alone makes in that time (density × √horizon, 1σ per axis), so that the attitude error is \
         the sensor's, not the integrator's. \"None at this rate\": no configuration measured at that rate \
         meets it (a higher rate does; over long horizons in f32 also the FloatFloat accumulator or f64, \
         the long-horizon section). Bias, scale and misalignment errors are the sensor front end's \
         (docs/calibration.md), not counted here.\n\n",
        M4F_HZ / 1e6,
    );
    let mut rows = Vec::new();
    for (gyro, density) in GYROS {
        for &rate in &rates {
            for t in HORIZONS {
                let budget = SHARE * density.to_radians() * t.sqrt();
                let best = points
                    .iter()
                    .filter(|p| p.1 == rate && p.2 * t / p.3 <= budget)
                    .filter_map(|p| {
                        let m = measured.iter().find(|m| m.label == p.0)?;
                        Some((m.instructions_per_step * f64::from(rate), p))
                    })
                    .min_by(|a, b| a.0.total_cmp(&b.0));
                rows.push(match best {
                    Some((per_second, p)) => SummaryRow {
                        gyro: gyro.to_string(),
                        rate_hz: rate,
                        horizon_s: t,
                        configuration: p.0.trim_start_matches("quatprop ").to_string(),
                        m4f_instructions_per_second: per_second,
                        m4f_cpu_share_percent: 100.0 * per_second / M4F_HZ,
                        error_rad: p.2 * t / p.3,
                        budget_rad: budget,
                    },
                    None => SummaryRow {
                        gyro: gyro.to_string(),
                        rate_hz: rate,
                        horizon_s: t,
                        configuration: String::new(),
                        m4f_instructions_per_second: f64::NAN,
                        m4f_cpu_share_percent: f64::NAN,
                        error_rad: f64::NAN,
                        budget_rad: budget,
                    },
                });
            }
        }
    }
    Ok((text, rows))
}

fn horizon_name(t: f64) -> String {
    if t >= 3600.0 {
        format!("{:.0} h", t / 3600.0)
    } else if t >= 60.0 {
        format!("{:.0} min", t / 60.0)
    } else {
        format!("{t:.0} s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grid of two configurations at one rate: the cheaper one passes the short horizon only, the dearer
    /// one every horizon but the hour; nothing passes the hour.
    #[test]
    fn the_cheapest_passing_configuration_is_named() {
        let dir = crate::table::scratch_dir("quatprop-summary");
        // Horizon 10 s at 100 Hz (1000 samples). The consumer gyro's budget at 10 s: 0.1 · 0.005° · √10 =
        // 2.76e-5 rad; at 60 s 6.76e-5 rad (scaled error must be ≤): the cheap one errs 2e-5 in 10 s
        // (1.2e-4 at 60 s: fails), the dear one 1e-6 (6e-6 at 60 s: passes; 3.6e-4 at 1 h vs budget
        // 5.2e-4: passes).
        std::fs::write(
            dir.join(GRID_FILE),
            "scene,precision,configuration,is_peer,rate_hz,samples,final_error_rad,max_error_rad,host_ns_per_sample,refused_steps,first_error,error_kind\n\
             coning,f32,quatprop ExpMap hold + FirstOrder,false,100,1000,0,2e-5,1,0,,\n\
             coning,f32,quatprop ExpMap history + FirstOrder,false,100,1000,0,1e-6,1,0,,\n\
             coning,f32,quatprop Euler hold + Off,false,100,1000,0,1e-9,1,0,,\n",
        )
        .unwrap();
        let bench_path = dir.join("bench.csv");
        std::fs::write(
            &bench_path,
            "precision,scheme,stabilizer,input,instructions_per_step\n\
             f32,ExpMap,FirstOrder,hold,80\n\
             f32,ExpMap,FirstOrder,history,160\n\
             f32-kahan,ExpMap,FirstOrder,hold,1\n",
        )
        .unwrap();
        let (_, rows) = summary(&dir, &bench_path).unwrap();
        let md = SummaryRow::render(&rows);
        let consumer: Vec<&str> = md.lines().filter(|l| l.starts_with("| consumer")).collect();
        assert_eq!(consumer.len(), 1, "{md}");
        let cells: Vec<&str> = consumer[0].split(" | ").collect();
        // 10 s: the cheap one (8000 instr/s); 1 min and 1 h: the dear one (16000 instr/s). Euler hold has
        // no bench row: never named, however small its error.
        assert!(
            cells[2].starts_with("ExpMap hold + FirstOrder (8.00e3 instr/s"),
            "{md}"
        );
        assert!(
            cells[3].starts_with("ExpMap history + FirstOrder (1.60e4"),
            "{md}"
        );
        assert!(
            cells[4].starts_with("ExpMap history + FirstOrder (1.60e4"),
            "{md}"
        );
        // The tactical gyro's hour: budget 0.1 · (0.01/60)° · 60 = 1.75e-5 rad; 3.6e-4 does not pass.
        let tactical = md.lines().find(|l| l.starts_with("| tactical")).unwrap();
        assert!(
            tactical.ends_with("none at this rate (budget 1.75e-5 rad) |"),
            "{tactical}"
        );
        // The rows read back from their CSV render the same table (NaN figures where none passes).
        table::write(&dir.join(SummaryRow::FILE), &rows).unwrap();
        let back = table::read::<SummaryRow>(&dir.join(SummaryRow::FILE)).unwrap();
        assert_eq!(SummaryRow::render(&back), md);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
