//! Prints the README's scheme table: stages, stability bounds and the per-step norm factor, all derived
//! from the tableaux at compile time (`src/scheme/tableau.rs`).
//!
//! Run: `cargo run --example schemes`

use quatprop::scheme::{ButcherTableau, Euler, Method, Rk2, Rk3, Rk4, Rk5, Scheme};

fn stages(m: Method) -> String {
    match m {
        Method::Euler => Euler::STAGES.to_string(),
        Method::Rk2 => Rk2::STAGES.to_string(),
        Method::Rk3 => Rk3::STAGES.to_string(),
        Method::Rk4 => Rk4::STAGES.to_string(),
        Method::Rk5 => Rk5::STAGES.to_string(),
        Method::ExpMap | Method::Magnus4 | Method::Cf4 => "–".to_string(),
    }
}

fn main() {
    println!("| scheme | stages | step-angle bound H·|w| (rad) | Baumgarte bound 4kH (half the real-axis interval) | 1 − |R(ix)|² at H|w| = 0.2 | at H|w| = 0.02 |");
    println!("|---|---|---|---|---|---|");
    for m in Method::ALL {
        let fmt = |v: f64| {
            if v.is_finite() {
                format!("{v:.4}")
            } else {
                "none".to_string()
            }
        };
        println!(
            "| {} | {} | {} | {} | {:+.3e} | {:+.3e} |",
            m.name(),
            stages(m),
            fmt(m.step_angle_limit()),
            fmt(m.gain_step_limit()),
            0.0 - m.norm_change(0.2),
            0.0 - m.norm_change(0.02),
        );
    }
}
