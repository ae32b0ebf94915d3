//! The arguments several studies share ([`Horizon`], [`Sweep`]) and `report`'s ([`ReportArgs`]), with their
//! value parsers (typed values, checked before anything runs).

use crate::configs::{self, Input, Precision, Stab};
use crate::scale::Scale;
use crate::scenes;
use clap::Args;
use quatprop::scheme::SchemeKind;

/// The arguments of `report` (handed to the studies that take them: `Study::report_args`).
#[derive(Args, Debug, Clone, Default)]
pub struct ReportArgs {
    #[command(flatten)]
    pub horizon: Horizon,
}

/// Step counts of the long runs.
#[derive(Args, Debug, Clone, Default)]
pub struct Horizon {
    /// To 1e9 steps (instead of 1e7 at the default scale, 1e8 with --full).
    #[arg(long)]
    pub long: bool,
    /// Steps (at least 1e3; `1e7` and `10000000` both work); overrides --long and --quick.
    #[arg(long, value_parser = parse_steps)]
    pub steps: Option<u64>,
}

/// Parameters of a work-precision or sensor sweep (empty lists: the defaults).
#[derive(Args, Debug, Clone, Default)]
pub struct Sweep {
    /// Scenes by key (comma-separated).
    #[arg(long = "scene", value_delimiter = ',', value_parser = parse_scene)]
    pub scenes: Vec<String>,
    /// Schemes (comma-separated): Euler, Rk2, Rk3, Rk4, Rk5, ExpMap, Magnus4, Cf4.
    #[arg(long, value_delimiter = ',', value_parser = parse_scheme)]
    pub schemes: Vec<SchemeKind>,
    /// Stabilizers (comma-separated): Off, Normalize, FirstOrder, EveryN (e.g. Every16), Baumgarte (k = 0.5)
    /// or Baumgarte=K (Runge–Kutta schemes only).
    #[arg(long, value_delimiter = ',', value_parser = parse_stab)]
    pub stabilizers: Vec<Stab>,
    /// Input models (comma-separated): hold, linear, history, mid.
    #[arg(long, value_delimiter = ',', value_parser = parse_input)]
    pub inputs: Vec<Input>,
    /// Precisions (comma-separated): f32, f64.
    #[arg(long, value_delimiter = ',', value_parser = parse_precision)]
    pub precision: Vec<Precision>,
    /// Gyro sample rates in Hz (comma-separated).
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..))]
    pub rates: Vec<u32>,
    /// Seconds per run.
    #[arg(long, value_parser = parse_positive)]
    pub horizon: Option<f64>,
}

fn parse_steps(s: &str) -> Result<u64, String> {
    let n: f64 = s.parse().map_err(|e| format!("{e}"))?;
    if (1e3..=1e12).contains(&n) {
        Ok(n.round() as u64)
    } else {
        Err("a step count from 1e3 to 1e12".into())
    }
}

fn parse_positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v > 0.0 && v.is_finite() => Ok(v),
        _ => Err("a positive number of seconds".into()),
    }
}

fn parse_scene(s: &str) -> Result<String, String> {
    let keys: Vec<&str> = scenes::catalogue(0.0).iter().map(|c| c.key()).collect();
    if keys.contains(&s) {
        Ok(s.to_string())
    } else {
        Err(format!("unknown scene; one of {}", keys.join(", ")))
    }
}

fn parse_scheme(s: &str) -> Result<SchemeKind, String> {
    SchemeKind::ALL
        .into_iter()
        .find(|&m| configs::scheme_name(m).eq_ignore_ascii_case(s))
        .ok_or_else(|| {
            let names: Vec<&str> = SchemeKind::ALL
                .iter()
                .map(|&m| configs::scheme_name(m))
                .collect();
            format!("unknown scheme; one of {}", names.join(", "))
        })
}

fn parse_stab(s: &str) -> Result<Stab, String> {
    let bad = || "one of Off, Normalize, FirstOrder, EveryN, Baumgarte, Baumgarte=K".to_string();
    Ok(match s {
        "Off" => Stab::Off,
        "Normalize" => Stab::Normalize,
        "FirstOrder" => Stab::FirstOrder,
        "Baumgarte" => Stab::Baumgarte(0.5),
        _ => {
            if let Some(n) = s.strip_prefix("Every") {
                let n: u32 = n
                    .trim_matches(|c| c == '(' || c == ')')
                    .parse()
                    .map_err(|_| bad())?;
                if n == 0 {
                    return Err("Every(0) is not a stabilizer".into());
                }
                Stab::Every(n)
            } else {
                let k: f64 = s
                    .strip_prefix("Baumgarte=")
                    .ok_or_else(bad)?
                    .parse()
                    .map_err(|_| bad())?;
                Stab::Baumgarte(k)
            }
        }
    })
}

fn parse_input(s: &str) -> Result<Input, String> {
    Input::ALL
        .into_iter()
        .find(|i| i.name() == s)
        .ok_or_else(|| "one of hold, linear, history, mid".into())
}

fn parse_precision(s: &str) -> Result<Precision, String> {
    match s {
        "f32" => Ok(Precision::F32),
        "f64" => Ok(Precision::F64),
        _ => Err("f32 or f64".into()),
    }
}

impl Horizon {
    /// Steps at the default scale: four decades, the last two for the growth exponents.
    pub const DEFAULT_STEPS: u64 = 10_000_000;

    /// The step count: `--steps`, else by scale (`--long`: 1e9 unless `--quick`).
    pub fn steps(&self, scale: Scale) -> u64 {
        self.steps.unwrap_or(match scale {
            Scale::Quick => 1_000_000,
            _ if self.long => 1_000_000_000,
            Scale::Default => Self::DEFAULT_STEPS,
            Scale::Full => 100_000_000,
        })
    }
}
